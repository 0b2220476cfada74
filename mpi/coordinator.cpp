#include "mpi/coordinator.h"

#include <fcntl.h>
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <condition_variable>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <thread>

#include "core/util/numbers.h"
#include "core/config/memory_limit.h"
#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/lower_bound.h"
#include "core/model/model_size.h"
#include "core/model/solution.h"
#include "core/util/errors.h"
#include "core/util/interrupt.h"
#include "search/run_start.h"
#include "search/run_manifest.h"
#include "search/search_plan.h"

namespace disco {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr int kTagWork = 1;  // worker -> rank 0: a result (or the first request)
constexpr int kTagTask = 2;  // rank 0 -> worker: a task
constexpr int kTagStop = 3;  // rank 0 -> worker: no more tasks

struct Task {
  int scene = 0, start = 0;
  double budget = 0.0;  // s; 0 = none
  BudgetSource source = BudgetSource::kNone;  // the limit that set the budget
};

// Whether a recorded outcome is final, so that --resume skips its start. A start cut short
// runs again, unless its own start_time_limit cut it and that limit is unchanged (running it
// again would only be cut again).
bool is_final(const StartOutcome& o, const SceneJob& job) {
  if (o.status == StartStatus::kInterrupted) return false;
  if (o.status == StartStatus::kTimeLimit)
    return o.budget_source == BudgetSource::kStart && o.budget == job.start_time_limit;
  return true;
}

// "solved T_f 2.294182", "time limit (search, 20 s): T_f 2.380710 so far",
// "interrupted: no point yet", "infeasible".
std::string outcome_words(const StartOutcome& o) {
  const std::string so_far =
      o.certified() ? fmt::format("T_f {:.6f} so far", o.T_f) : std::string("no point yet");
  switch (o.status) {
    case StartStatus::kSolved: return fmt::format("solved T_f {:.6f}", o.T_f);
    case StartStatus::kTimeLimit:
      return fmt::format("time limit ({}, {:.0f} s): {}", to_string(o.budget_source), o.budget, so_far);
    case StartStatus::kInterrupted: return "interrupted: " + so_far;
    default: return to_string(o.status);
  }
}

void send_string(const std::string& s, int dest, int tag) {
  MPI_Send(s.data(), static_cast<int>(s.size()), MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

std::string recv_string(int source, int tag, MPI_Status* status) {
  MPI_Status probe;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &probe);
  int n = 0;
  MPI_Get_count(&probe, MPI_CHAR, &n);
  std::string s(static_cast<std::size_t>(n), '\0');
  MPI_Recv(s.data(), n, MPI_CHAR, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, status);
  return s;
}

std::string clock_text(double s) {
  const int t = static_cast<int>(s + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02d:%02d:%02d", t / 3600, t / 60 % 60, t % 60);
  return buf;
}

// Rank 0's view of the search: the tasks still to hand out, and the files.
// Thread-safe: the coordinator thread and rank 0's own worker share it.
class Search {
 public:
  // The output directory is prepared (run_manifest.h); `resumed`: it holds an earlier run.
  Search(const SearchPlan& plan, const SearchOptions& options, bool resumed)
      : plan_(plan), options_(options), t0_(Clock::now()), best_(plan.scenes.size()) {
    const std::string runs = options.out + "/runs.jsonl";
    std::set<std::pair<int, int>> done;
    if (resumed) done = read_done(runs);
    // Larger scenes first (longest-processing-time order: fewer idle ranks at
    // the end); the order changes no result, only when each start runs.
    std::vector<int> order(plan.scenes.size());
    for (std::size_t s = 0; s < order.size(); ++s) order[s] = static_cast<int>(s);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return cost(plan.scenes[a].scene) > cost(plan.scenes[b].scene);
    });
    for (int s : order)
      for (int k = 0; k < plan.scenes[s].starts; ++k)
        if (!done.count({s, k})) pending_.push_back({s, k, 0.0});
    total_ = plan.total_starts();
    finished_ = total_ - static_cast<int>(pending_.size());
    runs_ = std::fopen(runs.c_str(), resumed ? "a" : "w");
    if (runs_ == nullptr) throw InputError(runs + ": cannot open for writing");
    write_best();
  }
  ~Search() {
    if (runs_ != nullptr) std::fclose(runs_);
  }

  // The next task, or none when all are handed out or the time limit passed.
  // A scene whose own time limit has passed (counted from the hand-out of its
  // first start) gets no more starts. A task's budget is the smallest of the
  // start's, the scene's and the search's remaining time.
  // `rank` will run it (for the live status line).
  std::optional<Task> next(int rank) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double elapsed = seconds();
    if (interrupt_requested()) return std::nullopt;
    if (options_.time_limit > 0 && elapsed >= options_.time_limit) {
      if (next_ < pending_.size()) time_limited_ = true;
      return std::nullopt;
    }
    while (next_ < pending_.size()) {
      Task t = pending_[next_++];
      const SceneJob& job = plan_.scenes[t.scene];
      Best& b = best_[t.scene];
      if (b.started_s < 0) b.started_s = elapsed;
      const double scene_left = job.time_limit > 0 ? job.time_limit - (elapsed - b.started_s) : 0.0;
      if (job.time_limit > 0 && scene_left <= 0) {
        b.time_limited = true;
        continue;
      }
      t.budget = job.start_time_limit;
      t.source = job.start_time_limit > 0 ? BudgetSource::kStart : BudgetSource::kNone;
      auto cap = [&](double left, BudgetSource source) {
        if (t.budget > 0 && t.budget <= left) return;
        t.budget = left;
        t.source = source;
      };
      if (job.time_limit > 0) cap(scene_left, BudgetSource::kScene);
      if (options_.time_limit > 0) cap(options_.time_limit - elapsed, BudgetSource::kSearch);
      running_[{t.scene, t.start}] = {rank, elapsed};
      return t;
    }
    return std::nullopt;
  }

