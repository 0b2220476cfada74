// disco — what a search runs: scenes, each with its number of starts and time
// budget, read from the CONFIG files given to `disco search`.
//
// A CONFIG is a scene file (core/model/scene_yaml.h) or a benchmark file:
//
//   benchmark: smoke              # the key that marks a benchmark file
//   starts: 4                     # optional default starts per scene (>= 1)
//   time_limit: 600               # optional default seconds per scene (0 = none): no start
//                                 # of the scene is handed out after it
//   start_time_limit: 60          # optional default seconds per start (0 = none)
//   scenes:
//     - file: ../scenarios/one_robot_axis.yaml   # relative to this file
//       starts: 3                 # optional
//       time_limit: 120           # optional
//       start_time_limit: 20      # optional
//       set: [steps=20]           # optional scene overrides (as --set scene.KEY=VALUE)
//
// --starts N on the command line replaces every scene's number of starts.
// Scene names must be unique across the plan: runs are keyed by scene name.
// Errors are InputErrors naming file, line and key.
#pragma once

#include <string>
#include <vector>

#include "core/model/scene.h"
#include "search/start.h"

namespace disco {

struct SceneJob {
  Scene scene;                     // scene.source is its file
  std::vector<std::string> overrides;  // scene overrides applied: the entry's `set`, then --set
  int starts = 1;
  double time_limit = 0.0;        // s for all the scene's starts, from its first; 0 = none
  double start_time_limit = 0.0;  // s per start; 0 = none
  // --guess FILE for this scene (search/trajectory.h): its start 0 starts from it instead of
  // the straight guess. Empty: none.
  Trajectory guess;
};

struct SearchPlan {
  std::vector<SceneJob> scenes;
  int total_starts() const;
};

// `starts_override` > 0 replaces every scene's starts; `default_starts`
// applies where a file gives none (time limits default to none);
// `scene_overrides` apply to every scene (after a benchmark entry's own `set`).
SearchPlan load_search_plan(const std::vector<std::string>& configs, int starts_override,
                            int default_starts, const std::vector<std::string>& scene_overrides);

// `disco search --guess FILE ...`: each solution file goes to the scene named by its
// "scenario", or, in a plan of one scene, to that scene whatever its name; read and checked
// against the scene by read_guess_file (search/trajectory.h). InputError for a file whose
// scenario is not in the plan, or a second file for one scene.
void attach_guesses(SearchPlan& plan, const std::vector<std::string>& files);

}  // namespace disco
