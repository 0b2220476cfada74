// Exact derivatives of the robot model, family by family.
//
// Every constraint family of core/model/ (plus the dynamics rows it adds its
// impulses to) is checked against central finite differences on small scenes:
// a contact pair, an avoid pair, a one-axis robot on a diagonal axis, robots
// without floor friction (mu = 0, contact mu = 0), and the whole model on
// three robots in contact. Points: random (fixed seeds), near the floor
// friction kink (robots almost at rest, d_k . v + gamma ~ 0) and near contact
// (gaps ~1e-7, nonzero contact forces). Gradient, Jacobian and Hessian must
// match to 1e-6 (relative) with nothing nonzero outside the declared
// sparsity. Finally, Ipopt's own second-order derivative test must pass on
// the elastic NLP of a whole two-robot contact scene.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "search/guess.h"
#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_nlp.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/gap.h"
#include "core/model/objective.h"
#include "core/model/obstacles.h"
#include "core/model/robot_problem.h"
#include "core/nlp/derivative_checker.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

using model_test::edge_direction;
using model_test::make_robot;
using model_test::make_scene;

constexpr double kTol = 1e-6;

// ------------------------------------------------------------- scenes ---

Robot moving(Robot r, double phi, double vx, double vy, double omega) {
  r.start[kPhi] = phi;
  r.start[kVx] = vx;
  r.start[kVy] = vy;
  r.start[kOmega] = omega;
  return r;
}

// Two robots of different sizes, in contact mode, start in motion.
Scene contact_pair_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0, 5), 0.3, 0.4, -0.1, 0.7);
  Robot b = moving(make_robot("b", 0.4, 1.5, 0.3, 8.0, 1.2, 0.3, 7), -0.2, -0.5, 0.2, -0.4);
  b.target.lower[kX] = 2.0;  // a terminal box, for the bounds family
  b.target.upper[kVx] = 0.1;
  return make_scene("contact_pair", 4, {a, b}, PairMode::kContact, 0.35);
}

// Two robots in avoid mode (d_s = 0.05).
Scene avoid_pair_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0, 4), 0.0, 0.3, 0.3, 0.2);
  Robot b = moving(make_robot("b", 0.6, 2.0, 0.1, 6.0, 2.0, 0.5, 8), 1.0, -0.3, 0.0, 0.0);
  a.target.lower[kX] = 1.0;
  a.target.upper[kX] = 1.0;
  return make_scene("avoid_pair", 3, {a, b}, PairMode::kAvoid, 0.3, 0.05);
}

// One robot pushing only along the diagonal (D_ef = 1).
Scene diagonal_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0, 8), 0.1, 0.2, 0.1, -0.3);
  a.force_dims = 1;
  a.force_axis = {1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0)};
  a.target.lower = {8, 8, -kInf, 0, 0, -kInf};
  a.target.upper = {8, 8, kInf, 0, 0, kInf};
  return make_scene("diagonal", 5, {a});
}

// A robot without floor friction (mu = 0) in contact, with contact mu = 0,
// with a robot that has floor friction on a square (K = 4).
Scene frictionless_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.0, 5.0, 0.0, 0.0, 6), 0.0, 0.6, 0.0, 0.5);
  Robot b = moving(make_robot("b", 0.5, 1.2, 0.25, 6.0, 1.5, -0.2, 4), 0.0, -0.4, 0.1, 0.0);
  return make_scene("frictionless", 4, {a, b}, PairMode::kContact, 0.0);
}

// Three equal-radius robots, every pair in contact mode.
Scene three_contact_scene(int steps = 3) {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, -1.5, 0.0, 6), 0.0, 0.5, 0.0, 0.1);
  Robot b = moving(make_robot("b", 0.5, 1.3, 0.3, 6.0, 1.5, 0.2, 5), 0.0, -0.5, 0.0, 0.0);
  Robot c = moving(make_robot("c", 0.5, 0.8, 0.15, 4.0, 0.0, -1.6, 7), 0.0, 0.0, 0.6, -0.2);
  return make_scene("three_contact", steps, {a, b, c}, PairMode::kContact, 0.3);
}

