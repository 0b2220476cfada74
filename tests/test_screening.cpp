// A screened search's bookkeeping without solves (search/screening.h, search/task_queue.h,
// search/coordinator.h): the screen's steps, the choice of refines, the settings' ranges, and
// a search driven through the coordinator's message protocol with made-up outcomes: screens
// first, refines once every screen has ended (a rank asking in between waits), early refines
// between batches of screens, the best only from refines, and --resume across the two stages.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "core/config/settings.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "search/coordinator.h"
#include "search/run_start.h"
#include "search/screening.h"
#include "search/search_plan.h"
#include "search/task_queue.h"

namespace disco {
namespace {

using json = nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string config(const std::string& path) { return std::string(DISCO_SOURCE_DIR) + "/configs/" + path; }

std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("disco_screening_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

TEST(Screening, TheScreenRunsAtTheFractionOfTheStepsAtLeastTwo) {
  Scene scene = load_scene(config("scenarios/paper/A3.yaml"));
  ASSERT_EQ(scene.steps, 50);
  EXPECT_EQ(screen_steps(scene, 0.5), 25);
  EXPECT_EQ(screen_steps(scene, 0.25), 13);  // round(12.5), away from zero
  EXPECT_EQ(screen_steps(scene, 0.01), 2);
  scene.steps = 3;
  EXPECT_EQ(screen_steps(scene, 0.9), 3);
}

TEST(Screening, RefinesAreTheBestOfEachClassFirstThenTheNextBest) {
  const std::vector<Screened> screened = {
      {0, 10.0, "a"}, {1, 9.0, "a"}, {2, 9.5, "b"}, {3, kNaN, "c"}, {4, 9.0, "a"}, {5, 11.0, ""},
      {6, 12.0, ""}};
  // Ranked: 1 (9.0 a), 4 (9.0 a, a tie to the lower start), 2 (9.5 b), 0 (10 a), 5, 6; 3 has
  // no certified point. Classes first: 1 (a), 2 (b), 5 and 6 (no class: each its own).
  EXPECT_EQ(refine_choice(screened, 2, 0.0), (std::vector<int>{1, 2}));
  EXPECT_EQ(refine_choice(screened, 4, 0.0), (std::vector<int>{1, 2, 5, 6}));
  EXPECT_EQ(refine_choice(screened, 6, 0.0), (std::vector<int>{1, 2, 5, 6, 4, 0}));
  EXPECT_EQ(refine_choice(screened, 10, 0.0).size(), 6u) << "never an uncertified screen";
  EXPECT_TRUE(refine_choice({{0, kNaN, ""}}, 3, 0.0).empty());
}

TEST(Screening, EarlyRefinesAreEachBatchsBestWhenBelowEveryEarlierBatchs) {
  // Batches of 2: {0, 1} best 1 (4.0): chosen. {2, 3} best 2 (4.5, 3 uncertified): not below
  // 4.0. {4, 5} a tie at 3.0, to the lower start: 4. {6} alone, 2.0: chosen.
  const std::vector<Screened> ended = {{0, 5.0, ""}, {1, 4.0, ""}, {2, 4.5, ""}, {3, kNaN, ""},
                                       {4, 3.0, ""}, {5, 3.0, ""}, {6, 2.0, ""}};
  EXPECT_EQ(early_refine_choice(ended, 7, 2, 0.0), (std::vector<int>{1, 4, 6}));
  // The same screens in another order: the same choice.
  std::vector<Screened> shuffled(ended.rbegin(), ended.rend());
  EXPECT_EQ(early_refine_choice(shuffled, 7, 2, 0.0), (std::vector<int>{1, 4, 6}));
  // Screen 3 not ended: batch 1 undecided, so nothing after it either (whatever ended there).
  std::vector<Screened> open = ended;
  open.erase(open.begin() + 3);
  EXPECT_EQ(early_refine_choice(open, 7, 2, 0.0), (std::vector<int>{1}));
  // A batch without a certified screen chooses nothing and moves no bar.
  EXPECT_EQ(early_refine_choice({{0, kNaN, ""}, {1, kNaN, ""}, {2, 7.0, ""}}, 3, 2, 0.0), (std::vector<int>{2}));
  // Batches of 1: every screen below all those before it (a running record).
  EXPECT_EQ(early_refine_choice({{0, 3.0, ""}, {1, 4.0, ""}, {2, 2.0, ""}, {3, 2.0, ""}, {4, 1.0, ""}}, 5, 1, 0.0),
            (std::vector<int>{0, 2, 4}));
  EXPECT_TRUE(early_refine_choice(ended, 7, 0, 0.0).empty()) << "0: no early refines";
}

TEST(Screening, ScreensWithinTheTieRankByStart) {
  // 1e-7 relative: 9.8168565680 and 9.8168565690 (1e-10 apart) are one optimum; 9.81686 is not.
  const double tie = 1e-7;
  EXPECT_TRUE(screen_below(9.8168565, 9.81686, tie)) << "3.5e-6 apart";
  EXPECT_FALSE(screen_below(9.8168565680, 9.8168565690, tie));
  EXPECT_FALSE(screen_below(9.8168565690, 9.8168565680, tie)) << "never below a higher value";
  EXPECT_TRUE(screen_below(1.0, 2.0, 0.0));
  EXPECT_FALSE(screen_below(2.0, 2.0, 0.0));
  // Ranked: {3, 7, 8} within the tie of 9.7846360739 (by start: 3 before 7 though 7 is lower by
  // 2e-11), then {1, 5, 6} within the tie of 9.8168565683, then 2 (9.9). Classes first: 3 (a),
  // 1 (b), 2 (c); then 5, 6, 7, 8 by their groups and starts.
  const std::vector<Screened> screened = {{1, 9.8168565684, "b"}, {2, 9.9, "c"},           {3, 9.78463607392, "a"},
                                          {5, 9.8168565683, "b"}, {6, 9.8168565690, "b"}, {7, 9.78463607390, "a"},
                                          {8, 9.78463607400, "a"}};
  EXPECT_EQ(refine_choice(screened, 7, tie), (std::vector<int>{3, 1, 2, 7, 8, 5, 6}));
  // Without the tie, by value to the last digit.
  EXPECT_EQ(refine_choice(screened, 7, 0.0), (std::vector<int>{7, 5, 2, 3, 8, 1, 6}));
  // A group is anchored at its lowest value: 1.0, 1.0 + 0.6e-7 and 1.0 + 1.2e-7 are two groups
  // (the third is more than the tie above the first), whatever the second's distance to the third.
  EXPECT_EQ(refine_choice({{0, 1.0 + 1.2e-7, ""}, {1, 1.0 + 0.6e-7, ""}, {2, 1.0, ""}}, 3, tie),
            (std::vector<int>{1, 2, 0}));
  // Early refines in batches of 1: screen 1 ties with screen 0 (not below it), screen 2 is below.
  EXPECT_EQ(early_refine_choice({{0, 9.8168565684, ""}, {1, 9.8168565683, ""}, {2, 9.78, ""}}, 3, 1, tie),
            (std::vector<int>{0, 2}));
  EXPECT_EQ(early_refine_choice({{0, 9.8168565684, ""}, {1, 9.8168565683, ""}, {2, 9.78, ""}}, 3, 1, 0.0),
            (std::vector<int>{0, 1, 2}));
  // In a batch of 3, the lowest start unless another is below it by more than the tie.
  EXPECT_EQ(early_refine_choice({{0, 9.8168565684, ""}, {1, 9.8168565683, ""}, {2, 9.9, ""}}, 3, 3, tie),
            (std::vector<int>{0}));
  EXPECT_EQ(early_refine_choice({{0, 9.8168565684, ""}, {1, 9.8168565683, ""}, {2, 9.9, ""}}, 3, 3, 0.0),
            (std::vector<int>{1}));
}

TEST(Screening, TheTimeLeftRunsTheRankingThenTheStartsWithoutACertifiedScreen) {
  // Certified: 1 (9.0 a), 4 (8.0 a), 2 (9.5 b); 3 and 6 screened without a certified point; 0
  // and 5 never screened. Hand-out order 0, 2, 4, 6, 1, 3, 5 (e.g. guess classes deferred).
  const std::vector<Screened> screened = {{1, 9.0, "a"}, {4, 8.0, "a"}, {2, 9.5, "b"},
                                          {3, kNaN, ""}, {6, kNaN, "c"}};
  const std::vector<int> order = {0, 2, 4, 6, 1, 3, 5};
  // refine_choice's ranking (4 a, 2 b, 1), then the unscreened 0, 5 and the uncertified 6, 3 in
  // the hand-out order.
  EXPECT_EQ(time_left_order(screened, order, 0.0), (std::vector<int>{4, 2, 1, 0, 5, 6, 3}));
  EXPECT_EQ(time_left_order({}, {2, 0, 1}, 0.0), (std::vector<int>{2, 0, 1})) << "nothing screened";
  // Every start once, whatever its screen.
  std::vector<int> all = time_left_order(screened, order, 0.0);
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
}

TEST(Screening, BadSettingsAreRefusedNamingTheKey) {
  const auto message = [](const std::string& o) {
    Settings s = Settings::load(default_settings_path());
    s.apply_override(o);
    try {
      screen_settings(s);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("search.screen_fraction=1").find("search.screen_fraction"), std::string::npos);
  EXPECT_NE(message("search.screen_fraction=-0.1").find("search.screen_fraction"), std::string::npos);
  EXPECT_NE(message("search.refine_count=0").find("search.refine_count"), std::string::npos);
  EXPECT_NE(message("search.screen_share=1").find("search.screen_share"), std::string::npos);
  EXPECT_NE(message("search.early_refine_batch=-1").find("search.early_refine_batch"), std::string::npos);
  EXPECT_NE(message("search.refine_from=guess").find("search.refine_from"), std::string::npos);
  EXPECT_EQ(message("search.screen_fraction=0.5"), "");
  EXPECT_EQ(message("search.refine_from=start"), "");
  EXPECT_NE(message("search.screen_tie=-1e-9").find("search.screen_tie"), std::string::npos);
  EXPECT_NE(message("search.screen_tie=0.01").find("search.screen_tie"), std::string::npos);
  EXPECT_EQ(message("search.screen_tie=0"), "");
  Settings s = Settings::load(default_settings_path());
  EXPECT_FALSE(screen_settings(s).on()) << "the default is today's search";
}

ScreenSettings screening(int refine_count, int early_batch = 0) {
  ScreenSettings s;
  s.fraction = 0.5;
  s.refine_count = refine_count;
  s.share = 0.5;
  s.early_batch = early_batch;
  return s;
}

// A made-up outcome of `task` (its stage kept) with T_f, in class `key`, and its solution.
json outcome_message(const SearchPlan& plan, const Task& task, double T_f, const std::string& key) {
  StartOutcome o;
  o.scene = plan.scenes[task.scene].scene.name;
  o.start = task.start;
  o.stage = task.stage;
  o.seed = 1;
  o.rank = 1;
  o.seconds = 0.01;
  o.status = StartStatus::kSolved;
  o.T_f = o.value = T_f;
  o.max_violation = o.max_complementarity = 1e-9;
  o.best_class = {{"key", key}, {"pairs", json::array()}};
  if (task.stage == Stage::kRefine && !task.guess.is_null()) o.guess = GuessKind::kGiven;  // as a worker reports it
  return {{"outcome", o.to_json()},
          {"solution", {{"T_f", T_f}, {"made_by", to_string(task.stage) + " " + std::to_string(task.start)}}}};
}

// Screened T_f per start (start 2 is the best screen, 0 and 3 share its class) and refined T_f.
double screened_T_f(int k) { return std::vector<double>{3.0, 4.0, 2.0, 2.5}.at(k); }
std::string class_of(int k) { return k == 1 ? "b" : "a"; }
double refined_T_f(int k) { return 5.0 + k; }

TEST(ScreenedSearch, ScreensFirstThenTheChosenRefinesAndTheBestOnlyFromARefine) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  const std::string dir = fresh_dir("flow");
  Coordinator c(plan, dir, 1, 0.0, false, false, {}, screening(2));
  Coordinator::Reply reply = c.on_result(1, "{}");
  std::vector<std::pair<std::string, int>> handed;
  while (reply.kind == MessageKind::kTask) {
    const Task t = Task::from_json(json::parse(reply.body));
    handed.push_back({to_string(t.stage), t.start});
    if (t.stage == Stage::kRefine) {
      // The refine starts from its screen's solution file.
      EXPECT_EQ(t.guess.at("made_by"), "screen " + std::to_string(t.start));
      EXPECT_EQ(t.guess.at("provenance").at("run").at("stage"), "screen");
    }
    const double T_f = t.stage == Stage::kScreen ? screened_T_f(t.start) : refined_T_f(t.start);
    reply = c.on_result(1, outcome_message(plan, t, T_f, class_of(t.start)).dump());
  }
  EXPECT_EQ(reply.kind, MessageKind::kStop);
  EXPECT_FALSE(reply.none);
  // Every screen, then the best of class a (start 2) and of class b (start 1).
  const std::vector<std::pair<std::string, int>> expected = {
      {"screen", 0}, {"screen", 1}, {"screen", 2}, {"screen", 3}, {"refine", 2}, {"refine", 1}};
  EXPECT_EQ(handed, expected);
  c.finish();
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  const json& scene = best["scenes"]["one_robot_axis"];
  EXPECT_EQ(scene["T_f"], refined_T_f(1)) << "the best refine, not the lower screened T_f";
  EXPECT_EQ(scene["start"], 1);
  EXPECT_EQ(scene["starts_run"], 2);
  EXPECT_EQ(scene["starts_screened"], 4);
  EXPECT_EQ(best["starts_total"], 6);
  EXPECT_EQ(best["starts_finished"], 6);
  const json file = json::parse(std::ifstream(dir + "/best/one_robot_axis.json"));
  EXPECT_EQ(file["made_by"], "refine 1");
  std::ifstream runs(dir + "/runs.jsonl");
  std::map<std::string, int> stages;
  for (std::string line; std::getline(runs, line);) ++stages[json::parse(line)["stage"]];
  EXPECT_EQ(stages, (std::map<std::string, int>{{"screen", 4}, {"refine", 2}}));
  for (int k = 0; k < 4; ++k)
    EXPECT_TRUE(std::filesystem::exists(dir + "/screened/one_robot_axis/" + std::to_string(k) + ".json"));
}

TEST(ScreenedSearch, ScreensTiedToTheSettingsTieAreRefinedInStartOrder) {
  // Screens 0, 2 and 3 within 1e-9 of each other (one optimum to the solver's accuracy), 1 above.
  const std::vector<double> screened = {2.0 + 1e-9, 3.0, 2.0, 2.0 + 5e-10};
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  const auto refines = [&](double tie) {
    ScreenSettings settings = screening(2);
    settings.tie = tie;
    Coordinator c(plan, fresh_dir("tie"), 1, 0.0, false, false, {}, settings);
    Coordinator::Reply reply = c.on_result(1, "{}");
    std::vector<int> out;
    while (reply.kind == MessageKind::kTask) {
      const Task t = Task::from_json(json::parse(reply.body));
      if (t.stage == Stage::kRefine) out.push_back(t.start);
      const double T_f = t.stage == Stage::kScreen ? screened.at(t.start) : refined_T_f(t.start);
      reply = c.on_result(1, outcome_message(plan, t, T_f, "a").dump());
    }
    return out;
  };
  EXPECT_EQ(refines(1e-7), (std::vector<int>{0, 2})) << "the tied group by start";
  EXPECT_EQ(refines(0.0), (std::vector<int>{2, 3})) << "by value to the last digit";
}

TEST(ScreenedSearch, ARankAskingWhileScreensStillRunWaitsAndGetsItsRefineOrStopLater) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 2, 1, {});
  Coordinator c(plan, fresh_dir("wait"), 1, 0.0, false, false, {}, screening(2));
  const Task a = Task::from_json(json::parse(c.on_result(1, "{}").body));
  const Task b = Task::from_json(json::parse(c.on_result(2, "{}").body));
  ASSERT_EQ(a.stage, Stage::kScreen);
  ASSERT_EQ(b.stage, Stage::kScreen);
  // Rank 1 ends its screen while rank 2's runs: nothing to hand out yet, and no stop.
  Coordinator::Reply r1 = c.on_result(1, outcome_message(plan, a, 3.0, "a").dump());
  EXPECT_TRUE(r1.none);
  EXPECT_TRUE(c.take_outbox().empty());
  // Rank 2's screen ends: both refines are chosen; rank 2 gets one at once, rank 1 the other.
  Coordinator::Reply r2 = c.on_result(2, outcome_message(plan, b, 2.0, "b").dump());
  ASSERT_EQ(r2.kind, MessageKind::kTask);
  const Task t2 = Task::from_json(json::parse(r2.body));
  EXPECT_EQ(t2.stage, Stage::kRefine);
  EXPECT_EQ(t2.start, b.start) << "the better screen first";
  const auto out = c.take_outbox();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].to, 1);
  ASSERT_EQ(out[0].kind, MessageKind::kTask);
  const Task t1 = Task::from_json(json::parse(out[0].body));
  EXPECT_EQ(t1.stage, Stage::kRefine);
  EXPECT_EQ(t1.start, a.start);
  // Both end: both are told to stop, with a reply (nothing is left to come).
  EXPECT_EQ(c.on_result(1, outcome_message(plan, t1, 6.0, "a").dump()).kind, MessageKind::kStop);
  const Coordinator::Reply last = c.on_result(2, outcome_message(plan, t2, 5.0, "b").dump());
  EXPECT_EQ(last.kind, MessageKind::kStop);
  EXPECT_FALSE(last.none);
  EXPECT_FALSE(c.await_work());
}

