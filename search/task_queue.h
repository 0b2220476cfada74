// disco — the tasks of a search and the order and budgets they are handed out with.
//
// A task is one start of one scene of the plan (search/search_plan.h). The queue holds
// the tasks not yet run, larger scenes first (longest-processing-time order: fewer idle
// ranks at the end; the order changes no result, only when each start runs), and hands
// them out one at a time, on demand (starts differ in cost by 10x and more).
//
// Time limits stop the handing out at three levels: the whole search (`--time-limit`),
// one scene (`time_limit` in a benchmark file, counted from the hand-out of the scene's
// first start) and one start (`start_time_limit`). A task's budget is the smallest of
// the start's own limit and what is left of its scene's and of the search's; its
// BudgetSource says which limit set it (search/run_start.h).
//
// Screening (search/screening.h): the queue first holds every start's screen; a scene's
// refines are added by the coordinator (add_refines) once none of its screens is open, and run
// before the screens still pending; so are its early refines (add_early_refine), added one at
// a time while it screens. Refines run in the order they were added. Under a time limit, screens are handed out only until the
// screening share of it (search.screen_share) is used, and their budgets end there; once a
// scene's chosen refines are handed out, the time left goes to more of its refines
// (add_refine), which the coordinator adds one at a time when a rank would otherwise idle: the
// next best screens, then the starts without a certified screen (search/screening.h,
// time_left_order, in start_order).
//
// Not thread-safe: search/coordinator.h guards it.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "core/util/numbers.h"
#include "search/run_start.h"
#include "search/screening.h"
#include "search/search_plan.h"

namespace disco {

struct Task {
  int scene = 0, start = 0;  // indices into the plan's scenes, and the start index
  Stage stage = Stage::kFull;
  double budget = 0.0;       // s; 0 = none
  BudgetSource source = BudgetSource::kNone;  // the limit that set the budget
  double incumbent = kInf;  // s: its scene's shared incumbent when handed out (+inf: none)
  nlohmann::json guess;     // kRefine: the start's screened solution document (null: a refine
                            // from the start's own guess, search.refine_from "start"; else null)
  nlohmann::json to_json() const;             // the message that hands it to a worker
  static Task from_json(const nlohmann::json& j);
};

// The homotopy class key of the guess of start `start` of scene `scene` (search/homotopy.h),
// "" when the guess decides none (some pair's turn is "?").
using GuessClassFunction = std::function<std::string(int scene, int start)>;

class TaskQueue {
 public:
  // Every task of `plan` but those in `done` ((scene, start) pairs: final outcomes of an
  // earlier run); `time_limit` is the whole search's (s; 0 = none). With `guess_class`
  // (search.defer_seen_classes), each scene's starts whose guess has a class ("" never
  // counts) that a lower start of the scene's guess already has are deferred after the
  // scene's other starts, index order kept within both groups: untried classes run first.
  // With `screen` on, the tasks are the screens of every start not in `screened` (final
  // screens of an earlier run) nor in `done` (its refine ended there).
  TaskQueue(const SearchPlan& plan, double time_limit, const std::set<std::pair<int, int>>& done,
            const GuessClassFunction& guess_class = {}, const ScreenSettings& screen = {},
            const std::set<std::pair<int, int>>& screened = {});

  // The next task for `rank` at search time `now` (s), or none: every task handed out,
  // or the search's time limit passed. Scenes whose own limit has passed are skipped.
  std::optional<Task> next(int rank, double now);
  // Task (scene, start) has an outcome: it no longer runs. `cut`: the limit that cut it short,
  // if one did (kSearch: the search's time limit was reached; kScene: the scene's).
  void finished(int scene, int start, BudgetSource cut = BudgetSource::kNone);

  // Screening. Whether scene s still has screens that may run or are running at `now`
  // (pending ones count until the screening share of a time limit is used).
  bool screens_open(int s, double now) const;
  // Whether scene s's refines have been added (always false without screening).
  bool refined(int s) const { return scenes_[s].refined; }
  // Scene s's refines, to run next, in this order; `chosen` counts the refines of the choice
  // (those `tasks` leaves out ended in an earlier run), but not those of starts never screened
  // (run in their screen's place, see add_refine). Fixes the scene's count in total().
  void add_refines(int s, int chosen, const std::vector<Task>& tasks);
  // One early refine of scene s (search/screening.h), to run next; counted in total() whether
  // it runs or not (none: it ended in an earlier run, or its screen's answer is missing).
  void add_early_refine(int s, const std::optional<Task>& task);
  // Whether scene s may take a refine beyond its choice at `now` (search/screening.h, "fill"):
  // its refines were added, a time limit bounds it (the search's or its own), and neither has
  // passed.
  bool may_fill(int s, double now) const;
  // One refine more (early or beyond the choice), to run after the refines pending; counted in
  // total() whether it runs or not (none: it ended in an earlier run, or its screen's answer is
  // missing). `in_place_of_screen`: the start was never screened and runs at full N_t in the
  // time left instead: it takes its screen's place in total(), and its screen, if pending, is
  // dropped.
  void add_refine(const std::optional<Task>& task, bool in_place_of_screen = false);
  // Whether refines may still be added: a scene with screening whose refines are not, and
  // whose time limit (and the search's) has not passed. A rank then waits for work.
  bool refines_to_come(double now) const;
  bool screening() const { return screen_.on(); }
  // Scene s's starts in the order the queue hands them out (guess classes deferred as above;
  // every start, also those an earlier run ended).
  const std::vector<int>& start_order(int s) const { return order_[s]; }
  // At the end: tasks left undone mean a time limit stopped the search (as a start it cut does).
  void finish();

  int total() const { return total_; }      // tasks of the plan
  double time_limit() const { return time_limit_; }  // the search's (s; 0 = none)
  int pending() const { return static_cast<int>(pending_.size() - next_); }
  bool time_limited() const { return time_limited_; }
  // Scene s: the search time its first start was handed out (< 0: not yet), and whether
  // its own time limit stopped it.
  double scene_started(int s) const { return scenes_[s].started_s; }
  bool scene_time_limited(int s) const { return scenes_[s].time_limited; }

  // The tasks handed out and not finished: (scene, start) -> rank, hand-out time.
  struct Running {
    int rank = 0;
    double handed_s = 0.0;
    Stage stage = Stage::kFull;
  };
  const std::map<std::pair<int, int>, Running>& running() const { return running_; }

  // At most this long (s) from `now` until the time limits stop the search: the search's
  // own limit, and every scene's limit left (scenes taken one after another); +inf if
  // no limit bounds it.
  double time_left(double now) const;

 private:
  struct SceneState {
    double started_s = -1.0;
    bool time_limited = false;
    bool refined = false;  // screening: its refines were added
  };
  // Screening: the search time at which screens of scene s stop being handed out (+inf: never).
  double screen_end(int s) const;
  // Screening: where the next refine goes: after the refines pending (first in, first out).
  std::ptrdiff_t refines_end() const;
  const SearchPlan& plan_;
  double time_limit_ = 0.0;
  ScreenSettings screen_;
  std::vector<Task> pending_;
  std::size_t next_ = 0;
  int total_ = 0;
  bool time_limited_ = false;
  std::vector<SceneState> scenes_;
  std::vector<std::vector<int>> order_;  // per scene: its starts in hand-out order
  std::map<std::pair<int, int>, Running> running_;
};

}  // namespace disco