// A robot pushing two objects (Robot::object: no force unknowns), one of which rubs on the
// other; every pair in contact mode.
Scene objects_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, -1.2, 0.0, 6), 0.0, 0.5, 0.0, 0.1);
  Robot b = moving(make_robot("b", 0.3, 0.5, 0.3, 0.0, 0.0, 0.1, 5), 0.0, 0.2, 0.1, 0.3);
  Robot c = moving(make_robot("c", 0.4, 0.7, 0.25, 0.0, 0.8, -0.4, 4), 0.0, -0.1, 0.2, 0.0);
  for (Robot* o : {&b, &c}) {
    o->object = true;
    o->force_dims = 0;
  }
  c.target.lower[kX] = c.target.upper[kX] = 2.0;
  return make_scene("objects", 3, {a, b, c}, PairMode::kContact, 0.3);
}

// A robot and an object among obstacles: a wall and a post in contact (with friction), a
// moving post, a second wall and a post that follows waypoints in avoid mode.
Scene obstacles_scene() {
  Robot a = moving(make_robot("a", 0.5, 1.0, 0.2, 5.0, -1.5, 0.0, 6), 0.0, 0.5, 0.0, 0.1);
  Robot b = moving(make_robot("b", 0.4, 0.8, 0.3, 0.0, 1.5, 0.2, 5), 0.0, -0.3, 0.1, 0.2);
  b.object = true;
  b.force_dims = 0;
  a.target.lower[kX] = a.target.upper[kX] = 1.0;
  Scene s = make_scene("obstacles", 3, {a, b}, PairMode::kContact, 0.3);
  model_test::add_obstacle(s, model_test::wall("floor_wall", {-3.0, -1.5}, {3.0, -1.2}, 0.05),
                           PairMode::kContact, 0.4);
  model_test::add_obstacle(s, model_test::post("post", {0.0, 1.5}, 0.3), PairMode::kContact, 0.2);
  model_test::add_obstacle(s, model_test::post("runner", {-3.0, 3.0}, 0.2, {1.0, -0.5}),
                           PairMode::kAvoid, 0.0, 0.05);
  model_test::add_obstacle(s, model_test::wall("side_wall", {2.5, -1.0}, {2.5, 2.0}), PairMode::kAvoid);
  model_test::add_obstacle(
      s, model_test::sentry("sentry", 0.25, {{0.0, {0.5, -2.0}}, {0.3, {1.0, -1.0}}, {0.6, {0.2, 0.5}}, {1.0, {1.5, 1.0}}}),
      PairMode::kAvoid, 0.0, 0.05);
  return s;
}

struct NamedScene {
  std::string name;
  Scene scene;
};

std::vector<NamedScene> small_scenes() {
  return {{"contact_pair", contact_pair_scene()},
          {"avoid_pair", avoid_pair_scene()},
          {"diagonal_one_axis", diagonal_scene()},
          {"mu_zero", frictionless_scene()},
          {"three_contact", three_contact_scene()},
          {"objects", objects_scene()},
          {"obstacles", obstacles_scene()}};
}

// ------------------------------------------------------------- points ---

// Sets unknown k of z; k < 0 is a quantity the model holds as a constant (or
// does not have), which is left alone.
void put(Vector& z, int k, double v) {
  if (k >= 0) z[k] = v;
}

// Every unknown uniform in [-1.5, 1.5], T_f in [0.5, 3].
Vector random_point(const RobotProblem& rp, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.5, 1.5), tf(0.5, 3.0);
  Vector z(rp.program().num_variables());
  for (int k = 0; k < z.size(); ++k) z[k] = u(rng);
  z[rp.layout().horizon_index()] = tf(rng);
  return z;
}