TEST(ScreenedSearch, AResumeSkipsEndedScreensAndRefinesAndChoosesFromTheRecordedScreens) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  const std::string dir = fresh_dir("resume");
  {  // The first run ends every screen and one refine (start 2), then stops (a kill).
    Coordinator c(plan, dir, 1, 0.0, false, false, {}, screening(2));
    while (const auto t = c.next(0)) {
      const double T_f = t->stage == Stage::kScreen ? screened_T_f(t->start) : refined_T_f(t->start);
      const json m = outcome_message(plan, *t, T_f, class_of(t->start));
      c.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
      if (t->stage == Stage::kRefine) break;
    }
  }
  Coordinator again(plan, dir, 1, 0.0, true, false, {}, screening(2));
  std::vector<std::pair<Stage, int>> handed;
  while (const auto t = again.next(0)) {
    handed.push_back({t->stage, t->start});
    EXPECT_EQ(t->guess.at("made_by"), "screen " + std::to_string(t->start));
    const json m = outcome_message(plan, *t, refined_T_f(t->start), class_of(t->start));
    again.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
  }
  EXPECT_EQ(handed, (std::vector<std::pair<Stage, int>>{{Stage::kRefine, 1}}));
  EXPECT_FALSE(again.await_work());
  again.finish();
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 1);
  EXPECT_EQ(best["starts_finished"], 6);
}

