#include "core/model/robot_problem.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "core/model/avoidance.h"
#include "core/model/bounds.h"
#include "core/model/contact_friction.h"
#include "core/model/dynamics.h"
#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/kinematics.h"
#include "core/model/lower_bound.h"
#include "core/model/nonpenetration.h"
#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

// The smallest horizon allowed, in model time units: keeps h > 0.
constexpr double kHorizonMin = 1e-3;

// The full guess for horizon T (model units) from the positions q[i][t][x, y,
// phi], t = 1..N, and the exact start state q[i][0]: velocities consistent with
// the kinematics, floor friction opposing the motion, forces balancing the
// momentum rows (clipped to their bounds), gaps from the positions, contact
// forces zero. Completes the velocity components of q.
Vector guess_from_positions(const Layout& layout, int num_variables,
                            std::vector<std::vector<State>>& q, double T) {
  const Scene& s = layout.scene();  // model units
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  const double h = T / N;
  Vector z = Vector::Zero(num_variables);
  z[layout.horizon_index()] = T;
  for (int i = 0; i < nr; ++i)
    for (int t = 1; t <= N; ++t) {
      q[i][t][kVx] = (q[i][t][kX] - q[i][t - 1][kX]) / h;
      q[i][t][kVy] = (q[i][t][kY] - q[i][t - 1][kY]) / h;
      q[i][t][kOmega] = (q[i][t][kPhi] - q[i][t - 1][kPhi]) / h;
      if (!layout.rotates(i)) q[i][t][kPhi] = q[i][0][kPhi], q[i][t][kOmega] = 0.0;
      for (int c = 0; c < kStateSize; ++c)
        if (const int k = layout.state_index(i, t, c); k >= 0) z[k] = q[i][t][c];
    }
  // Floor friction opposing v^{t+1}, and the force that balances momentum.
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    for (int t = 0; t < N; ++t) {
      const double vx = q[i][t + 1][kVx], vy = q[i][t + 1][kVy];
      double friction[2] = {0.0, 0.0};
      if (layout.has_floor_friction(i)) {
        int best = 0;
        double lowest = kInf;
        for (int k = 0; k < rb.friction_edges; ++k) {
          const double a = 2.0 * std::numbers::pi * k / rb.friction_edges;
          const double dv = std::cos(a) * vx + std::sin(a) * vy;
          if (dv < lowest) lowest = dv, best = k;
        }
        const bool moving = std::hypot(vx, vy) > 1e-12;
        const double beta = moving ? rb.mu * rb.mass * s.gravity : 0.0;
        const double a = 2.0 * std::numbers::pi * best / rb.friction_edges;
        z[layout.beta_index(i, t, best)] = beta;
        z[layout.floor_gamma_index(i, t)] = std::max(0.0, -lowest);
        friction[0] = beta * std::cos(a);
        friction[1] = beta * std::sin(a);
      }
      double f[2];
      for (int a = 0; a < 2; ++a) {
        const int vel = a == 0 ? kVx : kVy;
        f[a] = rb.mass * (q[i][t + 1][vel] - q[i][t][vel]) / h - friction[a];
      }
      const auto& idx = layout.force_indices(i, t);
      if (rb.force_dims == 2) {
        for (int a = 0; a < 2; ++a) z[idx[a]] = std::clamp(f[a], -rb.force_max, rb.force_max);
      } else {
        const double along = f[0] * rb.force_axis[0] + f[1] * rb.force_axis[1];
        z[idx[0]] = std::clamp(along, -rb.force_max, rb.force_max);
      }
    }
  }
  // Gaps from positions; contact multipliers: gamma = |v_T| (others zero).
  for (int p = 0; p < static_cast<int>(s.pairs.size()); ++p) {
    const Pair& pr = s.pairs[p];
    const double R = s.robots[pr.i].radius + s.robots[pr.j].radius;
    for (int t = 1; t <= N; ++t) {
      if (!layout.has_gap(p, t)) continue;
      const double nx = q[pr.j][t][kX] - q[pr.i][t][kX], ny = q[pr.j][t][kY] - q[pr.i][t][kY];
      z[layout.gap_index(p, t)] = std::hypot(nx, ny) - R;
    }
    if (!layout.has_contact_friction(p)) continue;
    for (int t = 0; t < N; ++t) {
      if (!layout.has_contact(p, t)) continue;
      const double nx = q[pr.j][t][kX] - q[pr.i][t][kX], ny = q[pr.j][t][kY] - q[pr.i][t][kY];
      const double vt = -ny * (q[pr.j][t + 1][kVx] - q[pr.i][t + 1][kVx]) +
                        nx * (q[pr.j][t + 1][kVy] - q[pr.i][t + 1][kVy]);
      z[layout.contact_gamma_index(p, t)] = std::abs(vt);
    }
  }
  return z;
}

}  // namespace

const std::vector<Family>& all_families() {
  static const std::vector<Family> all = {
      Family::kKinematics, Family::kDynamics,        Family::kFloorFriction, Family::kGap,
      Family::kNonpenetration, Family::kContactFriction, Family::kAvoidance, Family::kBounds};
  return all;
}

