// The starts of the multi-start search (search/start.h): deterministic
// parameters within their ranges, start 0 = what `disco solve` runs, detours
// only where straight paths conflict and on the requested side, perturbed
// guesses that keep the start and the target, perturbed feasible starts that
// re-time a feasible point with consistent kinematics, and a detour start that
// the objective reduction turns into a certified solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "search/guess.h"
#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/lower_bound.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "search/objective_reduction.h"
#include "search/start.h"
#include "test_support_start.h"

namespace disco {
namespace {

Scene scenario(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + name + ".yaml",
                    overrides);
}

// Robots whose straight paths never come close: two parallel moves 3 m apart
// (one with force_dims 1 along x), and one that does not move (no target).
constexpr const char* kApartScene = R"(
scenario: apart
steps: 20
defaults: {radius: 0.5, mass: 1.0, mu: 0.2, force_max: 5.0, K: 8}
robots:
  - name: a
    start: {x: 0, y: 0}
    target: {x: 4, y: 0, vx: 0, vy: 0}
  - name: b
    start: {x: 0, y: 3}
    target: {x: 4, y: 3, vx: 0, vy: 0}
    force_dims: 1
    force_axis: [1, 0]
  - name: c
    start: {x: -2, y: 8, phi: 0.5}
pairs: {mode: avoid, safe_distance: 0.01}
)";

Scene apart_scene() { return parse_scene(kApartScene, "apart"); }

ReductionSettings base_schedule() {
  ReductionSettings r;  // not the defaults, so that "kept from the base" is visible
  r.horizon_factor = 1.7;
  r.horizon_min = 0.25;
  r.rate = 0.04;
  r.grow = 1.3;
  r.shrink = 0.6;
  r.min_rate = 0.003;
  r.max_solves = 7;
  r.step_iterations = 123;
  r.time_limit = 42.0;
  return r;
}

ElasticSettings base_elastic() {
  ElasticSettings e;
  e.formulation = ElasticFormulation::kPerPair;
  e.zeta = 3.0;
  e.zeta_factor = 7.0;
  e.zeta_max = 1e5;
  e.stall_change = 2e-3;
  e.complementarity_tol = 1e-7;
  e.violation_tol = 2e-7;
  e.polish = false;
  return e;
}

bool same_schedule(const ReductionSettings& a, const ReductionSettings& b) {
  return a.horizon_factor == b.horizon_factor && a.horizon_min == b.horizon_min &&
         a.rate == b.rate && a.grow == b.grow && a.shrink == b.shrink &&
         a.min_rate == b.min_rate && a.max_solves == b.max_solves &&
         a.step_iterations == b.step_iterations &&
         a.segment_iterations == b.segment_iterations && a.time_limit == b.time_limit;
}

bool same_elastic(const ElasticSettings& a, const ElasticSettings& b) {
  return a.formulation == b.formulation && a.zeta == b.zeta && a.zeta_factor == b.zeta_factor &&
         a.zeta_max == b.zeta_max && a.stall_change == b.stall_change &&
         a.complementarity_tol == b.complementarity_tol && a.violation_tol == b.violation_tol &&
         a.polish == b.polish;
}

bool same_spec(const StartSpec& a, const StartSpec& b) {
  return a.index == b.index && a.seed == b.seed && a.guess == b.guess &&
         a.detour_side == b.detour_side && a.perturbation == b.perturbation &&
         a.T_scale == b.T_scale && a.margin == b.margin && same_schedule(a.schedule, b.schedule) && same_elastic(a.elastic, b.elastic);
}