// Runs every task `c` hands out (one rank), each ending at its made-up T_f after `edit` may
// change its message; returns the tasks handed out, in order.
std::vector<std::pair<Stage, int>> run_all(const SearchPlan& plan, Coordinator& c,
                                           const std::function<void(const Task&, json&)>& edit) {
  std::vector<std::pair<Stage, int>> handed;
  while (const auto t = c.next(0)) {
    handed.push_back({t->stage, t->start});
    const double T_f = t->stage == Stage::kScreen ? screened_T_f(t->start) : refined_T_f(t->start);
    json m = outcome_message(plan, *t, T_f, class_of(t->start));
    edit(*t, m);
    c.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
  }
  return handed;
}

// A screen cut short by a time limit can still hold a certified point (its salvage), be chosen
// and refined from it. Such a refine is not final: --resume runs the screen again and then the
// refine from the screen's new answer, so the resumed search holds the runs of a search that
// was never cut (tests/search_tests.py killrandom_screened). A refine from a screen that ended
// is final and is not run again.
TEST(ScreenedSearch, ARefineOfAScreenCutShortRunsAgainAfterItsScreenOnResume) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  const std::string dir = fresh_dir("stale");
  {  // The first run: screen 2 is cut by the limit (with a certified point), both refines end.
    Coordinator c(plan, dir, 1, 0.0, false, false, {}, screening(2));
    const auto handed = run_all(plan, c, [](const Task& t, json& m) {
      if (t.stage == Stage::kScreen && t.start == 2) m["outcome"]["status"] = "time_limit";
    });
    ASSERT_EQ(handed, (std::vector<std::pair<Stage, int>>{{Stage::kScreen, 0}, {Stage::kScreen, 1},
                                                          {Stage::kScreen, 2}, {Stage::kScreen, 3},
                                                          {Stage::kRefine, 2}, {Stage::kRefine, 1}}));
    c.finish();
    const json best = json::parse(std::ifstream(dir + "/best.json"));
    EXPECT_EQ(best["starts_finished"], 4) << "the cut screen and the refine from it are not final";
  }
  Coordinator again(plan, dir, 1, 0.0, true, false, {}, screening(2));
  const auto handed = run_all(plan, again, [](const Task& t, json& m) {
    if (t.stage == Stage::kScreen) m["solution"]["made_by"] = "screen 2, again";
    if (t.stage == Stage::kRefine) {  // from the screen's new answer
      EXPECT_EQ(t.guess.at("made_by"), "screen 2, again");
    }
  });
  EXPECT_EQ(handed, (std::vector<std::pair<Stage, int>>{{Stage::kScreen, 2}, {Stage::kRefine, 2}}));
  EXPECT_FALSE(again.await_work());
  again.finish();
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["starts_finished"], 6);
  EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 1);
}