// Almost at rest: every velocity ~1e-7, floor gamma = -min_k d_k . v^{t+1}
// (so at least one row d_k . v + gamma is ~0, here exactly at the kink) plus
// a jitter of 1e-9 on odd intervals; contact gamma ~1e-7 as well.
Vector kink_point(const RobotProblem& rp, unsigned seed) {
  Vector z = random_point(rp, seed);
  std::mt19937 rng(seed + 1000);
  std::uniform_real_distribution<double> tiny(-1e-7, 1e-7), pos(0.0, 1.0);
  const Layout& L = rp.layout();
  const Scene& s = L.model_scene();
  for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) {
    for (int t = 1; t <= L.steps(); ++t)
      for (int c : {kVx, kVy, kOmega}) put(z, L.state_index(i, t, c), tiny(rng));
    if (!L.has_floor_friction(i)) continue;
    const int K = s.robots[i].friction_edges;
    for (int t = 0; t < L.steps(); ++t) {
      const double vx = z[L.state_index(i, t + 1, kVx)], vy = z[L.state_index(i, t + 1, kVy)];
      double lowest = kInf;
      for (int k = 0; k < K; ++k) {
        const auto d = edge_direction(k, K);
        lowest = std::min(lowest, d[0] * vx + d[1] * vy);
        z[L.beta_index(i, t, k)] = pos(rng);
      }
      z[L.floor_gamma_index(i, t)] = -lowest + (t % 2 ? 1e-9 : 0.0);
    }
  }
  for (int p = 0; p < static_cast<int>(s.pairs.size()); ++p)
    for (int t = 0; t < L.steps(); ++t) put(z, L.contact_gamma_index(p, t), std::abs(tiny(rng)));
  return z;
}

// Robots almost touching at every state t >= 1 (gap 1e-7 for every pair, for
// up to three robots), gap unknowns set to the gaps, contact forces nonzero.
Vector contact_point(const RobotProblem& rp, unsigned seed) {
  Vector z = random_point(rp, seed);
  std::mt19937 rng(seed + 2000);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(0.0, 2.0 * std::numbers::pi),
      force(0.5, 2.0), slip(0.0, 1.0);
  const Layout& L = rp.layout();
  const Scene& s = L.model_scene();
  const int nr = static_cast<int>(s.robots.size());
  constexpr double kGap = 1e-7;
  auto R = [&](int i) { return s.robots[i].radius; };
  for (int t = 1; t <= L.steps(); ++t) {
    double p[3][2] = {};
    p[0][0] = u(rng);
    p[0][1] = u(rng);
    if (nr >= 2) {
      const double th = angle(rng), d = R(0) + R(1) + kGap;
      p[1][0] = p[0][0] + d * std::cos(th);
      p[1][1] = p[0][1] + d * std::sin(th);
    }
    if (nr >= 3) {  // intersection of the circles around robots 0 and 1
      const double d01 = std::hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]);
      const double r0 = R(0) + R(2) + kGap, r1 = R(1) + R(2) + kGap;
      const double a = (r0 * r0 - r1 * r1 + d01 * d01) / (2 * d01);
      const double h = std::sqrt(r0 * r0 - a * a);
      const double ex = (p[1][0] - p[0][0]) / d01, ey = (p[1][1] - p[0][1]) / d01;
      p[2][0] = p[0][0] + a * ex - h * ey;
      p[2][1] = p[0][1] + a * ey + h * ex;
    }
    for (int i = 0; i < std::min(nr, 3); ++i) {
      z[L.state_index(i, t, kX)] = p[i][0];
      z[L.state_index(i, t, kY)] = p[i][1];
    }
    for (int q = 0; q < static_cast<int>(s.pairs.size()); ++q) {
      const Pair& pr = s.pairs[q];
      if (pr.i >= 3 || pr.j >= 3) continue;
      const double gap = std::hypot(p[pr.j][0] - p[pr.i][0], p[pr.j][1] - p[pr.i][1]) -
                          R(pr.i) - R(pr.j);
      EXPECT_NEAR(gap, kGap, 1e-12);  // the construction itself
      put(z, L.gap_index(q, t), gap);
    }
  }
  for (int q = 0; q < static_cast<int>(s.pairs.size()); ++q) {
    for (int t = 0; t < L.steps(); ++t) {
      put(z, L.normal_multiplier_index(q, t), force(rng));
      put(z, L.alpha1_index(q, t), slip(rng));
      put(z, L.alpha2_index(q, t), slip(rng));
      put(z, L.contact_gamma_index(q, t), slip(rng));
    }
  }
  return z;
}