bool bitwise_equal(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// Position (SI) of robot i at state t of a guess; t = 0 is the scene's start.
std::array<double, 2> position(const RobotProblem& rp, const Vector& z, int i, int t) {
  if (t == 0) return {rp.scene().robots[i].start[kX], rp.scene().robots[i].start[kY]};
  const double L = rp.units().length;
  return {rp.layout().state(i, t, kX).value(z) * L, rp.layout().state(i, t, kY).value(z) * L};
}

double min_centre_distance(const RobotProblem& rp, const Vector& z, int i, int j) {
  double d = kInf;
  for (int t = 0; t <= rp.scene().steps; ++t) {
    const auto a = position(rp, z, i, t), b = position(rp, z, j, t);
    d = std::min(d, std::hypot(b[0] - a[0], b[1] - a[1]));
  }
  return d;
}

StartSpec find_start(const Scene& scene, GuessKind kind, int side = 0, std::uint64_t seed = 7) {
  return start_test::first_start_of(scene, seed, kind, side, base_schedule(), base_elastic());
}

bool all_finite(const Vector& z) { return z.allFinite(); }

TEST(Start, SameInputsGiveTheSameStartAndTheSameGuessBitwise) {
  for (const Scene& scene : {scenario("two_robots_swap_avoid"), scenario("three_robots_contact"),
                             apart_scene()}) {
    const RobotProblem rp(scene);
    for (int index = 0; index < 9; ++index) {
      const StartSpec a = make_start(scene, 12345, index, base_schedule(), base_elastic());
      const StartSpec b = make_start(scene, 12345, index, base_schedule(), base_elastic());
      EXPECT_TRUE(same_spec(a, b)) << scene.name << " " << a.describe();
      EXPECT_EQ(a.describe(), b.describe());
      const Vector za = make_guess(rp, a, 3.3), zb = make_guess(rp, b, 3.3);
      EXPECT_TRUE(bitwise_equal(za, zb)) << scene.name << " " << a.describe();
      EXPECT_TRUE(all_finite(za)) << scene.name << " " << a.describe();
    }
  }
}

TEST(Start, DifferentSeedIndexOrSceneGiveDifferentParameters) {
  const Scene scene = scenario("two_robots_swap_avoid");
  Scene renamed = scene;
  renamed.name = "other_name";
  const StartSpec a = make_start(scene, 1, 4, base_schedule(), base_elastic());
  const StartSpec seed = make_start(scene, 2, 4, base_schedule(), base_elastic());
  const StartSpec index = make_start(scene, 1, 9, base_schedule(), base_elastic());
  const StartSpec name = make_start(renamed, 1, 4, base_schedule(), base_elastic());
  for (const StartSpec* o : {&seed, &index, &name}) {
    EXPECT_NE(a.schedule.horizon_factor, o->schedule.horizon_factor) << o->describe();
    EXPECT_NE(a.schedule.rate, o->schedule.rate) << o->describe();
    EXPECT_NE(a.schedule.grow, o->schedule.grow) << o->describe();
    EXPECT_NE(a.schedule.shrink, o->schedule.shrink) << o->describe();
    EXPECT_NE(a.schedule.min_rate, o->schedule.min_rate) << o->describe();
  }
  // Perturbed guesses of different seeds differ too (start 4 is perturbed).
  ASSERT_EQ(a.guess, GuessKind::kPerturbed);
  ASSERT_EQ(seed.guess, GuessKind::kPerturbed);
  const RobotProblem rp(scene);
  StartSpec same_amplitude = seed;
  same_amplitude.perturbation = a.perturbation;
  EXPECT_FALSE(bitwise_equal(make_guess(rp, a, 3.0), make_guess(rp, same_amplitude, 3.0)));
}

TEST(Start, IndexZeroIsTheBaseSettingsAndTheStraightGuess) {
  for (const Scene& scene : {scenario("two_robots_swap_avoid"), apart_scene()}) {
    const StartSpec s = make_start(scene, 99, 0, base_schedule(), base_elastic());
    EXPECT_EQ(s.index, 0);
    EXPECT_EQ(s.seed, 99u);
    EXPECT_EQ(s.guess, GuessKind::kStraight);
    EXPECT_EQ(s.detour_side, 0);
    EXPECT_EQ(s.perturbation, 0.0);
    EXPECT_EQ(s.T_scale, 1.0);
    EXPECT_TRUE(same_schedule(s.schedule, base_schedule()));
    EXPECT_TRUE(same_elastic(s.elastic, base_elastic()));
    const RobotProblem rp(scene);
    for (double T : {1.0, 4.56})
      EXPECT_TRUE(bitwise_equal(make_guess(rp, s, T), smoothstep_guess(rp, T))) << T;
    EXPECT_EQ(s.describe(),
              "start 0: straight, horizon x1.70, rate 0.040, grow 1.30, shrink 0.60, min rate 0.0030, "
              "zeta 3");
  }
}

// The horizons of the feasibility phase of `start` (objective_reduction.h, step 1).
std::vector<double> feasibility_horizons(const RobotProblem& rp, const StartSpec& start) {
  double T = start.schedule.horizon_min;
  if (const auto ref = rp.reference_time()) T = std::max(T, start.schedule.horizon_factor * *ref);
  return {T, 2 * T, 4 * T};
}

// Can some robot not follow the smoothstep at horizon T, though some timing would do?
// Its largest acceleration 6 L / T^2 beats the robot's a_1 = (push - friction) / M, and T
// is at least the robot's minimum time (both from the scene, core/model/lower_bound.h).
bool some_robot_too_weak_for_the_smoothstep(const Scene& scene, double T) {
  for (const Robot& rb : scene.robots) {
    const auto m = straight_move_limits(rb, scene.gravity);
    if (!m || m->distance == 0.0) continue;
    const double a1 = (m->push - m->friction) / rb.mass, a2 = (m->push + m->friction) / rb.mass;
    if (a1 > 0 && 6 * m->distance / (T * T) > a1 &&
        T >= bang_bang_time(m->distance, a1, a2, m->stop_at_end))
      return true;
  }
  return false;
}

TEST(Start, TheStraightGuessFollowsWhatTheRobotsCanDo) {
  const Settings settings = Settings::load(default_settings_path());
  const std::string dir = std::string(DISCO_SOURCE_DIR) + "/configs/";
  int changed = 0;
  for (const char* name :
       {"scenarios/one_robot_axis", "scenarios/one_robot_diagonal", "scenarios/two_robots_swap_avoid",
        "scenarios/three_robots_contact", "scenarios/paper/A1", "scenarios/paper/A2",
        "scenarios/paper/A3", "scenarios/paper/A4", "scenarios/paper/B1", "scenarios/paper/B2",
        "scenarios/paper/B3", "stress/weak_force"}) {
    const Scene scene = load_scene(dir + name + ".yaml");
    RobotProblem rp(scene);
    const StartSpec s =
        make_start(scene, 1, 0, reduction_settings(settings), elastic_settings(settings));
    for (double T : feasibility_horizons(rp, s)) {
      SCOPED_TRACE(std::string(name) + " at " + std::to_string(T) + " s");
      const Vector guess = make_guess(rp, s, T), smooth = smoothstep_guess(rp, T);
      if (!some_robot_too_weak_for_the_smoothstep(scene, T)) {
        EXPECT_TRUE(bitwise_equal(guess, smooth));  // as before
        continue;
      }
      ++changed;
      EXPECT_FALSE(bitwise_equal(guess, smooth));
      if (scene.robots.size() != 1) continue;
      // Alone, a robot on its own timing satisfies the whole model (kinematics, dynamics,
      // friction, target); on the smoothstep, clipped forces break the momentum rows.
      rp.fix_horizon(T);
      const double own = certify(rp.program(), guess).max_violation;
      const double smoothstep = certify(rp.program(), smooth).max_violation;
      std::printf("%s at %.3f s: violation %.1e (own timing), %.1e (smoothstep)\n", name, T, own,
                  smoothstep);
      EXPECT_LE(own, 1e-9);
      EXPECT_GT(smoothstep, 1e-3);
    }
  }
  // weak_force (F_max = 1.001 mu M g) and the paper's robots (push < 2 friction) at least.
  EXPECT_GE(changed, 2);
}

TEST(Start, ParametersStayInTheirRangesAndOtherFieldsAreKept) {
  const Scene scene = scenario("two_robots_swap_avoid");
  std::set<double> zetas;
  int perturbed = 0, left = 0, right = 0, feasible = 0, yield = 0;
  double min_rate_lo = 1.0, min_rate_hi = 0.0, scale_lo = 2.0, scale_hi = 0.0;
  double margin_lo = 2.0, margin_hi = 0.0;
  for (int index = 1; index <= 200; ++index) {
    const StartSpec s = make_start(scene, 2026, index, base_schedule(), base_elastic());
    SCOPED_TRACE(s.describe());
    EXPECT_EQ(s.index, index);
    EXPECT_EQ(s.seed, 2026u);
    EXPECT_GE(s.schedule.horizon_factor, 1.2);
    EXPECT_LE(s.schedule.horizon_factor, 3.0);
    EXPECT_GE(s.schedule.rate, 0.02);
    EXPECT_LE(s.schedule.rate, 0.2);
    EXPECT_GE(s.schedule.grow, 1.2);
    EXPECT_LE(s.schedule.grow, 2.0);
    EXPECT_GE(s.schedule.shrink, 0.3);
    EXPECT_LE(s.schedule.shrink, 0.7);
    EXPECT_TRUE(s.elastic.zeta == 1.0 || s.elastic.zeta == 10.0 || s.elastic.zeta == 100.0);
    zetas.insert(s.elastic.zeta);
    EXPECT_GE(s.schedule.min_rate, 0.005);
    EXPECT_LE(s.schedule.min_rate, 0.02);
    EXPECT_LT(s.schedule.min_rate, s.schedule.rate);
    min_rate_lo = std::min(min_rate_lo, s.schedule.min_rate);
    min_rate_hi = std::max(min_rate_hi, s.schedule.min_rate);
    // Everything else is the base.
    ReductionSettings r = s.schedule;
    r.horizon_factor = base_schedule().horizon_factor;
    r.rate = base_schedule().rate;
    r.grow = base_schedule().grow;
    r.shrink = base_schedule().shrink;
    r.min_rate = base_schedule().min_rate;
    EXPECT_TRUE(same_schedule(r, base_schedule()));
    ElasticSettings e = s.elastic;
    e.zeta = base_elastic().zeta;
    EXPECT_TRUE(same_elastic(e, base_elastic()));
    // The kinds cycle: detour left, detour right, yield, perturbed, perturbed feasible.
    const int slot = (index - 1) % 5;
    if (slot != 2) {
      EXPECT_EQ(s.margin, 1.0);
    }
    if (slot == 2) {
      EXPECT_EQ(s.guess, GuessKind::kYield);
      EXPECT_GE(s.margin, 1.0);
      EXPECT_LE(s.margin, 1.5);
      margin_lo = std::min(margin_lo, s.margin);
      margin_hi = std::max(margin_hi, s.margin);
      EXPECT_EQ(s.perturbation, 0.0);
      EXPECT_EQ(s.detour_side, 0);
      EXPECT_EQ(s.T_scale, 1.0);
      EXPECT_NE(s.describe().find("yield margin"), std::string::npos);
      ++yield;
    } else if (slot == 3) {
      EXPECT_EQ(s.guess, GuessKind::kPerturbed);
      EXPECT_GE(s.perturbation, 0.05);
      EXPECT_LE(s.perturbation, 0.3);
      EXPECT_EQ(s.detour_side, 0);
      EXPECT_EQ(s.T_scale, 1.0);
      ++perturbed;
    } else if (slot == 4) {
      EXPECT_EQ(s.guess, GuessKind::kPerturbedFeasible);
      EXPECT_GE(s.perturbation, 0.05);
      EXPECT_LE(s.perturbation, 0.3);
      EXPECT_EQ(s.detour_side, 0);
      EXPECT_GE(s.T_scale, 0.8);
      EXPECT_LE(s.T_scale, 1.0);
      scale_lo = std::min(scale_lo, s.T_scale);
      scale_hi = std::max(scale_hi, s.T_scale);
      EXPECT_NE(s.describe().find("perturbed feasible"), std::string::npos);
      EXPECT_NE(s.describe().find(", T x"), std::string::npos);
      ++feasible;
    } else {
      EXPECT_EQ(s.guess, GuessKind::kDetour);
      EXPECT_EQ(s.detour_side, slot == 0 ? +1 : -1);
      EXPECT_EQ(s.perturbation, 0.0);
      EXPECT_EQ(s.T_scale, 1.0);
      EXPECT_NE(s.describe().find(slot == 0 ? "detour left" : "detour right"), std::string::npos);
      (slot == 0 ? left : right)++;
    }
  }
  EXPECT_EQ(zetas.size(), 3u);
  EXPECT_EQ(perturbed, 40);
  EXPECT_EQ(feasible, 40);
  EXPECT_EQ(left, 40);
  EXPECT_EQ(right, 40);
  EXPECT_EQ(yield, 40);
  // The draws cover their ranges.
  EXPECT_LT(min_rate_lo, 0.007);
  EXPECT_GT(min_rate_hi, 0.018);
  EXPECT_LT(scale_lo, 0.83);
  EXPECT_GT(scale_hi, 0.97);
  EXPECT_LT(margin_lo, 1.03);
  EXPECT_GT(margin_hi, 1.47);
}

TEST(Start, WithoutConflictsPerturbedAndPerturbedFeasibleAlternate) {
  const Scene scene = apart_scene();
  for (int index = 1; index <= 40; ++index) {
    const StartSpec s = make_start(scene, 5, index, base_schedule(), base_elastic());
    EXPECT_EQ(s.guess, (index - 1) % 2 == 0 ? GuessKind::kPerturbed
                                             : GuessKind::kPerturbedFeasible)
        << s.describe();
  }
}

TEST(Start, NewDrawsKeepTheEarlierParameters) {
  // Start 5 of two_robots_swap_avoid under seed 1, as drawn before min_rate,
  // T_scale and margin were appended to the stream: unchanged (it was a
  // perturbed start then, a perturbed feasible one since the yield kind).
  const StartSpec s = make_start(scenario("two_robots_swap_avoid"), 1, 5, base_schedule(),
                                 base_elastic());
  EXPECT_EQ(s.guess, GuessKind::kPerturbedFeasible);
  EXPECT_EQ(s.schedule.horizon_factor, 0x1.0246a53d7bccdp+1);
  EXPECT_EQ(s.schedule.rate, 0x1.766c556b2c01ap-3);
  EXPECT_EQ(s.schedule.grow, 0x1.ee9b7d1398238p+0);
  EXPECT_EQ(s.schedule.shrink, 0x1.03ed8c7cda43bp-1);
  EXPECT_EQ(s.perturbation, 0x1.b0a3863dc752cp-3);
  EXPECT_EQ(s.elastic.zeta, 1.0);
}

TEST(Start, DetourOnlyWhenStraightPathsConflict) {
  auto detours = [](const Scene& scene) {
    int n = 0;
    for (int index = 1; index <= 40; ++index)
      n += make_start(scene, 5, index, base_schedule(), base_elastic()).guess == GuessKind::kDetour;
    return n;
  };
  EXPECT_EQ(detours(scenario("two_robots_swap_avoid")), 16);
  EXPECT_EQ(detours(scenario("three_robots_contact")), 16);
  EXPECT_EQ(detours(apart_scene()), 0);
  // Moved 1.02 m apart (> R_i + R_j + d_s = 1.01), the swap no longer conflicts.
  EXPECT_EQ(detours(scenario("two_robots_swap_avoid", {"robots.0.start.y=0.51",
                                                       "robots.0.target.y=0.51",
                                                       "robots.1.start.y=-0.51",
                                                       "robots.1.target.y=-0.51"})),
            0);
  // 1.0 m apart conflicts only through the safe distance of an avoid pair.
  EXPECT_EQ(detours(scenario("two_robots_swap_avoid", {"robots.0.start.y=0.5",
                                                       "robots.0.target.y=0.5",
                                                       "robots.1.start.y=-0.5",
                                                       "robots.1.target.y=-0.5"})),
            16);
}

TEST(Start, YieldingRobotsWaitUntilTheWayIsClear) {
  // Paper B1: two robots whose straight diagonals cross at the same time. In a
  // yield guess one of them waits at its start (it has not moved after the
  // first step), the other leaves at once, and the pair stays at least
  // `margin` clearances apart at every step; the ends are the straight ones.
  const Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/paper/B1.yaml");
  const RobotProblem rp(scene);
  const double T = 12.0;
  const Vector straight = smoothstep_guess(rp, T);
  const double clearance = scene.robots[0].radius + scene.robots[1].radius;
  ASSERT_LT(min_centre_distance(rp, straight, 0, 1), clearance);
  int waited[2] = {0, 0};
  // Under three seeds, the first two yield starts (indices 3 and 8; m = 0 and 1).
  for (int k = 0; k < 6; ++k) {
    const StartSpec s = make_start(scene, 1 + k / 2, k % 2 == 0 ? 3 : 8, base_schedule(),
                                   base_elastic());
    ASSERT_EQ(s.guess, GuessKind::kYield) << s.describe();
    const Vector z = make_guess(rp, s, T);
    ASSERT_TRUE(all_finite(z));
    EXPECT_GE(min_centre_distance(rp, z, 0, 1), s.margin * clearance * (1 - 1e-3)) << s.describe();
    int waiting = 0;
    for (int i = 0; i < 2; ++i) {
      const auto start = position(rp, z, i, 0), first = position(rp, z, i, 1);
      if (std::hypot(first[0] - start[0], first[1] - start[1]) < 1e-12) {
        ++waiting;
        ++waited[i];
      }
      const auto end = position(rp, z, i, scene.steps), goal = position(rp, straight, i, scene.steps);
      EXPECT_NEAR(end[0], goal[0], 1e-12);
      EXPECT_NEAR(end[1], goal[1], 1e-12);
    }
    EXPECT_EQ(waiting, 1) << s.describe();
  }
  // One conflicting pair: the first yield start lets robot 0 go first (robot 1 waits), the
  // second robot 1, under every seed.
  EXPECT_EQ(waited[0], 3);
  EXPECT_EQ(waited[1], 3);
}

TEST(Start, YieldStartsTakeEveryOrderOfTheConflictingPairsInTurn) {
  // One conflicting pair (0, 1): 0 first, then 1 first, then again.
  const Scene swap = scenario("two_robots_swap_avoid");
  ASSERT_EQ(conflicts(swap).size(), 1u);
  EXPECT_EQ(yield_order(swap, 0), (std::vector<int>{0, 1}));
  EXPECT_EQ(yield_order(swap, 1), (std::vector<int>{1, 0}));
  EXPECT_EQ(yield_order(swap, 2), (std::vector<int>{0, 1}));
  // three_robots_contact: east-west (0.4 m apart), east-north (through the origin together)
  // and west-north (0.4 m) all conflict. Of the 2^3 first-in-each-pair patterns, the two
  // cyclic ones (0 before 1 before 2 before 0, and its reverse) have no order; the other
  // six are the six orders of three robots, each once, then the cycle repeats.
  const Scene three = scenario("three_robots_contact");
  ASSERT_EQ(conflicts(three).size(), 3u);
  std::set<std::vector<int>> seen;
  for (int m = 0; m < 6; ++m) {
    const std::vector<int> order = yield_order(three, m);
    ASSERT_EQ(order.size(), 3u);
    EXPECT_TRUE(std::is_permutation(order.begin(), order.end(), std::vector<int>{0, 1, 2}.begin()));
    seen.insert(order);
  }
  EXPECT_EQ(seen.size(), 6u);
  EXPECT_EQ(yield_order(three, 6), yield_order(three, 0));
  // The starts carry them: the m-th yield start (index 3 + 5 m) takes order m, and says so.
  for (int m = 0; m < 4; ++m) {
    const StartSpec s = make_start(three, 9, 3 + 5 * m, base_schedule(), base_elastic());
    ASSERT_EQ(s.guess, GuessKind::kYield);
    EXPECT_EQ(s.yield_order, yield_order(three, m));
    EXPECT_NE(s.describe().find(", order "), std::string::npos) << s.describe();
  }
  // No conflict, or more than kEnumeratedPairs: none (the order is drawn).
  EXPECT_TRUE(yield_order(apart_scene(), 0).empty());
  const Scene a3 = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/paper/A3.yaml");
  ASSERT_GT(conflicts(a3).size(), static_cast<std::size_t>(kEnumeratedPairs));
  EXPECT_TRUE(yield_order(a3, 0).empty());
  EXPECT_TRUE(make_start(a3, 9, 3, base_schedule(), base_elastic()).yield_order.empty());
}

TEST(Start, DetoursSeparateTheRobotsOnMirrorImageSides) {
  const Scene scene = scenario("two_robots_swap_avoid");
  const RobotProblem rp(scene);
  const double T = 4.0;
  const Vector straight = smoothstep_guess(rp, T);
  const StartSpec left = find_start(scene, GuessKind::kDetour, +1);
  const StartSpec right = find_start(scene, GuessKind::kDetour, -1);
  const Vector zl = make_guess(rp, left, T), zr = make_guess(rp, right, T);
  ASSERT_TRUE(all_finite(zl));
  ASSERT_TRUE(all_finite(zr));
  const double d0 = min_centre_distance(rp, straight, 0, 1);
  const double dl = min_centre_distance(rp, zl, 0, 1), dr = min_centre_distance(rp, zr, 0, 1);
  std::printf("swap: min centre distance straight %.3f, left %.3f, right %.3f m\n", d0, dl, dr);
  EXPECT_LT(d0, 1.01);
  EXPECT_GT(dl, d0);
  EXPECT_GT(dr, d0);
  EXPECT_GE(dl, 1.01);  // the bump (R_i + R_j + d_s each, opposite) clears the pair
  EXPECT_GE(dr, 1.01);
  // Mirror images: the offsets from the straight guess are opposite, and large.
  double largest = 0.0;
  for (int i = 0; i < 2; ++i)
    for (int t = 0; t <= scene.steps; ++t) {
      const auto s = position(rp, straight, i, t), l = position(rp, zl, i, t),
                 r = position(rp, zr, i, t);
      for (int c = 0; c < 2; ++c) {
        EXPECT_NEAR(l[c] - s[c], -(r[c] - s[c]), 1e-12) << "robot " << i << " t " << t;
        largest = std::max(largest, std::abs(l[c] - s[c]));
      }
    }
  EXPECT_GT(largest, 0.9);
  // Left: each robot keeps the other on its left. Robot 0 moves +x, so robot 1
  // passes above it (y_1 > y_0) half way; right: below.
  const int mid = scene.steps / 2;
  EXPECT_GT(position(rp, zl, 1, mid)[1], position(rp, zl, 0, mid)[1]);
  EXPECT_LT(position(rp, zr, 1, mid)[1], position(rp, zr, 0, mid)[1]);
  // End points: the targets.
  for (const Vector* z : {&zl, &zr})
    for (int i = 0; i < 2; ++i) {
      const auto e = position(rp, *z, i, scene.steps);
      EXPECT_NEAR(e[0], scene.robots[i].target.lower[kX], 1e-12);
      EXPECT_NEAR(e[1], scene.robots[i].target.lower[kY], 1e-12);
    }
}

TEST(Start, DetoursWidenTheClosestApproachOfEveryConflictingPair) {
  const Scene scene = scenario("three_robots_contact");
  const RobotProblem rp(scene);
  const Vector straight = smoothstep_guess(rp, 5.0);
  for (int side : {+1, -1}) {
    const Vector z = make_guess(rp, find_start(scene, GuessKind::kDetour, side), 5.0);
    ASSERT_TRUE(all_finite(z));
    double before = kInf, after = kInf;
    for (const Pair& p : scene.pairs) {
      before = std::min(before, min_centre_distance(rp, straight, p.i, p.j));
      after = std::min(after, min_centre_distance(rp, z, p.i, p.j));
    }
    std::printf("three robots, side %+d: closest approach straight %.3f, detour %.3f m\n", side,
                before, after);
    EXPECT_GT(after, before);
  }
}

TEST(Start, PerturbedGuessesDifferFromStraightButKeepStartAndTarget) {
  for (const Scene& scene : {scenario("two_robots_swap_avoid"), scenario("three_robots_contact"),
                             apart_scene()}) {
    const RobotProblem rp(scene);
    const Layout& lay = rp.layout();
    const Scene& ms = lay.model_scene();  // model units
    const double T = 3.5, h = T / rp.units().time / scene.steps;
    const Vector straight = smoothstep_guess(rp, T);
    for (int k = 0; k < 3; ++k) {
      const StartSpec s = find_start(scene, GuessKind::kPerturbed, 0, 100 + k);
      SCOPED_TRACE(scene.name + ": " + s.describe());
      const Vector z = make_guess(rp, s, T);
      ASSERT_TRUE(all_finite(z));
      ASSERT_EQ(z.size(), straight.size());
      EXPECT_EQ(z[lay.horizon_index()], straight[lay.horizon_index()]);
      for (int i = 0; i < static_cast<int>(ms.robots.size()); ++i) {
        const Robot& rb = ms.robots[i];
        // Moved away from the straight path somewhere, by a fair fraction of
        // the perturbation's scale (path length, or radius if not moving).
        State goal = rb.start;
        for (int c : {kX, kY, kPhi})
          goal[c] = std::clamp(rb.start[c], rb.target.lower[c], rb.target.upper[c]);
        const double scale =
            std::max(rb.radius, std::hypot(goal[kX] - rb.start[kX], goal[kY] - rb.start[kY]));
        double moved = 0.0;
        for (int t = 1; t < scene.steps; ++t)
          for (int c : {kX, kY})
            moved = std::max(moved, std::abs(lay.state(i, t, c).value(z) -
                                             lay.state(i, t, c).value(straight)));
        EXPECT_GT(moved, 0.01 * s.perturbation * scale) << "robot " << i;
        // The start is exact: the first velocity is measured from it.
        for (int c : {kX, kY, kPhi}) {
          const int v = c == kX ? kVx : c == kY ? kVy : kOmega;
          EXPECT_EQ(lay.state(i, 1, v).value(z), (lay.state(i, 1, c).value(z) - rb.start[c]) / h);
        }
        // The end is the nearest target point (the start where the target is free).
        for (int c : {kX, kY, kPhi})
          EXPECT_NEAR(lay.state(i, scene.steps, c).value(z), goal[c],
                      1e-12 * (1.0 + std::abs(goal[c])))
              << "robot " << i << " component " << c;
        // A force_dims 1 robot stays on its axis line (robot b of the apart scene).
        if (rb.force_dims == 1) {
          for (int t = 1; t <= scene.steps; ++t)
            EXPECT_NEAR(lay.state(i, t, kY).value(z), rb.start[kY], 1e-12);
        }
      }
    }
  }
}

TEST(Start, PerturbedFeasibleRetimesTheFeasiblePathsWithConsistentKinematics) {
  for (const Scene& scene : {scenario("two_robots_swap_avoid"), scenario("three_robots_contact"),
                             apart_scene()}) {
    const RobotProblem rp(scene);
    const Layout& lay = rp.layout();
    const Scene& ms = lay.model_scene();  // model units
    const int N = scene.steps;
    // A stand-in for a feasible point: a guess whose paths are not straight.
    const double T = 4.0;
    const bool conflict = scene.name != "apart";
    const Vector feasible =
        make_guess(rp, conflict ? find_start(scene, GuessKind::kDetour, +1)
                                : find_start(scene, GuessKind::kPerturbed),
                   T);
    for (std::uint64_t seed : {7u, 8u}) {
      const StartSpec s = find_start(scene, GuessKind::kPerturbedFeasible, 0, seed);
      SCOPED_TRACE(scene.name + ": " + s.describe());
      // Its feasibility phase starts from the straight lines.
      EXPECT_TRUE(bitwise_equal(make_guess(rp, s, T), smoothstep_guess(rp, T)));
      EXPECT_TRUE(static_cast<bool>(make_perturbation(rp, s)));
      // Deterministic.
      const Perturbation p = perturb_feasible(rp, s, feasible);
      const Perturbation again = make_perturbation(rp, s)(feasible);
      EXPECT_TRUE(bitwise_equal(p.guess, again.guess));
      EXPECT_EQ(p.seconds, again.seconds);
      ASSERT_TRUE(all_finite(p.guess));
      ASSERT_EQ(p.guess.size(), feasible.size());
      // The horizon: T_scale times the feasible one.
      EXPECT_NEAR(p.seconds, s.T_scale * T, 1e-12 * T);
      EXPECT_NEAR(rp.horizon(p.guess), p.seconds, 1e-12 * T);
      const double h = p.guess[lay.horizon_index()] / N;  // model units
      double moved = 0.0;
      for (int i = 0; i < static_cast<int>(ms.robots.size()); ++i) {
        const Robot& rb = ms.robots[i];
        auto at = [&](const Vector& z, int t, int c) {
          return t == 0 ? rb.start[c] : lay.state(i, t, c).value(z);
        };
        for (int c : {kX, kY, kPhi}) {
          const int v = c == kX ? kVx : c == kY ? kVy : kOmega;
          // The end state of the feasible point is kept.
          const double end = at(feasible, N, c);
          EXPECT_NEAR(at(p.guess, N, c), end, 1e-12 * (1.0 + std::abs(end)))
              << "robot " << i << " component " << c;
          for (int t = 0; t < N; ++t) {
            // Kinematics: x[t+1] - x[t] = h v[t+1], from the exact start on.
            const double dx = at(p.guess, t + 1, c) - at(p.guess, t, c);
            const double hv = h * lay.state(i, t + 1, v).value(p.guess);
            EXPECT_NEAR(dx, hv, 1e-9 * std::abs(dx) + 1e-15) << "robot " << i << " t " << t;
            moved = std::max(moved, std::abs(at(p.guess, t + 1, c) - at(feasible, t + 1, c)));
          }
        }
      }
      EXPECT_GT(moved, 1e-3);  // re-timed, not copied
      // Re-timing keeps a monotone coordinate monotone: robot 0 of the swap
      // moves along +x on its detour.
      if (scene.name == "two_robots_swap_avoid") {
        double x = ms.robots[0].start[kX];
        for (int t = 1; t <= N; ++t) {
          const double next = lay.state(0, t, kX).value(p.guess);
          EXPECT_GE(next, x) << "t " << t;
          x = next;
        }
      }
    }
  }
}

TEST(Start, OtherKindsHaveNoPerturbation) {
  const Scene scene = scenario("two_robots_swap_avoid");
  const RobotProblem rp(scene);
  for (const StartSpec& s : {make_start(scene, 7, 0, base_schedule(), base_elastic()),
                             find_start(scene, GuessKind::kPerturbed),
                             find_start(scene, GuessKind::kDetour, +1)})
    EXPECT_FALSE(static_cast<bool>(make_perturbation(rp, s))) << s.describe();
}

TEST(Start, ReductionFromADetourStartReachesACertifiedSolution) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  const Settings settings = Settings::load(default_settings_path());
  const StartSpec start = start_test::first_start_of(
      scene, 3, GuessKind::kDetour, +1, reduction_settings(settings), elastic_settings(settings));
  ASSERT_EQ(start.guess, GuessKind::kDetour);
  std::printf("%s\n", start.describe().c_str());
  RobotProblem problem(scene);
  IpoptSolver ipopt(ipopt_settings(settings));
  ElasticSolver solver(ipopt, start.elastic);
  const ReductionResult result = reduce_objective(
      problem, solver, start.schedule,
      [&](double seconds) { return make_guess(problem, start, seconds); });
  std::printf("T_best %.4f s, %zu solves, %d Ipopt iterations, %.2f s\n", result.best_value,
              result.solves.size(), result.iterations, result.seconds);
  ASSERT_TRUE(result.found) << to_string(result.status) << " " << result.feasibility_detail;
  EXPECT_EQ(result.status, MpccStatus::kSolved);
  EXPECT_TRUE(result.best.certificate.within(1e-6, 1e-6));
  EXPECT_GT(result.best_value, 0.0);
}

}  // namespace
}  // namespace disco