// Early refines in batches of 2 (screened T_f 3.0, 4.0 | 2.0, 2.5): after screens 0 and 1, start
// 0 is refined ahead of screens 2 and 3; after those, start 2 (below 3.0), then the final choice
// (starts 2 and 1, the best of each class) without start 2 again. A resume after the first
// refine runs the rest and nothing twice.
TEST(ScreenedSearch, EarlyRefinesRunBetweenBatchesOfScreensAndNothingTwiceAfterAResume) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  using Handed = std::vector<std::pair<Stage, int>>;
  const Handed all = {{Stage::kScreen, 0}, {Stage::kScreen, 1}, {Stage::kRefine, 0}, {Stage::kScreen, 2},
                      {Stage::kScreen, 3}, {Stage::kRefine, 2}, {Stage::kRefine, 1}};
  {
    const std::string dir = fresh_dir("early");
    Coordinator c(plan, dir, 1, 0.0, false, false, {}, screening(2, 2));
    EXPECT_EQ(run_all(plan, c, [](const Task&, json&) {}), all);
    EXPECT_FALSE(c.await_work());
    c.finish();
    const json best = json::parse(std::ifstream(dir + "/best.json"));
    EXPECT_EQ(best["starts_total"], 7);
    EXPECT_EQ(best["starts_finished"], 7);
    EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 0) << "refined T_f 5 + start: start 0's is lowest";
  }
  const std::string dir = fresh_dir("early_resume");
  {  // Killed after the early refine of start 0.
    Coordinator c(plan, dir, 1, 0.0, false, false, {}, screening(2, 2));
    while (const auto t = c.next(0)) {
      const double T_f = t->stage == Stage::kScreen ? screened_T_f(t->start) : refined_T_f(t->start);
      const json m = outcome_message(plan, *t, T_f, class_of(t->start));
      c.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
      if (t->stage == Stage::kRefine) break;
    }
  }
  Coordinator again(plan, dir, 1, 0.0, true, false, {}, screening(2, 2));
  EXPECT_EQ(run_all(plan, again, [](const Task&, json&) {}), Handed(all.begin() + 3, all.end()));
  again.finish();
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["starts_total"], 7);
  EXPECT_EQ(best["starts_finished"], 7);
}

