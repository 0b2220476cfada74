#include "core/model/floor_friction.h"

#include <cmath>
#include <numbers>

#include "core/util/numbers.h"

namespace disco {

void add_floor_friction(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.model_scene();
  L.for_each_robot_step([&](int t, int i) {
    if (!L.has_floor_friction(i)) return;
    const Robot& rb = s.robots[i];
    const int K = rb.friction_edges;
    const int budget = P.add_row(-kInf, kInf, L.robot_row_tag("floor friction", i));  // mu M g - sum_k beta_k
    P.add(budget, 1.0, Affine(rb.mu * rb.mass * s.gravity));
    for (int k = 0; k < K; ++k) {
      const std::array<double, 2> d = friction_direction(k, K);
      const int r = P.add_row(-kInf, kInf, L.robot_row_tag("floor friction", i));  // d_k . v^{t+1} + gamma
      P.add(r, d[0], L.state(i, t + 1, kVx));
      P.add(r, d[1], L.state(i, t + 1, kVy));
      P.add(r, 1.0, L.floor_gamma(i, t));
      P.add_pair(ComplementaritySide::variable(L.beta_index(i, t, k)),
                 ComplementaritySide::row(r));
      P.add(budget, -1.0, L.beta(i, t, k));
      for (int a = 0; a < 2; ++a) P.add(L.momentum_row(i, t, a), -d[a], L.step(), L.beta(i, t, k));
    }
    P.add_pair(ComplementaritySide::variable(L.floor_gamma_index(i, t)),
               ComplementaritySide::row(budget));
  });
}

std::array<double, 2> friction_direction(int k, int K) {
  const double angle = 2.0 * std::numbers::pi * k / K;
  return {std::cos(angle), std::sin(angle)};
}

FrictionVertex most_opposed_vertex(int K, double vx, double vy) {
  FrictionVertex best{0, kInf};
  for (int k = 0; k < K; ++k) {
    const std::array<double, 2> d = friction_direction(k, K);
    const double dot = d[0] * vx + d[1] * vy;
    if (dot < best.dot) best = {k, dot};
  }
  return best;
}

bool friction_polygon_symmetric_about(int K, double ux, double uy) {
  const double steps = std::atan2(uy, ux) * K / std::numbers::pi;
  return std::abs(steps - std::round(steps)) < 1e-9;
}

double least_dissipation_ratio(int K) { return std::cos(std::numbers::pi / K); }

std::array<double, 2> floor_friction_force(const Layout& L, const ConstVectorRef& z, int robot, int t) {
  std::array<double, 2> f{0.0, 0.0};
  if (!L.has_floor_friction(robot)) return f;
  const int K = L.model_scene().robots[robot].friction_edges;
  for (int k = 0; k < K; ++k) {
    const std::array<double, 2> d = friction_direction(k, K);
    const double beta = z[L.beta_index(robot, t, k)];
    f[0] += beta * d[0];
    f[1] += beta * d[1];
  }
  return f;
}

}  // namespace disco