// Every disk at a wall's end (the first wall, alternating ends by state), just past it and
// 1e-7 from touching, along a direction drawn at random beyond the end: the nearest point
// is the end itself (s = 0 or 1, a multiplier at its value), where a closed-form distance
// would switch formulas. Projection unknowns and gaps from the centres, contact forces on.
Vector wall_end_point(const RobotProblem& rp, unsigned seed) {
  Vector z = contact_point(rp, seed);
  std::mt19937 rng(seed + 4000);
  std::uniform_real_distribution<double> turn(-0.4 * std::numbers::pi, 0.4 * std::numbers::pi);
  const Layout& L = rp.layout();
  const Scene& s = L.model_scene();
  int first_wall = -1;
  for (int k = 0; k < static_cast<int>(s.obstacles.size()) && first_wall < 0; ++k)
    if (s.obstacles[k].shape == ObstacleShape::kWall) first_wall = k;
  if (first_wall < 0) return z;
  const Obstacle& w = s.obstacles[first_wall];
  const double dx = w.to[0] - w.from[0], dy = w.to[1] - w.from[1];
  for (int t = 1; t <= L.steps(); ++t) {
    const bool far_end = t % 2 == 0;
    const std::array<double, 2> end = far_end ? w.to : w.from;
    const double out = std::atan2(far_end ? dy : -dy, far_end ? dx : -dx) + turn(rng);
    for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) {
      const double d = s.robots[i].radius + w.radius + 1e-7;
      put(z, L.state_index(i, t, kX), end[0] + d * std::cos(out));
      put(z, L.state_index(i, t, kY), end[1] + d * std::sin(out));
    }
  }
  complete_obstacle_unknowns(L, z);
  for (int p = 0; p < L.num_pairs(); ++p)
    for (int t = 1; t <= L.steps(); ++t)
      if (L.has_gap(p, t)) put(z, L.gap_index(p, t), centre_gap(L, z, p, t));
  return z;
}

// A random point whose T_f puts state 2 just past an inner waypoint of the first path
// obstacle, where two pieces of the spline meet, with its centres q^t on the path. Just
// past: 1e-4 in model time, beyond the checker's finite-difference step (1e-6 relative). The
// spline is C^2 at a waypoint but its third derivative jumps there, so a central difference
// of the Hessian that straddles it is off by O(step) (tests/test_obstacle_path.cpp checks
// the C^2 joint itself).
Vector path_knot_point(const RobotProblem& rp, unsigned seed) {
  Vector z = random_point(rp, seed);
  const Layout& L = rp.layout();
  for (const Obstacle& ob : L.model_scene().obstacles) {
    if (ob.path.size() < 3) continue;
    z[L.horizon_index()] = (ob.path[1].t + 1e-4) * L.steps() / 2.0;
    complete_obstacle_unknowns(L, z);
    break;
  }
  return z;
}

Vector random_multipliers(int m, unsigned seed) {
  std::mt19937 rng(seed + 3000);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector lambda(m);
  for (int r = 0; r < m; ++r) lambda[r] = u(rng);
  return lambda;
}

void expect_exact_derivatives(const RobotProblem& rp, const Vector& z, unsigned seed) {
  const Vector lambda = random_multipliers(rp.program().num_constraints(), seed);
  const double sigma = 0.5 + (seed % 7) * 0.25;
  test_support::expect_exact_derivatives(check_derivatives(rp.program(), z, sigma, lambda), kTol);
}

std::string family_name(Family f) {
  switch (f) {
    case Family::kKinematics: return "Kinematics";
    case Family::kDynamics: return "Dynamics";
    case Family::kFloorFriction: return "FloorFriction";
    case Family::kGap: return "Gap";
    case Family::kNonpenetration: return "Nonpenetration";
    case Family::kContactFriction: return "ContactFriction";
    case Family::kAvoidance: return "Avoidance";
    case Family::kSweptClearance: return "SweptClearance";
    case Family::kBounds: return "Bounds";
  }
  return "Unknown";
}

