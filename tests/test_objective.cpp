// The scene file's `objective` (core/model/scene.h, core/model/objective.h): what is read,
// what is refused (each message names file, line and key), and what the model's J is.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "core/model/lower_bound.h"
#include "core/model/objective.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "tests/test_support_messages.h"

namespace disco {
namespace {

using test_support::expect_prefix;
using test_support::scene_error_of;

// One robot moving 10 m along x; `objective` is line 7 when given.
std::string scene_text(const std::string& objective) {
  return "scenario: s\nsteps: 10\n"
         "robots:\n"
         "  - {name: a, radius: 0.5, mass: 1, mu: 0.2, force_max: 5,\n"
         "     start: {x: 0, y: 0}, target: {x: 10, y: 0, vx: 0, vy: 0}}\n"
         "pairs: {mode: avoid}\n" +
         (objective.empty() ? std::string() : "objective: " + objective + "\n");
}

TEST(SceneObjective, TimeIsTheDefaultAndEachKindIsRead) {
  EXPECT_EQ(parse_scene(scene_text(""), "s.yaml").objective.kind, ObjectiveKind::kTime);
  EXPECT_EQ(parse_scene(scene_text("time"), "s.yaml").objective.kind, ObjectiveKind::kTime);
  const Scene e = parse_scene(scene_text("{kind: energy, horizon: 9}"), "s.yaml");
  EXPECT_EQ(e.objective.kind, ObjectiveKind::kEnergy);
  EXPECT_EQ(e.objective.horizon, 9.0);
  EXPECT_EQ(e.objective.energy_weight, 0.0);
  for (const std::string spelling : {"time + energy", "time+energy", "time  +energy"}) {
    const Scene w = parse_scene(scene_text("{kind: " + spelling + ", energy_weight: 0.25}"), "s.yaml");
    EXPECT_EQ(w.objective.kind, ObjectiveKind::kTimeEnergy) << spelling;
    EXPECT_EQ(w.objective.energy_weight, 0.25);
    EXPECT_EQ(w.objective.horizon, 0.0);
  }
  EXPECT_EQ(to_string(ObjectiveKind::kTimeEnergy), "time + energy");
  EXPECT_EQ(objective_unit(ObjectiveKind::kEnergy), "N^2 s");
}

TEST(SceneObjective, BadObjectivesAreErrorsNamingFileLineAndKey) {
  const std::pair<std::string, std::string> cases[] = {
      {"energi",
       "key 'objective': unknown objective 'energi' (did you mean 'energy'?) (allowed: 'time', "
       "'energy', 'time + energy')"},
      {"{kind: speed}",
       "key 'objective.kind': unknown objective 'speed' (allowed: 'time', 'energy', 'time + energy')"},
      {"energy",
       "key 'objective.horizon': is required for objective 'energy' (write objective: {kind: "
       "energy, horizon: ...})"},
      {"{kind: time + energy}",
       "key 'objective.energy_weight': is required for objective 'time + energy' (write "
       "objective: {kind: time + energy, energy_weight: ...})"},
      {"{kind: energy, horizon: 9, energy_weight: 1}",
       "key 'objective.energy_weight': applies to objective 'time + energy' only, not 'energy'"},
      {"{kind: time, horizon: 9}",
       "key 'objective.horizon': applies to objective 'energy' only, not 'time'"},
      {"{kind: energy, horizon: -1}", "key 'objective.horizon': must be > 0 (got -1)"},
      {"{horizon: 9}", "key 'objective.kind': is required but missing"},
      {"{kind: energy, horizon: 9, weight: 1}",
       "key 'objective.weight': unknown key (allowed: kind, horizon, energy_weight)"},
  };
  for (const auto& [objective, message] : cases)
    EXPECT_EQ(scene_error_of(scene_text(objective)), "s.yaml:7: " + message) << objective;
}

// A fixed T_f below the lower bound on T_f (core/model/lower_bound.h) has no solution.
TEST(SceneObjective, AnEnergyHorizonBelowTheLowerBoundIsRefused) {
  const auto lb = scene_lower_bound(parse_scene(scene_text(""), "s.yaml"));
  ASSERT_TRUE(lb && *lb > 1.0) << "10 m at 5 N from rest to rest takes over a second";
  const std::string e = scene_error_of(scene_text("{kind: energy, horizon: 1}"));
  expect_prefix(e, "s.yaml:7: key 'objective.horizon': is below the scene's lower bound on T_f, ",
                "no motion reaches the targets in 1 s");
  char bound[40];
  std::snprintf(bound, sizeof bound, "%.10g s", *lb);
  EXPECT_NE(e.find(bound), std::string::npos) << e;
}

// The bounds the reduction puts on J: time bounds T_f itself; energy bounds the row of J with
// T_f at the scene's horizon; time + energy bounds the row with T_f free.
TEST(SceneObjective, TheReductionBoundsJWhereTheObjectiveSaysAndFreesItAgain) {
  {
    RobotProblem p(parse_scene(scene_text(""), "s.yaml"), ModelOptions{true, 20.0});
    const int T = p.layout().horizon_index();
    p.bound_objective(7.0, false);
    EXPECT_NEAR(p.program().variable_upper()[T] * p.units().time, 7.0, 1e-12);
    p.bound_objective(7.0, true);
    EXPECT_NEAR(p.program().variable_lower()[T] * p.units().time, 7.0, 1e-12);
    p.free_objective();
    EXPECT_NEAR(p.program().variable_upper()[T] * p.units().time, 20.0, 1e-12);
  }
  for (const std::string kind : {"{kind: energy, horizon: 9}", "{kind: time + energy, energy_weight: 0.1}"}) {
    SCOPED_TRACE(kind);
    RobotProblem p(parse_scene(scene_text(kind), "s.yaml"), ModelOptions{true, 20.0});
    const PolynomialProgram& P = p.program();
    const int T = p.layout().horizon_index(), J = P.num_constraints() - 1;
    const bool energy = p.horizon_is_fixed();
    EXPECT_EQ(energy, kind.find("kind: energy") != std::string::npos);
    EXPECT_EQ(P.constraint_upper()[J], kInf) << "J is free until bounded";
    const double T_lo = P.variable_lower()[T], T_hi = P.variable_upper()[T];
    if (energy) {
      EXPECT_NEAR(T_lo * p.units().time, 9.0, 1e-12) << "T_f is the scene's";
      EXPECT_EQ(T_lo, T_hi);
    } else {
      EXPECT_LT(T_lo, T_hi);
    }
    p.bound_objective(3.0, false);
    EXPECT_EQ(P.constraint_lower()[J], -kInf);
    EXPECT_NEAR(P.constraint_upper()[J] * objective_scale(p.objective_kind(), p.units()), 3.0, 1e-12);
    EXPECT_EQ(P.variable_lower()[T], T_lo) << "T_f's bounds stay";
    EXPECT_EQ(P.variable_upper()[T], T_hi);
    p.bound_objective(3.0, true);
    EXPECT_EQ(P.constraint_lower()[J], P.constraint_upper()[J]);
    p.free_objective();
    EXPECT_EQ(P.constraint_upper()[J], kInf);
    EXPECT_EQ(P.variable_upper()[T], T_hi);
  }
}

}  // namespace
}  // namespace disco