  // Records a start's outcome: a line in runs.jsonl (also for a start cut short, with its
  // best so far), the scene's best (and its solution file), best.json, the progress line.
  void record(StartOutcome o, const json* solution) {
    std::lock_guard<std::mutex> lock(mutex_);
    o.finished_s = seconds();
    const std::string line = o.to_json().dump() + "\n";
    std::fputs(line.c_str(), runs_);
    std::fflush(runs_);
    ::fsync(fileno(runs_));  // a kill (or a crash) loses no finished start
    const int s = scene_index(o.scene);
    if (s >= 0) running_.erase({s, o.start});
    if (s >= 0 && is_final(o, plan_.scenes[s])) {
      ++finished_;
    } else {
      ++cut_short_;
    }
    if (o.status == StartStatus::kInterrupted) ++interrupted_;
    const bool best = update(s, o);
    if (best && solution != nullptr)
      write_json_file(options_.out + "/best/" + o.scene + ".json", *solution);
    write_best();
    spdlog::info("[{}/{}] {} start {} (rank {}): {} in {:.1f} s | best {} | {}", finished_,
                 total_, o.scene, o.start, o.rank, outcome_words(o), o.seconds,
                 best_summary(s), clock_locked());
  }

  // After an interrupt: what was kept and what was lost, for the last message.
  struct Kept {
    int kept = 0;   // starts with a final outcome in runs.jsonl (this run and earlier ones)
    int lost = 0;   // starts cut short by the interrupt (their best so far is recorded)
    int total = 0;  // starts of the plan
    int cut = 0;    // this run's starts cut short (time limit or interrupt)
  };
  Kept kept() {
    std::lock_guard<std::mutex> lock(mutex_);
    return {finished_, interrupted_, total_, cut_short_};
  }

