#include "core/model/robot_problem.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/model/avoidance.h"
#include "core/model/bounds.h"
#include "core/model/contact_friction.h"
#include "core/model/dynamics.h"
#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/kinematics.h"
#include "core/model/lower_bound.h"
#include "core/model/nonpenetration.h"
#include "core/model/objective.h"
#include "core/model/obstacles.h"
#include "core/model/swept.h"
#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

// The smallest horizon allowed, in model time units: keeps h > 0.
constexpr double kHorizonMin = 1e-3;

}  // namespace

const std::vector<Family>& all_families() {
  static const std::vector<Family> all = {
      Family::kKinematics, Family::kDynamics,        Family::kFloorFriction, Family::kGap,
      Family::kNonpenetration, Family::kContactFriction, Family::kAvoidance, Family::kSweptClearance,
      Family::kBounds};
  return all;
}

RobotProblem::RobotProblem(const Scene& scene, const std::vector<Family>& families,
                           const ModelOptions& options)
    : scene_(scene), units_(choose_units(scene)), families_(families), options_(options) {
  DISCO_CHECK(options.horizon_max > 0, "the largest horizon is positive");
  if (horizon_is_fixed()) options_.horizon_max = scene.objective.horizon;  // never another T_f
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
  if (has(Family::kSweptClearance)) add_swept_clearance(L, program_);
  if (has(Family::kBounds)) add_bounds(L, program_, kHorizonMin, std::max(kHorizonMin, T_max));
  add_objective(L, program_);
  objective_row_ = scene_.objective.kind == ObjectiveKind::kTime ? -1 : add_objective_row(L, program_);
  program_.finalize();
  free_objective();
}

void RobotProblem::set_horizon_max(double max_seconds) {
  DISCO_CHECK(max_seconds > 0, "the largest horizon is positive");
  if (horizon_is_fixed()) max_seconds = scene_.objective.horizon;
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

ObjectiveKind RobotProblem::objective_kind() const { return scene_.objective.kind; }

void RobotProblem::bound_objective(double value, bool fixed) {
  if (objective_row_ < 0) {  // time: the bound is on T_f itself
    if (fixed)
      fix_horizon(value);
    else
      limit_horizon(value);
    return;
  }
  const double J = value / objective_scale(objective_kind(), units_);
  program_.set_constraint_bounds(objective_row_, fixed ? J : -kInf, J);
}

void RobotProblem::free_objective() {
  if (objective_row_ >= 0) program_.set_constraint_bounds(objective_row_, -kInf, kInf);
  if (horizon_is_fixed())
    fix_horizon(scene_.objective.horizon);
  else
    limit_horizon(kInf);
}

double RobotProblem::objective(const ConstVectorRef& z) const {
  double f = 0.0;
  DISCO_CHECK(program_.objective(z, f), "the objective is a polynomial: finite at a finite point");
  return f * objective_scale(objective_kind(), units_);
}

double RobotProblem::objective_floor() const {
  // T_f >= max(lower bound, smallest horizon); E >= 0.
  const double T = std::max(lower_bound().value_or(0.0), kHorizonMin * units_.time);
  return objective_kind() == ObjectiveKind::kEnergy ? 0.0 : T;
}

double RobotProblem::horizon_reach(double T) const {
  const Objective& o = scene_.objective;
  if (o.kind == ObjectiveKind::kEnergy) return o.horizon;
  if (o.kind == ObjectiveKind::kTime) return T;
  double push = 0.0;  // sum_i Fbar_i^2
  for (const Robot& r : scene_.robots) push += r.push_bound() * r.push_bound();
  return T * (1.0 + o.energy_weight * push);
}

double RobotProblem::horizon(const ConstVectorRef& z) const {
  return z[layout_->horizon_index()] * units_.time;
}

std::optional<double> RobotProblem::lower_bound() const { return scene_lower_bound(scene_); }

std::optional<double> RobotProblem::reference_time() const { return scene_reference_time(scene_); }

Vector RobotProblem::transfer(const Vector& z, const RobotProblem& to) const {
  const Layout& A = *layout_;
  const Layout& B = to.layout();
  const Scene& s = A.model_scene();
  DISCO_CHECK(z.size() == program_.num_variables(), "a point of this model");
  DISCO_CHECK(B.model_scene().robots.size() == s.robots.size() && B.num_pairs() == A.num_pairs() &&
                  B.steps() == A.steps() && to.units_.length == units_.length &&
                  to.units_.time == units_.time,
              "a model of the same scene");
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  const int np = A.num_pairs();
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
  // A wall's nearest point from the centres (exact where A has none): before the gaps and
  // contact gammas, which use it through N.
  complete_obstacle_unknowns(B, out);
  for (int p = 0; p < np; ++p) {
    for (int t = 1; t <= N; ++t) {
      if (!B.has_gap(p, t)) continue;
      put(B.gap_index(p, t), A.has_gap(p, t) ? value(A.gap(p, t)) : centre_gap(A, z, p, t));
      if (!A.is_wall_pair(p) || A.wall_parameter_index(p, t) < 0) continue;
      out[B.wall_parameter_index(p, t)] = z[A.wall_parameter_index(p, t)];
      out[B.wall_low_index(p, t)] = z[A.wall_low_index(p, t)];
      out[B.wall_high_index(p, t)] = z[A.wall_high_index(p, t)];
    }
    for (int t = 0; t < N; ++t) {
      put(B.normal_multiplier_index(p, t), value(A.normal_multiplier(p, t)));
      put(B.alpha1_index(p, t), value(A.alpha1(p, t)));
      put(B.alpha2_index(p, t), value(A.alpha2(p, t)));
      if (B.contact_gamma_index(p, t) < 0) continue;
      if (A.contact_gamma_index(p, t) >= 0) {
        out[B.contact_gamma_index(p, t)] = z[A.contact_gamma_index(p, t)];
        continue;
      }
      // No friction acts: gamma >= |v_T| satisfies both rows; take the least.
      out[B.contact_gamma_index(p, t)] = std::abs(sliding_velocity(B, out, p, t));
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
      const std::string owner = !o.pair ? robot(o.index)
                                : L.with_obstacle(o.index)
                                    ? "pair ('" + scene_.robots[L.pair(o.index).i].name + "', obstacle '" +
                                          scene_.obstacles[L.pair(o.index).j].name + "')"
                                    : "pair ('" + scene_.robots[scene_.pairs[o.index].i].name + "', '" +
                                          scene_.robots[scene_.pairs[o.index].j].name + "')";
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
