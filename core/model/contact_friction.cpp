#include "core/model/contact_friction.h"

#include <cmath>

#include "core/util/numbers.h"

namespace disco {

void add_contact_friction(Layout& L, PolynomialProgram& P) {
  const Scene& s = L.model_scene();
  L.for_each_contact_step([&](int t, int p) {
    if (!L.has_contact_friction(p)) return;
    const Pair& pr = L.pair(p);
    const int j = L.other_disk(p);  // -1: an obstacle (omega 0, no impulse)
    const double Ri = s.robots[pr.i].radius, Rj = j >= 0 ? s.robots[j].radius : 0.0;
    const Affine o = L.centre_distance(p, t);
    const Affine slip = L.alpha1(p, t) - L.alpha2(p, t);

    // v_T + gamma and -v_T + gamma.
    const int tag = L.pair_row_tag("contact friction", p);
    const int r1 = P.add_row(-kInf, kInf, tag), r2 = P.add_row(-kInf, kInf, tag);
    for (int sign : {1, -1}) {
      const int r = sign > 0 ? r1 : r2;
      for (int a = 0; a < 2; ++a) {
        const int vel = a == 0 ? kVx : kVy;
        P.add(r, sign, L.tangent(p, t, a), L.other_state(p, t + 1, vel) - L.state(pr.i, t + 1, vel));
      }
      P.add(r, -sign, o, Rj * L.other_state(p, t + 1, kOmega) + Ri * L.state(pr.i, t + 1, kOmega));
      P.add(r, 1.0, L.contact_gamma(p, t));
    }
    P.add_pair(ComplementaritySide::variable(L.alpha1_index(p, t)), ComplementaritySide::row(r1));
    P.add_pair(ComplementaritySide::variable(L.alpha2_index(p, t)), ComplementaritySide::row(r2));

    // mu c_n - alpha_1 - alpha_2.
    const int r3 = P.add_row(-kInf, kInf, tag);
    P.add(r3, 1.0, pr.mu * L.normal_multiplier(p, t) - L.alpha1(p, t) - L.alpha2(p, t));
    P.add_pair(ComplementaritySide::variable(L.contact_gamma_index(p, t)),
               ComplementaritySide::row(r3));

    // Impulses (rows are M dv - impulses).
    for (int a = 0; a < 2; ++a) {
      if (j >= 0) P.add(L.momentum_row(j, t, a), -1.0, L.step(), slip, L.tangent(p, t, a));
      P.add(L.momentum_row(pr.i, t, a), 1.0, L.step(), slip, L.tangent(p, t, a));
    }
    // Torque impulse -h R o slip on each robot; the row subtracts it.
    if (j >= 0) P.add(L.momentum_row(j, t, 2), Rj, L.step(), o, slip);
    P.add(L.momentum_row(pr.i, t, 2), Ri, L.step(), o, slip);
  });
}

double sliding_velocity(const Layout& L, const ConstVectorRef& z, int pair, int t) {
  const Scene& s = L.model_scene();
  const Pair& pr = L.pair(pair);
  const int j = L.other_disk(pair);
  auto value = [&](const Affine& a) { return a.value(z); };
  const double o = std::hypot(value(L.normal(pair, t, 0)), value(L.normal(pair, t, 1)));
  double vT = -o * s.robots[pr.i].radius * value(L.state(pr.i, t + 1, kOmega));
  if (j >= 0) vT -= o * s.robots[j].radius * value(L.state(j, t + 1, kOmega));
  for (int a = 0; a < 2; ++a) {
    const int vel = a == 0 ? kVx : kVy;
    vT += value(L.tangent(pair, t, a)) * (value(L.other_state(pair, t + 1, vel)) - value(L.state(pr.i, t + 1, vel)));
  }
  return vT;
}

ContactForce contact_force(const Layout& L, const ConstVectorRef& z, int pair, int t) {
  ContactForce f;
  if (!L.is_contact(pair) || !L.has_contact(pair, t)) return f;  // no force acts
  const Scene& s = L.model_scene();
  const Pair& pr = L.pair(pair);
  const int j = L.other_disk(pair);
  auto value = [&](const Affine& a) { return a.value(z); };
  const double cn = value(L.normal_multiplier(pair, t));
  const double slip = value(L.alpha1(pair, t)) - value(L.alpha2(pair, t));
  const double o = value(L.centre_distance(pair, t));
  f.normal = cn * o;
  f.tangential = slip * o;
  for (int a = 0; a < 2; ++a) f.on_j[a] = cn * value(L.normal(pair, t, a)) + slip * value(L.tangent(pair, t, a));
  f.torque_j = j >= 0 ? -s.robots[j].radius * o * slip : 0.0;
  f.torque_i = -s.robots[pr.i].radius * o * slip;
  return f;
}

}  // namespace disco
