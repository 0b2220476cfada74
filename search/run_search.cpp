#include "search/run_search.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <condition_variable>
#include <csignal>
#include <chrono>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/model_size.h"
#include "core/model/solution.h"
#include "core/util/check.h"
#include "core/util/clock.h"
#include "core/util/interrupt.h"
#include "core/util/numbers.h"
#include "search/coordinator.h"
#include "search/guess.h"
#include "search/homotopy.h"
#include "search/run_manifest.h"
#include "search/run_start.h"
#include "search/screening.h"
#include "search/search_plan.h"
#include "search/start.h"
#include "search/trajectory.h"

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
  bool share = false;  // search.share_incumbent (false: --deterministic)
  ScreenSettings screen;  // search.screen_fraction, ... (search/screening.h)
};

// How a start running on this rank meets the shared incumbent (search/coordinator.h):
// `incumbent` gives its scene's, `found` passes on a new best of its own. Both are called
// between solves only. Unset when the incumbent is not shared.
struct IncumbentLink {
  IncumbentFunction incumbent;
  std::function<void(double T_f)> found;
};

StartOutcome run_task(const Context& c, const Task& t, json* solution, const IncumbentLink& link) {
  const SceneJob& job = c.plan.scenes[t.scene];
  // A screen runs on the scene at fewer steps (search/screening.h).
  Scene screened_scene;
  if (t.stage == Stage::kScreen) {
    screened_scene = job.scene;
    screened_scene.steps = screen_steps(job.scene, c.screen.fraction);
  }
  const Scene& scene = t.stage == Stage::kScreen ? screened_scene : job.scene;
  StartSpec spec = make_start(scene, c.seed, t.start, c.schedule, c.elastic);
  const bool guessed = t.start == 0 && !job.guess.empty();
  if (guessed) {
    Trajectory guess = job.guess;
    guess.paths = resample(guess.paths, scene.steps);
    spec = with_guess(spec, guess);
  }
  StartSpec from_screen;
  const bool screened_answer = t.stage == Stage::kRefine && !t.guess.is_null();
  if (screened_answer) {  // a refine from its screened answer
    // Its minimisations, from the screen and (search.refine_from both) from the start's own
    // guess, run search.refine_minimize_weak (search/screening.h).
    spec.schedule.weak_homotopy = c.screen.refine_weak_homotopy;
    try {
      from_screen = with_guess(spec, trajectory_from_solution(t.guess, scene,
                                                              fmt::format("screened start {}", t.start)));
    } catch (const std::exception& e) {  // an error outcome, as run_start makes them
      StartOutcome o;
      o.scene = scene.name;
      o.start = t.start;
      o.seed = c.seed;
      o.stage = t.stage;
      o.status = StartStatus::kError;
      o.detail = e.what();
      o.rank = c.rank;
      return o;
    }
  }
  // --verbose: every elastic-mode solve of every start, on the rank that runs it.
  const bool verbose = spdlog::should_log(spdlog::level::debug);
  SolveCallback on_solve;
  if (verbose || link.found) {
    on_solve = [&, count = 0](const SolveRecord& r) mutable {
      if (verbose) spdlog::debug("  {} start {}: {}", scene.name, t.start, solve_log_line(++count, r, scene.objective.kind));
      if (link.found && r.improved) link.found(r.value);
    };
  }
  const auto run = [&](const StartSpec& s, double budget, json* sol) {
    StartOutcome o = run_start(scene, c.settings, s, budget, t.source, sol, on_solve, link.incumbent);
    if (sol != nullptr && !sol->is_null())
      (*sol)["provenance"] = provenance_json(
          {"search", scene.source, job.overrides, c.sets, c.seed, t.start,
           guessed ? job.guess.source : std::string()},
          c.settings);
    return o;
  };
  StartOutcome o;
  if (!screened_answer) {
    o = run(spec, t.budget, solution);
  } else if (c.screen.refine_from != RefineFrom::kBoth) {
    o = run(from_screen, t.budget, solution);
  } else {  // from the screen, then from the start in the budget left: the better one
    json first_solution, second_solution;
    o = run(from_screen, t.budget, solution != nullptr ? &first_solution : nullptr);
    const double left = t.budget > 0 ? t.budget - o.seconds : 0.0;
    if (!o.cut_short() && !interrupt_requested() && (t.budget <= 0 || left > 0)) {
      const StartOutcome second = run(spec, left, solution != nullptr ? &second_solution : nullptr);
      const bool second_kept = keeps_second(o, second);
      o = better_of(o, second);
      if (solution != nullptr) *solution = std::move(second_kept ? second_solution : first_solution);
    } else {
      if (!o.cut_short()) o.status = interrupt_requested() ? StartStatus::kInterrupted : StartStatus::kTimeLimit;
      if (solution != nullptr) *solution = std::move(first_solution);
    }
  }
  o.rank = c.rank;
  o.stage = t.stage;
  spdlog::debug("  {} start {}: {}", scene.name, t.start, o.stopped);
  return o;
}

