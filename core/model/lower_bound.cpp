#include "core/model/lower_bound.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/model/bounds.h"
#include "core/model/floor_friction.h"
#include "core/model/model_plan.h"
#include "core/util/numbers.h"

namespace disco {

double bang_bang_time(double distance, double a1, double a2, bool stop_at_end) {
  if (distance <= 0) return 0.0;
  if (a1 <= 0) return kInf;
  if (!stop_at_end) return std::sqrt(2.0 * distance / a1);
  const double v_peak = std::sqrt(2.0 * distance * a1 * a2 / (a1 + a2));
  return v_peak / a1 + v_peak / a2;
}

bool straight_move_is_optimal(const Robot& rb, double ux, double uy) {
  constexpr double kTol = 1e-9;
  if (rb.force_dims == 1)
    return std::abs(std::abs(rb.force_axis[0] * ux + rb.force_axis[1] * uy) - 1.0) < kTol;
  return std::abs(std::abs(ux) - std::abs(uy)) < kTol;
}

std::optional<MoveLimits> straight_move_limits(const Robot& rb, double gravity) {
  const auto& s = rb.start;
  if (s[kVx] != 0.0 || s[kVy] != 0.0) return std::nullopt;
  const auto& lo = rb.target.lower;
  const auto& hi = rb.target.upper;
  const bool rest = lo[kVx] == 0.0 && hi[kVx] == 0.0 && lo[kVy] == 0.0 && hi[kVy] == 0.0;
  const bool free = lo[kVx] == -kInf && hi[kVx] == kInf && lo[kVy] == -kInf && hi[kVy] == kInf;
  if (!rest && !free) return std::nullopt;

  MoveLimits m;
  m.stop_at_end = rest;
  const Pose to = target_pose(rb);
  const double dx = to[kX] - s[kX];
  const double dy = to[kY] - s[kY];
  m.distance = std::hypot(dx, dy);
  if (m.distance == 0.0) return m;
  const double ux = dx / m.distance, uy = dy / m.distance;
  m.push = rb.force_dims == 2
               ? rb.force_max * (std::abs(ux) + std::abs(uy))
               : rb.force_max * std::abs(rb.force_axis[0] * ux + rb.force_axis[1] * uy);
  // Moving along u, maximum dissipation picks the vertex minimising d_k . u:
  // the friction against the motion is mu M g max_k (-d_k . u). (For even K
  // this equals max_k d_k . u; for odd K it does not.)
  const double support = -most_opposed_vertex(rb.friction_edges, ux, uy).dot;
  m.friction = rb.mu * rb.mass * gravity * support;
  m.optimal = straight_move_is_optimal(rb, ux, uy);
  return m;
}

std::optional<double> straight_move_time(const Robot& rb, double gravity) {
  const auto m = straight_move_limits(rb, gravity);
  if (!m) return std::nullopt;
  if (m->distance == 0.0) return 0.0;
  const double a2 = m->brake(rb.mass);
  // Off the optimal directions, the provable relaxation: no friction while speeding up.
  const double a1 = m->optimal ? m->accel(rb.mass) : m->push / rb.mass;
  return bang_bang_time(m->distance, a1, a2, m->stop_at_end);
}

std::optional<double> scene_lower_bound(const Scene& scene) {
  std::vector<bool> pushable(scene.robots.size(), false);
  for (const auto& p : scene.pairs) {
    if (p.mode != PairMode::kContact) continue;
    pushable[p.i] = pushable[p.j] = true;
  }
  std::optional<double> best;
  for (size_t i = 0; i < scene.robots.size(); ++i) {
    if (pushable[i]) continue;
    const auto t = straight_move_time(scene.robots[i], scene.gravity);
    if (!t) return std::nullopt;  // a robot without a closed form: no bound claimed
    best = std::max(best.value_or(0.0), *t);
  }
  return best;
}

std::optional<double> pushed_move_time(const Scene& scene, int object) {
  const Robot& ob = scene.robots[object];
  const auto m = straight_move_limits(ob, scene.gravity);
  if (!m) return std::nullopt;
  if (m->distance == 0.0) return 0.0;
  const std::vector<int> comp = contact_components(scene);
  double push = 0.0, mass = ob.mass, friction = m->friction;
  for (std::size_t r = 0; r < scene.robots.size(); ++r) {
    const Robot& rb = scene.robots[r];
    if (rb.object || comp[r] != comp[object]) continue;
    push += rb.push_bound();
    mass += rb.mass;
    friction += rb.mu * rb.mass * scene.gravity;
  }
  if (push == 0.0) return std::nullopt;
  return bang_bang_time(m->distance, (push - friction) / mass, ob.mu * scene.gravity, m->stop_at_end);
}

std::optional<double> scene_reference_time(const Scene& scene) {
  std::optional<double> best;
  for (int i = 0; i < static_cast<int>(scene.robots.size()); ++i) {
    const auto t = scene.robots[i].object ? pushed_move_time(scene, i)
                                          : straight_move_time(scene.robots[i], scene.gravity);
    if (t && std::isfinite(*t)) best = std::max(best.value_or(0.0), *t);
  }
  return best;
}

}  // namespace disco