namespace disco {
namespace {

// A lone finger and two coins (configs/scenarios/push_two_coins.yaml): the guess
// (search/guess.h, "Pushers") pushes one coin, then the other. Checked on the paths alone:
// each coin waits at its start, then moves with the finger touching it (centre distance
// R_f + R_c) up to its last moving step, where it arrives at its target while the finger
// may already be on its way to the next coin; the two pushes do not overlap in time.
TEST(GuessPushers, ALonePusherPushesItsCoinsOneAfterTheOther) {
  const Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/push_two_coins.yaml");
  StartSpec start;
  start.guess = GuessKind::kStraight;
  const Paths paths = guess_paths(scene, start);
  const int N = scene.steps;
  std::vector<std::pair<int, int>> pushed;  // per coin: its first and last moving step
  for (int o = 1; o <= 2; ++o) {
    const Robot& coin = scene.robots[o];
    int first = -1, last = -1;
    for (int t = 1; t <= N; ++t) {
      const bool moved = std::hypot(paths[o][t][kX] - paths[o][t - 1][kX], paths[o][t][kY] - paths[o][t - 1][kY]) > 1e-12;
      if (!moved) continue;
      if (first < 0) first = t;
      last = t;
    }
    ASSERT_GT(first, 0) << coin.name << " is pushed";
    for (int t = first; t < last; ++t)
      EXPECT_NEAR(std::hypot(paths[0][t][kX] - paths[o][t][kX], paths[0][t][kY] - paths[o][t][kY]),
                  scene.robots[0].radius + coin.radius, 1e-9)
          << coin.name << " moves at step " << t << " with the finger touching it";
    for (int t = last; t <= N; ++t)
      EXPECT_EQ(paths[o][t], paths[o][N]) << coin.name << " rests from step " << last;
    EXPECT_EQ(paths[o][first - 1][kX], coin.start[kX]);
    EXPECT_EQ(paths[o][first - 1][kY], coin.start[kY]);
    for (int c : {kX, kY}) {
      EXPECT_GE(paths[o][N][c], coin.target.lower[c]);
      EXPECT_LE(paths[o][N][c], coin.target.upper[c]);
    }
    pushed.push_back({first, last});
  }
  EXPECT_TRUE(pushed[0].second < pushed[1].first || pushed[1].second < pushed[0].first)
      << "one coin after the other: steps " << pushed[0].first << "-" << pushed[0].second << " and "
      << pushed[1].first << "-" << pushed[1].second;
}

// Robots with targets of their own and a coin to push (configs/scenarios/push_coin_and_park.yaml):
// the guess (search/guess.h, "Pushers") sends the robot whose way the push lengthens least,
// the courier (0.54 m longer, against 1.47 m for the other, from the scene's numbers), to the contact
// point behind the coin, pushes the coin home touching it, and then goes on to its own
// target, which it reaches exactly at the last state; the other robot is not involved and
// keeps its own straight path. From the straight guess with the coin moving on its own,
// start 0 found no feasible point (tests/CMakeLists.txt: guess.push_and_park).
// The first horizon follows the pushers' way (search/guess.h, pushers_way_time): where a robot
// with a target takes a coin on its way, that way (to the coin, the push, on to the target)
// takes longer than any straight move alone, the scene's reference time. Scenes without such a
// robot have none, so their horizons are what they were: the lone finger of push_two_coins
// (no target of its own), robots without objects.
TEST(GuessPushers, TheWayOfARobotThatTakesACoinScalesTheHorizon) {
  const std::string dir = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/";
  const Scene park = load_scene(dir + "push_coin_and_park.yaml");
  const auto way = pushers_way_time(park);
  const auto reference = scene_reference_time(park);
  ASSERT_TRUE(way.has_value());
  ASSERT_TRUE(reference.has_value());
  EXPECT_GT(*way, *reference);
  EXPECT_LT(*way, 3.0 * *reference) << "a scale: the way is about twice the courier's straight way";
  for (const char* name : {"push_two_coins.yaml", "push_coin.yaml", "push_heavy_together.yaml",
                           "three_robots_contact.yaml", "doorway.yaml"})
    EXPECT_FALSE(pushers_way_time(load_scene(dir + name)).has_value()) << name;
}

TEST(GuessPushers, ARobotWithATargetTakesTheCoinOnItsWay) {
  const Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/push_coin_and_park.yaml");
  ASSERT_EQ(scene.robots.size(), 3u);
  const int courier = 0, other = 1, coin = 2;
  ASSERT_TRUE(scene.robots[coin].object);
  StartSpec start;
  start.guess = GuessKind::kStraight;
  const Paths paths = guess_paths(scene, start);
  const int N = scene.steps;
  const Robot& c = scene.robots[coin];
  const double touching = scene.robots[courier].radius + c.radius;
  int first = -1, last = -1;  // the coin's first and last moving step
  for (int t = 1; t <= N; ++t) {
    if (std::hypot(paths[coin][t][kX] - paths[coin][t - 1][kX], paths[coin][t][kY] - paths[coin][t - 1][kY]) <= 1e-12)
      continue;
    if (first < 0) first = t;
    last = t;
  }
  ASSERT_GT(first, 1) << "the coin waits for the courier, then is pushed";
  ASSERT_LT(last, N) << "the courier leaves the coin before it parks";
  // Touching up to the coin's last moving step, at which the coin arrives while the courier
  // may already be on its way to park.
  for (int t = first; t < last; ++t)
    EXPECT_NEAR(std::hypot(paths[courier][t][kX] - paths[coin][t][kX], paths[courier][t][kY] - paths[coin][t][kY]),
                touching, 1e-9)
        << "the coin moves at step " << t << " with the courier touching it";
  // Behind the coin: the courier pushes along the coin's move.
  const double ux = c.target.lower[kX] - c.start[kX], uy = c.target.lower[kY] - c.start[kY];
  EXPECT_GT((paths[coin][first][kX] - paths[courier][first][kX]) * ux +
                (paths[coin][first][kY] - paths[courier][first][kY]) * uy,
            0.0);
  for (int t = last; t <= N; ++t) {
    EXPECT_EQ(paths[coin][t][kX], c.target.lower[kX]) << "the coin rests in its target from step " << last;
    EXPECT_EQ(paths[coin][t][kY], c.target.lower[kY]);
  }
  for (int r : {courier, other})
    for (int k : {kX, kY}) EXPECT_EQ(paths[r][N][k], scene.robots[r].target.lower[k]) << scene.robots[r].name;
  // The other robot's path is its straight guess: every state on its straight segment.
  const Robot& o = scene.robots[other];
  const double dx = o.target.lower[kX] - o.start[kX], dy = o.target.lower[kY] - o.start[kY];
  for (int t = 0; t <= N; ++t)
    EXPECT_NEAR((paths[other][t][kX] - o.start[kX]) * dy - (paths[other][t][kY] - o.start[kY]) * dx, 0.0, 1e-9)
        << "step " << t;
}

// A robot that must turn (phi 0 to 1 rad) and the only other robot, passing the other way
// 3 m from it: a robot turns only by contact (search/guess.h, "Turners"). The turner is
// heavy: from guesses without the meeting `disco solve` took 2,346 iterations to T_f
// 4.571536 s, with it 982 iterations to 4.042804 s (2026-11-29).
constexpr const char* kTurnerScene = R"(
scenario: turner
steps: 20
defaults: {radius: 0.4, mass: 1.0, mu: 0.2, force_max: 6.0, K: 8}
robots:
  - {name: turner, mass: 2.8, start: {x: 0, y: 0}, target: {x: 0, y: -3, vx: 0, vy: 0, phi: 1.0}}
  - {name: passer, start: {x: 3, y: -3}, target: {x: 3, y: 0, vx: 0, vy: 0}}
pairs: {mode: contact, mu: 0.3}
)";

// The straight guess's paths, with or without the turners' meetings, and the centre
// distance of disks a and b at step t on them.
Paths straight_paths(const Scene& scene, bool meet_turners) {
  StartSpec start;
  start.guess = GuessKind::kStraight;
  start.meet_turners = meet_turners;
  return guess_paths(scene, start);
}
double centre_distance(const Paths& paths, int a, int b, int t) {
  return std::hypot(paths[b][t][kX] - paths[a][t][kX], paths[b][t][kY] - paths[a][t][kY]);
}

// The turner and its partner are moved towards each other, half the excess of their
// closest approach (3 m) over their clearance (0.8 m) each, most at that approach (tau 0.5,
// step 10 of 20), where they touch; they never overlap, start and end where the straight
// guess does, and the turner's phi still runs from its start to its target.
TEST(GuessTurners, ATurnerAndItsPartnerTouchWhereTheirStraightPathsComeClosest) {
  const Scene scene = parse_scene(kTurnerScene, "turner");
  const std::vector<Meeting> ms = meetings(scene);
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0].i, 0);
  EXPECT_EQ(ms[0].j, 1);
  EXPECT_NEAR(ms[0].shift_i, 0.5 * (3.0 - 0.8), 1e-12);
  EXPECT_NEAR(ms[0].shift_j, 0.5 * (3.0 - 0.8), 1e-12);
  EXPECT_NEAR(ms[0].ux, 1.0, 1e-12);
  const Paths paths = straight_paths(scene, true);
  const int N = scene.steps;
  auto distance = [&](int t) { return centre_distance(paths, 0, 1, t); };
  // The plain straight paths: 3 m apart at the closest approach.
  EXPECT_NEAR(centre_distance(straight_paths(scene, false), 0, 1, N / 2), 3.0, 1e-9);
  EXPECT_NEAR(distance(N / 2), 0.8, 1e-9) << "touching at the closest approach";
  for (int t = 0; t <= N; ++t) EXPECT_GE(distance(t), 0.8 - 1e-9) << "step " << t;
  EXPECT_LT(distance(N / 2 - 2), 3.0 - 1.0) << "and near each other around it";
  for (int r : {0, 1}) {
    EXPECT_EQ(paths[r][0], straight_move(scene.robots[r]).from) << scene.robots[r].name;
    EXPECT_EQ(paths[r][N], straight_move(scene.robots[r]).to) << scene.robots[r].name;
  }
  for (int t = 1; t <= N; ++t) EXPECT_GE(paths[0][t][kPhi], paths[0][t - 1][kPhi]) << "step " << t;
  EXPECT_EQ(paths[0][N][kPhi], 1.0);
}

