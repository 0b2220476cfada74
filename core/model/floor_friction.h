// disco — friction between each robot and the floor (Section III-A.1 and
// Appendix A, "dynamics constraints of disk-robot A^i and floor").
//
// The friction disk of radius mu M g is approximated by the K-gon with
// vertex directions d_k = (cos 2 pi k / K, sin 2 pi k / K), k = 0..K-1. For
// every robot with mu > 0 and interval t, maximum dissipation as
// complementarity:
//     0 <= beta_k  _|_  d_k . v^{t+1} + gamma >= 0,        k = 0..K-1
//     0 <= gamma   _|_  mu M g - sum_k beta_k >= 0
// and the friction impulse  h sum_k beta_k d_k  enters the momentum rows.
// At a sliding velocity the active beta lies on the vertex most opposed to v
// and gamma = -min_k d_k . v; at rest gamma = 0 and the force is anything in
// the K-gon (static friction). A robot with mu = 0 gets none of this.
//
// The polygon's quantities are computed here and nowhere else: the guesses, the
// lower bound (core/model/lower_bound.h), the adaptive plan (core/model/model_plan.h)
// and the solution file use these functions.
#pragma once

#include <array>

#include "core/model/layout.h"

namespace disco {

void add_floor_friction(Layout& L, PolynomialProgram& P);

// d_k = (cos 2 pi k / K, sin 2 pi k / K), the k-th vertex direction of the K-gon.
std::array<double, 2> friction_direction(int k, int K);

// The vertex maximum dissipation picks for a robot sliding at velocity v: the k
// minimising d_k . v (the first on ties), and that product, min_k d_k . v (< 0
// when v != 0). The friction then acts along d_k, and gamma = -dot.
struct FrictionVertex {
  int k = 0;
  double dot = 0.0;
};
FrictionVertex most_opposed_vertex(int K, double vx, double vy);

// cos(pi / K): the friction of a sliding robot dissipates at least
// mu M g cos(pi / K) |v| (f . v <= -mu M g cos(pi / K) |v|), the worst case
// being a velocity halfway between two vertices.
double least_dissipation_ratio(int K);

// Whether the K-gon is symmetric about the line along the unit vector u (u lies on a
// vertex direction or halfway between two).
bool friction_polygon_symmetric_about(int K, double ux, double uy);

// The floor friction force sum_k beta_k d_k on robot i over interval t at the
// point z (model units); zero for a robot without floor friction.
std::array<double, 2> floor_friction_force(const Layout& L, const ConstVectorRef& z, int robot, int t);

}  // namespace disco