// Runs the three kinds of points (two random seeds) on one problem.
void check_all_points(const RobotProblem& rp, unsigned base_seed) {
  for (unsigned seed : {base_seed, base_seed + 17}) {
    SCOPED_TRACE("random point, seed " + std::to_string(seed));
    expect_exact_derivatives(rp, random_point(rp, seed), seed);
  }
  {
    SCOPED_TRACE("near the friction kink");
    expect_exact_derivatives(rp, kink_point(rp, base_seed + 5), base_seed + 5);
  }
  {
    SCOPED_TRACE("near contact");
    expect_exact_derivatives(rp, contact_point(rp, base_seed + 9), base_seed + 9);
  }
  if (!rp.layout().model_scene().obstacles.empty()) {
    SCOPED_TRACE("at a wall's ends");
    expect_exact_derivatives(rp, wall_end_point(rp, base_seed + 13), base_seed + 13);
  }
  for (const Obstacle& ob : rp.layout().model_scene().obstacles)
    if (ob.path.size() >= 3) {
      SCOPED_TRACE("just past a path's waypoint");
      expect_exact_derivatives(rp, path_knot_point(rp, base_seed + 21), base_seed + 21);
      break;
    }
}

// ------------------------------------------------------------- tests ---

class ModelFamilyDerivatives : public testing::TestWithParam<Family> {};

TEST_P(ModelFamilyDerivatives, MatchFiniteDifferencesOnSmallScenes) {
  unsigned seed = 11 + 100 * static_cast<unsigned>(GetParam());
  for (const auto& [name, scene] : small_scenes()) {
    SCOPED_TRACE("scene " + name);
    const RobotProblem rp(scene, {GetParam()});
    check_all_points(rp, seed++);
  }
}

INSTANTIATE_TEST_SUITE_P(Model, ModelFamilyDerivatives, testing::ValuesIn(all_families()),
                         [](const testing::TestParamInfo<Family>& info) {
                           return family_name(info.param);
                         });

// The family checks above prove nothing about a family that adds nothing:
// each one must change the program (rows, nonzeros, pairs or bounds) in at
// least one of the scenes it was checked on.
TEST(ModelFamilies, EveryFamilyContributesToTheCheckedScenes) {
  auto signature = [](const RobotProblem& rp) {
    const auto& P = rp.program();
    std::ostringstream os;
    os << P.num_constraints() << ' ' << P.jacobian_pattern().size() << ' '
       << P.hessian_pattern().size() << ' ' << P.num_complementarity_pairs() << ' '
       << P.num_monomials() << ' ' << P.variable_lower().transpose() << ' '
       << P.variable_upper().transpose();
    return os.str();
  };
  for (Family f : all_families()) {
    if (f == Family::kDynamics) continue;
    bool changed = false;
    for (const auto& [name, scene] : small_scenes()) {
      const RobotProblem base(scene, {Family::kDynamics}), with(scene, {f});
      changed = changed || signature(base) != signature(with);
    }
    EXPECT_TRUE(changed) << family_name(f) << " adds nothing to any checked scene";
  }
  // The dynamics rows exist on their own (3 per robot and interval).
  const Scene s = contact_pair_scene();
  EXPECT_EQ(RobotProblem(s, {Family::kDynamics}).program().num_constraints(), 3 * 2 * s.steps);
}

TEST(ModelFullDerivatives, ThreeRobotContactScene) {
  const RobotProblem rp(three_contact_scene(4), all_families());
  check_all_points(rp, 4242);
  // The straight-line guess is a point like any other.
  SCOPED_TRACE("straight-line guess");
  expect_exact_derivatives(rp, smoothstep_guess(rp, 3.0), 77);
}

// The full model (every unknown at every step, friction unknowns even with
// mu = 0) and the adaptive one with pair windows that start late: the rows
// at a window's edge use constants and unknowns side by side.
TEST(ModelFullDerivatives, FullModelAndAdaptiveWindows) {
  for (const auto& [name, scene] :
       std::vector<NamedScene>{{"three_contact", three_contact_scene(12)}, {"mu_zero", frictionless_scene()}}) {
    SCOPED_TRACE(name);
    {
      SCOPED_TRACE("full");
      check_all_points(RobotProblem(scene, ModelOptions{false, kInf}), 5151);
    }
    SCOPED_TRACE("adaptive, T_max 0.6 s");
    const RobotProblem rp(scene, ModelOptions{true, 0.6});
    if (name == "three_contact") {
      bool partial = false;
      for (const PairPlan& w : rp.plan().pairs) partial = partial || (w.first > 1 && w.first <= w.last);
      EXPECT_TRUE(partial) << "no window starts late: the check would not cover window edges";
    }
    check_all_points(rp, 6161);
  }
}

