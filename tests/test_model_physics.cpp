// Independent physics checks of the model equations (not of the solver).
//
// Each test builds a RobotProblem for a tiny scene, computes a motion BY HAND
// in SI units from elementary mechanics (semi-implicit Euler, Coulomb
// friction, inelastic impact), converts it to model units with
// RobotProblem::units() and places it with the Layout accessors. Every row of
// the model must then vanish (|c| < 1e-12 in model units), every bound and
// complementarity pair must hold; and the physically wrong variant of the
// same motion (friction aiding motion, the wrong torque sign, penetration,
// another damping law, ...) must violate them.
//
// The paper-vs-physics choices documented in the headers are each pinned:
//   * damping -sigma_d M g omega^{t+1}          (DampingIs...)
//   * impulse c_n^t paired with rho^{t+1}       (ImpactImpulse...)
//   * torque -R o (alpha_1 - alpha_2) on BOTH robots, same sign (SlidingContact...)
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "core/model/robot_problem.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

using model_test::edge_direction;
using model_test::make_robot;
using model_test::make_scene;
using model_test::Residuals;
using model_test::residuals;
using model_test::ToModel;

constexpr double kExact = 1e-12;  // "satisfied", model units
constexpr double kG = 9.81;

using Trajectory = std::vector<State>;  // SI states, t = 0..N

// Places SI values into a model-unit point of a RobotProblem.
class PointBuilder {
 public:
  explicit PointBuilder(const RobotProblem& rp)
      : rp_(rp), L_(rp.layout()), to_{rp.units()}, z_(Vector::Zero(rp.program().num_variables())) {
    // Every robot starts out resting where the scene starts it.
    for (int i = 0; i < static_cast<int>(rp.scene().robots.size()); ++i)
      states(i, Trajectory(L_.steps() + 1, rp.scene().robots[i].start));
  }

  void horizon(double seconds) { z_[L_.horizon_index()] = to_.time(seconds); }
  // States t = 1..N of robot i (t = 0 is the scene's start).
  void states(int i, const Trajectory& q) {
    EXPECT_EQ(static_cast<int>(q.size()), L_.steps() + 1);
    for (int t = 1; t <= L_.steps(); ++t) {
      set(i, t, kX, to_.length(q[t][kX]));
      set(i, t, kY, to_.length(q[t][kY]));
      set(i, t, kPhi, q[t][kPhi]);
      set(i, t, kVx, to_.velocity(q[t][kVx]));
      set(i, t, kVy, to_.velocity(q[t][kVy]));
      set(i, t, kOmega, to_.omega(q[t][kOmega]));
    }
  }
  // A state the model holds as a constant (phi, omega of a robot that does
  // not turn) must already have the value the motion gives it.
  void set(int i, int t, int c, double v) {
    if (const int k = L_.state_index(i, t, c); k >= 0) {
      z_[k] = v;
    } else {
      EXPECT_EQ(L_.state(i, t, c).value(z_), v) << "robot " << i << ", state " << t << ", component " << c;
    }
  }
  // World-frame force [N]; a one-axis robot takes the component along its axis.
  void force(int i, int t, double fx, double fy) {
    const Robot& rb = rp_.scene().robots[i];
    const auto& idx = L_.force_indices(i, t);
    if (rb.force_dims == 2) {
      z_[idx[0]] = to_.force(fx);
      z_[idx[1]] = to_.force(fy);
    } else {
      z_[idx[0]] = to_.force(fx * rb.force_axis[0] + fy * rb.force_axis[1]);
    }
  }
  void beta(int i, int t, int k, double newtons) { z_[L_.beta_index(i, t, k)] = to_.force(newtons); }
  void floor_gamma(int i, int t, double speed) {
    z_[L_.floor_gamma_index(i, t)] = to_.velocity(speed);
  }
  void gap(int p, int t, double metres) { z_[L_.gap_index(p, t)] = to_.length(metres); }
  // Gaps t = 1..N from the robots' positions.
  void gaps_from(int p, const Trajectory& qi, const Trajectory& qj) {
    const Pair& pr = rp_.scene().pairs[p];
    const double R = rp_.scene().robots[pr.i].radius + rp_.scene().robots[pr.j].radius;
    for (int t = 1; t <= L_.steps(); ++t)
      gap(p, t, std::hypot(qj[t][kX] - qi[t][kX], qj[t][kY] - qi[t][kY]) - R);
  }
  void normal_multiplier(int p, int t, double v) { z_[L_.normal_multiplier_index(p, t)] = to_.contact_multiplier(v); }
  void alpha1(int p, int t, double v) { z_[L_.alpha1_index(p, t)] = to_.contact_multiplier(v); }
  void alpha2(int p, int t, double v) { z_[L_.alpha2_index(p, t)] = to_.contact_multiplier(v); }
  void contact_gamma(int p, int t, double v) { z_[L_.contact_gamma_index(p, t)] = to_.contact_gamma(v); }

