// Rank 0's side of the search without MPI and without solves (search/task_queue.h,
// search/search_record.h, search/coordinator.h): the order and budgets tasks are handed out
// with, the message protocol, and that a start's error is recorded while the search goes on.
// Outcomes here are made up (the solves are tested elsewhere); only the bookkeeping is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/scene_yaml.h"
#include "core/util/numbers.h"
#include "search/coordinator.h"
#include "search/search_plan.h"
#include "search/search_record.h"
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

TEST(TaskQueue, AStartCutByALimitMeansThatLimitWasReachedThoughEveryTaskWasHandedOut) {
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 1, /*scene*/ 10.0), job("two_robots_swap_avoid", 1)};
  TaskQueue q(plan, /*search*/ 20.0, {});
  const auto a = q.next(0, 0.0), b = q.next(1, 0.0);
  ASSERT_TRUE(a && b);
  EXPECT_FALSE(q.next(0, 1.0)) << "every task is handed out";
  // The scene's start ends on its own; the other start is cut by the search's limit.
  q.finished(a->scene, a->start, BudgetSource::kNone);
  EXPECT_FALSE(q.scene_time_limited(a->scene));
  EXPECT_FALSE(q.time_limited());
  q.finished(b->scene, b->start, BudgetSource::kSearch);
  EXPECT_TRUE(q.time_limited()) << "a start the search's limit cut";
  // A scene's limit that cuts its start marks that scene, not the search.
  TaskQueue r(plan, 0.0, {});
  const auto c = r.next(0, 0.0);
  ASSERT_TRUE(c);
  r.finished(c->scene, c->start, BudgetSource::kScene);
  EXPECT_TRUE(r.scene_time_limited(c->scene));
  EXPECT_FALSE(r.time_limited());
}

TEST(TaskQueue, StartsOfAGuessClassAlreadyTriedAreDeferredAfterTheScenesOthers) {
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 7)};
  // Start 6 is done already; "" (an undecided guess) is never deferred.
  const std::vector<std::string> classes = {"", "L", "R", "L", "", "R", "M"};
  TaskQueue q(plan, 0.0, {{0, 6}}, [&](int scene, int start) {
    EXPECT_EQ(scene, 0);
    return classes.at(start);
  });
  std::vector<int> order;
  while (const auto t = q.next(0, 0.0)) order.push_back(t->start);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 4, 3, 5}));
  // Without the function: index order.
  TaskQueue plain(plan, 0.0, {});
  order.clear();
  while (const auto t = plain.next(0, 0.0)) order.push_back(t->start);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
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
    o.T_f = o.value = T_f;
    o.max_violation = o.max_complementarity = 1e-9;
  }
  return {{"outcome", o.to_json()}, {"solution", {{"T_f", T_f}}}};
}

// best/SCENE.json's start (its provenance.run), or -1 without a file.
int start_in_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return -1;
  return json::parse(in).at("provenance").at("run").at("start").get<int>();
}

TEST(SearchRecord, AStartRunAgainThatEndsAboveItsCutBestHandsTheFileBackToTheBestFinalStart) {
  // A start cut by the search's time limit keeps its best so far, which a salvage can put
  // below where the same start ends when --resume runs it again. Start 0 ends at 3.0, start 1
  // is cut at 2.9 (the best), start 2 ends at 2.95 (the best final start, not the best);
  // then start 1 runs again and ends at 3.1: start 2 is the best, and its file is best/.
  SearchPlan plan;
  plan.scenes = {job("one_robot_axis", 3)};
  const std::string dir = fresh_dir("record_fallback");
  SearchRecord record(plan, dir, 1, false, false);
  auto outcome = [](int start, double T_f, StartStatus status) {
    StartOutcome o;
    o.scene = "one_robot_axis";
    o.start = start;
    o.seed = 1;
    o.status = status;
    o.T_f = o.value = T_f;
    o.max_violation = o.max_complementarity = 1e-9;
    if (status == StartStatus::kTimeLimit) {
      o.budget = 1.0;
      o.budget_source = BudgetSource::kSearch;
    }
    return o;
  };
  const std::string best = dir + "/best/one_robot_axis.json";
  const std::string last = dir + "/best/.final/one_robot_axis.json";
  auto add = [&](int start, double T_f, StartStatus status) {
    const json solution = {{"T_f", T_f}, {"start", start}};
    record.record(outcome(start, T_f, status), &solution, 0.0, 0.0);
  };
  add(0, 3.0, StartStatus::kSolved);
  EXPECT_EQ(start_in_file(best), 0);
  EXPECT_EQ(start_in_file(last), 0);
  add(1, 2.9, StartStatus::kTimeLimit);
  EXPECT_EQ(start_in_file(best), 1) << "a cut start's best counts";
  EXPECT_EQ(start_in_file(last), 0) << "but it is not final";
  add(2, 2.95, StartStatus::kSolved);
  EXPECT_EQ(start_in_file(best), 1);
  EXPECT_EQ(start_in_file(last), 2);
  add(1, 3.1, StartStatus::kSolved);
  EXPECT_EQ(record.best_value(0), 2.95);
  EXPECT_EQ(start_in_file(best), 2) << "the file follows the best back to a final start";
  std::ifstream in(best);
  EXPECT_EQ(json::parse(in).at("T_f"), 2.95);
}

