#include "core/model/gap.h"

namespace disco {

void add_gap(Layout& L, PolynomialProgram& P) {
  L.for_each_gap_state([&](int t, int p) {
    const int r = P.add_row(0.0, 0.0, L.pair_row_tag("gap", p));
    const Affine o = L.centre_distance(p, t), nx = L.normal(p, t, 0), ny = L.normal(p, t, 1);
    P.add(r, 1.0, o, o);
    P.add(r, -1.0, nx, nx);
    P.add(r, -1.0, ny, ny);
  });
}

}  // namespace disco