  const Vector& z() const { return z_; }

 private:
  const RobotProblem& rp_;
  const Layout& L_;
  ToModel to_;
  Vector z_;
};

void expect_satisfied(const RobotProblem& rp, const Vector& z) {
  const Residuals r = residuals(rp.program(), z);
  EXPECT_LT(r.equality, kExact) << "worst equality row " << r.worst_equality_row;
  EXPECT_LE(r.inequality, kExact);
  EXPECT_LE(r.bounds, kExact);
  EXPECT_LE(r.side_negative, kExact) << "pair " << r.worst_pair;
  EXPECT_LT(r.complementarity, kExact) << "worst pair " << r.worst_pair;
}

// Semi-implicit Euler positions from the velocities: p^{t+1} = p^t + h v^{t+1}.
void integrate_positions(Trajectory& q, double h) {
  for (size_t t = 1; t < q.size(); ++t) {
    q[t][kX] = q[t - 1][kX] + h * q[t][kVx];
    q[t][kY] = q[t - 1][kY] + h * q[t][kVy];
    q[t][kPhi] = q[t - 1][kPhi] + h * q[t][kOmega];
  }
}

// A one-robot experiment, with an idle partner far away (at rest, avoid
// mode) that is 3 times heavier, twice as large and strong: so the model's
// units are not the robot's own (its mass, radius and F_max are not 1 in
// model units) and a unit error in any term shows.
Scene with_idle_partner(const std::string& name, int steps, const Robot& r) {
  Robot idle = make_robot("idle", 2 * r.radius, 3 * r.mass, 0.1, 2 * r.force_max, 100.0, 100.0, 5);
  return make_scene(name, steps, {r, idle}, PairMode::kAvoid);
}

const std::vector<Family> kFloorOnly = {Family::kKinematics, Family::kDynamics,
                                        Family::kFloorFriction};

// ------------------------------------------------------- floor friction ---

// One robot sliding along the K-gon vertex direction 45 degrees (K = 8) with
// no force: it decelerates at mu g, the friction (mu M g, on the vertex at
// 225 degrees) opposing the motion, gamma = |v|; in the last interval the
// remaining speed is less than h mu g and static friction stops it exactly
// (v = 0, friction M v / h < mu M g, gamma = 0): it never reverses.
struct Slide {
  Scene scene;
  double h = 0.1, T = 0.5;
  int steps = 5;
  Trajectory q;
  std::vector<double> friction;  // magnitude [N] per interval, on the vertex at 225 deg
};

Slide make_slide(double decel_factor) {
  Slide s;
  Robot r = make_robot("slider", 0.3, 2.0, 0.25, 30.0, 0.5, -0.2, 8);
  const double v0 = 1.0, c = std::sqrt(0.5);
  r.start = {0.5, -0.2, 0.4, v0 * c, v0 * c, 0.0};
  s.scene = with_idle_partner("slide", s.steps, r);
  s.q.assign(s.steps + 1, r.start);
  double speed = v0;
  for (int t = 0; t < s.steps; ++t) {
    double friction = decel_factor * r.mu * r.mass * kG;  // kinetic
    double next = speed - s.h * friction / r.mass;
    if (next < 0.0) next = 0.0, friction = r.mass * speed / s.h;  // static: it stops
    s.friction.push_back(friction);
    speed = next;
    s.q[t + 1][kVx] = speed * c;
    s.q[t + 1][kVy] = speed * c;
    s.q[t + 1][kOmega] = 0.0;
  }
  integrate_positions(s.q, s.h);
  return s;
}

Vector slide_point(const RobotProblem& rp, const Slide& s) {
  PointBuilder b(rp);
  b.horizon(s.T);
  b.states(0, s.q);
  for (int t = 0; t < s.steps; ++t) {
    b.force(0, t, 0.0, 0.0);
    b.beta(0, t, 5, s.friction[t]);
    b.floor_gamma(0, t, std::hypot(s.q[t + 1][kVx], s.q[t + 1][kVy]));
  }
  return b.z();
}

TEST(ModelPhysics, SlidingRobotDeceleratesAtMuGAndStopsWithoutReversing) {
  const Slide s = make_slide(1.0);
  const RobotProblem rp(s.scene, kFloorOnly);
  // The construction: kinetic friction in the first four intervals, the stop in the last.
  const double mMg = 0.25 * 2.0 * kG;
  for (int t = 0; t < 4; ++t) EXPECT_EQ(s.friction[t], mMg);
  EXPECT_GT(s.friction[4], 0.0);
  EXPECT_LT(s.friction[4], mMg);
  EXPECT_EQ(s.q[5][kVx], 0.0);
  expect_satisfied(rp, slide_point(rp, s));
}

