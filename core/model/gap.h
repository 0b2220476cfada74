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
//
// The same rows hold for a disk and an obstacle (core/model/obstacles.h: the obstacle's
// point nearest to the disk, and for walls the rows that define that point).
//
// clearance() is the least centre distance the model allows a pair, R^i + R^j + d_s
// (avoid, core/model/avoidance.h) or R^i + R^j (contact: rho >= 0,
// core/model/nonpenetration.h); the scene parser, the reachability checks, the adaptive
// plan and the guesses use it.
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_gap(Layout& L, PolynomialProgram& P);

// The gap |p^j - p^i| - R^i - R^j of pair p (or an obstacle pair's, with the obstacle's
// nearest point) at state t of the point z, from the centres (model units): defined at
// every state, whether rho^t (or a wall's s^t) is an unknown or not.
double centre_gap(const Layout& L, const ConstVectorRef& z, int pair, int t);

// R^i + R^j (+ d_s for an avoid pair), in the scene's units.
double clearance(const Scene& scene, const Pair& pair);

}  // namespace disco
