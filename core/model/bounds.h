// disco — simple bounds (Appendix A, "external force constraints" and "the
// box constrained final values"; the initial values are the constants of
// state t = 0, see core/model/layout.h).
//
//     |F_x^{i,t}| <= F_max^i, |F_y^{i,t}| <= F_max^i     (D_ef = 2, infinity norm)
//     |f^{i,t}|   <= F_max^i                              (D_ef = 1, F = f * axis)
//     q_low^i <= q^i(T_f) <= q_upp^i,  v_low^i <= v^i(T_f) <= v_upp^i
//     horizon_min <= T_f <= horizon_max
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_bounds(Layout& L, PolynomialProgram& P, double horizon_min, double horizon_max);

// The pose of the target box nearest the robot's start: x, y and phi of the start, each
// clamped to its target interval. A robot's straight move goes there (the guesses,
// search/guess.h; the lower bound, core/model/lower_bound.h).
Pose target_pose(const Robot& robot);

}  // namespace disco
