#include "core/model/kinematics.h"

namespace disco {

void add_kinematics(Layout& L, PolynomialProgram& P) {
  constexpr int kPosition[3] = {kX, kY, kPhi};
  constexpr int kVelocity[3] = {kVx, kVy, kOmega};
  L.for_each_robot_step([&](int t, int i) {
    for (int c = 0; c < (L.rotates(i) ? 3 : 2); ++c) {
      const int r = P.add_row(0.0, 0.0, L.robot_row_tag(c == 2 ? "rotation kinematics" : "kinematics", i));
      P.add(r, 1.0, L.state(i, t + 1, kPosition[c]));
      P.add(r, -1.0, L.state(i, t, kPosition[c]));
      P.add(r, -1.0, L.step(), L.state(i, t + 1, kVelocity[c]));
    }
  });
}

}  // namespace disco