// The objectives other than time (core/model/objective.h): sum h |F|^2 in the objective and in
// the row that bounds it, on every small scene (one-axis forces, objects without force,
// obstacles) with the whole model. The row must carry exactly the objective: at a point the
// row's value is the objective's, in model units.
TEST(ModelObjectiveDerivatives, EnergyAndTimePlusEnergy) {
  unsigned seed = 9100;
  for (const ObjectiveKind kind : {ObjectiveKind::kEnergy, ObjectiveKind::kTimeEnergy}) {
    for (auto [name, scene] : small_scenes()) {
      SCOPED_TRACE(to_string(kind) + ", scene " + name);
      scene.objective.kind = kind;
      scene.objective.horizon = kind == ObjectiveKind::kEnergy ? 2.0 : 0.0;
      scene.objective.energy_weight = kind == ObjectiveKind::kTimeEnergy ? 0.3 : 0.0;
      const RobotProblem rp(scene, ModelOptions{false, kInf});
      const PolynomialProgram& P = rp.program();
      Scene timed = scene;
      timed.objective = Objective{};
      ASSERT_EQ(P.num_constraints(),
                RobotProblem(timed, ModelOptions{false, kInf}).program().num_constraints() + 1)
          << "one row bounds J";
      const Vector z = random_point(rp, seed);
      check_all_points(rp, seed);
      seed += 31;
      // The row of J is the last; its value is the objective (model units).
      double f = 0.0;
      ASSERT_TRUE(P.objective(z, f));
      Vector c(P.num_constraints());
      ASSERT_TRUE(P.constraints(z, c));
      EXPECT_NEAR(c[P.num_constraints() - 1], f, 1e-12 * std::max(1.0, std::abs(f)));
    }
  }
}

// ------------------------------------------- Ipopt's derivative checker ---

// Wraps an Nlp and shifts one Jacobian value: the negative control proving
// that Ipopt's checker, run as below, does report errors.
class ShiftedJacobian : public test_support::ForwardingNlp {
 public:
  using ForwardingNlp::ForwardingNlp;

 private:
  bool do_jacobian(const ConstVectorRef& z, VectorRef v) const override {
    if (!inner_.jacobian(z, v)) return false;
    v[v.size() / 2] += 0.5;
    return true;
  }
};

// Ipopt's derivative test (`order`: first-order or second-order) at x0, no iterations.
// Returns what Ipopt printed on stdout.
std::string ipopt_derivative_test(const Nlp& nlp, const Vector& x0, const std::string& order) {
  const Settings settings = Settings::load(default_settings_path());
  auto options = ipopt_options(settings);
  for (const IpoptOption& o : std::vector<IpoptOption>{{"derivative_test", order, "test"},
                                                       {"derivative_test_print_all", "no", "test"},
                                                       {"max_iter", "0", "test"},
                                                       {"print_level", "5", "test"}})
    options.push_back(o);
  IpoptSolver solver(options);
  NlpPoint start;
  start.z = x0;
  testing::internal::CaptureStdout();
  solver.solve(nlp, start);
  std::fflush(stdout);
  return testing::internal::GetCapturedStdout();
}

TEST(ModelIpoptDerivativeTest, TwoRobotContactSceneHasNoErrors) {
  const Scene scene = model_test::two_robots_meeting_in_contact(5);
  const RobotProblem rp(scene);
  const ElasticNlp elastic(rp.program(), ElasticFormulation::kLumped, 10.0);
  const Vector x0 = elastic.lift(smoothstep_guess(rp, 4.0));

  const std::string out = ipopt_derivative_test(elastic, x0, "second-order");
  EXPECT_NE(out.find("Starting derivative checker for second derivatives"), std::string::npos)
      << out;
  EXPECT_NE(out.find("No errors detected by derivative checker."), std::string::npos) << out;
  EXPECT_EQ(out.find("Derivative checker detected"), std::string::npos) << out;

  // Negative control: the same run on a corrupted Jacobian reports errors.
  const std::string bad = ipopt_derivative_test(ShiftedJacobian(elastic), x0, "first-order");
  EXPECT_NE(bad.find("Derivative checker detected"), std::string::npos) << bad;
  EXPECT_EQ(bad.find("No errors detected by derivative checker."), std::string::npos);
}

}  // namespace
}  // namespace disco