  // The live status line, most important first (a terminal cuts the end):
  // starts done / total, elapsed and ETA, the best T_f per scene, the starts
  // running (scene #start, rank, seconds so far).
  std::string status_text() {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = seconds();
    std::string running;
    for (const auto& [task, r] : running_)
      running += fmt::format("{}{} #{} r{} {:.0f}s", running.empty() ? "" : ", ",
                             plan_.scenes[task.first].scene.name, task.second, r.rank,
                             now - r.handed_s);
    return fmt::format("[{}/{}] {} | best {} | running: {}", finished_, total_, clock_locked(),
                       best_summary(-1), running.empty() ? "-" : running);
  }

  // "elapsed HH:MM:SS ETA HH:MM:SS": the ETA from the mean time per start run
  // here, capped by the time limits left.
  std::string clock_locked() const {
    const double elapsed = seconds();
    const int ran_now = finished_ - resumed_;
    double eta = ran_now > 0 ? elapsed / ran_now * (total_ - finished_) : 0.0;
    eta = std::min(eta, time_left(elapsed));
    return "elapsed " + clock_text(elapsed) + " ETA " + (ran_now > 0 ? clock_text(eta) : "-");
  }

  // At most this long until the time limits stop the search: the search's own
  // limit, and every scene's limit left (scenes taken one after another).
  double time_left(double elapsed) const {
    double scenes = 0.0;
    for (size_t s = 0; s < plan_.scenes.size(); ++s) {
      const double limit = plan_.scenes[s].time_limit;
      if (!(limit > 0)) {
        scenes = kInf;
        break;
      }
      const Best& b = best_[s];
      scenes += b.started_s < 0 ? limit : std::max(0.0, limit - (elapsed - b.started_s));
    }
    const double search =
        options_.time_limit > 0 ? std::max(0.0, options_.time_limit - elapsed) : kInf;
    return std::min(scenes, search);
  }