// Under a time limit the chosen refines do not end the search: while time is left, a rank that
// would idle refines the next screen of the same ranking (the best of each class first, then by
// screened T_f), never one refined already, until none is left; then the starts whose screen has
// no certified point run at full N_t from their own guess. The limit here is far beyond the
// made-up outcomes' milliseconds, so no verdict depends on speed.
TEST(ScreenedSearch, UnderATimeLimitTheTimeLeftRefinesTheNextBestScreens) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 5, 1, {});
  using Handed = std::vector<std::pair<Stage, int>>;
  // Screens: start 4 without a certified point; 2 (a, 2.0), 3 (a, 2.5), 0 (a, 3.0), 1 (b, 4.0).
  auto uncertified_4 = [](const Task& t, json& m) {
    if (t.stage == Stage::kScreen && t.start == 4) {
      m["outcome"]["status"] = "infeasible";
      m["outcome"]["T_f"] = m["outcome"]["value"] = nullptr;
    }
  };
  auto screened = [](int k) { return k == 4 ? 9.0 : screened_T_f(k); };
  auto run = [&](Coordinator& c) {
    Handed handed;
    while (const auto t = c.next(0)) {
      handed.push_back({t->stage, t->start});
      if (handed.size() > 20) break;  // a start refined again and again would never end
      if (t->stage == Stage::kRefine) {
        EXPECT_EQ(t->guess.is_null(), t->start == 4) << "from the screen, but 4 from its own guess";
      }
      const double T_f = t->stage == Stage::kScreen ? screened(t->start) : refined_T_f(t->start);
      json m = outcome_message(plan, *t, T_f, class_of(t->start));
      uncertified_4(*t, m);
      c.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
    }
    return handed;
  };
  const Handed screens = {{Stage::kScreen, 0}, {Stage::kScreen, 1}, {Stage::kScreen, 2},
                          {Stage::kScreen, 3}, {Stage::kScreen, 4}};
  {  // No time limit: refine_count (1) refines, then the end.
    Coordinator c(plan, fresh_dir("fill_none"), 1, 0.0, false, false, {}, screening(1));
    Handed expected = screens;
    expected.insert(expected.end(), {{Stage::kRefine, 2}});
    EXPECT_EQ(run(c), expected);
    EXPECT_FALSE(c.await_work());
  }
  const std::string dir = fresh_dir("fill");
  Coordinator c(plan, dir, 1, /*time limit, s*/ 3600.0, false, false, {}, screening(1));
  Handed expected = screens;  // the choice (2), then class b's best (1), then 3 and 0 by T_f,
                              // then 4 (no certified screen) from its own guess
  expected.insert(expected.end(), {{Stage::kRefine, 2}, {Stage::kRefine, 1}, {Stage::kRefine, 3}, {Stage::kRefine, 0},
                                   {Stage::kRefine, 4}});
  EXPECT_EQ(run(c), expected);
  EXPECT_FALSE(c.await_work()) << "every start is refined: nothing is left to come";
  c.finish();
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["starts_total"], 10) << "5 screens and 5 refines";
  EXPECT_EQ(best["starts_finished"], 10);
  EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 0) << "refined T_f 5 + start: a fill refine's is lowest";
}

