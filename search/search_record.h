// disco — what a search keeps: DIR/runs.jsonl, the best start of every scene,
// DIR/best.json and DIR/best/SCENE.json (DIR = --out; search/README.md gives the fields).
//
//   runs.jsonl      one line per start that ended (search/run_start.h, StartOutcome), also
//                   a start cut short by a time limit (status time_limit) or an interrupt
//                   (interrupted), with its best point so far; each line is flushed and
//                   fsync'ed as it is written, so a kill loses no finished start;
//   best.json       the mode ("shared": starts shared the incumbent, or "deterministic");
//                   per scene: the best certified T_f, its start, starts run and solved,
//                   time to first feasible and to best (from the hand-out of the scene's
//                   first start); whether a time limit cut the search short;
//   best/SCENE.json the full solution of the best start (core/model/solution.h), with its
//                   runs.jsonl line as provenance.run. It is written before that line, so
//                   a kill between the two leaves the file, and --resume appends the
//                   missing line from it: a recorded best always has its file.
//   best/.final/SCENE.json  the same for the best start with a final outcome (not cut
//                   short), written when it changes. A start cut by a time limit keeps its
//                   best so far, and with a salvage (reduction.salvage_iterations) that point
//                   can lie below where the same start ends when --resume runs it again; the
//                   best then falls back to a final start, whose file is copied from here.
//
// Screening (search/screening.h): a screen's line (stage "screen") is kept apart from the
// starts' outcomes: it is never a scene's best nor counted in best.json's starts_run. Its
// solution file goes to DIR/screened/SCENE/K.json before its line, and the refine of start K
// starts from it (also after --resume, which reads the screens back from runs.jsonl).
//
// The best of a scene is the smallest certified T_f, ties to the lower start index, so the
// outcome does not depend on which rank ran what. A start's later line replaces its
// earlier one (a start cut short and run again by --resume).
//
// --resume: the record reads the earlier runs.jsonl first. A start with a final outcome
// there is done (done()); a start cut short is not, unless its own start_time_limit cut it
// and that limit is unchanged (it would only be cut again). Deterministic starts
// (search/start.h) make a resumed search end with the runs and best of one run without
// interruption.
//
// Not thread-safe: search/coordinator.h guards it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "search/run_start.h"
#include "search/search_plan.h"
#include "search/task_queue.h"

namespace disco {

// Whether a recorded outcome is final, so that --resume skips its start.
bool is_final(const StartOutcome& o, const SceneJob& job);

class SearchRecord {
 public:
  // Opens DIR/runs.jsonl: for writing, or, if `resumed`, for appending after reading the
  // lines of `seed` it holds. InputError if it cannot be opened.
  // `shared`: the search shares its incumbent (best.json's "mode": "shared", else
  // "deterministic").
  SearchRecord(const SearchPlan& plan, const std::string& out_dir, std::uint64_t seed, bool resumed,
               bool shared);
  ~SearchRecord();
  SearchRecord(const SearchRecord&) = delete;
  SearchRecord& operator=(const SearchRecord&) = delete;

  // The (scene, start) pairs with a final outcome in the earlier run (empty unless resumed).
  const std::set<std::pair<int, int>>& done() const { return done_; }
  // The same for screens (stage "screen").
  const std::set<std::pair<int, int>>& screened_done() const { return screened_done_; }
  // The starts of scene s with an outcome that is not a screen (this run's and the earlier's).
  std::set<int> ran(int s) const;
  // Scene s's screen outcomes so far (this run's and the earlier run's), by start.
  std::map<int, StartOutcome> screened(int s) const;
  // DIR/screened/SCENE/K.json: the solution file of start K's screen.
  std::string screened_file(const std::string& scene, int start) const;

  // Records `o`, finished at search time `now` (s); its scene's first start was handed out
  // at `scene_started`. Appends its line to runs.jsonl, recounts its scene and, when `o`
  // is now the scene's best and `solution` is given, writes best/SCENE.json (and
  // best/.final/SCENE.json when it is the best final outcome); when `o` ran again and ended
  // above its earlier best, which was the scene's, the best final start's file takes its place.
  void record(const StartOutcome& o, const nlohmann::json* solution, double now, double scene_started);

  // Writes best.json (the scenes' hand-out times and limits from `queue`).
  void write_best(const TaskQueue& queue, double now, bool interrupted) const;

  int finished() const { return finished_; }      // final outcomes, this run's and earlier ones
  int resumed() const { return resumed_; }        // of those, read from the earlier run
  int cut_short() const { return cut_short_; }    // this run's outcomes that are not final
  int interrupted() const { return interrupted_; }  // of those, cut by an interrupt
  bool all_solved() const;  // every scene has a certified best
  std::optional<double> best_value(int s) const;  // scene s's best certified J, if any

  // "scene T_f" for every scene with at most four, else for scene s (or, with s < 0, how
  // many scenes are solved): the progress lines' best.
  std::string best_summary(int s) const;

 private:
  struct Best {
    int start = -1;
    double value = 0.0;  // J (T_f for objective time)
    StartOutcome outcome;
    int run = 0, solved = 0;  // starts with an outcome; with a certified point
    int cut_short = 0;        // of those, cut short (not final: --resume runs them again)
    double first_feasible_s = -1.0, best_s = -1.0;
    double last_s = -1.0;     // search time its last start was recorded
  };
  // What update() found for the outcome it recorded.
  struct Standing {
    bool best = false;        // it is now the scene's best
    bool final_best = false;  // it is now the scene's best final outcome
    bool back_to_final = false;  // it replaced the best with a worse point; the best final
                                 // outcome is the scene's best again
  };
  int scene_index(const std::string& name) const;
  Standing update(int s, const StartOutcome& o, double now, double scene_started);
  void record_result(const StartOutcome& o, const nlohmann::json* solution,
                     const nlohmann::json& line, int s, double now, double scene_started);
  void read_earlier(const std::string& path, std::uint64_t seed);
  void recover_lines(const std::string& path, std::uint64_t seed, const std::set<std::string>& lines);
  std::string best_file(const std::string& scene) const;  // DIR/best/SCENE.json
  std::string final_file(const std::string& scene) const;  // DIR/best/.final/SCENE.json
  void append(const std::string& line);  // to runs.jsonl, flushed and fsync'ed

  const SearchPlan& plan_;
  std::string out_;
  std::uint64_t seed_ = 0;
  bool shared_ = false;
  std::FILE* runs_ = nullptr;
  std::vector<Best> best_;
  std::map<std::pair<int, int>, StartOutcome> outcomes_;  // (scene, start): its latest outcome
  std::map<std::pair<int, int>, StartOutcome> screens_;   // the same for screens
  std::set<std::pair<int, int>> done_, screened_done_;
  // Refines that ran from the answer of a screen cut short (a time limit), or without a screen
  // (a start the screening share left unscreened, run in the time left): not final, since
  // --resume runs that screen and then the refine from its answer, as a search without the cut
  // does (search/README.md, "Screening").
  std::set<std::pair<int, int>> stale_refines_;
  // is_final, and for a refine: not stale.
  bool final_outcome(int s, const StartOutcome& o) const;
  // Notes whether refine `o` of scene s ran after a final screen (stale_refines_).
  void note_refine(int s, const StartOutcome& o);
  std::vector<std::string> recovered_;  // lines read_earlier took from best/SCENE.json
  int finished_ = 0, resumed_ = 0, cut_short_ = 0, interrupted_ = 0;
};

}  // namespace disco
