// A start never takes the search down: whatever goes wrong inside it becomes
// a recorded status (search/run_start.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <csignal>
#include <stdexcept>
#include <cstdio>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "core/util/clock.h"
#include "core/util/interrupt.h"
#include "search/run_start.h"

namespace disco {
namespace {

Scene small_scene() {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/one_robot_axis.yaml",
                    {"steps=10"});
}

TEST(RunStart, AnExceptionInsideTheStartBecomesStatusError) {
  // An option Ipopt rejects makes the solver's constructor throw inside the start.
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("ipopt.no_such_option=1");
  const Scene scene = small_scene();
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings),
                                    elastic_settings(settings));
  StartOutcome out;
  EXPECT_NO_THROW(out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone));
  EXPECT_EQ(out.status, StartStatus::kError);
  EXPECT_NE(out.detail.find("no_such_option"), std::string::npos) << out.detail;
  EXPECT_TRUE(std::isnan(out.T_f));
  // The outcome survives the runs.jsonl round trip (NaN written as null).
  const StartOutcome back = StartOutcome::from_json(nlohmann::json::parse(out.to_json().dump()));
  EXPECT_EQ(back.status, StartStatus::kError);
  EXPECT_TRUE(std::isnan(back.T_f));
}

TEST(RunStart, AFailedInternalCheckInsideTheStartIsItsErrorStatusNotAnAbort) {
  // A perturbation whose horizon exceeds the feasible one breaks an invariant of the
  // reduction (step 1b: "a perturbation's horizon is ... at most the feasible one"), a
  // DISCO_CHECK: the start records it as status error, with the check's message, and the
  // process goes on (run_start.h's promise; a check used to abort the whole search).
  const Settings settings = Settings::load(default_settings_path());
  const Scene scene = small_scene();
  StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings), elastic_settings(settings));
  spec.guess = GuessKind::kPerturbedFeasible;
  spec.T_scale = 1.5;  // make_start draws it in [0.8, 1]: only a bug could give 1.5
  StartOutcome out;
  EXPECT_NO_THROW(out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone));
  EXPECT_EQ(out.status, StartStatus::kError);
  EXPECT_NE(out.detail.find("internal check failed at"), std::string::npos) << out.detail;
  EXPECT_NE(out.detail.find("at most the feasible one"), std::string::npos) << out.detail;
}

TEST(RunStart, ASolvedStartRecordsItsCertifiedResult) {
  const Settings settings = Settings::load(default_settings_path());
  const Scene scene = small_scene();
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings),
                                    elastic_settings(settings));
  nlohmann::json solution;
  const StartOutcome out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone, &solution);
  ASSERT_EQ(out.status, StartStatus::kSolved);
  EXPECT_LE(out.max_violation, 1e-6);
  EXPECT_LE(out.max_complementarity, 1e-6);
  EXPECT_EQ(solution["T_f"].get<double>(), out.T_f);
  const StartOutcome back = StartOutcome::from_json(nlohmann::json::parse(out.to_json().dump()));
  EXPECT_EQ(back.T_f, out.T_f);  // bit for bit through JSON
  EXPECT_EQ(back.start, out.start);
  EXPECT_EQ(back.seed, out.seed);
}

TEST(RunStart, ItsHistoryListsEveryNewBestOnTheStartsOwnClock) {
  // Start 2 of the swap: a reduction with several improvements (the report's
  // T_f-against-time plot is drawn from this).
  const Settings settings = Settings::load(default_settings_path());
  const Scene scene = load_scene(
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/two_robots_swap_avoid.yaml",
      {"steps=15"});
  const StartSpec spec = make_start(scene, 1, 2, reduction_settings(settings),
                                    elastic_settings(settings));
  const StartOutcome out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone);
  ASSERT_EQ(out.status, StartStatus::kSolved);
  ASSERT_GE(out.history.size(), 2u);
  // The first entry is the feasible point, the last the best; T_f falls
  // strictly and the clock does not go back.
  EXPECT_EQ(out.history.front()[0], out.time_to_first_feasible);
  EXPECT_EQ(out.history.back()[0], out.time_to_best);
  EXPECT_EQ(out.history.back()[1], out.T_f);
  for (std::size_t k = 1; k < out.history.size(); ++k) {
    EXPECT_GE(out.history[k][0], out.history[k - 1][0]);
    EXPECT_LT(out.history[k][1], out.history[k - 1][1]);
  }
  EXPECT_LE(out.time_to_best, out.seconds);
  // The guess and the schedule are recorded as data, as make_start drew them.
  EXPECT_EQ(out.guess, spec.guess);
  EXPECT_EQ(out.to_json()["guess"], to_string(spec.guess));
  EXPECT_EQ(out.schedule.at("rate").get<double>(), spec.schedule.rate);
  EXPECT_EQ(out.schedule.at("zeta").get<double>(), spec.elastic.zeta);
  EXPECT_EQ(out.schedule.at("minimize_weak").get<std::string>(),
            spec.schedule.weak_homotopy ? "homotopy" : "penalty");
  const StartOutcome back = StartOutcome::from_json(nlohmann::json::parse(out.to_json().dump()));
  EXPECT_EQ(back.history, out.history);
  EXPECT_EQ(back.guess, out.guess);
  EXPECT_EQ(back.schedule, out.schedule);
}

TEST(RunStart, AStartWithoutASolutionHasAnEmptyHistory) {
  Settings settings = Settings::load(default_settings_path());
  const Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/stress/spin_short.yaml");
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings),
                                    elastic_settings(settings));
  const StartOutcome out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone);
  EXPECT_EQ(out.status, StartStatus::kInfeasible);
  EXPECT_TRUE(out.history.empty());
  EXPECT_EQ(out.to_json().at("history"), nlohmann::json::array());
}