  void finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (next_ < pending_.size()) time_limited_ = true;
    write_best();
  }

  bool all_solved() const {
    for (const auto& b : best_)
      if (b.start < 0) return false;
    return true;
  }
  const SearchPlan& plan() const { return plan_; }

 private:
  struct Best {
    int start = -1;
    double T_f = 0.0;
    StartOutcome outcome;
    int run = 0, solved = 0;  // starts with an outcome; with a certified point
    int cut_short = 0;        // of those, cut short (not final: --resume runs them again)
    double first_feasible_s = -1.0, best_s = -1.0;
    double started_s = -1.0;    // search time its first start was handed out
    double last_s = -1.0;       // search time its last start was recorded
    bool time_limited = false;  // its own time limit stopped it
  };

  double seconds() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }

  // Best T_f per scene (every scene when there are at most four, else the
  // scene `s`, or with s < 0 how many scenes are solved), for the progress lines.
  std::string best_summary(int s) const {
    auto one = [&](std::size_t k) {
      const Best& b = best_[k];
      return plan_.scenes[k].scene.name + " " +
             (b.start >= 0 ? fmt::format("{:.6f}", b.T_f) : std::string("-"));
    };
    if (best_.size() > 4) {
      if (s >= 0) return one(static_cast<std::size_t>(s));
      const auto solved = std::count_if(best_.begin(), best_.end(),
                                        [](const Best& b) { return b.start >= 0; });
      return fmt::format("{} of {} scenes solved", solved, best_.size());
    }
    std::string out;
    for (std::size_t k = 0; k < best_.size(); ++k) out += (k ? ", " : "") + one(k);
    return out;
  }

  // A rough cost of one start: unknowns per step times steps.
  static double cost(const Scene& s) {
    double per_step = 0;
    for (const auto& r : s.robots) per_step += 6 + r.force_dims + (r.mu > 0 ? r.friction_edges + 1 : 0);
    for (const auto& p : s.pairs) per_step += p.mode == PairMode::kContact ? 5 : 1;
    return per_step * s.steps;
  }

  int scene_index(const std::string& name) const {
    for (std::size_t s = 0; s < plan_.scenes.size(); ++s)
      if (plan_.scenes[s].scene.name == name) return static_cast<int>(s);
    return -1;
  }

  // Keeps `o` as its start's outcome (it replaces an earlier one: a start cut short and run
  // again), recounts the scene, and returns whether `o` is now the scene's best.
  bool update(int s, const StartOutcome& o) {
    if (s < 0) return false;
    Best& b = best_[s];
    b.last_s = seconds();
    outcomes_[{s, o.start}] = o;
    b.run = b.solved = b.cut_short = 0;
    const StartOutcome* least = nullptr;
    for (auto it = outcomes_.lower_bound({s, 0}); it != outcomes_.end() && it->first.first == s; ++it) {
      const StartOutcome& x = it->second;
      ++b.run;
      if (!is_final(x, plan_.scenes[s])) ++b.cut_short;
      if (!x.certified()) continue;
      ++b.solved;
      if (least == nullptr || x.T_f < least->T_f) least = &x;  // ties: the lower start (map order)
    }
    // Scene times count from the hand-out of the scene's first start, to the
    // moment a rank found the point: the start was handed out o.seconds ago
    // and found it its own time_to_first_feasible / time_to_best after that.
    const double handed = seconds() - o.seconds - std::max(0.0, b.started_s);
    if (o.certified()) {
      const double feasible = handed + std::max(0.0, o.time_to_first_feasible);
      if (b.first_feasible_s < 0 || feasible < b.first_feasible_s)
        b.first_feasible_s = std::max(0.0, feasible);
    }
    if (least == nullptr) return false;
    if (least->start != o.start && b.start == o.start)  // o replaced the best with a worse point
      spdlog::warn("{}: start {} ended above its earlier best, so start {} is now the best, but "
                   "best/{}.json still holds start {}'s earlier point", o.scene, o.start,
                   least->start, o.scene, o.start);
    b.start = least->start;
    b.T_f = least->T_f;
    b.outcome = *least;
    if (least->start != o.start || !o.certified()) return false;
    b.best_s = std::max(0.0, handed + std::max(0.0, o.time_to_best));
    return true;
  }

  // The starts runs.jsonl holds a final outcome for (--resume skips them). A start's later
  // line replaces its earlier ones; a start cut short keeps its best so far in the scene's
  // best until it runs again.
  std::set<std::pair<int, int>> read_done(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    int bad = 0;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      try {
        const StartOutcome o = StartOutcome::from_json(json::parse(line));
        const int s = scene_index(o.scene);
        if (s < 0 || o.start >= plan_.scenes[s].starts || o.seed != options_.seed) continue;
        update(s, o);
      } catch (const std::exception&) {
        ++bad;  // e.g. a line cut short by a kill
      }
    }
    std::set<std::pair<int, int>> done;
    int again = 0;
    for (const auto& [key, o] : outcomes_) {
      if (is_final(o, plan_.scenes[key.first])) {
        done.insert(key);
      } else {
        ++again;
      }
    }
    // Times of an earlier run are not comparable with this one's clock.
    for (auto& b : best_) b.first_feasible_s = b.best_s = b.start >= 0 ? 0.0 : -1.0;
    if (bad > 0) spdlog::warn("{}: skipped {} unreadable line(s)", path, bad);
    resumed_ = static_cast<int>(done.size());
    spdlog::info("resume: {} start(s) already in {}{}", resumed_, path,
                 again > 0 ? fmt::format("; {} cut short there run again", again) : "");
    return done;
  }

  void write_best() {
    json scenes = json::object();
    for (std::size_t s = 0; s < plan_.scenes.size(); ++s) {
      const Best& b = best_[s];
      json j = {{"starts", plan_.scenes[s].starts},
                {"starts_run", b.run},
                {"starts_solved", b.solved},
                {"starts_cut_short", b.cut_short},
                {"time_to_first_feasible_s", b.first_feasible_s >= 0 ? json(b.first_feasible_s) : json(nullptr)},
                {"time_to_best_s", b.best_s >= 0 ? json(b.best_s) : json(nullptr)},
                {"started_s", b.started_s >= 0 ? json(b.started_s) : json(nullptr)},
                {"wall_s", b.started_s >= 0 ? json(b.last_s - b.started_s) : json(nullptr)},
                {"time_limit_s", plan_.scenes[s].time_limit},
                {"time_limit_reached", b.time_limited}};
      const Scene& scene = plan_.scenes[s].scene;
      const auto lb = scene_lower_bound(scene), ref = scene_reference_time(scene);
      j["lower_bound"] = lb && std::isfinite(*lb) ? json(*lb) : json(nullptr);
      j["reference_time"] = ref ? json(*ref) : json(nullptr);
      if (b.start >= 0) {
        j["T_f"] = b.T_f;
        j["start"] = b.start;
        j["description"] = b.outcome.description;
        j["certificate"] = {{"max_violation", b.outcome.max_violation},
                            {"max_complementarity", b.outcome.max_complementarity}};
        j["solution"] = "best/" + plan_.scenes[s].scene.name + ".json";
      } else {
        j["T_f"] = nullptr;
      }
      scenes[plan_.scenes[s].scene.name] = j;
    }
    const json doc = {{"seed", options_.seed},
                      {"elapsed_s", seconds()},
                      {"starts_total", total_},
                      {"starts_finished", finished_},
                      {"interrupted", interrupt_requested()},
                      {"time_limit_s", options_.time_limit},
                      {"time_limit_reached", time_limited_},
                      {"scenes", scenes}};
    write_json_file(options_.out + "/best.json", doc);
  }

  const SearchPlan& plan_;
  const SearchOptions& options_;
  Clock::time_point t0_;
  std::mutex mutex_;
  std::vector<Task> pending_;
  std::size_t next_ = 0;
  int total_ = 0;
  int finished_ = 0;    // starts with a final outcome (is_final), this run's and earlier ones
  int resumed_ = 0;     // of those, read from an earlier run's runs.jsonl
  int cut_short_ = 0;   // this run's outcomes that are not final
  int interrupted_ = 0; // of those, cut short by an interrupt
  std::map<std::pair<int, int>, StartOutcome> outcomes_;  // (scene, start): its latest outcome
  bool time_limited_ = false;
  struct Running {
    int rank = 0;
    double handed_s = 0.0;  // search time of its hand-out
  };
  std::map<std::pair<int, int>, Running> running_;  // (scene, start) handed out, not recorded
  std::vector<Best> best_;
  std::FILE* runs_ = nullptr;
};

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

