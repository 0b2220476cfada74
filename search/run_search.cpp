#include "search/run_search.h"

#include <spdlog/spdlog.h>

#include <condition_variable>
#include <csignal>
#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/model_size.h"
#include "core/model/solution.h"
#include "core/util/interrupt.h"
#include "search/coordinator.h"
#include "search/run_manifest.h"
#include "search/run_start.h"
#include "search/search_plan.h"
#include "search/start.h"

namespace disco {
namespace {

using json = nlohmann::json;

// Everything every rank needs to run a task.
struct Context {
  Settings settings;
  std::vector<std::string> sets;  // --set, as given (for the solutions' provenance)
  SearchPlan plan;
  ReductionSettings schedule;
  ElasticSettings elastic;
  std::uint64_t seed = 1;
  int rank = 0;
};

StartOutcome run_task(const Context& c, const Task& t, json* solution) {
  const Scene& scene = c.plan.scenes[t.scene].scene;
  const StartSpec spec = make_start(scene, c.seed, t.start, c.schedule, c.elastic);
  // --verbose: every elastic-mode solve of every start, on the rank that runs it.
  SolveCallback on_solve;
  if (spdlog::should_log(spdlog::level::debug)) {
    on_solve = [&, count = 0](const SolveRecord& r) mutable {
      spdlog::debug("  {} start {}: {}", scene.name, t.start, solve_log_line(++count, r));
    };
  }
  StartOutcome o = run_start(scene, c.settings, spec, t.budget, t.source, solution, on_solve);
  if (solution != nullptr && !solution->is_null())
    (*solution)["provenance"] = provenance_json(
        {"search", scene.source, c.plan.scenes[t.scene].overrides, c.sets, c.seed, t.start},
        c.settings);
  o.rank = c.rank;
  spdlog::debug("  {} start {}: {}", scene.name, t.start, o.stopped);
  return o;
}

// A worker (rank >= 1): asks rank 0 for work, runs each task it gets and sends back its
// outcome (with the solution file when certified), until rank 0 says stop.
void worker_loop(const Context& c, Transport& transport) {
  transport.send(0, MessageKind::kResult, "{}");  // the first request
  while (true) {
    const Message msg = transport.receive();
    if (msg.kind == MessageKind::kStop) return;
    json solution;
    const StartOutcome o = run_task(c, Task::from_json(json::parse(msg.body)), &solution);
    json reply = {{"outcome", o.to_json()}};
    if (o.certified()) reply["solution"] = solution;
    transport.send(0, MessageKind::kResult, reply.dump());
  }
}

// Rank 0's coordinator thread: answers every worker until each has been told to stop.
void coordinator_loop(Coordinator& coordinator, Transport& transport) {
  int active = transport.size() - 1;
  while (active > 0) {
    // Poll rather than block: a blocking probe spins a core in Open MPI,
    // and that core is rank 0's own worker's. Solves take seconds; 2 ms of
    // latency costs nothing.
    const auto msg = transport.poll();
    if (!msg) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const Coordinator::Reply reply = coordinator.on_result(msg->source, msg->body);
    transport.send(msg->source, reply.kind, reply.body);
    if (reply.kind == MessageKind::kStop) --active;
  }
}

}  // namespace

int run_search(const SearchOptions& o, Transport& transport) {
  Context c;
  c.rank = transport.rank();
  c.seed = o.seed;
  c.sets = o.sets;
  std::vector<std::string> scene_sets, settings_sets;
  split_overrides(o.sets, scene_sets, settings_sets);
  c.settings = Settings::load(o.settings);
  for (const auto& s : settings_sets) c.settings.apply_override(s);
  c.schedule = reduction_settings(c.settings);
  c.elastic = elastic_settings(c.settings);
  IpoptSolver check(ipopt_options(c.settings));  // bad Ipopt options fail here, on every rank
  c.plan = load_search_plan(o.configs, o.starts, 1, scene_sets);
  // Every scene's model must fit model.memory_limit, shared by this machine's ranks (each
  // solves one start at a time): refused here, on every rank, before any start runs.
  for (const SceneJob& job : c.plan.scenes)
    check_model_size(job.scene, model_options(c.settings).adaptive, memory_limit(c.settings),
                     transport.ranks_on_this_host());

  if (c.rank != 0) {
    worker_loop(c, transport);
    return 0;
  }
  spdlog::info("search: {} scene(s), {} start(s), seed {}, {} rank(s){}", c.plan.scenes.size(),
               c.plan.total_starts(), o.seed, transport.size(),
               o.time_limit > 0 ? fmt::format(", time limit {:.0f} s", o.time_limit) : "");
  const json manifest = search_manifest(
      c.plan, c.settings, {o.configs, o.sets, o.seed, o.starts, o.time_limit, o.resume});
  const int earlier = prepare_out_dir(
      o.out, o.resume ? OutDirMode::kResume : o.force ? OutDirMode::kForce : OutDirMode::kFresh,
      manifest);
  if (o.resume && earlier == 0) spdlog::info("resume: {} holds no run yet; starting afresh", o.out);
  Coordinator coordinator(c.plan, o.out, o.seed, o.time_limit, earlier > 0);
  std::thread answering;
  if (transport.size() > 1) answering = std::thread([&] { coordinator_loop(coordinator, transport); });
  // The live line: refreshed every second by a thread that only reads the
  // search's state and calls on_status (no transport, no solver).
  std::mutex tick_mutex;
  std::condition_variable tick;
  bool done = false;
  std::thread ticker;
  if (o.on_status) {
    ticker = std::thread([&] {
      std::unique_lock<std::mutex> lock(tick_mutex);
      while (!tick.wait_for(lock, std::chrono::seconds(1), [&] { return done; }))
        o.on_status(coordinator.status_text());
      o.on_status("");
    });
  }
  while (const auto t = coordinator.next(0)) {  // rank 0 works too
    json solution;
    const StartOutcome out = run_task(c, *t, &solution);
    coordinator.record(out, out.certified() ? &solution : nullptr);
  }
  if (answering.joinable()) answering.join();
  if (ticker.joinable()) {
    {
      std::lock_guard<std::mutex> lock(tick_mutex);
      done = true;
    }
    tick.notify_one();
    ticker.join();
  }
  coordinator.finish();
  if (interrupt_requested()) {
    const auto k = coordinator.kept();
    const int signal = interrupt_signal();
    spdlog::warn("interrupted{}: {} of {} starts kept in {}/runs.jsonl, {} lost (cut short; "
                 "their best so far is in best.json); continue with --resume",
                 signal == SIGINT ? " (SIGINT)" : signal == SIGTERM ? " (SIGTERM)" : "", k.kept,
                 k.total, o.out, k.lost);
    return 128 + (signal > 0 ? signal : SIGINT);
  }
  if (const auto k = coordinator.kept(); k.cut > 0)
    spdlog::info("time limit: {} start(s) cut short (recorded with their best so far); --resume "
                 "runs them again", k.cut);
  spdlog::info("wrote {}/runs.jsonl, {}/best.json; an HTML report: scripts/report {}", o.out,
               o.out, o.out);
  return coordinator.all_solved() ? 0 : 3;
}

}  // namespace disco