TEST(ModelPhysics, FrictionOfTheWrongSizeOrDirectionIsRejected) {
  // Half the kinetic friction while sliding: gamma > 0 but the budget
  // mu M g - sum beta is not used up.
  {
    const Slide s = make_slide(0.5);
    const RobotProblem rp(s.scene, kFloorOnly);
    const Residuals r = residuals(rp.program(), slide_point(rp, s));
    EXPECT_LT(r.equality, kExact);  // kinematics and momentum still balance
    EXPECT_GT(r.complementarity, 1e-2);
  }
  // Friction aiding the motion: the robot speeds up at mu g with friction on
  // the vertex along v (45 degrees).
  {
    Slide s = make_slide(1.0);
    const RobotProblem rp(s.scene, kFloorOnly);
    const Robot& rb = s.scene.robots[0];
    double speed = 1.0;
    const double c = std::sqrt(0.5);
    for (int t = 0; t < s.steps; ++t) {
      speed += s.h * rb.mu * kG;
      s.q[t + 1][kVx] = s.q[t + 1][kVy] = speed * c;
    }
    integrate_positions(s.q, s.h);
    PointBuilder b(rp);
    b.horizon(s.T);
    b.states(0, s.q);
    for (int t = 0; t < s.steps; ++t) {
      b.beta(0, t, 1, rb.mu * rb.mass * kG);
      b.floor_gamma(0, t, std::hypot(s.q[t + 1][kVx], s.q[t + 1][kVy]));
    }
    const Residuals r = residuals(rp.program(), b.z());
    EXPECT_LT(r.equality, kExact);
    EXPECT_GT(r.complementarity, 1e-2);
  }
  // Explicit Euler positions (p^{t+1} = p^t + h v^t): the kinematics rows break.
  {
    Slide s = make_slide(1.0);
    const RobotProblem rp(s.scene, kFloorOnly);
    for (int t = 1; t <= s.steps; ++t) {
      s.q[t][kX] = s.q[t - 1][kX] + s.h * s.q[t - 1][kVx];
      s.q[t][kY] = s.q[t - 1][kY] + s.h * s.q[t - 1][kVy];
    }
    EXPECT_GT(residuals(rp.program(), slide_point(rp, s)).equality, 1e-3);
  }
}

// A robot at rest pushed with |F| = 0.8 mu M g: static friction -F, split on
// the two polygon vertices around -F (K = 8: 90 and 135 degrees), gamma = 0.
TEST(ModelPhysics, StaticFrictionHoldsARobotPushedBelowMuMg) {
  Robot r = make_robot("held", 0.4, 1.5, 0.3, 20.0, 1.0, 2.0, 8);
  r.start[kPhi] = 0.7;
  const Scene scene = with_idle_partner("held", 3, r);
  const RobotProblem rp(scene, kFloorOnly);
  const double mMg = r.mu * r.mass * kG, h = 0.2;
  const auto d2 = edge_direction(2, 8), d3 = edge_direction(3, 8);
  const double a = 0.5 * mMg, bb = 0.3 * mMg;  // friction = a d2 + bb d3
  const double fx = -(a * d2[0] + bb * d3[0]), fy = -(a * d2[1] + bb * d3[1]);
  ASSERT_LT(std::hypot(fx, fy), mMg);

  // At rest: valid.
  {
    PointBuilder b(rp);
    b.horizon(3 * h);
    b.states(0, Trajectory(4, r.start));
    for (int t = 0; t < 3; ++t) {
      b.force(0, t, fx, fy);
      b.beta(0, t, 2, a);
      b.beta(0, t, 3, bb);
    }
    expect_satisfied(rp, b.z());
  }
  // Accelerating as if there were no floor friction: momentum balances, but
  // the robot slides (gamma > 0) while the friction budget is unused.
  {
    Trajectory q(4, r.start);
    for (int t = 0; t < 3; ++t) {
      q[t + 1][kVx] = q[t][kVx] + h * fx / r.mass;
      q[t + 1][kVy] = q[t][kVy] + h * fy / r.mass;
    }
    integrate_positions(q, h);
    PointBuilder b(rp);
    b.horizon(3 * h);
    b.states(0, q);
    for (int t = 0; t < 3; ++t) {
      b.force(0, t, fx, fy);
      double lowest = kInf;
      for (int k = 0; k < 8; ++k) {
        const auto d = edge_direction(k, 8);
        lowest = std::min(lowest, d[0] * q[t + 1][kVx] + d[1] * q[t + 1][kVy]);
      }
      b.floor_gamma(0, t, -lowest);
    }
    const Residuals res = residuals(rp.program(), b.z());
    EXPECT_LT(res.equality, kExact);
    EXPECT_GT(res.complementarity, 1e-2);
  }
}

