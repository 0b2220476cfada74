// disco — the gap rho between two disks (Appendix A, "nonpenetration").
//
//     rho^{ij,t} = o^{ij,t} - R^i - R^j,   o = || p^j - p^i ||.
//
// rho is an unknown at the states of the pair's window (every state t = 1..N
// in the full model; t = 0 is the start), defined by the polynomial row
//     (rho + R^i + R^j)^2 - (x^j - x^i)^2 - (y^j - y^i)^2 = 0.
// With rho >= 0 (contact pairs) or rho >= d_s (avoid pairs) the root is the
// unique one with o = rho + R^i + R^j > 0. This keeps every row of the model
// polynomial: o enters the contact friction and torque terms as rho + R, never
// as a square root, and its derivatives stay bounded even where the centres
// would coincide.
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_gap(Layout& L, PolynomialProgram& P);

}  // namespace disco
