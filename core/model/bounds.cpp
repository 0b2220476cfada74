#include "core/model/bounds.h"

#include <algorithm>

namespace disco {

void add_bounds(Layout& L, PolynomialProgram& P, double horizon_min, double horizon_max) {
  const Scene& s = L.model_scene();
  const int N = L.steps();
  P.set_variable_bounds(L.horizon_index(), horizon_min, horizon_max);
  for (int i = 0; i < static_cast<int>(s.robots.size()); ++i) {
    const Robot& rb = s.robots[i];
    for (int t = 0; t < N; ++t)
      for (int k : L.force_indices(i, t)) P.set_variable_bounds(k, -rb.force_max, rb.force_max);
    for (int c = 0; c < kStateSize; ++c)  // not the constants: phi, omega of a robot
      if (L.state_index(i, N, c) >= 0)      // that does not turn lie in the box (model_plan.h)
        P.set_variable_bounds(L.state_index(i, N, c), rb.target.lower[c], rb.target.upper[c]);
  }
}

Pose target_pose(const Robot& robot) {
  Pose p;
  for (int c : {kX, kY, kPhi}) p[c] = std::clamp(robot.start[c], robot.target.lower[c], robot.target.upper[c]);
  return p;
}

}  // namespace disco