TEST(Coordinator, AStartsErrorIsRecordedAndTheSearchGoesOnToTheEnd) {
  const SearchPlan plan = load_search_plan({config("benchmarks/smoke.yaml")}, 0, 1, {});
  const std::string dir = fresh_dir("errors");
  Coordinator c(plan, dir, 1, 0.0, false, false);
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
    Coordinator c(plan, dir, 1, 0.0, false, false);
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
  Coordinator again(plan, dir, 1, 0.0, true, false);
  std::vector<int> handed;
  while (const auto t = again.next(0)) handed.push_back(t->start);
  EXPECT_EQ(handed, (std::vector<int>{0, 2}));
}

// best/SCENE.json is written before its start's runs.jsonl line (search/search_record.h). A
// kill between the two (here: the last line cut off) leaves the file, and --resume takes
// the line from the file's provenance.run: the start is neither lost nor run twice, and the
// recorded best has its file.
TEST(Coordinator, AKillBetweenABestsFileAndItsLineLosesNeither) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 3, 1, {});
  const std::string dir = fresh_dir("kill_window");
  const std::string runs = dir + "/runs.jsonl", file = dir + "/best/one_robot_axis.json";
  auto lines = [&] {
    std::vector<std::string> v;
    std::ifstream in(runs);
    for (std::string line; std::getline(in, line);) v.push_back(line);
    return v;
  };
  {
    Coordinator c(plan, dir, 1, 0.0, false, false);
    for (int k : {0, 1}) {  // start 1 (T_f 2) improves on start 0 (T_f 3)
      const auto t = c.next(0);
      ASSERT_TRUE(t);
      ASSERT_EQ(t->start, k);
      const json solution = {{"T_f", 3.0 - k}, {"provenance", {{"start", k}}}};
      c.record(StartOutcome::from_json(outcome_message(plan, *t, 3.0 - k)["outcome"]), &solution);
    }
  }  // no finish(): as if killed
  const std::vector<std::string> before = lines();
  ASSERT_EQ(before.size(), 2u);
  EXPECT_EQ(json::parse(std::ifstream(file))["provenance"]["run"], json::parse(before[1]))
      << "the best's file carries its runs.jsonl line";
  std::ofstream(runs, std::ios::trunc) << before[0] << "\n";  // the kill came before line 2

  Coordinator again(plan, dir, 1, 0.0, true, false);
  std::vector<int> handed;
  while (const auto t = again.next(0)) {
    handed.push_back(t->start);
    again.record(StartOutcome::from_json(outcome_message(plan, *t, 4.0)["outcome"]), nullptr);
  }
  EXPECT_EQ(handed, (std::vector<int>{2})) << "start 1 ended before the kill: not run again";
  again.finish();
  const std::vector<std::string> after = lines();
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(json::parse(after[1]), json::parse(before[1])) << "the lost line, taken from the file";
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 1);
  EXPECT_EQ(best["scenes"]["one_robot_axis"]["T_f"], 2.0);
  EXPECT_EQ(best["starts_finished"], 3);

  // A second resume finds every line: it appends nothing and runs nothing.
  Coordinator third(plan, dir, 1, 0.0, true, false);
  EXPECT_FALSE(third.next(0));
  third.finish();
  EXPECT_EQ(lines().size(), 3u);
}

