#include "core/model/nonpenetration.h"

namespace disco {

void add_nonpenetration(Layout& L, PolynomialProgram& P) {
  L.for_each_contact_step([&](int t, int p) {
    const Pair& pr = L.pair(p);
    const int j = L.other_disk(p);  // -1: an obstacle, which nothing moves
    P.add_pair(ComplementaritySide::variable(L.normal_multiplier_index(p, t)),
               ComplementaritySide::variable(L.gap_index(p, t + 1)));
    for (int a = 0; a < 2; ++a) {
      // Rows are M dv - impulses: the impulse on j enters with a minus.
      if (j >= 0) P.add(L.momentum_row(j, t, a), -1.0, L.step(), L.normal_multiplier(p, t), L.normal(p, t, a));
      P.add(L.momentum_row(pr.i, t, a), 1.0, L.step(), L.normal_multiplier(p, t), L.normal(p, t, a));
    }
  });
}

}  // namespace disco
