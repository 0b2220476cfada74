// Tests of the scene-adaptive model (core/model/model_plan.h): what it leaves
// out, that what it leaves out is provably idle (on certified solutions of the
// FULL model, which knows nothing of the plan), and that it solves to the same
// T_f.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/model_plan.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "search/solve_scene.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

using model_test::make_robot;
using model_test::make_scene;

Scene scenario(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + name + ".yaml",
                    overrides);
}

Settings settings_with(bool adaptive) {
  Settings s = Settings::load(default_settings_path());
  s.apply_override(std::string("model.adaptive=") + (adaptive ? "true" : "false"));
  return s;
}

// The unknowns of the full model, counted from Appendix A as written: per robot
// and step 6 states, D_ef forces, K + 1 floor-friction multipliers if mu > 0;
// per pair and step a gap, plus c_n, alpha_1, alpha_2, gamma for contact pairs.
int appendix_a_variables(const Scene& s) {
  int per_step = 0;
  for (const Robot& r : s.robots) per_step += 6 + r.force_dims + (r.mu > 0 ? r.friction_edges + 1 : 0);
  for (const Pair& p : s.pairs) per_step += 1 + (p.mode == PairMode::kContact ? 4 : 0);
  return 1 + s.steps * per_step;
}

int count_unknowns(const Layout& L, int pair) {
  int n = 0;
  for (int t = 0; t <= L.steps(); ++t) {
    n += L.gap_index(pair, t) >= 0;
    if (t == L.steps()) break;
    for (int k : {L.normal_multiplier_index(pair, t), L.alpha1_index(pair, t), L.alpha2_index(pair, t),
                  L.contact_gamma_index(pair, t)})
      n += k >= 0;
  }
  return n;
}

TEST(AdaptiveModel, SwitchedOffItIsAppendixAAsWritten) {
  for (const char* name : {"two_robots_swap_avoid", "three_robots_contact", "one_robot_axis"}) {
    const Scene s = scenario(name);
    const RobotProblem full(s, ModelOptions{false, 5.0});
    EXPECT_EQ(full.size().variables, appendix_a_variables(s)) << name;
    for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) EXPECT_TRUE(full.layout().rotates(i));
    // Every row of every family: 3 kinematic and 3 momentum rows per robot and
    // step, a gap row per pair and state, 3 contact-friction rows per contact
    // pair and step, K + 1 floor-friction rows per robot with mu > 0.
    int rows = 0;
    for (const Robot& r : s.robots) rows += 6 + (r.mu > 0 ? r.friction_edges + 1 : 0);
    for (const Pair& p : s.pairs) rows += 1 + (p.mode == PairMode::kContact ? 3 : 0);
    EXPECT_EQ(full.size().constraints, rows * s.steps) << name;
  }
}

TEST(AdaptiveModel, RobotsNothingCanTurnHaveNoOrientationUnknowns) {
  auto rotates = [](Scene s) {
    const RobotProblem rp(s, ModelOptions{true, 3.0});
    std::vector<bool> out;
    for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) {
      const bool r = rp.layout().rotates(i);
      // Either both unknowns exist at every state or neither at any.
      for (int t = 1; t <= s.steps; ++t)
        for (int c : {kPhi, kOmega}) EXPECT_EQ(rp.layout().state_index(i, t, c) >= 0, r);
      // And the constants are the start's orientation and no spin.
      if (!r) {
        EXPECT_EQ(rp.layout().state(i, s.steps, kPhi).value(Vector()), s.robots[i].start[kPhi]);
        EXPECT_EQ(rp.layout().state(i, s.steps, kOmega).value(Vector()), 0.0);
      }
      out.push_back(r);
    }
    return out;
  };
  Robot a = make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0), b = make_robot("b", 0.5, 1.0, 0.2, 5.0, 1.2, 0.0);
  a.start[kPhi] = 0.7;
  // Avoid pairs exert no forces at all.
  EXPECT_EQ(rotates(make_scene("avoid", 8, {a, b}, PairMode::kAvoid)), (std::vector<bool>{false, false}));
  // Contact with friction turns both; frictionless contact turns neither.
  EXPECT_EQ(rotates(make_scene("rub", 8, {a, b}, PairMode::kContact, 0.3)), (std::vector<bool>{true, true}));
  EXPECT_EQ(rotates(make_scene("slip", 8, {a, b}, PairMode::kContact, 0.0)), (std::vector<bool>{false, false}));
  // A start spin (damping slows it), or a target orientation other than the
  // start's, keeps the unknowns.
  Robot spinning = a;
  spinning.start[kOmega] = 0.5;
  EXPECT_EQ(rotates(make_scene("spin", 8, {spinning, b}, PairMode::kAvoid)), (std::vector<bool>{true, false}));
  Robot turn = b;
  turn.target.lower[kPhi] = turn.target.upper[kPhi] = 1.0;
  EXPECT_EQ(rotates(make_scene("turn", 8, {a, turn}, PairMode::kAvoid)), (std::vector<bool>{false, true}));
  Robot keep = b;
  keep.target.lower[kPhi] = -1.0, keep.target.upper[kPhi] = 1.0;  // contains phi^0 = 0
  keep.target.lower[kOmega] = keep.target.upper[kOmega] = 0.0;
  EXPECT_EQ(rotates(make_scene("keep", 8, {a, keep}, PairMode::kAvoid)), (std::vector<bool>{false, false}));
}

