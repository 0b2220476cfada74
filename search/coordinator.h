// disco — rank 0 of a search: hands out the tasks (search/task_queue.h), records their
// outcomes (search/search_record.h) and reports progress.
//
// Thread-safe: rank 0's coordinator thread (answering the workers' messages) and its own
// worker share it. It never calls the transport itself: on_result() turns a worker's
// message into the reply to send, so the same logic runs over MPI (search/run_search.h)
// or any other Transport.
//
// Progress. After every recorded start, rank 0 logs (info) one line:
//   [3/6] two_robots_swap_avoid start 0 (rank 0): solved T_f 2.380635 in 1.6 s | best ... |
//   elapsed 00:00:02 ETA 00:00:02
// (starts done / total, the start's result, the best T_f per scene, elapsed time, and the
// ETA from the mean time per start run here, capped by the time limits left); a start cut
// short says "time limit (search, 20 s): T_f 2.380710 so far" or "interrupted: ...".
// status_text() is the live status line (mpi/live_line.h): starts done / total, elapsed,
// ETA, best T_f, and the starts running (scene #start, rank, seconds so far).
//
// The shared incumbent (search.share_incumbent; search/reduction_phases.h says how a start
// uses it): the smallest certified T_f of each scene recorded, or reported by a start still
// running (progress()), so far. A task carries its scene's incumbent when handed out; when
// an incumbent improves, take_outbox() gives one kIncumbent message for every worker rank
// then running a start of that scene (rank 0's own worker reads incumbent() instead). Not
// shared, the incumbent is +inf everywhere and no message is made: each start runs alone.
//
// Screening (search/screening.h): a screen's outcome never moves the incumbent. Once none of
// a scene's screens is open, the coordinator chooses its refines (refine_choice over the
// recorded screens) and queues them with their screened solution files; with early refines
// (search.early_refine_batch) it queues each as soon as early_refine_choice decides it, and the
// final choice skips the starts refined early. Under a time limit, a rank that would otherwise
// idle once a scene's chosen refines are handed out gets the scene's next screened start in the
// same ranking, and once those are refined a start without a certified screen, at full N_t from
// its own guess (add_fill_refine): the limit, not refine_count, ends the refines. A rank that asks for
// work while only refines still to come could give it some waits: rank 0's own worker in
// await_work(), a worker rank by getting no reply until take_outbox() has a task (or kStop)
// for it.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <set>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/util/clock.h"
#include "search/run_start.h"
#include "search/search_plan.h"
#include "search/search_record.h"
#include "search/task_queue.h"
#include "search/transport.h"

namespace disco {

class Coordinator {
 public:
  // The output directory `out_dir` is prepared (search/run_manifest.h); `resumed`: it
  // holds an earlier run of the same command, whose final starts are skipped.
  // `share_incumbent`: search.share_incumbent (false: the deterministic mode).
  // `guess_class`: the hand-out order defers starts of classes already tried (TaskQueue).
  Coordinator(const SearchPlan& plan, const std::string& out_dir, std::uint64_t seed,
              double time_limit, bool resumed, bool share_incumbent,
              const GuessClassFunction& guess_class = {}, const ScreenSettings& screen = {});

  // The next task for `rank`, or none: none now (see await_work), all handed out, a time
  // limit, or an interrupt.
  std::optional<Task> next(int rank);
  // After next() gave none: false when no task can come any more; else waits until an
  // outcome is recorded (at most 0.2 s) and returns true (ask next() again).
  bool await_work();
  // Records a start's outcome: its runs.jsonl line, the scene's best (and its solution
  // file, when `solution` is given and it is the best), best.json, the progress line.
  void record(StartOutcome o, const nlohmann::json* solution);

  // A worker's message (MessageKind::kResult from `rank`: "{}" for its first request, else
  // {"outcome": ..., "solution": ...}) recorded, and the reply: the next task, or kStop.
  struct Reply {
    MessageKind kind = MessageKind::kStop;
    std::string body;
    bool none = false;  // no reply now: the rank waits for refines (take_outbox answers it)
  };
  Reply on_result(int rank, const std::string& body);

  // Scene `scene`'s incumbent: its best certified J (T_f in s for objective time;
  // core/model/objective.h); +inf: none, or not shared.
  double incumbent(int scene);
  // A start still running found a certified J for scene `scene`.
  void progress(int scene, double value);
  // A worker's kProgress message: {"scene": index, "start": k, "value": J}.
  void on_progress(const std::string& body);
  // The messages to send now: kIncumbent {"scene": index, "value": J} to each worker rank
  // running a start of a scene whose incumbent improved since the last call; and to each
  // waiting rank its task (kTask), or kStop once no task can come.
  struct Outgoing {
    int to = 0;
    MessageKind kind = MessageKind::kIncumbent;
    std::string body;
  };
  std::vector<Outgoing> take_outbox();

  // At the end: best.json, with whether a time limit left tasks undone.
  void finish();
  std::string status_text();  // the live status line
  bool all_solved();

  // What this run kept, for the last message.
  struct Kept {
    int kept = 0;   // starts with a final outcome in runs.jsonl (this run and earlier ones)
    int lost = 0;   // starts cut short by an interrupt (their best so far is recorded)
    int total = 0;  // starts of the plan
    int cut = 0;    // this run's starts cut short (time limit or interrupt)
  };
  Kept kept();

 private:
  double seconds() const;
  std::string clock_locked() const;  // "elapsed HH:MM:SS ETA HH:MM:SS"
  int scene_index(const std::string& name) const;

  // Lowers scene s's incumbent to `value` if that is lower (and marks it for take_outbox()).
  void lower_incumbent(int s, double value);
  // Queues the early refines decided so far and the refines of every scene whose screens are
  // all closed (screening only).
  void advance_stages(double now);
  // Scene s's early refines decided since the last call, queued (screening only).
  void add_early_refines(int s);
  // The refine of start k of scene s: from its screened solution file (none, with a warning,
  // if that file cannot be read), or from its own guess with search.refine_from "start" or
  // when its screen has no certified point (or it was never screened: the time left).
  std::optional<Task> refine_task(int s, int k) const;
  // Whether start k of scene s has a recorded screen with a certified point.
  bool certified_screen(int s, int k) const;
  // Under a time limit with nothing else to hand out: queues the next refine of the scene with
  // the fewest refines so far (ties: the lower index) that may take one (TaskQueue::may_fill)
  // and has a start not yet refined: the next in time_left_order (search/screening.h): its
  // certified screens in refine_choice's ranking, then its starts without one, from their own
  // guess. False if there is none.
  bool add_fill_refine(double now);
  // Scene s's recorded screens as the refine choices rank them (with their classes).
  std::vector<Screened> ranked_screens(int s) const;
  std::optional<Task> next_locked(int rank);

  const SearchPlan& plan_;
  const bool share_;
  Clock::time_point t0_;
  std::mutex mutex_;
  SearchRecord record_;
  TaskQueue queue_;
  std::vector<double> incumbent_;  // per scene, J (+inf: none)
  std::vector<bool> improved_;     // per scene: incumbent lowered since take_outbox()
  ScreenSettings screen_;
  std::set<int> waiting_;          // worker ranks without a reply (waiting for refines)
  std::vector<std::set<int>> early_;  // per scene: the starts chosen for an early refine
  std::vector<std::set<int>> refines_;  // per scene: every start chosen for a refine (any kind)
  std::condition_variable recorded_;  // notified at every record()
};

}  // namespace disco