// Pushed with 1.2 mu M g along -y (a vertex direction): static friction
// cannot hold it (the budget row would go negative); it slides with
// acceleration (|F| - mu M g) / M, friction mu M g on the vertex along +y.
TEST(ModelPhysics, PushAboveMuMgCannotBeHeldAndAcceleratesTheRobot) {
  Robot r = make_robot("pushed", 0.4, 1.5, 0.3, 20.0, 1.0, 2.0, 8);
  const Scene scene = with_idle_partner("pushed", 3, r);
  const RobotProblem rp(scene, kFloorOnly);
  const double mMg = r.mu * r.mass * kG, h = 0.2, F = 1.2 * mMg;
  {  // "held" by a friction larger than mu M g
    PointBuilder b(rp);
    b.horizon(3 * h);
    b.states(0, Trajectory(4, r.start));
    for (int t = 0; t < 3; ++t) {
      b.force(0, t, 0.0, -F);
      b.beta(0, t, 2, F);
    }
    const Residuals res = residuals(rp.program(), b.z());
    EXPECT_LT(res.equality, kExact);
    EXPECT_GT(res.side_negative, 1e-3);
  }
  {  // sliding: valid
    Trajectory q(4, r.start);
    for (int t = 0; t < 3; ++t) q[t + 1][kVy] = q[t][kVy] - h * (F - mMg) / r.mass;
    integrate_positions(q, h);
    PointBuilder b(rp);
    b.horizon(3 * h);
    b.states(0, q);
    for (int t = 0; t < 3; ++t) {
      b.force(0, t, 0.0, -F);
      b.beta(0, t, 2, mMg);
      b.floor_gamma(0, t, -q[t + 1][kVy]);
    }
    expect_satisfied(rp, b.z());
  }
}

// A one-axis robot (D_ef = 1, axis on the diagonal) at full force F_max from
// rest: it slides along its axis at (F_max - mu M g) / M, friction on the
// vertex at 225 degrees; the force bound is active. 1.1 F_max breaks the bound.
TEST(ModelPhysics, OneAxisRobotAcceleratesAlongItsAxisWithinItsForceBound) {
  Robot r = make_robot("axis", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0, 8);
  r.force_dims = 1;
  r.force_axis = {std::sqrt(0.5), std::sqrt(0.5)};
  const Scene scene = with_idle_partner("axis", 4, r);
  const RobotProblem rp(scene, {Family::kKinematics, Family::kDynamics, Family::kFloorFriction,
                                Family::kBounds});
  const double h = 0.1, mMg = r.mu * r.mass * kG;
  auto point = [&](double f) {
    Trajectory q(5, r.start);
    double speed = 0;
    for (int t = 0; t < 4; ++t) {
      speed += h * (f - mMg) / r.mass;
      q[t + 1][kVx] = speed * r.force_axis[0];
      q[t + 1][kVy] = speed * r.force_axis[1];
    }
    integrate_positions(q, h);
    PointBuilder b(rp);
    b.horizon(4 * h);
    b.states(0, q);
    for (int t = 0; t < 4; ++t) {
      b.force(0, t, f * r.force_axis[0], f * r.force_axis[1]);
      b.beta(0, t, 5, mMg);
      b.floor_gamma(0, t, std::hypot(q[t + 1][kVx], q[t + 1][kVy]));
    }
    return b.z();
  };
  expect_satisfied(rp, point(r.force_max));
  const Residuals res = residuals(rp.program(), point(1.1 * r.force_max));
  EXPECT_LT(res.equality, kExact);
  EXPECT_GT(res.bounds, 1e-3);

  // Without floor friction, on an axis that is not symmetric in x and y: the
  // velocity follows the axis, (0.6, -0.8), not (-0.8, 0.6) nor (0.8, -0.6).
  Robot free = r;
  free.mu = 0.0;
  free.force_axis = {0.6, -0.8};
  const Scene free_scene = with_idle_partner("free_axis", 4, free);
  const RobotProblem frp(free_scene, {Family::kKinematics, Family::kDynamics,
                                      Family::kFloorFriction, Family::kBounds});
  for (const auto& [ax, ay, valid] : {std::tuple{0.6, -0.8, true}, std::tuple{-0.8, 0.6, false},
                                      std::tuple{0.8, -0.6, false}}) {
    const double f = 0.7 * free.force_max;
    Trajectory q(5, free.start);
    for (int t = 0; t < 4; ++t) {
      q[t + 1][kVx] = q[t][kVx] + h * f * ax / free.mass;
      q[t + 1][kVy] = q[t][kVy] + h * f * ay / free.mass;
    }
    integrate_positions(q, h);
    PointBuilder b(frp);
    b.horizon(4 * h);
    b.states(0, q);
    for (int t = 0; t < 4; ++t) b.force(0, t, f * 0.6, -f * 0.8);
    const Residuals fr = residuals(frp.program(), b.z());
    if (valid) {
      EXPECT_LT(fr.worst(), kExact);
    } else {
      EXPECT_GT(fr.equality, 1e-3) << "velocity along (" << ax << ", " << ay << ")";
    }
  }
}