TEST(AdaptiveModel, FrictionlessContactPairsHaveOnlyNormalForces) {
  Robot a = make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0), b = make_robot("b", 0.5, 1.0, 0.2, 5.0, 1.0, 0.0);
  const Scene s = make_scene("slip", 6, {a, b}, PairMode::kContact, 0.0);
  const RobotProblem adaptive(s, ModelOptions{true, kInf}), full(s, ModelOptions{false, kInf});
  EXPECT_FALSE(adaptive.layout().has_contact_friction(0));
  EXPECT_TRUE(full.layout().has_contact_friction(0));
  for (int t = 0; t < s.steps; ++t) {
    EXPECT_GE(adaptive.layout().normal_multiplier_index(0, t), 0);
    EXPECT_LT(adaptive.layout().alpha1_index(0, t), 0);
    EXPECT_EQ(adaptive.layout().alpha1(0, t).value(Vector()), 0.0);
  }
  // 3 friction unknowns and 3 rows per step; 2 orientation unknowns, 1
  // kinematic and 1 momentum row per robot and step.
  EXPECT_EQ(full.size().variables - adaptive.size().variables, s.steps * (3 + 2 * 2));
  EXPECT_EQ(full.size().constraints - adaptive.size().constraints, s.steps * (3 + 2 * 2));
  EXPECT_EQ(full.size().complementarity_pairs - adaptive.size().complementarity_pairs, s.steps * 3);
}

// Two robots whose lanes are 100 m apart never meet (contact partners can push
// each other, so their reach is larger: 40 m would be too close to tell); two
// that swap places meet only in the middle of the horizon.
TEST(AdaptiveModel, PairsGetUnknownsOnlyWhereTheyCanMeet) {
  Robot a = make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0), b = make_robot("b", 0.5, 1.0, 0.2, 5.0, 0.0, 100.0);
  for (Robot* r : {&a, &b}) {
    r->target.lower = r->target.upper = {r->start[kX] + 6.0, r->start[kY], 0.0, 0.0, 0.0, 0.0};
    r->target.lower[kPhi] = -kInf, r->target.upper[kPhi] = kInf;
    r->target.lower[kOmega] = -kInf, r->target.upper[kOmega] = kInf;
  }
  for (PairMode mode : {PairMode::kAvoid, PairMode::kContact}) {
    const Scene far = make_scene("far", 30, {a, b}, mode);
    const RobotProblem rp(far, ModelOptions{true, 4.0});  // 1.6 x the one-robot time
    EXPECT_TRUE(rp.plan().pairs[0].empty());
    EXPECT_EQ(count_unknowns(rp.layout(), 0), 0);
  }
  const Scene swap = scenario("two_robots_swap_avoid");
  const RobotProblem rp(swap, ModelOptions{true, 1.5 * 2.2});  // 1.5 x the one-robot time
  const PairPlan w = rp.plan().pairs[0];
  std::printf("swap, T_max 3.3 s: window states %d..%d of 1..%d\n", w.first, w.last, swap.steps);
  EXPECT_GT(w.first, 1);
  EXPECT_LT(w.last, swap.steps);
  EXPECT_EQ(count_unknowns(rp.layout(), 0), w.last - w.first + 1);
  // Far from the origin the reach test must neither overflow nor lose the gap
  // to rounding: a swap across 1e160 m still has its crossing window (it was
  // once pruned: |d|^2 overflowed to Inf).
  const Scene huge = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/stress/overflow.yaml");
  RobotProblem far_rp(huge, ModelOptions{true, kInf});
  far_rp.set_horizon_max(*far_rp.reference_time() * 1.5);
  EXPECT_FALSE(far_rp.plan().pairs[0].empty());
  EXPECT_GT(far_rp.plan().pairs[0].first, 1);
  // No window at all without a horizon bound.
  EXPECT_EQ(RobotProblem(swap, ModelOptions{true, kInf}).plan().pairs[0].first, 1);
}

// A contact pair's gap is >= 0 at every kept state, the first of its window
// too (there it is no side of a complementarity pair, and its row alone would
// admit rho + R = -|d|).
TEST(AdaptiveModel, ContactGapsAreNonnegativeAtEveryKeptState) {
  const Scene s = scenario("three_robots_contact", {"steps=30"});
  const RobotProblem rp(s, ModelOptions{true, 3.0});
  const Layout& L = rp.layout();
  int late = 0;
  for (int p = 0; p < static_cast<int>(s.pairs.size()); ++p) {
    const PairPlan& w = rp.plan().pairs[p];
    late += w.first > 1 && !w.empty();
    for (int t = 1; t <= s.steps; ++t) {
      if (L.gap_index(p, t) >= 0) {
        EXPECT_EQ(rp.program().variable_lower()[L.gap_index(p, t)], 0.0) << p << " " << t;
      }
    }
  }
  EXPECT_GT(late, 0);  // some window starts late: its first gap is the case in point
}