// The shared incumbent (search/coordinator.h): tasks carry their scene's best, a better one
// goes to every worker rank running that scene, once; rank 0 reads it directly.
TEST(CoordinatorIncumbent, ABetterBestGoesToTheWorkersRunningItsSceneOnce) {
  const SearchPlan plan = load_search_plan({config("benchmarks/smoke.yaml")}, 0, 1, {});
  Coordinator c(plan, fresh_dir("incumbent"), 1, 0.0, false, true);
  const Task t1 = Task::from_json(json::parse(c.on_result(1, "{}").body));  // larger scene first
  const auto t0 = c.next(0);
  const Task t2 = Task::from_json(json::parse(c.on_result(2, "{}").body));
  ASSERT_TRUE(t0);
  const int s = t1.scene;
  ASSERT_EQ(t0->scene, s);
  ASSERT_EQ(t2.scene, s);
  EXPECT_EQ(t1.incumbent, kInf);  // nothing known yet
  EXPECT_EQ(c.incumbent(s), kInf);
  EXPECT_TRUE(c.take_outbox().empty());

  c.progress(s, 3.0);  // rank 0's start found 3 s
  EXPECT_EQ(c.incumbent(s), 3.0);
  auto out = c.take_outbox();
  ASSERT_EQ(out.size(), 2u);  // ranks 1 and 2, not rank 0
  std::vector<int> to;
  for (const auto& m : out) {
    to.push_back(m.to);
    EXPECT_EQ(m.kind, MessageKind::kIncumbent);
    EXPECT_EQ(json::parse(m.body), (json{{"scene", s}, {"value", 3.0}}));
  }
  std::sort(to.begin(), to.end());
  EXPECT_EQ(to, (std::vector<int>{1, 2}));
  EXPECT_TRUE(c.take_outbox().empty()) << "each improvement is sent once";
  c.on_progress(json{{"scene", s}, {"start", t1.start}, {"value", 4.0}}.dump());  // not better
  EXPECT_EQ(c.incumbent(s), 3.0);
  EXPECT_TRUE(c.take_outbox().empty());

  // Worker 1 ends its start at 2.5: recorded, the incumbent; its next task carries it, and
  // only worker 2 (still running scene s) is told.
  const Task n1 = Task::from_json(json::parse(c.on_result(1, outcome_message(plan, t1, 2.5).dump()).body));
  EXPECT_EQ(c.incumbent(s), 2.5);
  if (n1.scene == s) {
    EXPECT_EQ(n1.incumbent, 2.5);
  }
  out = c.take_outbox();
  int to_2 = 0;
  for (const auto& m : out) to_2 += m.to == 2;
  EXPECT_EQ(to_2, 1);
  for (const auto& m : out) EXPECT_TRUE(m.to == 2 || (m.to == 1 && n1.scene == s)) << m.to;
}

TEST(CoordinatorIncumbent, NotSharedThereIsNoneAndNoMessage) {
  const SearchPlan plan = load_search_plan({config("benchmarks/smoke.yaml")}, 0, 1, {});
  Coordinator c(plan, fresh_dir("deterministic"), 1, 0.0, false, false);
  const Task t1 = Task::from_json(json::parse(c.on_result(1, "{}").body));
  c.progress(t1.scene, 3.0);
  EXPECT_EQ(c.incumbent(t1.scene), kInf);
  EXPECT_TRUE(c.take_outbox().empty());
  const Task n1 = Task::from_json(json::parse(c.on_result(1, outcome_message(plan, t1, 2.5).dump()).body));
  EXPECT_EQ(n1.incumbent, kInf);
  EXPECT_FALSE(json::parse(t1.to_json().dump()).contains("incumbent"));
  c.finish();
}

TEST(CoordinatorIncumbent, BestJsonSaysWhichModeRanAndAResumeStartsFromTheEarlierBest) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 3, 1, {});
  const std::string dir = fresh_dir("mode");
  {
    Coordinator c(plan, dir, 1, 0.0, false, true);
    const auto t = c.next(0);
    ASSERT_TRUE(t);
    c.record(StartOutcome::from_json(outcome_message(plan, *t, 3.5)["outcome"]), nullptr);
    c.finish();
    EXPECT_EQ(json::parse(std::ifstream(dir + "/best.json"))["mode"], "shared");
  }
  Coordinator again(plan, dir, 1, 0.0, true, true);
  EXPECT_EQ(again.incumbent(0), 3.5);
  const auto t = again.next(0);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->incumbent, 3.5);
  const std::string det_dir = fresh_dir("mode_det");
  Coordinator det(plan, det_dir, 1, 0.0, false, false);
  det.finish();
  EXPECT_EQ(json::parse(std::ifstream(det_dir + "/best.json"))["mode"], "deterministic");
}

}  // namespace
}  // namespace disco