// ------------------------------------------------------------- damping ---

// A robot spinning in place, no force, no contact. The model's damping is
// I (w' - w) + h sigma_d M g w' = 0 (implicit, Section III-A.2's torque).
// Explicit damping, the appendix's "-sigma_d I phi", no damping and
// anti-damping all break the rotational momentum rows.
TEST(ModelPhysics, DampingIsMinusSigmaMGOmegaAtTheNewStep) {
  Robot r = make_robot("spinner", 0.3, 2.0, 0.25, 30.0, 1.0, 1.0, 6);
  r.damping = 0.05;
  r.start[kOmega] = 4.0;
  const Scene scene = with_idle_partner("spinner", 4, r);
  const RobotProblem rp(scene, kFloorOnly);
  const double h = 0.1, I = r.inertia, sMg = r.damping * r.mass * kG;
  ASSERT_DOUBLE_EQ(I, 0.09);

  auto point = [&](auto next_omega) {
    Trajectory q(5, r.start);
    for (int t = 0; t < 4; ++t) q[t + 1][kOmega] = next_omega(q[t][kOmega]);
    integrate_positions(q, h);
    PointBuilder b(rp);
    b.horizon(4 * h);
    b.states(0, q);
    return b.z();
  };
  const Vector right = point([&](double w) { return I * w / (I + h * sMg); });
  expect_satisfied(rp, right);
  EXPECT_LT(right[rp.layout().state_index(0, 4, kOmega)],
            0.5 * right[rp.layout().state_index(0, 1, kOmega)]);  // it does slow down

  const std::vector<std::pair<std::string, std::function<double(double)>>> wrong = {
      {"explicit damping", [&](double w) { return w * (1.0 - h * sMg / I); }},
      {"appendix -sigma_d I omega", [&](double w) { return w / (1.0 + h * r.damping); }},
      {"no damping", [&](double w) { return w; }},
      {"anti-damping", [&](double w) { return I * w / (I - h * sMg); }},
  };
  for (const auto& [name, law] : wrong) {
    SCOPED_TRACE(name);
    const Vector z = point(law);
    Vector c(rp.program().num_constraints());
    ASSERT_TRUE(rp.program().constraints(z, c));
    double rot = 0.0, other = 0.0;
    for (int row = 0; row < c.size(); ++row) {
      bool is_rot = false;
      for (int t = 0; t < 4; ++t) is_rot = is_rot || row == rp.layout().momentum_row(0, t, 2);
      if (rp.program().constraint_lower()[row] != rp.program().constraint_upper()[row]) continue;
      double& worst = is_rot ? rot : other;
      worst = std::max(worst, std::abs(c[row]));
    }
    EXPECT_GT(rot, 1e-3);
    EXPECT_LT(other, kExact);  // only the rotational rows tell
  }
}

// ------------------------------------------------------------- contact ---

// Two robots without floor friction, touching (gap 0), at rest, pushed
// together by equal and opposite forces P along the line of centres: the
// normal force c_n N, N = p_j - p_i NOT unit, balances them: c_n = P / o.
struct Pushed {
  Scene scene;
  Trajectory qi, qj;
  double o = 0.8, P = 10.0, h = 0.1;
  double ex = 0.6, ey = 0.8;  // unit vector from i to j
};

Pushed make_pushed(double centre_distance) {
  Pushed s;
  Robot i = make_robot("i", 0.3, 2.0, 0.0, 30.0, 1.0, 2.0, 6);
  Robot j = make_robot("j", 0.5, 3.0, 0.0, 30.0, 1.0 + centre_distance * s.ex,
                       2.0 + centre_distance * s.ey, 6);
  s.scene = make_scene("pushed", 3, {i, j}, PairMode::kContact, 0.3);
  s.qi.assign(4, i.start);
  s.qj.assign(4, j.start);
  return s;
}

Vector pushed_point(const RobotProblem& rp, const Pushed& s, double cn) {
  PointBuilder b(rp);
  b.horizon(3 * s.h);
  b.states(0, s.qi);
  b.states(1, s.qj);
  b.gaps_from(0, s.qi, s.qj);
  for (int t = 0; t < 3; ++t) {
    b.force(0, t, s.P * s.ex, s.P * s.ey);
    b.force(1, t, -s.P * s.ex, -s.P * s.ey);
    b.normal_multiplier(0, t, cn);
  }
  return b.z();
}