// The speed bounds and windows are proofs about the model: check them on
// certified solutions of the full model, which has every gap at every step.
// Where the plan leaves a pair out, the solution's robots must be apart.
void expect_plan_holds_on_full_solution(const Scene& scene) {
  SCOPED_TRACE(scene.name);
  const SceneSolve full = solve_scene(scene, settings_with(false));
  ASSERT_TRUE(full.solved());
  const RobotProblem& rp = *full.problem;
  EXPECT_FALSE(rp.options().adaptive);
  const Layout& L = rp.layout();
  const Scene& ms = L.model_scene();  // model units
  const int N = ms.steps;
  const double T_max = rp.options().horizon_max / rp.units().time;  // the feasibility horizon
  const double h = full.z[L.horizon_index()] / N;
  // 1. Speeds within the bounds for the solution's own step.
  const auto u = speed_bounds(ms, h);
  double tightest = 0.0;
  for (int i = 0; i < static_cast<int>(ms.robots.size()); ++i)
    for (int t = 0; t <= N; ++t) {
      const double v = std::hypot(L.state(i, t, kVx).value(full.z), L.state(i, t, kVy).value(full.z));
      EXPECT_LE(v, u[i][t] * (1 + 1e-6) + 1e-9) << "robot " << i << " state " << t;
      tightest = std::max(tightest, v / u[i][t]);
    }
  // 2. Outside each window of the plan for T_max, the pair is out of reach.
  const ModelPlan plan = plan_model(ms, true, T_max);
  int left_out = 0;
  for (int p = 0; p < static_cast<int>(ms.pairs.size()); ++p) {
    const Pair& pr = ms.pairs[p];
    const double reach = ms.robots[pr.i].radius + ms.robots[pr.j].radius +
                         (pr.mode == PairMode::kAvoid ? pr.safe_distance : 0.0);
    for (int t = 1; t <= N; ++t) {
      if (t >= plan.pairs[p].first && t <= plan.pairs[p].last) continue;
      ++left_out;
      const double o = std::hypot(L.normal(p, t, 0).value(full.z), L.normal(p, t, 1).value(full.z));
      EXPECT_GT(o, reach) << "pair " << p << " state " << t;
    }
  }
  std::printf("%s: T_f %.6f s, largest speed / bound %.3f, %d pair states left out of %d\n",
              scene.name.c_str(), full.T_f(), tightest, left_out,
              N * static_cast<int>(ms.pairs.size()));
  EXPECT_GT(left_out, 0);  // the check checked something
}

TEST(AdaptiveModel, WhatItLeavesOutIsIdleInFullModelSolutions) {
  expect_plan_holds_on_full_solution(scenario("two_robots_swap_avoid", {"steps=25"}));
  expect_plan_holds_on_full_solution(scenario("three_robots_contact", {"steps=20"}));
}

// The adaptive model solves the full model with T_f <= T_max: its answers,
// carried over to the full model (RobotProblem::transfer), are certified there.
// A one-robot scene (nothing but orientation left out) reaches the same T_f.
TEST(AdaptiveModel, ItsAnswersAreCertifiedAnswersOfTheFullModel) {
  const Settings settings = settings_with(true);
  const ElasticSettings tol = elastic_settings(settings);
  for (const Scene& scene : {scenario("two_robots_swap_avoid", {"steps=25"}),
                             scenario("three_robots_contact", {"steps=20"})}) {
    const SceneSolve adaptive = solve_scene(scene, settings);
    ASSERT_TRUE(adaptive.solved()) << scene.name;
    const RobotProblem& rp = *adaptive.problem;
    const RobotProblem full(scene, ModelOptions{false, rp.options().horizon_max});
    EXPECT_LT(rp.size().variables, full.size().variables);
    const Vector z = rp.transfer(adaptive.z, full);
    const Certificate c = certify(full.program(), z);
    std::printf("%s: T_f %.6f s; %d of %d variables; on the full model: violation %.1e, "
                "complementarity %.1e\n",
                scene.name.c_str(), adaptive.T_f(), rp.size().variables, full.size().variables,
                c.max_violation, c.max_complementarity);
    EXPECT_TRUE(c.within(tol.violation_tol, tol.complementarity_tol)) << scene.name;
    EXPECT_EQ(full.horizon(z), adaptive.T_f());
    // The reported certificate covers the full model's.
    EXPECT_GE(adaptive.info.certificate.max_violation, c.max_violation);
  }
  const Scene one = scenario("one_robot_diagonal", {"steps=25"});
  const SceneSolve a = solve_scene(one, settings), f = solve_scene(one, settings_with(false));
  ASSERT_TRUE(a.solved() && f.solved());
  EXPECT_NEAR(a.T_f(), f.T_f(), 1e-6 * f.T_f());
}

}  // namespace
}  // namespace disco
