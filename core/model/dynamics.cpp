#include "core/model/dynamics.h"

namespace disco {

void add_dynamics(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.model_scene();
  L.for_each_robot_step([&](int t, int i) {
    const Robot& rb = s.robots[i];
    for (int a = 0; a < 2; ++a) {
      const int velocity = a == 0 ? kVx : kVy;
      const int r = P.add_row(0.0, 0.0, L.robot_row_tag("dynamics", i));
      P.add(r, rb.mass, L.state(i, t + 1, velocity) - L.state(i, t, velocity));
      P.add(r, -1.0, L.step(), L.force(i, t, a));
      L.set_momentum_row(i, t, a, r);
    }
    if (!L.rotates(i)) return;  // phi, omega constant: no rotational row
    const int r = P.add_row(0.0, 0.0, L.robot_row_tag("rotation dynamics", i));
    P.add(r, rb.inertia, L.state(i, t + 1, kOmega) - L.state(i, t, kOmega));
    P.add(r, rb.damping * rb.mass * s.gravity, L.step(), L.state(i, t + 1, kOmega));
    L.set_momentum_row(i, t, 2, r);
  });
}

}  // namespace disco