TEST(ModelPhysics, TouchingRobotsPushedTogetherAreHeldByTheNormalForce) {
  const Pushed s = make_pushed(0.8);
  const RobotProblem rp(s.scene);  // the whole model
  expect_satisfied(rp, pushed_point(rp, s, s.P / s.o));
  // A unit-normal reading (c_n = P) or no contact force leaves momentum unbalanced.
  EXPECT_GT(residuals(rp.program(), pushed_point(rp, s, s.P)).equality, 1e-3);
  EXPECT_GT(residuals(rp.program(), pushed_point(rp, s, 0.0)).equality, 1e-3);
  // A pulling contact force (forces reversed) breaks c_n >= 0.
  Pushed pulled = s;
  pulled.P = -s.P;
  const Residuals pull = residuals(rp.program(), pushed_point(rp, pulled, pulled.P / s.o));
  EXPECT_LT(pull.equality, kExact);
  EXPECT_GT(pull.bounds + pull.side_negative, 1e-3);
}

TEST(ModelPhysics, NoContactForceAtADistanceAndNoPenetration) {
  {  // 0.2 m apart: a push "through the air" violates c_n _|_ rho.
    const Pushed s = make_pushed(1.0);
    Pushed apart = s;
    apart.o = 1.0;
    const RobotProblem rp(apart.scene);
    const Residuals r = residuals(rp.program(), pushed_point(rp, apart, apart.P / apart.o));
    EXPECT_LT(r.equality, kExact);
    EXPECT_GT(r.complementarity, 1e-3);
  }
  {  // Overlapping by 0.1 m (a scene start that overlaps, states too): rho < 0.
    Pushed s = make_pushed(0.7);
    s.o = 0.7;
    const RobotProblem rp(s.scene);
    const Residuals r = residuals(rp.program(), pushed_point(rp, s, s.P / s.o));
    EXPECT_LT(r.equality, kExact);
    EXPECT_GT(r.side_negative, 0.1);
  }
}

// Collinear impact (x axis, no floor friction). Robot j (R 0.5, M 3) comes at
// 6 m/s towards robot i (R 0.3, M 2, at rest); the gap is 0.5 m at t = 0 and
// 0.2 m at t = 1, and h = 0.05. Interval 1 is the impact: the impulse c_n^1 > 0
// lands the disks exactly touching at t = 2 (rho^2 = 0) while rho^1 = 0.2 > 0,
// which is what pairing c_n^t with rho^{t+1} allows (Appendix A's c_n^t _|_
// rho^t would forbid it). Interval 2 stops the relative motion; in interval
// 3 they move together at the momentum-conserving -3.6 m/s with c_n = 0.
TEST(ModelPhysics, ImpactImpulseIsPairedWithTheGapAtTheEndOfTheInterval) {
  Robot i = make_robot("i", 0.3, 2.0, 0.0, 30.0, 0.0, 0.5, 6);
  Robot j = make_robot("j", 0.5, 3.0, 0.0, 30.0, 1.3, 0.5, 6);
  j.start[kVx] = -6.0;
  const Scene scene = make_scene("impact", 4, {i, j}, PairMode::kContact, 0.3);
  const RobotProblem rp(scene);
  const Layout& L = rp.layout();
  const double h = 0.05, inv_m = 1.0 / 2.0 + 1.0 / 3.0;

  Trajectory qi(5, i.start), qj(5, j.start);
  std::vector<double> cn(4, 0.0);
  // One semi-implicit step of both robots under the normal impulse h c_n N^t
  // (N^t = p_j^t - p_i^t, along x here).
  auto step = [&](int t) {
    const double N = qj[t][kX] - qi[t][kX];
    qj[t + 1][kVx] = qj[t][kVx] + h * cn[t] * N / 3.0;
    qi[t + 1][kVx] = qi[t][kVx] - h * cn[t] * N / 2.0;
    qj[t + 1][kX] = qj[t][kX] + h * qj[t + 1][kVx];
    qi[t + 1][kX] = qi[t][kX] + h * qi[t + 1][kVx];
  };
  step(0);  // free flight
  // Interval 1, the impact: choose c_n^1 so that x_j^2 - x_i^2 = R_i + R_j.
  const double o1 = qj[1][kX] - qi[1][kX];
  cn[1] = (-(o1 - 0.8) / h - (qj[1][kVx] - qi[1][kVx])) / (h * o1 * inv_m);
  step(1);
  // Interval 2, touching: stop the relative motion.
  const double o2 = qj[2][kX] - qi[2][kX];
  cn[2] = -(qj[2][kVx] - qi[2][kVx]) / (h * o2 * inv_m);
  step(2);
  step(3);  // together, no force
  // The construction, checked on its own.
  ASSERT_GT(cn[1], 0.0);
  ASSERT_GT(cn[2], 0.0);
  EXPECT_NEAR(o1, 1.0, 1e-14);
  EXPECT_NEAR(o2, 0.8, 1e-14);
  EXPECT_NEAR(qj[4][kX] - qi[4][kX], o2, 1e-14);
  EXPECT_NEAR(qi[4][kVx], -3.6, 1e-12);
  EXPECT_NEAR(qj[4][kVx], -3.6, 1e-12);

  PointBuilder b(rp);
  b.horizon(4 * h);
  b.states(0, qi);
  b.states(1, qj);
  b.gaps_from(0, qi, qj);
  for (int t = 0; t < 4; ++t) b.normal_multiplier(0, t, cn[t]);
  expect_satisfied(rp, b.z());

  // The pairing itself: c_n^t with rho^{t+1}, both variables.
  for (int t = 0; t < 4; ++t) {
    int found = 0;
    for (const auto& p : rp.program().complementarity_pairs())
      if (p.g.kind == ComplementaritySide::Kind::kVariable && p.g.index == L.normal_multiplier_index(0, t))
        found += p.h.kind == ComplementaritySide::Kind::kVariable && p.h.index == L.gap_index(0, t + 1);
    EXPECT_EQ(found, 1) << "c_n^" << t;
  }
  // Without the impulse j passes into i: rho^2 = -0.1 < 0.
  Trajectory qj_free(5, j.start);
  for (int t = 1; t <= 4; ++t) qj_free[t][kVx] = -6.0;
  integrate_positions(qj_free, h);
  PointBuilder free(rp);
  free.horizon(4 * h);
  free.states(0, Trajectory(5, i.start));
  free.states(1, qj_free);
  free.gaps_from(0, Trajectory(5, i.start), qj_free);
  const Residuals r = residuals(rp.program(), free.z());
  EXPECT_LT(r.equality, kExact);
  EXPECT_GT(r.side_negative, 0.1);
}