Task task_from_json(const json& j) {
  return {j.at("scene").get<int>(), j.at("start").get<int>(), j.at("budget").get<double>(),
          budget_source_from_string(j.at("source").get<std::string>())};
}
json task_json(const Task& t) {
  return {{"scene", t.scene}, {"start", t.start}, {"budget", t.budget}, {"source", to_string(t.source)}};
}

void worker_loop(const Context& c) {
  send_string("{}", 0, kTagWork);  // the first request
  while (true) {
    MPI_Status st;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    const std::string msg = recv_string(0, st.MPI_TAG, &st);
    if (st.MPI_TAG == kTagStop) return;
    json solution;
    const StartOutcome o = run_task(c, task_from_json(json::parse(msg)), &solution);
    json reply = {{"outcome", o.to_json()}};
    if (o.certified()) reply["solution"] = solution;
    send_string(reply.dump(), 0, kTagWork);
  }
}

void coordinator_loop(Search& search, int workers) {
  int active = workers;
  while (active > 0) {
    // Poll rather than block: a blocking probe spins a core in Open MPI,
    // and that core is rank 0's own worker's. Solves take seconds; 2 ms of
    // latency costs nothing.
    int ready = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagWork, MPI_COMM_WORLD, &ready, &st);
    if (!ready) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const json msg = json::parse(recv_string(st.MPI_SOURCE, kTagWork, &st));
    if (msg.contains("outcome")) {
      const StartOutcome o = StartOutcome::from_json(msg["outcome"]);
      search.record(o, msg.contains("solution") ? &msg["solution"] : nullptr);
    }
    if (const auto t = search.next(st.MPI_SOURCE)) {
      send_string(task_json(*t).dump(), st.MPI_SOURCE, kTagTask);
    } else {
      send_string("", st.MPI_SOURCE, kTagStop);
      --active;
    }
  }
}

}  // namespace