// Starts the screening share left unscreened are not lost: once a scene's certified screens are
// refined, the time left runs them at full N_t from their own guess, in the queue's order (here
// guess classes deferred: 0, 2, 1), each in its screen's place in the count. Like a refine of a
// screen cut short, such a run is not final: --resume screens the start and then refines it, so
// the resumed search holds every run of a search that was never cut. A share of 1e-9 of 3600 s
// (3.6 µs, less than the 1 ms slept before the first hand-out) lets no screen out, so no verdict
// depends on speed.
TEST(ScreenedSearch, StartsNeverScreenedRunFromTheirOwnGuessInTheTimeLeft) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 3, 1, {});
  ScreenSettings settings = screening(2);
  settings.share = 1e-9;
  const GuessClassFunction guess_class = [](int, int k) { return k < 2 ? std::string("a") : std::string("b"); };
  const std::string dir = fresh_dir("fill_unscreened");
  using Handed = std::vector<std::pair<Stage, int>>;
  auto run = [&](Coordinator& c, bool limited) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    Handed handed;
    while (const auto t = c.next(0)) {
      handed.push_back({t->stage, t->start});
      if (handed.size() > 10) break;
      EXPECT_EQ(t->guess.is_null(), limited || t->stage == Stage::kScreen) << "start " << t->start;
      const double T_f = t->stage == Stage::kScreen ? screened_T_f(t->start) : refined_T_f(t->start);
      const json m = outcome_message(plan, *t, T_f, class_of(t->start));
      c.record(StartOutcome::from_json(m["outcome"]), &m["solution"]);
    }
    EXPECT_FALSE(c.await_work());
    c.finish();
    return handed;
  };
  {
    Coordinator c(plan, dir, 1, /*time limit, s*/ 3600.0, false, false, guess_class, settings);
    EXPECT_EQ(run(c, true), (Handed{{Stage::kRefine, 0}, {Stage::kRefine, 2}, {Stage::kRefine, 1}}));
    const json best = json::parse(std::ifstream(dir + "/best.json"));
    EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 0);
    EXPECT_EQ(best["scenes"]["one_robot_axis"]["T_f"], refined_T_f(0));
    EXPECT_EQ(best["starts_total"], 3) << "each run in its screen's place";
    EXPECT_EQ(best["starts_finished"], 0) << "none is final without its screen";
  }
  {  // Resumed under the limit again: no screen again, so each runs again in its screen's place
     // (the starts an earlier run chose, in start order).
    Coordinator c(plan, dir, 1, 3600.0, true, false, guess_class, settings);
    EXPECT_EQ(run(c, true), (Handed{{Stage::kRefine, 0}, {Stage::kRefine, 1}, {Stage::kRefine, 2}}));
    const json best = json::parse(std::ifstream(dir + "/best.json"));
    EXPECT_EQ(best["starts_total"], 3);
    EXPECT_EQ(best["starts_finished"], 0);
  }
  // Without the limit: every screen (in the queue's order), the choice (2 of class a, 1 of class
  // b) and start 0, which the earlier runs ran.
  Coordinator again(plan, dir, 1, 0.0, true, false, guess_class, settings);
  EXPECT_EQ(run(again, false), (Handed{{Stage::kScreen, 0}, {Stage::kScreen, 2}, {Stage::kScreen, 1},
                                       {Stage::kRefine, 2}, {Stage::kRefine, 1}, {Stage::kRefine, 0}}));
  const json best = json::parse(std::ifstream(dir + "/best.json"));
  EXPECT_EQ(best["starts_total"], 6);
  EXPECT_EQ(best["starts_finished"], 6);
}

