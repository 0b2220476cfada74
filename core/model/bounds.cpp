#include "core/model/bounds.h"

namespace disco {

void add_bounds(Layout& L, PolynomialProgram& P, double horizon_min, double horizon_max) {
  const Scene& s = L.scene();
  const int N = L.steps();
  P.set_variable_bounds(L.horizon_index(), horizon_min, horizon_max);
  for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) {
    const Robot& rb = s.robots[i];
    for (int t = 0; t < N; ++t)
      for (int k : L.force_indices(i, t)) P.set_variable_bounds(k, -rb.force_max, rb.force_max);
    for (int c = 0; c < kStateSize; ++c)  // not the constants: phi, omega of a robot
      if (L.state_index(i, N, c) >= 0)      // that does not turn lie in the box (adaptive.h)
        P.set_variable_bounds(L.state_index(i, N, c), rb.target.lower[c], rb.target.upper[c]);
  }
}

}  // namespace disco