RobotProblem::RobotProblem(const Scene& scene, const std::vector<Family>& families,
                           const ModelOptions& options)
    : scene_(scene), units_(choose_units(scene)), families_(families), options_(options) {
  DISCO_CHECK(options.horizon_max > 0, "the largest horizon is positive");
  build();
}

void RobotProblem::build() {
  const Scene model_scene = to_model_units(scene_, units_);
  const double T_max = options_.horizon_max / units_.time;
  plan_ = plan_model(model_scene, options_.adaptive, T_max);
  program_ = PolynomialProgram();
  layout_.emplace(model_scene, plan_, program_);
  Layout& L = *layout_;
  auto has = [&](Family f) { return std::find(families_.begin(), families_.end(), f) != families_.end(); };
  // Dynamics first: the force families add impulses to its rows.
  add_dynamics(L, program_);
  if (has(Family::kKinematics)) add_kinematics(L, program_);
  if (has(Family::kFloorFriction)) add_floor_friction(L, program_);
  if (has(Family::kGap)) add_gap(L, program_);
  if (has(Family::kNonpenetration)) add_nonpenetration(L, program_);
  if (has(Family::kContactFriction)) add_contact_friction(L, program_);
  if (has(Family::kAvoidance)) add_avoidance(L, program_);
  if (has(Family::kBounds)) add_bounds(L, program_, kHorizonMin, std::max(kHorizonMin, T_max));
  program_.add(PolynomialProgram::kObjective, 1.0, L.horizon());  // minimize T_f
  program_.finalize();
}

void RobotProblem::set_horizon_max(double max_seconds) {
  DISCO_CHECK(max_seconds > 0, "the largest horizon is positive");
  if (max_seconds == options_.horizon_max) return;
  options_.horizon_max = max_seconds;
  build();
}

ModelSize RobotProblem::size() const {
  return {program_.num_variables(), program_.num_constraints(),
          program_.num_complementarity_pairs()};
}

void RobotProblem::fix_horizon(double seconds) {
  DISCO_CHECK(seconds <= options_.horizon_max * (1 + 1e-12), "a fixed horizon within the largest one");
  const double T = std::min(seconds, options_.horizon_max) / units_.time;
  program_.set_variable_bounds(layout_->horizon_index(), T, T);
}

void RobotProblem::limit_horizon(double max_seconds) {
  const double T = std::min(max_seconds, options_.horizon_max) / units_.time;
  program_.set_variable_bounds(layout_->horizon_index(), kHorizonMin, std::max(kHorizonMin, T));
}

double RobotProblem::horizon(const ConstVectorRef& z) const {
  return z[layout_->horizon_index()] * units_.time;
}

std::optional<double> RobotProblem::lower_bound() const { return scene_lower_bound(scene_); }

std::optional<double> RobotProblem::reference_time() const { return scene_reference_time(scene_); }

Vector RobotProblem::straight_line_guess(double seconds) const {
  const Scene& s = layout_->scene();  // model units
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  // States: t = 0 is the start; positions follow a smoothstep.
  std::vector<std::vector<State>> q(nr, std::vector<State>(N + 1));
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    State goal = rb.start;
    for (int c : {kX, kY, kPhi}) goal[c] = std::clamp(rb.start[c], rb.target.lower[c], rb.target.upper[c]);
    q[i][0] = rb.start;
    for (int t = 1; t <= N; ++t) {
      const double tau = static_cast<double>(t) / N, w = tau * tau * (3.0 - 2.0 * tau);
      for (int c : {kX, kY, kPhi}) q[i][t][c] = rb.start[c] + w * (goal[c] - rb.start[c]);
    }
  }
  return guess_from_positions(*layout_, program_.num_variables(), q, seconds / units_.time);
}

Vector RobotProblem::guess_from_paths(const std::vector<std::vector<std::array<double, 3>>>& xyphi,
                                      double seconds) const {
  const Scene& s = layout_->scene();  // model units
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  DISCO_CHECK(static_cast<int>(xyphi.size()) == nr, "one path per robot");
  std::vector<std::vector<State>> q(nr, std::vector<State>(N + 1));
  for (int i = 0; i < nr; ++i) {
    DISCO_CHECK(static_cast<int>(xyphi[i].size()) == N + 1, "a path has N + 1 points");
    q[i][0] = s.robots[i].start;  // exact: the start is a constant of the model
    for (int t = 1; t <= N; ++t) {
      q[i][t][kX] = xyphi[i][t][0] / units_.length;
      q[i][t][kY] = xyphi[i][t][1] / units_.length;
      q[i][t][kPhi] = xyphi[i][t][2];  // angles are unitless
    }
  }
  return guess_from_positions(*layout_, program_.num_variables(), q, seconds / units_.time);
}

