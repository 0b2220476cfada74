// The search's rank-0 side at scale, without MPI: serve_workers (search/run_search.h) and the
// Coordinator (search/coordinator.h) driven by a simulated transport of 1,024 workers. Each
// worker is a sequence of events on a simulated clock: its first request, then for every task
// it is handed a progress report half-way (a new best of its start) and its outcome at the
// end, after a made-up duration. Checked: every start is handed out and recorded exactly once;
// no worker is told to stop while a task is left; every incumbent message goes to a worker
// running a start of that scene, with the best reported so far; the incumbent reaches the
// running starts. The coordinator's wall time per task (its real overhead: recording, fsync
// of runs.jsonl, best.json) is printed.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <queue>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/util/clock.h"
#include "search/coordinator.h"
#include "search/run_search.h"
#include "search/run_start.h"
#include "search/search_plan.h"
#include "search/task_queue.h"
#include "search/transport.h"

namespace disco {
namespace {

using json = nlohmann::json;

// A deterministic number in [0, 1) for (a, b): splitmix64.
double unit(std::uint64_t a, std::uint64_t b) {
  std::uint64_t z = a * 0x9E3779B97F4A7C15ULL + b + 0x632BE59BD9B4E019ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

class SimTransport : public Transport {
 public:
  SimTransport(const SearchPlan& plan, int workers) : plan_(plan), workers_(workers), running_(workers + 1) {
    for (int w = 1; w <= workers; ++w) push(1e-3 * w, w, MessageKind::kResult, "{}");
  }
  int rank() const override { return 0; }
  int size() const override { return workers_ + 1; }
  int ranks_on_this_host() const override { return 1; }

  void send(int to, MessageKind kind, const std::string& body) override {
    ASSERT_TRUE(to >= 1 && to <= workers_) << to;
    switch (kind) {
      case MessageKind::kTask: {
        const Task t = Task::from_json(json::parse(body));
        ASSERT_FALSE(running_[to]) << "worker " << to << " was handed a task while running one";
        running_[to] = t;
        ++handed_[{t.scene, t.start}];
        ++tasks_;
        const double d = 1.0 + 9.0 * unit(t.scene, t.start);  // 1-10 s of simulated solving
        // The start's best: 5-15 s, reported half-way 1 % higher, then final.
        const double T_f = 5.0 + 10.0 * unit(t.start, t.scene + 17);
        push(now_ + 0.5 * d, to, MessageKind::kProgress,
             json{{"scene", t.scene}, {"start", t.start}, {"value", 1.01 * T_f}}.dump());
        StartOutcome o;
        o.scene = plan_.scenes[t.scene].scene.name;
        o.start = t.start;
        o.seed = 1;
        o.status = StartStatus::kSolved;
        o.T_f = o.value = T_f;
        o.max_violation = o.max_complementarity = 1e-9;
        o.seconds = d;
        o.rank = to;
        push(now_ + d, to, MessageKind::kResult, json{{"outcome", o.to_json()}}.dump());
        break;
      }
      case MessageKind::kIncumbent: {
        const json j = json::parse(body);
        ++incumbent_messages_;
        ASSERT_TRUE(running_[to]) << "an incumbent for worker " << to << ", which runs nothing";
        EXPECT_EQ(j["scene"].get<int>(), running_[to]->scene);
        EXPECT_EQ(j["value"].get<double>(), reported_.at(j["scene"].get<int>()))
            << "the best reported so far";
        if (j["value"].get<double>() < 1.01 * 5.0 + 1e-9) ++told_best_;
        break;
      }
      case MessageKind::kStop:
        ASSERT_FALSE(running_[to]);
        EXPECT_EQ(tasks_, plan_.total_starts()) << "worker " << to << " stopped with tasks left";
        ++stopped_;
        break;
      default: ADD_FAILURE() << "rank 0 sends tasks, stops and incumbents only";
    }
  }

  std::optional<Message> poll() override {
    if (events_.empty()) throw std::runtime_error("the simulation ran dry with workers active");
    const Event e = events_.top();
    events_.pop();
    now_ = e.t;
    if (e.kind == MessageKind::kResult && running_[e.rank]) running_[e.rank].reset();
    if (e.kind != MessageKind::kResult || e.body != "{}") {  // a reported point
      const json j = json::parse(e.body);
      const int s = e.kind == MessageKind::kProgress
                        ? j["scene"].get<int>()
                        : scene_index(j["outcome"]["scene"].get<std::string>());
      const double T_f = e.kind == MessageKind::kProgress ? j["value"].get<double>()
                                                          : j["outcome"]["T_f"].get<double>();
      if (!reported_.count(s) || T_f < reported_[s]) reported_[s] = T_f;
    }
    return Message{e.kind, e.rank, e.body};
  }
  Message receive() override { throw std::logic_error("rank 0 never blocks on a receive"); }

  int tasks() const { return tasks_; }
  int stopped() const { return stopped_; }
  int incumbent_messages() const { return incumbent_messages_; }
  int told_best() const { return told_best_; }
  const std::map<std::pair<int, int>, int>& handed() const { return handed_; }

 private:
  struct Event {
    double t;
    long seq;
    int rank;
    MessageKind kind;
    std::string body;
    bool operator>(const Event& o) const { return t != o.t ? t > o.t : seq > o.seq; }
  };
  void push(double t, int rank, MessageKind kind, std::string body) {
    events_.push({t, seq_++, rank, kind, std::move(body)});
  }
  int scene_index(const std::string& name) const {
    for (std::size_t s = 0; s < plan_.scenes.size(); ++s)
      if (plan_.scenes[s].scene.name == name) return static_cast<int>(s);
    return -1;
  }

  const SearchPlan& plan_;
  int workers_;
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> events_;
  long seq_ = 0;
  double now_ = 0.0;
  std::vector<std::optional<Task>> running_;  // per worker rank
  std::map<std::pair<int, int>, int> handed_;
  std::map<int, double> reported_;  // per scene: the least T_f a worker reported
  int tasks_ = 0, stopped_ = 0, incumbent_messages_ = 0, told_best_ = 0;
};

TEST(CoordinatorSimulation, AThousandWorkersEveryStartOnceNoStarvationIncumbentsDelivered) {
  constexpr int kWorkers = 1024;
  const SearchPlan plan = load_search_plan(
      {std::string(DISCO_SOURCE_DIR) + "/configs/benchmarks/smoke.yaml"}, 1536, 1, {});
  ASSERT_EQ(plan.total_starts(), 3072);
  const auto dir = std::filesystem::temp_directory_path() / "disco_coordinator_simulation";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "best");
  Coordinator coordinator(plan, dir.string(), 1, 0.0, false, true);
  SimTransport sim(plan, kWorkers);

  const Stopwatch stopwatch;  // the machine's time, printed only
  serve_workers(coordinator, sim);
  const double wall = stopwatch.seconds();
  coordinator.finish();
  std::printf("coordinator: %d tasks, %d workers, %.3f s of wall time: %.1f us per task "
              "(recording, runs.jsonl fsync, best.json); %d incumbent messages\n",
              sim.tasks(), kWorkers, wall, 1e6 * wall / sim.tasks(), sim.incumbent_messages());

  EXPECT_EQ(sim.tasks(), plan.total_starts());
  EXPECT_EQ(sim.stopped(), kWorkers) << "every worker told to stop once";
  EXPECT_EQ(static_cast<int>(sim.handed().size()), plan.total_starts());
  for (const auto& [task, n] : sim.handed()) EXPECT_EQ(n, 1) << task.first << "/" << task.second;
  std::ifstream runs(dir / "runs.jsonl");
  std::set<std::pair<std::string, int>> recorded;
  int lines = 0;
  for (std::string line; std::getline(runs, line); ++lines) {
    const json j = json::parse(line);
    recorded.insert({j["scene"].get<std::string>(), j["start"].get<int>()});
  }
  EXPECT_EQ(lines, plan.total_starts());
  EXPECT_EQ(static_cast<int>(recorded.size()), plan.total_starts()) << "each start recorded once";
  EXPECT_GT(sim.incumbent_messages(), kWorkers) << "improvements reached the running starts";
  EXPECT_GT(sim.told_best(), 0) << "the scenes' best points were passed on";
  const json best = json::parse(std::ifstream(dir / "best.json"));
  EXPECT_EQ(best["starts_finished"], plan.total_starts());
  EXPECT_EQ(best["mode"], "shared");
}

}  // namespace
}  // namespace disco
