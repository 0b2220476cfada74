// disco — collision avoidance for avoid pairs (the paper's set A).
//
// For every avoid pair (i, j), a disk-obstacle pair's included, and state t = 1..N:
//     rho^{ij,t} >= d_s,
// a bound on the gap unknown (core/model/gap.h). No contact forces exist
// between such robots. (t = 0 is the start, checked when the scene is read;
// outside the pair's window the robots are provably farther apart,
// core/model/model_plan.h.)
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_avoidance(Layout& L, PolynomialProgram& P);

}  // namespace disco
