// The quantities each constraint family computes at a point, for the guesses, the
// transfer between plans and the solution file (sliding_velocity, contact_force,
// floor_friction_force, centre_gap; the friction polygon's vertex and dissipation ratio),
// are the ones its rows contain. Each is checked against the rows of models built with and
// without the family, at random points: a family's impulse is the difference its rows make
// to the momentum rows (rows are M dv - h F - impulses, core/model/dynamics.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "core/model/bounds.h"
#include "core/model/contact_friction.h"
#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/robot_problem.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

using model_test::make_robot;
using model_test::make_scene;

// Three robots in contact pairs, K = 6, spinning at random: every term of every row acts.
Scene three_in_contact() {
  std::vector<Robot> robots = {make_robot("a", 0.5, 1.0, 0.3, 5.0, 0.0, 0.0),
                               make_robot("b", 0.4, 2.0, 0.2, 6.0, 1.2, 0.1),
                               make_robot("c", 0.6, 1.5, 0.25, 7.0, 0.4, 1.3)};
  for (Robot& r : robots) r.target.lower[kX] = r.target.upper[kX] = r.start[kX] + 1.0;
  return make_scene("three", 6, robots, PairMode::kContact, 0.4);
}

const ModelOptions kFull{false, kInf};

// A random point of `rp`: every unknown uniform in [-1, 1], T_f = 1.3 (model units), and
// the gap unknowns consistent with the centres (so o = rho + R = |N|).
Vector random_point(const RobotProblem& rp, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector z(rp.program().num_variables());
  for (int k = 0; k < z.size(); ++k) z[k] = u(g);
  const Layout& L = rp.layout();
  z[L.horizon_index()] = 1.3;
  for (int p = 0; p < static_cast<int>(L.model_scene().pairs.size()); ++p)
    for (int t = 1; t <= L.steps(); ++t)
      if (L.gap_index(p, t) >= 0) z[L.gap_index(p, t)] = centre_gap(L, z, p, t);
  return z;
}

Vector rows(const RobotProblem& rp, const Vector& z) {
  Vector c(rp.program().num_constraints());
  EXPECT_TRUE(rp.program().constraints(z, c));
  return c;
}

// (momentum row without `extra` - with it) / h per robot, step and axis: the impulse `extra`
// adds, divided by h (a force, or a torque for axis 2).
std::vector<std::vector<std::array<double, 3>>> added_force(const Scene& scene, Family extra,
                                                              std::uint64_t seed) {
  const RobotProblem base(scene, {Family::kDynamics}, kFull);
  const RobotProblem with(scene, {Family::kDynamics, extra}, kFull);
  const Vector z = random_point(with, seed);
  EXPECT_EQ(base.program().num_variables(), with.program().num_variables());
  const Vector a = rows(base, z), b = rows(with, z);
  const Layout& L = with.layout();
  const double h = z[L.horizon_index()] / L.steps();
  const int nr = static_cast<int>(scene.robots.size());
  std::vector<std::vector<std::array<double, 3>>> f(nr, std::vector<std::array<double, 3>>(L.steps()));
  for (int i = 0; i < nr; ++i)
    for (int t = 0; t < L.steps(); ++t)
      for (int axis = 0; axis < 3; ++axis) {
        const int r = L.momentum_row(i, t, axis);
        EXPECT_EQ(r, base.layout().momentum_row(i, t, axis));
        f[i][t][axis] = (a[r] - b[r]) / h;
      }
  return f;
}

TEST(FamilyQuantities, ContactForceIsWhatTheContactFamiliesAddToTheMomentumRows) {
  const Scene scene = three_in_contact();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto normal = added_force(scene, Family::kNonpenetration, seed);
    const auto friction = added_force(scene, Family::kContactFriction, seed);
    const RobotProblem with(scene, {Family::kDynamics}, kFull);
    const Vector z = random_point(with, seed);
    const Layout& L = with.layout();
    for (int t = 0; t < L.steps(); ++t) {
      std::vector<std::array<double, 3>> sum(scene.robots.size(), {0.0, 0.0, 0.0});
      for (int p = 0; p < static_cast<int>(scene.pairs.size()); ++p) {
        const ContactForce f = contact_force(L, z, p, t);
        const Pair& pr = scene.pairs[p];
        for (int a = 0; a < 2; ++a) {
          sum[pr.j][a] += f.on_j[a];
          sum[pr.i][a] -= f.on_j[a];
        }
        sum[pr.j][2] += f.torque_j;
        sum[pr.i][2] += f.torque_i;
      }
      for (int i = 0; i < static_cast<int>(scene.robots.size()); ++i)
        for (int a = 0; a < 3; ++a) {
          const double rows_say = normal[i][t][a] + friction[i][t][a];
          EXPECT_NEAR(sum[i][a], rows_say, 1e-12 * (1.0 + std::abs(rows_say)))
              << "robot " << i << " step " << t << " axis " << a << " seed " << seed;
        }
    }
  }
}

TEST(FamilyQuantities, FloorFrictionForceIsWhatTheFloorFamilyAddsToTheMomentumRows) {
  const Scene scene = three_in_contact();
  const auto added = added_force(scene, Family::kFloorFriction, 7);
  const RobotProblem rp(scene, {Family::kDynamics}, kFull);
  const Vector z = random_point(rp, 7);
  for (int i = 0; i < static_cast<int>(scene.robots.size()); ++i)
    for (int t = 0; t < rp.layout().steps(); ++t) {
      const std::array<double, 2> f = floor_friction_force(rp.layout(), z, i, t);
      for (int a = 0; a < 2; ++a)
        EXPECT_NEAR(f[a], added[i][t][a], 1e-12 * (1.0 + std::abs(added[i][t][a]))) << i << " " << t;
      EXPECT_EQ(added[i][t][2], 0.0) << "floor friction exerts no torque";
    }
}