Vector RobotProblem::transfer(const Vector& z, const RobotProblem& to) const {
  const Layout& A = *layout_;
  const Layout& B = to.layout();
  const Scene& s = A.scene();
  DISCO_CHECK(z.size() == program_.num_variables(), "a point of this model");
  DISCO_CHECK(B.scene().robots.size() == s.robots.size() && B.scene().pairs.size() == s.pairs.size() &&
                  B.steps() == A.steps() && to.units_.length == units_.length &&
                  to.units_.time == units_.time,
              "a model of the same scene");
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  const int np = static_cast<int>(s.pairs.size());
  Vector out = Vector::Zero(to.program().num_variables());
  auto value = [&](const Affine& a) { return a.value(z); };
  auto put = [&](int k, double v) {
    if (k >= 0) out[k] = v;
  };
  out[B.horizon_index()] = z[A.horizon_index()];
  for (int i = 0; i < nr; ++i) {
    for (int t = 1; t <= N; ++t)
      for (int c = 0; c < kStateSize; ++c) put(B.state_index(i, t, c), value(A.state(i, t, c)));
    for (int t = 0; t < N; ++t) {
      const auto& fa = A.force_indices(i, t);
      const auto& fb = B.force_indices(i, t);
      for (std::size_t a = 0; a < fb.size(); ++a) out[fb[a]] = z[fa[a]];
      if (!B.has_floor_friction(i)) continue;
      for (int k = 0; k < s.robots[i].friction_edges; ++k) out[B.beta_index(i, t, k)] = z[A.beta_index(i, t, k)];
      out[B.floor_gamma_index(i, t)] = z[A.floor_gamma_index(i, t)];
    }
  }
  for (int p = 0; p < np; ++p) {
    const Pair& pr = s.pairs[p];
    const double R = s.robots[pr.i].radius + s.robots[pr.j].radius;
    for (int t = 1; t <= N; ++t) {
      if (!B.has_gap(p, t)) continue;
      put(B.gap_index(p, t), A.has_gap(p, t) ? value(A.gap(p, t))
                                             : std::hypot(value(A.normal(p, t, 0)), value(A.normal(p, t, 1))) - R);
    }
    for (int t = 0; t < N; ++t) {
      put(B.normal_force_index(p, t), value(A.normal_force(p, t)));
      put(B.alpha1_index(p, t), value(A.alpha1(p, t)));
      put(B.alpha2_index(p, t), value(A.alpha2(p, t)));
      if (B.contact_gamma_index(p, t) < 0) continue;
      if (A.contact_gamma_index(p, t) >= 0) {
        out[B.contact_gamma_index(p, t)] = z[A.contact_gamma_index(p, t)];
        continue;
      }
      // No friction acts: gamma >= |v_T| satisfies both rows; take the least.
      const double o = std::hypot(value(A.normal(p, t, 0)), value(A.normal(p, t, 1)));
      double vT = -o * (s.robots[pr.j].radius * value(A.state(pr.j, t + 1, kOmega)) +
                        s.robots[pr.i].radius * value(A.state(pr.i, t + 1, kOmega)));
      for (int a = 0; a < 2; ++a) {
        const int vel = a == 0 ? kVx : kVy;
        vT += value(A.tangent(p, t, a)) * (value(A.state(pr.j, t + 1, vel)) - value(A.state(pr.i, t + 1, vel)));
      }
      out[B.contact_gamma_index(p, t)] = std::abs(vT);
    }
  }
  return out;
}

std::vector<RobotProblem::Violation> RobotProblem::violations(const Vector& z, double tolerance) const {
  std::vector<Violation> out;
  if (z.size() != program_.num_variables()) return out;
  const Layout& L = *layout_;
  std::map<std::pair<std::string, std::string>, double> worst;  // (owner, family) -> amount
  auto note = [&](const std::string& owner, const std::string& family, double v) {
    if (!(v > tolerance)) return;
    double& w = worst[{owner, family}];
    w = std::max(w, v);
  };
  auto robot = [&](int i) { return "robot '" + scene_.robots[i].name + "'"; };
  Vector c(program_.num_constraints());
  if (program_.constraints(z, c)) {
    for (int r = 0; r < program_.num_constraints(); ++r) {
      const int tag = program_.row_tag(r);
      if (tag < 0) continue;
      const double v = std::max({program_.constraint_lower()[r] - c[r], c[r] - program_.constraint_upper()[r], 0.0});
      const Layout::RowOwner& o = L.row_owner(tag);
      const std::string owner =
          o.pair ? "pair ('" + scene_.robots[scene_.pairs[o.index].i].name + "', '" +
                       scene_.robots[scene_.pairs[o.index].j].name + "')"
                 : robot(o.index);
      note(owner, o.family, v);
    }
  }
  const int N = scene_.steps;
  for (int i = 0; i < static_cast<int>(scene_.robots.size()); ++i)
    for (int k = 0; k < kStateSize; ++k) {
      const int v = L.state_index(i, N, k);
      if (v < 0) continue;
      note(robot(i), "target",
           std::max({program_.variable_lower()[v] - z[v], z[v] - program_.variable_upper()[v], 0.0}));
    }
  for (const auto& [key, amount] : worst) out.push_back({key.first, key.second, amount});
  std::stable_sort(out.begin(), out.end(),
                   [](const Violation& a, const Violation& b) { return a.amount > b.amount; });
  return out;
}

}  // namespace disco