// A worker (rank >= 1): asks rank 0 for work, runs each task it gets and sends back its
// outcome (with the solution file when certified), until rank 0 says stop.
void worker_loop(const Context& c, Transport& transport) {
  transport.send(0, MessageKind::kResult, "{}");  // the first request
  std::vector<double> incumbent(c.plan.scenes.size(), kInf);  // what rank 0 said, per scene
  auto take = [&](const Message& m) {
    DISCO_CHECK(m.kind == MessageKind::kIncumbent, "rank 0 sends a running start incumbents only");
    const json j = json::parse(m.body);
    const auto scene = j.at("scene").get<std::size_t>();
    double& x = incumbent.at(scene);
    x = std::min(x, j.at("value").get<double>());
    spdlog::debug("rank {}: incumbent of {} now {:.6f} (from rank 0)", c.rank,
                  c.plan.scenes.at(scene).scene.name, x);
  };
  while (true) {
    const Message msg = transport.receive();
    if (msg.kind == MessageKind::kIncumbent) {  // sent while the last start was running
      take(msg);
      continue;
    }
    if (msg.kind == MessageKind::kStop) return;
    const Task task = Task::from_json(json::parse(msg.body));
    IncumbentLink link;
    if (c.share && task.stage != Stage::kScreen) {  // a screen's T_f is a coarser model's
      incumbent[task.scene] = std::min(incumbent[task.scene], task.incumbent);
      link.incumbent = [&] {
        while (const auto m = transport.poll()) take(*m);
        return incumbent[task.scene];
      };
      link.found = [&](double value) {
        transport.send(0, MessageKind::kProgress,
                       json{{"scene", task.scene}, {"start", task.start}, {"value", value}}.dump());
      };
    }
    json solution;
    const StartOutcome o = run_task(c, task, &solution, link);
    json reply = {{"outcome", o.to_json()}};
    if (o.certified()) reply["solution"] = solution;
    transport.send(0, MessageKind::kResult, reply.dump());
  }
}

}  // namespace

void serve_workers(Coordinator& coordinator, Transport& transport) {
  int active = transport.size() - 1;
  while (active > 0) {
    // Poll rather than block: a blocking probe spins a core in Open MPI,
    // and that core is rank 0's own worker's. Solves take seconds; 2 ms of
    // latency costs nothing.
    for (const auto& m : coordinator.take_outbox()) {  // also the waiting ranks' tasks or stops
      transport.send(m.to, m.kind, m.body);
      if (m.kind == MessageKind::kStop) --active;
    }
    const auto msg = transport.poll();
    if (!msg) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    if (msg->kind == MessageKind::kProgress) {
      coordinator.on_progress(msg->body);
      continue;
    }
    const Coordinator::Reply reply = coordinator.on_result(msg->source, msg->body);
    if (reply.none) continue;  // it waits for refines: take_outbox() answers it
    transport.send(msg->source, reply.kind, reply.body);
    if (reply.kind == MessageKind::kStop) --active;
  }
}

int run_search(const SearchOptions& o, Transport& transport) {
  Context c;
  c.rank = transport.rank();
  c.seed = o.seed;
  c.sets = o.sets;
  std::vector<std::string> scene_sets, settings_sets;
  split_overrides(o.sets, scene_sets, settings_sets);
  c.settings = Settings::load(o.settings);
  for (const auto& s : settings_sets) c.settings.apply_override(s);
  if (o.deterministic) c.settings.apply_override(std::string(kShareIncumbentKey) + "=false");
  c.share = share_incumbent(c.settings);
  c.screen = screen_settings(c.settings);
  c.schedule = reduction_settings(c.settings);
  c.elastic = elastic_settings(c.settings);
  // Every time of the search (limits, budgets, the seconds recorded) is read on this clock.
  const std::unique_ptr<TimeSource> time_source = make_time_source(clock_settings(c.settings));
  const ScopedTimeSource clock(*time_source);
  IpoptSolver check(ipopt_settings(c.settings));  // bad Ipopt options fail here, on every rank
  c.plan = load_search_plan(o.configs, o.starts, 1, scene_sets);
  attach_guesses(c.plan, o.guesses);
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
  GuessClassFunction guess_class;
  if (defer_seen_classes(c.settings)) {
    guess_class = [&c](int s, int k) {
      const SceneJob& job = c.plan.scenes[s];
      StartSpec spec = make_start(job.scene, c.seed, k, c.schedule, c.elastic);
      if (k == 0 && !job.guess.empty()) spec = with_guess(spec, job.guess);
      const HomotopyClass h = homotopy_class(job.scene, guess_paths(job.scene, spec));
      return h.decided() ? h.key(job.scene) : std::string();
    };
  }
  Coordinator coordinator(c.plan, o.out, o.seed, o.time_limit, earlier > 0, c.share, guess_class,
                          c.screen);
  std::thread answering;
  if (transport.size() > 1) answering = std::thread([&] { serve_workers(coordinator, transport); });
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
  while (true) {  // rank 0 works too
    const auto t = coordinator.next(0);
    if (!t) {
      if (coordinator.await_work()) continue;  // refines may still come
      break;
    }
    IncumbentLink link;
    if (c.share && t->stage != Stage::kScreen) {
      link.incumbent = [&] { return coordinator.incumbent(t->scene); };
      link.found = [&](double T_f) { coordinator.progress(t->scene, T_f); };
    }
    json solution;
    const StartOutcome out = run_task(c, *t, &solution, link);
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
    spdlog::info("time limit: {} run(s) not final (cut short, or a refine whose screen the limit cut "
                 "short or left out; recorded with their best so far); --resume runs them again",
                 k.cut);
  spdlog::info("wrote {}/runs.jsonl, {}/best.json; an HTML report: scripts/report {}", o.out,
               o.out, o.out);
  return coordinator.all_solved() ? 0 : 3;
}

}  // namespace disco