Scene contact_scene() {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/three_robots_contact.yaml");
}

// Simulated time (core/util/clock.h) at about a real iteration's pace on this scene.
constexpr double kTick = 0.035;  // s per Ipopt iteration report

TEST(RunStart, ATimeBudgetCapsTheWholeStartAndItsOutcomeSaysSo) {
  // A start of three_robots_contact runs for well over a thousand Ipopt iterations unbounded.
  // With a budget, every elastic solve gets only the time left of the whole start, so on the
  // simulated clock the start ends at most one report past the budget (its last solve, or the
  // salvage of a cut one, stops at the first report past it), keeps its best point so far and
  // is recorded as cut short by that budget, not as solved. 3 s is about 85 reports, before
  // or around the first feasible point; 7 s about 200, among the steps.
  const Settings settings = Settings::load(default_settings_path());
  const Scene scene = contact_scene();
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings),
                                    elastic_settings(settings));
  for (double budget : {3.0, 7.0}) {
    IterationTime time(kTick);
    const ScopedTimeSource clock(time);
    const StartOutcome out = run_start(scene, settings, spec, budget, BudgetSource::kSearch);
    std::printf("budget %.0f s: %s T_f %.4f in %.3f s, %lld reports (%s)\n", budget,
                to_string(out.status).c_str(), out.T_f, out.seconds,
                static_cast<long long>(time.iterations()), out.detail.c_str());
    EXPECT_LE(out.seconds, budget + kTick + 1e-9) << out.detail;
    EXPECT_NEAR(out.seconds, kTick * time.iterations(), 1e-9) << "the start's time is the clock's";
    EXPECT_EQ(out.status, StartStatus::kTimeLimit);
    EXPECT_TRUE(out.cut_short());
    EXPECT_EQ(out.budget, budget);
    EXPECT_EQ(out.budget_source, BudgetSource::kSearch);
    if (out.certified()) {
      EXPECT_LE(out.max_violation, 1e-6);
      EXPECT_LE(out.max_complementarity, 1e-6);
    }
    const StartOutcome back = StartOutcome::from_json(nlohmann::json::parse(out.to_json().dump()));
    EXPECT_EQ(back.status, StartStatus::kTimeLimit);
    EXPECT_EQ(back.budget, budget);
    EXPECT_EQ(back.budget_source, BudgetSource::kSearch);
    EXPECT_EQ(out.to_json().at("status"), "time_limit");
  }
}

// A simulated clock that requests an interrupt (as SIGINT does through mpi/disco_main.cpp) at
// its `at`-th iteration report.
class InterruptingTime : public IterationTime {
 public:
  InterruptingTime(double seconds_per_iteration, std::int64_t at)
      : IterationTime(seconds_per_iteration), at_(at) {}
  void on_iteration() override {
    IterationTime::on_iteration();
    if (iterations() == at_) request_interrupt(SIGINT);
  }

 private:
  std::int64_t at_;
};

TEST(RunStart, AnInterruptStopsTheStartAtOnceAndItIsRecordedAsInterrupted) {
  // The same long start, interrupted at its 40th Ipopt iteration report (in its first
  // feasibility solve): the solve stops at that very report and no Ipopt iteration runs after
  // it, so the start's time is exactly 40 reports.
  const Settings settings = Settings::load(default_settings_path());
  const Scene scene = contact_scene();
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings),
                                    elastic_settings(settings));
  clear_interrupt();
  StartOutcome out;
  {
    InterruptingTime time(kTick, 40);
    const ScopedTimeSource clock(time);
    out = run_start(scene, settings, spec, 0.0, BudgetSource::kNone);
    EXPECT_EQ(time.iterations(), 40) << "no iteration after the interrupt";
  }
  EXPECT_TRUE(interrupt_requested());
  EXPECT_EQ(interrupt_signal(), SIGINT);
  clear_interrupt();
  EXPECT_EQ(out.status, StartStatus::kInterrupted) << to_string(out.status) << " " << out.detail;
  EXPECT_NEAR(out.seconds, 40 * kTick, 1e-9);
  EXPECT_EQ(StartOutcome::from_json(out.to_json()).status, StartStatus::kInterrupted);
  // Afterwards solves run again: a short start ends solved.
  const Scene small = small_scene();
  const StartSpec s0 = make_start(small, 1, 0, reduction_settings(settings), elastic_settings(settings));
  EXPECT_EQ(run_start(small, settings, s0, 0.0, BudgetSource::kNone).status, StartStatus::kSolved);
}

TEST(RunStart, StatusNamesRoundTripAndAnUnknownNameIsRefused) {
  for (StartStatus s : {StartStatus::kSolved, StartStatus::kInfeasible, StartStatus::kFailed,
                        StartStatus::kElasticNotTight, StartStatus::kError, StartStatus::kTimeLimit,
                        StartStatus::kInterrupted, StartStatus::kDominated})
    EXPECT_EQ(start_status_from_string(to_string(s)), s);
  for (BudgetSource b : {BudgetSource::kNone, BudgetSource::kStart, BudgetSource::kScene,
                         BudgetSource::kSearch})
    EXPECT_EQ(budget_source_from_string(to_string(b)), b);
  EXPECT_THROW(start_status_from_string("finished"), std::invalid_argument);
  EXPECT_THROW(budget_source_from_string("rank"), std::invalid_argument);
}

}  // namespace
}  // namespace disco
