#include "core/model/gap.h"

#include <array>
#include <cmath>

#include "core/model/obstacle_path.h"
#include "core/model/obstacles.h"

namespace disco {

void add_gap(Layout& L, PolynomialProgram& P) {
  L.for_each_gap_state([&](int t, int p) {
    const int r = P.add_row(0.0, 0.0, L.pair_row_tag("gap", p));
    const Affine o = L.centre_distance(p, t), nx = L.normal(p, t, 0), ny = L.normal(p, t, 1);
    P.add(r, 1.0, o, o);
    P.add(r, -1.0, nx, nx);
    P.add(r, -1.0, ny, ny);
  });
  add_wall_projection(L, P);  // a wall's nearest point, which its pairs' N uses
  add_obstacle_path(L, P);    // a path obstacle's centre, likewise
}

double centre_gap(const Layout& L, const ConstVectorRef& z, int pair, int t) {
  if (L.with_obstacle(pair)) {  // the obstacle itself, not the unknowns s or q
    const int i = L.pair(pair).i;
    const std::array<double, 2> c{L.state(i, t, kX).value(z), L.state(i, t, kY).value(z)};
    const double tau = t * L.horizon().value(z) / L.steps();
    return obstacle_distance(L.obstacle(pair), c, tau) - L.radius_sum(pair);
  }
  return std::hypot(L.normal(pair, t, 0).value(z), L.normal(pair, t, 1).value(z)) - L.radius_sum(pair);
}

double clearance(const Scene& scene, const Pair& pair) {
  return scene.robots[pair.i].radius + scene.robots[pair.j].radius +
         (pair.mode == PairMode::kAvoid ? pair.safe_distance : 0.0);
}

}  // namespace disco
