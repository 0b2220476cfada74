// Rank 0's side of the search without MPI and without solves (search/task_queue.h,
// search/search_record.h, search/coordinator.h): the order and budgets tasks are handed out
// with, the message protocol, and that a start's error is recorded while the search goes on.
// Outcomes here are made up (the solves are tested elsewhere); only the bookkeeping is.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/scene_yaml.h"
#include "search/coordinator.h"
#include "search/search_plan.h"
#include "search/task_queue.h"

namespace disco {
namespace {

using json = nlohmann::json;

std::string config(const std::string& path) { return std::string(DISCO_SOURCE_DIR) + "/configs/" + path; }

SceneJob job(const std::string& scenario, int starts, double time_limit = 0.0, double start_limit = 0.0) {
  SceneJob j;
  j.scene = load_scene(config("scenarios/" + scenario + ".yaml"));
  j.starts = starts;
  j.time_limit = time_limit;
  j.start_time_limit = start_limit;
  return j;
}

std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("disco_coordinator_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "best");
  return dir.string();
}

TEST(TaskQueue, LargerScenesFirstEveryStartOnceAndDoneStartsSkipped) {
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 2), job("three_robots_contact", 3)};
  TaskQueue q(plan, 0.0, {{1, 1}});  // start 1 of the contact scene is done already
  std::vector<std::pair<int, int>> order;
  while (const auto t = q.next(0, 0.0)) order.push_back({t->scene, t->start});
  const std::vector<std::pair<int, int>> expected = {{1, 0}, {1, 2}, {0, 0}, {0, 1}};
  EXPECT_EQ(order, expected);
  EXPECT_EQ(q.total(), 5);
  EXPECT_EQ(q.running().size(), 4u);
  q.finished(1, 0);
  EXPECT_EQ(q.running().size(), 3u);
  q.finish();
  EXPECT_FALSE(q.time_limited()) << "every task was handed out";
}

TEST(TaskQueue, ABudgetIsTheSmallestLimitLeftAndSaysWhichSetIt) {
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 4, /*scene*/ 10.0, /*start*/ 4.0)};
  TaskQueue q(plan, /*search*/ 7.0, {});
  auto t = q.next(0, 0.0);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->budget, 4.0);
  EXPECT_EQ(t->source, BudgetSource::kStart);
  t = q.next(0, 5.0);  // search: 2 s left, scene: 5 s left, start: 4 s
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(t->budget, 2.0);
  EXPECT_EQ(t->source, BudgetSource::kSearch);
  EXPECT_DOUBLE_EQ(q.time_left(5.0), 2.0);
  EXPECT_FALSE(q.next(0, 7.5)) << "past the search's limit nothing is handed out";
  EXPECT_TRUE(q.time_limited()) << "tasks were left";
  // The JSON a worker receives gives the same task back.
  const Task back = Task::from_json(t->to_json());
  EXPECT_EQ(back.scene, t->scene);
  EXPECT_EQ(back.start, t->start);
  EXPECT_EQ(back.budget, t->budget);
  EXPECT_EQ(back.source, t->source);
}

TEST(TaskQueue, ASceneLimitCountsFromItsFirstHandOut) {
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 3, /*scene*/ 10.0)};
  TaskQueue q(plan, 0.0, {});
  ASSERT_TRUE(q.next(0, 100.0));  // the scene starts at 100 s
  const auto t = q.next(0, 104.0);
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(t->budget, 6.0);
  EXPECT_EQ(t->source, BudgetSource::kScene);
  EXPECT_FALSE(q.next(0, 110.5));
  EXPECT_TRUE(q.scene_time_limited(0));
  EXPECT_EQ(q.scene_started(0), 100.0);
}

// A made-up outcome of `task`: solved at `T_f`, or (NaN) an error.
json outcome_message(const SearchPlan& plan, const Task& task, double T_f) {
  StartOutcome o;
  o.scene = plan.scenes[task.scene].scene.name;
  o.start = task.start;
  o.seed = 1;
  o.rank = 1;
  o.seconds = 0.01;
  if (std::isnan(T_f)) {
    o.status = StartStatus::kError;
    o.detail = "internal check failed at somewhere.cpp:1: false (a made-up bug)";
  } else {
    o.status = StartStatus::kSolved;
    o.T_f = T_f;
    o.max_violation = o.max_complementarity = 1e-9;
  }
  return {{"outcome", o.to_json()}, {"solution", {{"T_f", T_f}}}};
}

TEST(Coordinator, AStartsErrorIsRecordedAndTheSearchGoesOnToTheEnd) {
  const SearchPlan plan = load_search_plan({config("benchmarks/smoke.yaml")}, 0, 1, {});
  const std::string dir = fresh_dir("errors");
  Coordinator c(plan, dir, 1, 0.0, false);
  // Worker 1 asks for work, then answers every task: errors for start 0 of each scene,
  // solved with T_f = 5 - start otherwise (start 2 the best), then gets "stop".
  Coordinator::Reply reply = c.on_result(1, "{}");
  int tasks = 0;
  while (reply.kind == MessageKind::kTask) {
    const Task t = Task::from_json(json::parse(reply.body));
    ++tasks;
    const double T_f = t.start == 0 ? std::nan("") : 5.0 - t.start;
    reply = c.on_result(1, outcome_message(plan, t, T_f).dump());
  }
  EXPECT_EQ(reply.kind, MessageKind::kStop);
  EXPECT_EQ(tasks, plan.total_starts());
  c.finish();
  std::ifstream runs(dir + "/runs.jsonl");
  int lines = 0, errors = 0;
  for (std::string line; std::getline(runs, line); ++lines)
    errors += json::parse(line)["status"] == "error";
  EXPECT_EQ(lines, plan.total_starts());
  EXPECT_EQ(errors, static_cast<int>(plan.scenes.size()));
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  for (const SceneJob& j : plan.scenes) {
    const json& s = best["scenes"][j.scene.name];
    EXPECT_EQ(s["starts_run"], j.starts) << j.scene.name;
    EXPECT_EQ(s["starts_solved"], j.starts - 1) << j.scene.name;
    EXPECT_EQ(s["start"], j.starts - 1) << j.scene.name;
    EXPECT_EQ(s["T_f"], 5.0 - (j.starts - 1)) << j.scene.name;
    const json file = json::parse(std::ifstream(dir + "/best/" + j.scene.name + ".json"));
    EXPECT_EQ(file["T_f"], s["T_f"]) << "best/SCENE.json holds the best start's solution";
  }
  EXPECT_EQ(best["starts_finished"], plan.total_starts());
  EXPECT_TRUE(c.all_solved());
}

TEST(Coordinator, TiesGoToTheLowerStartAndAResumeSkipsWhatIsFinal) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  const std::string dir = fresh_dir("ties");
  {
    Coordinator c(plan, dir, 1, 0.0, false);
    for (int k : {3, 1}) {  // two starts, equal T_f, the higher index first
      const auto t = c.next(0);
      ASSERT_TRUE(t);
      Task fake = *t;
      fake.start = k;
      c.record(StartOutcome::from_json(outcome_message(plan, fake, 2.5)["outcome"]), nullptr);
    }
    c.finish();
    const json best = json::parse(std::ifstream(dir + "/best.json"));
    EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 1);
  }
  // Resumed: starts 1 and 3 are final; 0 and 2 are handed out, nothing else.
  Coordinator again(plan, dir, 1, 0.0, true);
  std::vector<int> handed;
  while (const auto t = again.next(0)) handed.push_back(t->start);
  EXPECT_EQ(handed, (std::vector<int>{0, 2}));
}

}  // namespace
}  // namespace disco
