// disco — kinematics (Appendix A, "the Kinematics Equations").
//
// For every robot i and interval t = 0..N-1, semi-implicit Euler:
//     x^{t+1}   - x^t   - h vx^{t+1}    = 0
//     y^{t+1}   - y^t   - h vy^{t+1}    = 0
//     phi^{t+1} - phi^t - h omega^{t+1} = 0,        h = T_f / N.
// The appendix writes the translational rows; the orientation row is the
// same scheme applied to phi (Figure 3 reports orientations). A robot that
// does not turn (core/model/model_plan.h) has no orientation row.
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_kinematics(Layout& L, PolynomialProgram& P);

}  // namespace disco
