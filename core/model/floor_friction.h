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
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_floor_friction(Layout& L, PolynomialProgram& P);

}  // namespace disco