// search.refine_from start: a refine carries no guess (the worker runs the start's own), so it
// needs no screened answer; the choice and the resume are those of refines from the screen (one
// chosen from a screen cut short runs again after it: the screen's new outcome may change the
// choice). With "both" the refine carries its screen's answer, as from the screen.
TEST(ScreenedSearch, RefinesFromTheStartNeedNoScreenedAnswer) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 4, 1, {});
  using Handed = std::vector<std::pair<Stage, int>>;
  for (const RefineFrom from : {RefineFrom::kStart, RefineFrom::kBoth}) {
    ScreenSettings settings = screening(2);
    settings.refine_from = from;
    const bool start = from == RefineFrom::kStart;
    const std::string dir = fresh_dir(start ? "from_start" : "from_both");
    {
      Coordinator c(plan, dir, 1, 0.0, false, false, {}, settings);
      const Handed handed = run_all(plan, c, [&](const Task& t, json&) {
        if (t.stage == Stage::kRefine) {
          EXPECT_EQ(t.guess.is_null(), start) << "refine " << t.start;
        } else if (start) {
          std::filesystem::remove_all(dir + "/screened");  // the refines must not need it
        }
      });
      EXPECT_EQ(handed, (Handed{{Stage::kScreen, 0}, {Stage::kScreen, 1}, {Stage::kScreen, 2},
                                {Stage::kScreen, 3}, {Stage::kRefine, 2}, {Stage::kRefine, 1}}));
      c.finish();
      const json best = json::parse(std::ifstream(dir + "/best.json"));
      EXPECT_EQ(best["starts_finished"], 6);
      EXPECT_EQ(best["scenes"]["one_robot_axis"]["start"], 1);
    }
  }
}

