// disco — the momentum balance of every robot (Appendix A, "the Dynamics
// Equations"), written as impulses over one interval (multiplied by h):
//
//     M (v^{t+1} - v^t) - h F^t - [impulses of floor and contact forces] = 0
//     I (omega^{t+1} - omega^t) + h sigma_d M g omega^{t+1}
//                                 - [contact torque impulses]  = 0
//
// This unit creates the rows with the inertia, control and damping terms; the
// floor-friction, nonpenetration and contact-friction units add their own
// impulses to the same rows (Layout::momentum_row), so a scene without, say,
// contact pairs carries no contact terms at all. A robot that does not turn
// (core/model/model_plan.h) has no rotational row.
//
// Rotational damping. The paper has three forms: Section III-A.2 gives the
// floor torque -sigma_d M g phi_dot; Appendix A writes "-sigma_d I^j phi" in
// one line and "-sigma_d M^j v^{j,t}" in the next. Only the first is a torque
// opposing the spin with the right units (sigma_d in m s): we use it, and
// evaluate omega at t+1 (implicit, like every other velocity term), which is
// unconditionally stable for any h.
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_dynamics(Layout& L, PolynomialProgram& P);

}  // namespace disco
