// disco — Coulomb friction between robots in contact (Section III-B and
// Appendix A, the Psi(T_1), Psi(T_2) rows).
//
// For every contact pair (i, j) with friction unknowns (all in the full model,
// those with mu > 0 in the adaptive one) and contact interval t, with N = p^j - p^i and
// T = (-N_y, N_x) at state t, o = rho^t + R^i + R^j, and the relative sliding
// velocity at the contact point, scaled by o, at t+1:
//     v_T = T . (v^j - v^i) - o (R^j omega^j + R^i omega^i)
// the complementarity conditions are
//     0 <= alpha_1 _|_  v_T + gamma >= 0
//     0 <= alpha_2 _|_ -v_T + gamma >= 0
//     0 <= gamma   _|_  mu c_n - alpha_1 - alpha_2 >= 0
// The tangential impulse h (alpha_1 - alpha_2) T acts on j and its opposite on
// i; both robots receive the torque impulse  -h R o (alpha_1 - alpha_2)  with
// their own radius R.
//
// Signs (derived, then checked against Appendix A). The contact point is at
// -R^j n from j's centre and +R^i n from i's (n = N / o), so the tangential
// velocity of j's point relative to i's, along T, is v_T / o as written:
// Psi(T_1) v in the appendix. The force (alpha_1 - alpha_2) T applied at
// -R^j n gives the torque det(-R^j n, (alpha_1 - alpha_2) T) = -R^j o
// (alpha_1 - alpha_2), the appendix's final line; its first line, "R_j x (-f_n
// - f_T)", has the opposite sign and is a typo. The same computation for i
// (force -(alpha_1 - alpha_2) T at +R^i n) gives -R^i o (alpha_1 - alpha_2):
// both torques have the same sign. With these signs friction dissipates:
// its power (alpha_1 - alpha_2) v_T is never positive.
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_contact_friction(Layout& L, PolynomialProgram& P);

}  // namespace disco