// Two turners that are each other's nearest partner meet once: each moved half the excess,
// so they touch at the closest approach instead of overlapping.
TEST(GuessTurners, TwoTurnersMeetOnce) {
  std::string both(kTurnerScene);
  both.replace(both.find("target: {x: 3, y: 0, vx: 0, vy: 0}"), 34,
               "target: {x: 3, y: 0, vx: 0, vy: 0, phi: -0.5}");
  const Scene scene = parse_scene(both, "two turners");
  const std::vector<Meeting> ms = meetings(scene);
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_NEAR(centre_distance(straight_paths(scene, true), 0, 1, scene.steps / 2), 0.8, 1e-9);
}

// A turner whose robot partners are avoid pairs meets the object it has a contact pair with,
// and moves the whole excess itself: the coin (at rest at its target, 3 m to the side of the
// turner's path's midpoint) keeps its place. The other robot crosses the turner's path (a
// conflict of an avoid pair, which keeps them apart: no contact, so it does not stop the
// meeting). Measured on scripts/bench_random scenes: random_mixed_4_9, whose two turners
// could touch only the object, found no certified point from start 0 in 30 s before
// (2026-11-29).
constexpr const char* kObjectPartnerScene = R"(
scenario: object_partner
steps: 20
defaults: {radius: 0.4, mass: 1.0, mu: 0.2, force_max: 6.0, K: 8}
robots:
  - {name: turner, start: {x: 0, y: 0}, target: {x: 0, y: -3, vx: 0, vy: 0, phi: 1.0}}
  - {name: crosser, start: {x: -2, y: -1.5}, target: {x: 2, y: -1.5, vx: 0, vy: 0}}
