// disco — nonpenetration of contact pairs (Section III-B; Appendix A,
// "0 <= c_n _|_ rho").
//
// For every contact pair (i, j) and contact interval t (every t = 0..N-1 in
// the full model, the pair's window in the adaptive one, core/model/model_plan.h):
//     0 <= c_n^t  _|_  rho^{t+1} >= 0
// and the normal impulse h c_n^t N^t acts on robot j, its opposite on robot i,
// with N^t = p^j(t) - p^i(t) (not a unit vector: the push has magnitude
// c_n o^t). For a disk and an obstacle, p^j is the obstacle's nearest point
// (core/model/obstacles.h) and only the disk receives the impulse.
//
// Time index. Appendix A pairs c_n^t with rho^t, the gap at the START of the
// interval. Then a force can act only between disks that already touch, and
// two robots closing in during interval t must brake by themselves to land
// exactly at rho^{t+1} = 0. The time-stepping schemes the paper builds on
// (Stewart-Trinkle; Anitescu-Potra, ref. [3]) pair the impulse with the gap at
// the END of the interval, so that the impulse is what prevents penetration.
// We use that physically right form; the direction N^t stays at the start of
// the interval, as in the appendix (semi-implicit).
#pragma once

#include "core/model/layout.h"

namespace disco {

void add_nonpenetration(Layout& L, PolynomialProgram& P);

}  // namespace disco
