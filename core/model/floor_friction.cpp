#include "core/model/floor_friction.h"

#include <cmath>
#include <numbers>

#include "core/util/numbers.h"

namespace disco {

void add_floor_friction(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.scene();
  L.for_each_robot_step([&](int t, int i) {
    if (!L.has_floor_friction(i)) return;
    const Robot& rb = s.robots[i];
    const int K = rb.friction_edges;
    const int budget = P.add_row(-kInf, kInf, L.robot_row_tag("floor friction", i));  // mu M g - sum_k beta_k
    P.add(budget, 1.0, Affine(rb.mu * rb.mass * s.gravity));
    for (int k = 0; k < K; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / K;
      const double d[2] = {std::cos(angle), std::sin(angle)};
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

}  // namespace disco