// Sliding contact by spin. i (R 0.3, M 2) and j (R 0.5, M 3) touch along x
// (j on the right), held at rest by forces that balance the normal push and
// the contact friction. j spins clockwise (omega < 0), so its contact point
// moves up relative to i's: v_T = -o (R_j w_j + R_i w_i) > 0. Coulomb: the
// friction on j is down (-T), alpha_2 = mu c_n, alpha_1 = 0, gamma = v_T.
// Its torque on j, at j's leftmost point, is counter-clockwise; the opposite
// friction on i, at i's rightmost point, is counter-clockwise too: both
// robots receive -R o (alpha_1 - alpha_2) > 0. j's spin decays (damping plus
// friction), i starts turning counter-clockwise (the two meshing like gears).
struct SpinContact {
  Scene scene;
  Trajectory qi, qj;
  double h = 0.01, cn = 20.0, mu = 0.4, o = 0.8;
  std::vector<double> vT;  // v_T^{t+1} per interval [m^2/s]
};

// slip_sign: -1 friction opposing the slip (alpha_2 = mu c_n), +1 aiding it.
// torque_i, torque_j: +1 the model's torque -R o slip, -1 its opposite.
SpinContact make_spin(int slip_sign, int torque_i, int torque_j) {
  SpinContact s;
  Robot i = make_robot("i", 0.3, 2.0, 0.2, 40.0, 0.0, 0.0, 6);
  Robot j = make_robot("j", 0.5, 3.0, 0.2, 40.0, 0.8, 0.0, 6);
  j.start[kOmega] = -20.0;
  s.scene = make_scene("spin", 4, {i, j}, PairMode::kContact, s.mu);
  s.qi.assign(5, i.start);
  s.qj.assign(5, j.start);
  const double slip = slip_sign * s.mu * s.cn;  // alpha_1 - alpha_2
  for (int t = 0; t < 4; ++t) {
    auto next = [&](const Robot& r, double w, int sign) {
      const double torque = -sign * r.radius * s.o * slip;  // sign +1: the model's
      return (r.inertia * w + s.h * torque) / (r.inertia + s.h * r.damping * r.mass * kG);
    };
    s.qi[t + 1][kOmega] = next(i, s.qi[t][kOmega], torque_i);
    s.qj[t + 1][kOmega] = next(j, s.qj[t][kOmega], torque_j);
    s.vT.push_back(-s.o * (j.radius * s.qj[t + 1][kOmega] + i.radius * s.qi[t + 1][kOmega]));
  }
  integrate_positions(s.qi, s.h);
  integrate_positions(s.qj, s.h);
  return s;
}

Vector spin_point(const RobotProblem& rp, const SpinContact& s, int slip_sign) {
  const double slip = slip_sign * s.mu * s.cn;
  PointBuilder b(rp);
  b.horizon(4 * s.h);
  b.states(0, s.qi);
  b.states(1, s.qj);
  b.gaps_from(0, s.qi, s.qj);
  // N = (o, 0), T = (0, o). Robot j: F_j + c_n N + slip T = 0; i the opposite.
  for (int t = 0; t < 4; ++t) {
    b.force(1, t, -s.cn * s.o, -slip * s.o);
    b.force(0, t, s.cn * s.o, slip * s.o);
    b.normal_multiplier(0, t, s.cn);
    (slip_sign > 0 ? b.alpha1(0, t, s.mu * s.cn) : b.alpha2(0, t, s.mu * s.cn));
    b.contact_gamma(0, t, std::abs(s.vT[t]));
  }
  return b.z();
}

