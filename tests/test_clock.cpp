// disco's one clock (core/util/clock.h): the simulated clock advances by rule and by nothing
// else, a scoped source is put back, and the `clock:` settings are checked.
#include <gtest/gtest.h>

#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/util/clock.h"
#include "core/util/errors.h"

namespace disco {
namespace {

TEST(Clock, TheSimulatedClockAdvancesByItsStepAtEachIterationReportAndOnlyThen) {
  IterationTime time(0.25);
  const ScopedTimeSource clock(time);
  const Clock::time_point t0 = Clock::now();
  EXPECT_EQ(Clock::now(), t0) << "no report, no time";
  EXPECT_EQ(seconds_since(t0), 0.0);
  for (int k = 0; k < 3; ++k) clock_iteration();
  EXPECT_EQ(time.iterations(), 3);
  EXPECT_EQ(seconds_since(t0), 0.75);
  EXPECT_EQ(Clock::now(), after(t0, 0.75));
  EXPECT_LT(after(t0, 0.7), Clock::now());
  EXPECT_GT(after(t0, 0.8), Clock::now());
}

TEST(Clock, AScopedSourceIsPutBackWhenItsScopeEnds) {
  IterationTime outer(1.0), inner(1.0);
  const ScopedTimeSource a(outer);
  {
    const ScopedTimeSource b(inner);
    clock_iteration();
    clock_iteration();
  }
  clock_iteration();
  EXPECT_EQ(inner.iterations(), 2);
  EXPECT_EQ(outer.iterations(), 1);
  EXPECT_EQ(Clock::now().time_since_epoch(), outer.now());
}

TEST(Clock, TheWallClockIgnoresIterationReportsAndNeverGoesBack) {
  // The default source is the machine's: reports leave it alone (its own time goes on).
  IterationTime simulated(1000.0);
  const ScopedTimeSource outside(simulated);
  WallTime wall;
  const ScopedTimeSource clock(wall);
  const Clock::time_point t0 = Clock::now();
  clock_iteration();
  EXPECT_EQ(simulated.iterations(), 0) << "only the installed source hears a report";
  const Clock::time_point t1 = Clock::now();
  EXPECT_LE(t0, t1);
  EXPECT_LT(seconds_since(t0), 1000.0);
}

TEST(Clock, MakeTimeSourceFollowsTheSettings) {
  const auto wall = make_time_source({ClockKind::kWall, 0.5});
  EXPECT_NE(dynamic_cast<WallTime*>(wall.get()), nullptr);
  const auto simulated = make_time_source({ClockKind::kIterations, 0.5});
  auto* it = dynamic_cast<IterationTime*>(simulated.get());
  ASSERT_NE(it, nullptr);
  it->on_iteration();
  it->on_iteration();
  EXPECT_EQ(it->now(), std::chrono::seconds(1));
}

std::string error_of(const Settings& s) {
  try {
    clock_settings(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no exception";
}

TEST(Clock, TheClockSettingsAreReadAndCheckedNamingTheKey) {
  Settings s = Settings::load(default_settings_path());
  const ClockSettings configured = clock_settings(s);
  EXPECT_EQ(configured.kind, ClockKind::kWall) << "configs/disco.yaml: the machine's clock";
  EXPECT_GT(configured.seconds_per_iteration, 0.0);
  s.apply_override("clock.kind=iterations");
  s.apply_override("clock.seconds_per_iteration=0.02");
  const ClockSettings simulated = clock_settings(s);
  EXPECT_EQ(simulated.kind, ClockKind::kIterations);
  EXPECT_EQ(simulated.seconds_per_iteration, 0.02);

  const struct {
    const char* assignment;
    const char* message;
  } cases[] = {
      {"clock.kind=cpu", "--set: key 'clock.kind': must be 'wall' or 'iterations', got 'cpu'"},
      {"clock.seconds_per_iteration=0", "--set: key 'clock.seconds_per_iteration': must be positive"},
      {"clock.seconds_per_iteration=1e-9",
       "--set: key 'clock.seconds_per_iteration': must be finite and at least 1e-6 (seconds)"},
      {"clock.seconds_per_iteration=.inf",
       "--set: key 'clock.seconds_per_iteration': must be finite and at least 1e-6 (seconds)"},
  };
  for (const auto& c : cases) {
    Settings bad = Settings::load(default_settings_path());
    bad.apply_override(c.assignment);
    EXPECT_EQ(error_of(bad), c.message) << c.assignment;
  }
}

}  // namespace
}  // namespace disco
