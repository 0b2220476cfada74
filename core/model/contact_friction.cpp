#include "core/model/contact_friction.h"

#include "core/util/numbers.h"

namespace disco {

void add_contact_friction(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.scene();
  L.for_each_contact_step([&](int t, int p) {
    if (!L.has_contact_friction(p)) return;
    const Pair& pr = s.pairs[p];
    const double Ri = s.robots[pr.i].radius, Rj = s.robots[pr.j].radius;
    const Affine o = L.centre_distance(p, t);
    const Affine slip = L.alpha1(p, t) - L.alpha2(p, t);

    // v_T + gamma and -v_T + gamma.
    const int tag = L.pair_row_tag("contact friction", p);
    const int r1 = P.add_row(-kInf, kInf, tag), r2 = P.add_row(-kInf, kInf, tag);
    for (int sign : {1, -1}) {
      const int r = sign > 0 ? r1 : r2;
      for (int a = 0; a < 2; ++a) {
        const int vel = a == 0 ? kVx : kVy;
        P.add(r, sign, L.tangent(p, t, a), L.state(pr.j, t + 1, vel) - L.state(pr.i, t + 1, vel));
      }
      P.add(r, -sign, o, Rj * L.state(pr.j, t + 1, kOmega) + Ri * L.state(pr.i, t + 1, kOmega));
      P.add(r, 1.0, L.contact_gamma(p, t));
    }
    P.add_pair(ComplementaritySide::variable(L.alpha1_index(p, t)), ComplementaritySide::row(r1));
    P.add_pair(ComplementaritySide::variable(L.alpha2_index(p, t)), ComplementaritySide::row(r2));

    // mu c_n - alpha_1 - alpha_2.
    const int r3 = P.add_row(-kInf, kInf, tag);
    P.add(r3, 1.0, pr.mu * L.normal_force(p, t) - L.alpha1(p, t) - L.alpha2(p, t));
    P.add_pair(ComplementaritySide::variable(L.contact_gamma_index(p, t)),
               ComplementaritySide::row(r3));

    // Impulses (rows are M dv - impulses).
    for (int a = 0; a < 2; ++a) {
      P.add(L.momentum_row(pr.j, t, a), -1.0, L.step(), slip, L.tangent(p, t, a));
      P.add(L.momentum_row(pr.i, t, a), 1.0, L.step(), slip, L.tangent(p, t, a));
    }
    // Torque impulse -h R o slip on each robot; the row subtracts it.
    P.add(L.momentum_row(pr.j, t, 2), Rj, L.step(), o, slip);
    P.add(L.momentum_row(pr.i, t, 2), Ri, L.step(), o, slip);
  });
}

}  // namespace disco