// search.refine_from both: the better of the two runs, their costs summed, the history of new
// bests across both, and cut short if the second was.
TEST(ScreenedSearch, BothRefinesKeepTheBetterRunAndCountBoth) {
  StartOutcome a, b;
  a.status = b.status = StartStatus::kSolved;
  a.guess = GuessKind::kGiven;
  b.guess = GuessKind::kDetour;
  a.value = a.T_f = 5.0;
  b.value = b.T_f = 4.0;
  a.seconds = 2.0;
  b.seconds = 3.0;
  a.iterations = 100;
  b.iterations = 250;
  a.time_to_first_feasible = 0.5;
  b.time_to_first_feasible = 0.2;
  a.time_to_best = 1.5;
  b.time_to_best = 2.5;
  a.history = {{0.5, 6.0}, {1.5, 5.0}};
  b.history = {{0.2, 7.0}, {1.0, 4.5}, {2.5, 4.0}};
  a.stopped = "converged";
  b.stopped = "stalled";
  StartOutcome o = better_of(a, b);
  EXPECT_EQ(o.value, 4.0);
  EXPECT_EQ(o.seconds, 5.0);
  EXPECT_EQ(o.iterations, 350);
  EXPECT_EQ(o.time_to_first_feasible, 0.5);
  EXPECT_EQ(o.time_to_best, 4.5) << "the second's best, 2.5 s into it, after the first's 2 s";
  EXPECT_EQ(o.history, (std::vector<std::array<double, 2>>{{0.5, 6.0}, {1.5, 5.0}, {3.0, 4.5}, {4.5, 4.0}}));
  EXPECT_EQ(o.guess, GuessKind::kGiven) << "a refine that depends on its screen's answer";
  EXPECT_EQ(o.status, StartStatus::kSolved);
  EXPECT_NE(o.stopped.find("stalled"), std::string::npos);
  EXPECT_NE(o.stopped.find("start's kept"), std::string::npos);
  b.value = b.T_f = 5.0;  // a tie: the first
  b.status = StartStatus::kTimeLimit;
  o = better_of(a, b);
  EXPECT_EQ(o.value, 5.0);
  EXPECT_EQ(o.time_to_best, 1.5);
  EXPECT_EQ(o.stopped.rfind("converged", 0), 0u);
  EXPECT_EQ(o.status, StartStatus::kTimeLimit) << "the second was cut: the refine runs again on --resume";
  a.value = a.T_f = kNaN;  // the first found nothing: the second's, even if above
  a.history.clear();
  a.time_to_first_feasible = -1.0;
  b.value = b.T_f = 9.0;
  o = better_of(a, b);
  EXPECT_EQ(o.value, 9.0);
  EXPECT_DOUBLE_EQ(o.time_to_first_feasible, 2.2);
}

TEST(ScreenedSearch, WithoutScreeningEveryTaskIsAFullStart) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 3, 1, {});
  TaskQueue q(plan, 0.0, {});
  int n = 0;
  while (const auto t = q.next(0, 0.0)) {
    EXPECT_EQ(t->stage, Stage::kFull);
    EXPECT_TRUE(t->guess.is_null());
    EXPECT_FALSE(q.refines_to_come(0.0));
    ++n;
  }
  EXPECT_EQ(n, 3);
  EXPECT_EQ(q.total(), 3);
}

TEST(ScreenedSearch, UnderATimeLimitScreensStopAtTheShareAndTheirBudgetsEndThere) {
  const SearchPlan plan = load_search_plan({config("scenarios/one_robot_axis.yaml")}, 3, 1, {});
  TaskQueue q(plan, /*search*/ 100.0, {}, {}, screening(1));
  const auto first = q.next(0, 10.0);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->stage, Stage::kScreen);
  EXPECT_DOUBLE_EQ(first->budget, 40.0) << "until half of the search's 100 s";
  EXPECT_EQ(first->source, BudgetSource::kSearch);
  EXPECT_TRUE(q.screens_open(0, 10.0));
  EXPECT_FALSE(q.next(0, 50.0)) << "the screening share is used: no more screens";
  q.finished(first->scene, first->start);
  EXPECT_FALSE(q.screens_open(0, 50.0));
  EXPECT_TRUE(q.refines_to_come(50.0));
  EXPECT_FALSE(q.refines_to_come(100.0)) << "the search's limit has passed";
  EXPECT_FALSE(q.may_fill(0, 50.0)) << "no refine beyond the choice before the choice";
  q.add_refines(0, 0, {});
  EXPECT_TRUE(q.may_fill(0, 50.0));
  EXPECT_FALSE(q.may_fill(0, 100.0)) << "the search's limit has passed";
  TaskQueue unlimited(plan, 0.0, {}, {}, screening(1));
  unlimited.add_refines(0, 0, {});
  EXPECT_FALSE(unlimited.may_fill(0, 50.0)) << "without a time limit, refine_count ends the refines";
  SearchPlan own = plan;  // a scene's own limit (a benchmark file's time_limit), from its first hand-out
  own.scenes[0].time_limit = 40.0;
  TaskQueue scene_limited(own, 0.0, {}, {}, screening(1));
  ASSERT_TRUE(scene_limited.next(0, 10.0));
  scene_limited.add_refines(0, 0, {});
  EXPECT_TRUE(scene_limited.may_fill(0, 49.0));
  EXPECT_FALSE(scene_limited.may_fill(0, 50.0)) << "the scene's 40 s from its first hand-out at 10 s";
}

}  // namespace
}  // namespace disco
