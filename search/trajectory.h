// disco — trajectories to start from: a solution file (`--guess FILE`) or a model point,
// resampled to a scene's steps.
//
// A Trajectory (search/start.h) is the robots' paths, one Pose (x, y, phi) per robot and
// state t = 0..N (SI units), and the horizon T_f they were found at. A start of kind kGiven
// completes the paths into a point of the model (search/guess.h, complete_guess) at any
// horizon, first at (1 + feasibility.guess_slack) times that T_f: the same paths, timed to
// the new horizon (each state keeps its fraction t / N of it).
//
// Resampling. A path of n steps becomes one of N steps by linear interpolation at the same
// fraction of the horizon: state t of the new path is the old path at the continuous step
// u = t n / N, between its states floor(u) and floor(u) + 1. Both ends are kept exactly.
//
// The guess file is a solution file (core/model/solution.h): `disco solve`'s solution.json or
// a search's best/SCENE.json, of the same scene at any N_t, or of another scene with the
// same robots. What must match (else an InputError naming the file): a certified
// trajectory (T_f and x, y, phi present), the robots' number and names, in the scene's
// order, and their start positions (within 1e-6, in metres, relative beyond 1 m).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/model/robot_problem.h"
#include "search/start.h"

namespace disco {

// The pose at continuous step u in [0, n] of `path` (n + 1 poses), linearly interpolated.
Pose pose_at(const std::vector<Pose>& path, double u);

// `paths` resampled to N steps (see above).
Paths resample(const Paths& paths, int N);

// The paths of model point z (model units) of `problem`, SI; state 0 is each robot's start.
Paths paths_of(const RobotProblem& problem, const Vector& z);

// The trajectory of solution document `doc` for `scene`, resampled to scene.steps;
// `source` names it in messages (and becomes Trajectory::source). InputError if it does not
// match the scene (see above).
Trajectory trajectory_from_solution(const nlohmann::json& doc, const Scene& scene,
                                    const std::string& source);
// The JSON document in the file at `path`; InputError if it cannot be read or parsed.
nlohmann::json read_guess_document(const std::string& path);
// trajectory_from_solution of the file at `path`.
Trajectory read_guess_file(const std::string& path, const Scene& scene);

}  // namespace disco
