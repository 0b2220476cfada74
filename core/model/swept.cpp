#include "core/model/swept.h"

#include "core/util/numbers.h"

namespace disco {

void add_swept_clearance(Layout& L, PolynomialProgram& P) {
  for (int p = 0; p < L.num_pairs(); ++p) {
    if (!L.with_obstacle(p)) continue;
    const int i = L.pair(p).i;
    const bool wall = L.is_wall_pair(p);
    for (int t = 1; t <= L.steps(); ++t) {
      if (!L.has_gap(p, t - 1) || !L.has_gap(p, t)) continue;
      const Affine cover = Affine(2.0 * L.radius_sum(p) * (1.0 - kSweptMargin)) + L.gap(p, t - 1) + L.gap(p, t);
      // The disk's move (a wall), or its move relative to the disk obstacle's centre.
      const Affine dx = wall ? L.state(i, t, kX) - L.state(i, t - 1, kX) : L.normal(p, t - 1, 0) - L.normal(p, t, 0);
      const Affine dy = wall ? L.state(i, t, kY) - L.state(i, t - 1, kY) : L.normal(p, t - 1, 1) - L.normal(p, t, 1);
      const int r = P.add_row(0.0, kInf, L.pair_row_tag("swept", p));
      P.add(r, 1.0, cover, cover);
      P.add(r, -1.0, dx, dx);
      P.add(r, -1.0, dy, dy);
    }
  }
}

}  // namespace disco
