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
//
// A disk and an obstacle (core/model/obstacles.h): j is the obstacle, with its own
// velocity (0 for a wall or a post) and omega = 0; only the disk receives impulses.
//
// The same quantities at a point z are computed here, once, for every other user (the
// guesses, RobotProblem::transfer, the solution file): sliding_velocity() and
// contact_force(). tests/test_model_physics.cpp checks them against the rows.
#pragma once

#include <array>

#include "core/model/layout.h"

namespace disco {

void add_contact_friction(Layout& L, PolynomialProgram& P);

// v_T of contact pair p over interval t at the point z (model units): T . (v^j - v^i)
// - o (R^j omega^j + R^i omega^i), with T and o at state t and the velocities at t+1.
// o is computed from the centres (|N|), so the gap unknown need not exist at t.
double sliding_velocity(const Layout& L, const ConstVectorRef& z, int pair, int t);

// The contact force between the robots of pair p over interval t at the point z (model
// units; zero where the pair has no contact unknowns): `normal` c_n o (the push of i on j
// along the unit vector n from i's centre to j's) and `tangential` (alpha_1 - alpha_2) o
// (along n turned +90 degrees), `on_j` their sum c_n N + (alpha_1 - alpha_2) T in the
// world frame (the force on i is its opposite), and the torques -R o (alpha_1 - alpha_2)
// about each centre.
struct ContactForce {
  double normal = 0.0, tangential = 0.0;
  std::array<double, 2> on_j{0.0, 0.0};
  double torque_i = 0.0, torque_j = 0.0;
};
ContactForce contact_force(const Layout& L, const ConstVectorRef& z, int pair, int t);

}  // namespace disco