TEST(ModelPhysics, SlidingContactFrictionOpposesTheSlipAndTurnsBothRobotsTheSameWay) {
  const SpinContact s = make_spin(-1, +1, +1);
  const RobotProblem rp(s.scene);  // the whole model
  for (double v : s.vT) ASSERT_GT(v, 0.0);  // sliding throughout
  const Vector z = spin_point(rp, s, -1);
  expect_satisfied(rp, z);
  // The physics of the construction: j slows down, i is turned counter-clockwise,
  // and the friction dissipates: (alpha_1 - alpha_2) v_T < 0.
  EXPECT_GT(s.qj[4][kOmega], -20.0 * std::pow(1.0 / (1.0 + 0.01 * 0.05 * 3 * kG / 0.375), 4) + 1e-3);
  EXPECT_GT(s.qi[4][kOmega], 0.5);
  EXPECT_LT(-s.mu * s.cn * s.vT[0], 0.0);
  EXPECT_NEAR(z[rp.layout().alpha2_index(0, 0)],
              s.mu * z[rp.layout().normal_multiplier_index(0, 0)], 1e-15);
}

TEST(ModelPhysics, ContactFrictionAidingTheSlipIsRejected) {
  const SpinContact s = make_spin(+1, +1, +1);  // alpha_1 = mu c_n while v_T > 0
  const RobotProblem rp(s.scene);
  for (double v : s.vT) ASSERT_GT(v, 0.0);
  const Residuals r = residuals(rp.program(), spin_point(rp, s, +1));
  EXPECT_LT(r.equality, kExact);  // the motion is consistent with that friction
  EXPECT_GT(r.complementarity, 1e-2);
}

TEST(ModelPhysics, ContactTorqueOfTheWrongSignOnEitherRobotIsRejected) {
  for (const auto& [robot, ti, tj] : {std::tuple{1, +1, -1}, std::tuple{0, -1, +1}}) {
    SCOPED_TRACE(robot == 1 ? "appendix's first line: opposite torque on j"
                            : "equal and opposite torques: opposite torque on i");
    const SpinContact s = make_spin(-1, ti, tj);
    const RobotProblem rp(s.scene);
    const Vector z = spin_point(rp, s, -1);
    Vector c(rp.program().num_constraints());
    ASSERT_TRUE(rp.program().constraints(z, c));
    double wrong_rows = 0.0;
    for (int t = 0; t < 4; ++t) {
      wrong_rows = std::max(wrong_rows, std::abs(c[rp.layout().momentum_row(robot, t, 2)]));
      EXPECT_LT(std::abs(c[rp.layout().momentum_row(1 - robot, t, 2)]), kExact);
    }
    EXPECT_GT(wrong_rows, 1e-3);
  }
}

// ----------------------------------------------------------- avoidance ---

TEST(ModelPhysics, AvoidPairsKeepTheSafeDistanceAndHaveNoContactForces) {
  // Two robots at rest with their centres xj apart along x: gap xj - 0.8, d_s = 0.02.
  auto at_rest = [](double xj) {
    Robot i = make_robot("i", 0.3, 2.0, 0.0, 30.0, 0.0, 0.0, 6);
    Robot j = make_robot("j", 0.5, 3.0, 0.0, 30.0, xj, 0.0, 6);
    const RobotProblem rp(make_scene("avoid", 2, {i, j}, PairMode::kAvoid, 0.3, 0.02));
    EXPECT_FALSE(rp.layout().is_contact(0));
    for (int t = 0; t < rp.layout().steps(); ++t) EXPECT_FALSE(rp.layout().has_contact(0, t));
    PointBuilder b(rp);
    b.horizon(1.0);
    b.states(0, Trajectory(3, i.start));
    b.states(1, Trajectory(3, j.start));
    b.gaps_from(0, Trajectory(3, i.start), Trajectory(3, j.start));
    Residuals r = residuals(rp.program(), b.z());
    r.bounds *= rp.units().length;  // back to metres
    return r;
  };
  EXPECT_LT(at_rest(0.85).worst(), kExact);  // gap 0.05 > d_s
  EXPECT_LT(at_rest(0.82).worst(), kExact);  // gap = d_s
  const Residuals r = at_rest(0.81);         // gap 0.01 < d_s
  EXPECT_LT(r.equality, kExact);
  EXPECT_NEAR(r.bounds, 0.01, 1e-12);
}

}  // namespace
}  // namespace disco
