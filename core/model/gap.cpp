#include "core/model/gap.h"

#include <cmath>

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

double centre_gap(const Layout& L, const ConstVectorRef& z, int pair, int t) {
  const Scene& s = L.model_scene();
  const Pair& pr = s.pairs[pair];
  return std::hypot(L.normal(pair, t, 0).value(z), L.normal(pair, t, 1).value(z)) -
         (s.robots[pr.i].radius + s.robots[pr.j].radius);
}

double clearance(const Scene& scene, const Pair& pair) {
  return scene.robots[pair.i].radius + scene.robots[pair.j].radius +
         (pair.mode == PairMode::kAvoid ? pair.safe_distance : 0.0);
}

}  // namespace disco