int run_search(const SearchOptions& o) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  Context c;
  c.rank = rank;
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
  MPI_Comm host;
  int host_ranks = 1;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &host_ranks);
  MPI_Comm_free(&host);
  for (const SceneJob& job : c.plan.scenes)
    check_model_size(job.scene, model_options(c.settings).adaptive, memory_limit(c.settings),
                     host_ranks);

  if (rank != 0) {
    worker_loop(c);
    return 0;
  }
  spdlog::info("search: {} scene(s), {} start(s), seed {}, {} rank(s){}", c.plan.scenes.size(),
               c.plan.total_starts(), o.seed, size,
               o.time_limit > 0 ? fmt::format(", time limit {:.0f} s", o.time_limit) : "");
  const json manifest = search_manifest(
      c.plan, c.settings, {o.configs, o.sets, o.seed, o.starts, o.time_limit, o.resume});
  const int earlier = prepare_out_dir(
      o.out, o.resume ? OutDirMode::kResume : o.force ? OutDirMode::kForce : OutDirMode::kFresh,
      manifest);
  if (o.resume && earlier == 0) spdlog::info("resume: {} holds no run yet; starting afresh", o.out);
  Search search(c.plan, o, earlier > 0);
  std::thread coordinator;
  if (size > 1) coordinator = std::thread([&] { coordinator_loop(search, size - 1); });
  // The live line: refreshed every second by a thread that only reads the
  // search's state and calls on_status (no MPI, no solver).
  std::mutex tick_mutex;
  std::condition_variable tick;
  bool done = false;
  std::thread ticker;
  if (o.on_status) {
    ticker = std::thread([&] {
      std::unique_lock<std::mutex> lock(tick_mutex);
      while (!tick.wait_for(lock, std::chrono::seconds(1), [&] { return done; }))
        o.on_status(search.status_text());
      o.on_status("");
    });
  }
  while (const auto t = search.next(0)) {  // rank 0 works too
    json solution;
    const StartOutcome out = run_task(c, *t, &solution);
    search.record(out, out.certified() ? &solution : nullptr);
  }
  if (coordinator.joinable()) coordinator.join();
  if (ticker.joinable()) {
    {
      std::lock_guard<std::mutex> lock(tick_mutex);
      done = true;
    }
    tick.notify_one();
    ticker.join();
  }
  search.finish();
  if (interrupt_requested()) {
    const auto k = search.kept();
    const int signal = interrupt_signal();
    spdlog::warn("interrupted{}: {} of {} starts kept in {}/runs.jsonl, {} lost (cut short; "
                 "their best so far is in best.json); continue with --resume",
                 signal == SIGINT ? " (SIGINT)" : signal == SIGTERM ? " (SIGTERM)" : "", k.kept,
                 k.total, o.out, k.lost);
    return 128 + (signal > 0 ? signal : SIGINT);
  }
  if (const auto k = search.kept(); k.cut > 0)
    spdlog::info("time limit: {} start(s) cut short (recorded with their best so far); --resume "
                 "runs them again", k.cut);
  spdlog::info("wrote {}/runs.jsonl, {}/best.json; an HTML report: scripts/report {}", o.out,
               o.out, o.out);
  return search.all_solved() ? 0 : 3;
}

}  // namespace disco