objects:
  - {name: coin, radius: 0.5, start: {x: 3, y: -1.5}, target: {x: 3, y: -1.5, vx: 0, vy: 0}}
pairs: {mode: avoid}
)";

TEST(GuessTurners, ATurnerWithoutARobotToTouchMeetsAnObject) {
  const Scene scene = parse_scene(kObjectPartnerScene, "object partner");
  ASSERT_EQ(conflicts(scene).size(), 1u) << "the crosser crosses the turner's path";
  const std::vector<Meeting> ms = meetings(scene);
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0].i, 0);
  EXPECT_EQ(ms[0].j, 2) << "the coin, not the crosser (an avoid pair)";
  EXPECT_NEAR(ms[0].shift_i, 3.0 - 0.9, 1e-12) << "the whole excess over R + R_coin";
  EXPECT_EQ(ms[0].shift_j, 0.0);
  const Paths paths = straight_paths(scene, true);
  const int N = scene.steps;
  auto distance = [&](int t) { return centre_distance(paths, 0, 2, t); };
  EXPECT_NEAR(distance(N / 2), 0.9, 1e-9) << "touching the coin at the closest approach";
  for (int t = 0; t <= N; ++t) {
    EXPECT_GE(distance(t), 0.9 - 1e-9) << "step " << t;
    EXPECT_EQ(paths[2][t][kX], 3.0) << "the coin stays, step " << t;
    EXPECT_EQ(paths[2][t][kY], -1.5) << "the coin stays, step " << t;
  }
  // A crossing in a contact pair touches: no meeting needed.
  std::string contact(kObjectPartnerScene);
  contact.replace(contact.find("pairs: {mode: avoid}"), 20, "pairs: {mode: contact}");
  EXPECT_TRUE(meetings(parse_scene(contact, "contact")).empty());
  // With a robot to touch (a contact pair, its straight path 4.7 m from the turner's at the
  // closest, the coin's 3 m), the robot is the partner, as before: robots first.
  const std::string crossing = "start: {x: -2, y: -1.5}, target: {x: 2, y: -1.5";
  contact.replace(contact.find(crossing), crossing.size(), "start: {x: -4, y: -6.5}, target: {x: 4, y: -6.5");
  const std::vector<Meeting> robot_first = meetings(parse_scene(contact, "contact"));
  ASSERT_EQ(robot_first.size(), 1u);
  EXPECT_EQ(robot_first[0].j, 1);
  EXPECT_EQ(robot_first[0].shift_i, robot_first[0].shift_j);
}