TEST(FamilyQuantities, SlidingVelocityIsTheContactFrictionRowLessGamma) {
  // Rows of the contact friction family, per pair and contact step in order: v_T + gamma,
  // -v_T + gamma, mu c_n - alpha_1 - alpha_2 (core/model/contact_friction.h).
  const Scene scene = three_in_contact();
  const RobotProblem rp(scene, {Family::kDynamics, Family::kContactFriction}, kFull);
  const Layout& L = rp.layout();
  for (std::uint64_t seed : {4u, 5u}) {
    const Vector z = random_point(rp, seed);
    const Vector c = rows(rp, z);
    std::map<int, std::vector<int>> by_pair;
    for (int r = 0; r < rp.program().num_constraints(); ++r) {
      const int tag = rp.program().row_tag(r);
      if (tag < 0) continue;
      const Layout::RowOwner& o = L.row_owner(tag);
      if (o.pair && std::strcmp(o.family, "contact friction") == 0) by_pair[o.index].push_back(r);
    }
    ASSERT_EQ(by_pair.size(), scene.pairs.size());
    for (const auto& [p, list] : by_pair) {
      ASSERT_EQ(static_cast<int>(list.size()), 3 * L.steps());
      for (int t = 0; t < L.steps(); ++t) {
        const double vT = sliding_velocity(L, z, p, t), gamma = z[L.contact_gamma_index(p, t)];
        EXPECT_NEAR(c[list[3 * t]], vT + gamma, 1e-12 * (1.0 + std::abs(vT))) << p << " " << t;
        EXPECT_NEAR(c[list[3 * t + 1]], -vT + gamma, 1e-12 * (1.0 + std::abs(vT))) << p << " " << t;
      }
    }
  }
}

TEST(FamilyQuantities, TheMostOpposedVertexDissipatesAtLeastTheLeastRatio) {
  // Maximum dissipation picks the vertex minimising d_k . v; the adaptive plan's bound
  // (core/model/model_plan.h) rests on min_k d_k . v <= -cos(pi / K) |v|, with equality
  // halfway between two vertices.
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  for (int K : {3, 4, 6, 16, 64}) {
    for (int n = 0; n < 200; ++n) {
      const double a = angle(g), speed = 0.1 + n;
      const double vx = speed * std::cos(a), vy = speed * std::sin(a);
      const FrictionVertex v = most_opposed_vertex(K, vx, vy);
      double lowest = kInf;
      for (int k = 0; k < K; ++k) {
        const double d = std::cos(2.0 * std::numbers::pi * k / K) * vx + std::sin(2.0 * std::numbers::pi * k / K) * vy;
        lowest = std::min(lowest, d);
      }
      EXPECT_EQ(v.dot, lowest);
      const auto d = friction_direction(v.k, K);
      EXPECT_EQ(d[0] * vx + d[1] * vy, v.dot);
      EXPECT_LE(v.dot, -least_dissipation_ratio(K) * speed * (1.0 - 1e-12)) << K;
    }
    // Halfway between vertices 0 and 1 the bound is reached.
    const double half = std::numbers::pi / K;
    EXPECT_NEAR(most_opposed_vertex(K, -std::cos(half), -std::sin(half)).dot, -least_dissipation_ratio(K), 1e-12);
  }
}

TEST(FamilyQuantities, CentreGapClearanceAndTargetPose) {
  const Scene scene = three_in_contact();
  const RobotProblem rp(scene, kFull);
  const Vector z = random_point(rp, 9);
  const Layout& L = rp.layout();
  for (int p = 0; p < static_cast<int>(scene.pairs.size()); ++p) {
    const Pair& pr = L.model_scene().pairs[p];
    for (int t = 0; t <= L.steps(); ++t) {
      const double dx = L.state(pr.j, t, kX).value(z) - L.state(pr.i, t, kX).value(z);
      const double dy = L.state(pr.j, t, kY).value(z) - L.state(pr.i, t, kY).value(z);
      EXPECT_NEAR(centre_gap(L, z, p, t),
                  std::sqrt(dx * dx + dy * dy) - L.model_scene().robots[pr.i].radius -
                      L.model_scene().robots[pr.j].radius, 1e-13);
    }
  }
  Scene s = scene;
  s.pairs[0].mode = PairMode::kAvoid;
  s.pairs[0].safe_distance = 0.25;
  EXPECT_DOUBLE_EQ(clearance(s, s.pairs[0]), 0.5 + 0.4 + 0.25);
  EXPECT_DOUBLE_EQ(clearance(s, s.pairs[1]), 0.5 + 0.6);  // contact: no safe distance
  Robot r = scene.robots[0];
  r.start[kX] = 3.0;
  r.start[kY] = -2.0;
  r.start[kPhi] = 0.5;
  r.target.lower[kX] = 1.0, r.target.upper[kX] = 2.0;    // start above: the upper end
  r.target.lower[kY] = -1.0, r.target.upper[kY] = kInf;  // below: the lower end
  const Pose to = target_pose(r);                        // phi unbounded: the start's
  EXPECT_EQ(to[0], 2.0);
  EXPECT_EQ(to[1], -1.0);
  EXPECT_EQ(to[2], 0.5);
}

}  // namespace
}  // namespace disco