// A turner with no disk to touch meets the closest fixed contact obstacle: a post 2 m to the
// side of its path's midpoint, or a wall whose nearest point is 1.5 m from its path. It moves
// the whole excess itself and touches the obstacle there. Before, the input check refused
// such a target (nothing to turn the robot); random_mixed_4_5 and 4_10, so refused, now reach
// certified points from start 0 (2026-11-29).
std::string lone_turner(const std::string& obstacles) {
  return "scenario: lone_turner\nsteps: 20\n"
         "robots:\n"
         "  - {name: turner, radius: 0.4, mass: 1, mu: 0.2, force_max: 6, K: 8, start: {x: 0, y: 0}, "
         "target: {x: 0, y: -3, vx: 0, vy: 0, phi: 1.0}}\n"
         "obstacles:\n" + obstacles;
}

TEST(GuessTurners, ATurnerWithNoDiskToTouchMeetsAContactObstacle) {
  const Scene post = parse_scene(
      lone_turner("  - {name: far, disk: {x: -4, y: -1.5, radius: 0.3}, mode: contact}\n"
                  "  - {name: post, disk: {x: 2, y: -1.5, radius: 0.3}, mode: contact}\n"
                  "  - {name: near, disk: {x: 1.2, y: -1.5, radius: 0.3}, mode: avoid}\n"),
      "post");
  const std::vector<Meeting> ms = meetings(post);
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0].j, -1);
  EXPECT_EQ(ms[0].obstacle, 1) << "the closest contact obstacle (an avoid one touches nothing)";
  // A ternary search: the distance is flat (quadratic) at its least, so w is found to about
  // the square root of the rounding unit; the distances themselves to rounding.
  EXPECT_NEAR(ms[0].w, 0.5, 1e-6);
  EXPECT_NEAR(ms[0].ux, 1.0, 1e-9);
  EXPECT_NEAR(ms[0].shift_i, 2.0 - 0.7, 1e-9);
  const Paths paths = straight_paths(post, true);
  const int N = post.steps;
  auto to_post = [&](int t) { return std::hypot(paths[0][t][kX] - 2.0, paths[0][t][kY] + 1.5); };
  EXPECT_NEAR(to_post(N / 2), 0.7, 1e-9) << "touching the post at the closest approach";
  for (int t = 0; t <= N; ++t) EXPECT_GE(to_post(t), 0.7 - 1e-9) << "step " << t;
  // A wall from (1.5, -2.5) to (3, -1), slanted away from the path: its first end is its
  // nearest point.
  const Scene wall = parse_scene(
      lone_turner("  - {name: wall, wall: {from: [1.5, -2.5], to: [3, -1]}, mode: contact}\n"), "wall");
  const std::vector<Meeting> mw = meetings(wall);
  ASSERT_EQ(mw.size(), 1u);
  EXPECT_EQ(mw[0].obstacle, 0);
  // The wall's first end (1.5, -2.5) is nearest: the path's point (0, -2.5), 1.5 m away.
  EXPECT_NEAR(mw[0].w, 2.5 / 3.0, 1e-6);
  EXPECT_NEAR(mw[0].shift_i, 1.5 - 0.4, 1e-6);
  // A robot partner, even one farther away than the post, comes first.
  const Scene with_robot = parse_scene(
      "scenario: with_robot\nsteps: 20\n"
      "robots:\n"
      "  - {name: turner, radius: 0.4, mass: 1, mu: 0.2, force_max: 6, K: 8, start: {x: 0, y: 0}, "
      "target: {x: 0, y: -3, vx: 0, vy: 0, phi: 1.0}}\n"
      "  - {name: other, radius: 0.4, mass: 1, mu: 0.2, force_max: 6, K: 8, start: {x: -5, y: 0}, "
      "target: {x: -5, y: -3, vx: 0, vy: 0}}\n"
      "pairs: {mode: contact}\n"
      "obstacles:\n"
      "  - {name: post, disk: {x: 2, y: -1.5, radius: 0.3}, mode: contact}\n",
      "with_robot");
  const std::vector<Meeting> mr = meetings(with_robot);
  ASSERT_EQ(mr.size(), 1u);
  EXPECT_EQ(mr[0].j, 1);
  EXPECT_EQ(mr[0].obstacle, -1);
}

// Start 0 (what `disco solve` runs) meets, and the later starts in pairs: 1-2 do, 3-4 do not,
// 5-6 do, so both guess kinds of a scene without conflicts come with and without the meeting;
// the start's description says so. A scene without a turner never meets.
TEST(GuessTurners, Start0AndHalfTheOthersMeet) {
  const Scene scene = parse_scene(kTurnerScene, "turner");
  const ReductionSettings schedule = base_schedule();
  const ElasticSettings elastic;
  for (int k = 0; k <= 8; ++k) {
    const StartSpec s = make_start(scene, 1, k, schedule, elastic);
    const bool meets = k == 0 || k == 1 || k == 2 || k == 5 || k == 6;
    EXPECT_EQ(s.meet_turners, meets) << "start " << k;
    EXPECT_EQ(s.describe().find("turners meet partners") != std::string::npos, meets);
  }
  for (int k = 0; k <= 2; ++k)
    EXPECT_FALSE(make_start(apart_scene(), 1, k, schedule, elastic).meet_turners) << k;
}

// No meeting where no robot must turn, or where the turners' straight paths already bring them
// into contact (a conflict): the paper's scenes and the contact scene of the start set keep
// their guesses bit for bit; nor for a turner whose target phi is its start's.
TEST(GuessTurners, NoMeetingWhereNoTurnerIsLeftWithoutContact) {
  for (const char* name : {"paper/A3", "paper/A4", "paper/B1", "paper/B2", "paper/B3",
                           "three_robots_contact", "push_coin_and_park"})
    EXPECT_TRUE(meetings(scenario(name)).empty()) << name;
  EXPECT_TRUE(meetings(apart_scene()).empty());
  std::string same(kTurnerScene);
  same.replace(same.find("phi: 1.0"), 8, "phi: 0.0");
  EXPECT_TRUE(meetings(parse_scene(same, "no turn")).empty());
}

}  // namespace
}  // namespace disco
