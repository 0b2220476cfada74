#include "core/model/obstacles.h"

#include <algorithm>
#include <cmath>

#include "core/model/obstacle_path.h"
#include "core/util/numbers.h"

namespace disco {

void add_wall_projection(Layout& L, PolynomialProgram& P) {
  L.for_each_gap_state([&](int t, int p) {
    if (!L.is_wall_pair(p)) return;
    const Obstacle& ob = L.obstacle(p);
    const double dx = ob.to[0] - ob.from[0], dy = ob.to[1] - ob.from[1], len = std::hypot(dx, dy);
    const int tag = L.pair_row_tag("gap", p);
    const int r = P.add_row(0.0, 0.0, tag);
    P.add(r, dx / len, L.normal(p, t, 0));
    P.add(r, dy / len, L.normal(p, t, 1));
    P.add(r, -1.0, Affine::variable(L.wall_low_index(p, t)));
    P.add(r, 1.0, Affine::variable(L.wall_high_index(p, t)));
    P.add_pair(ComplementaritySide::variable(L.wall_low_index(p, t)),
               ComplementaritySide::variable(L.wall_parameter_index(p, t)));
    const int rest = P.add_row(-kInf, kInf, tag);  // 1 - s
    P.add(rest, 1.0, Affine(1.0) - L.wall_parameter(p, t));
    P.add_pair(ComplementaritySide::variable(L.wall_high_index(p, t)), ComplementaritySide::row(rest));
  });
}

double wall_projection(const Obstacle& ob, const std::array<double, 2>& p) {
  const double dx = ob.to[0] - ob.from[0], dy = ob.to[1] - ob.from[1];
  const double along = (p[0] - ob.from[0]) * dx + (p[1] - ob.from[1]) * dy;
  return std::clamp(along / (dx * dx + dy * dy), 0.0, 1.0);
}

std::array<double, 2> obstacle_centre(const Obstacle& ob, double tau) {
  if (!ob.path.empty()) return path_point(ob.path, tau);
  return {ob.from[0] + tau * ob.velocity[0], ob.from[1] + tau * ob.velocity[1]};
}

std::array<std::array<double, 2>, 2> obstacle_box(const Obstacle& ob, double tau0, double tau1) {
  std::array<double, 2> a = ob.from, b = ob.to;
  if (ob.shape == ObstacleShape::kDisk && !ob.path.empty()) {
    std::array<std::array<double, 2>, 2> box;
    for (int axis = 0; axis < 2; ++axis) {
      const auto r = PathCoordinate(ob.path, axis).range(tau0, tau1);
      box[0][axis] = r[0], box[1][axis] = r[1];
    }
    return box;
  }
  if (ob.shape == ObstacleShape::kDisk) a = obstacle_centre(ob, tau0), b = obstacle_centre(ob, tau1);
  return {{{std::min(a[0], b[0]), std::min(a[1], b[1])}, {std::max(a[0], b[0]), std::max(a[1], b[1])}}};
}

std::array<double, 2> obstacle_point(const Obstacle& ob, const std::array<double, 2>& p, double tau) {
  if (ob.shape == ObstacleShape::kDisk) return obstacle_centre(ob, tau);
  const double s = wall_projection(ob, p);
  return {ob.from[0] + s * (ob.to[0] - ob.from[0]), ob.from[1] + s * (ob.to[1] - ob.from[1])};
}

double obstacle_distance(const Obstacle& ob, const std::array<double, 2>& p, double tau) {
  const auto q = obstacle_point(ob, p, tau);
  return std::hypot(p[0] - q[0], p[1] - q[1]);
}

double obstacle_clearance(const Scene& scene, const Pair& pair) {
  return scene.robots[pair.i].radius + scene.obstacles[pair.j].radius +
         (pair.mode == PairMode::kAvoid ? pair.safe_distance : 0.0);
}

namespace {

// Distance from the origin to the segment r0-r1.
double origin_to_segment(const std::array<double, 2>& r0, const std::array<double, 2>& r1) {
  const double dx = r1[0] - r0[0], dy = r1[1] - r0[1], dd = dx * dx + dy * dy;
  const double s = dd > 0 ? std::clamp(-(r0[0] * dx + r0[1] * dy) / dd, 0.0, 1.0) : 0.0;
  return std::hypot(r0[0] + s * dx, r0[1] + s * dy);
}

double cross(const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

}  // namespace

double swept_distance(const Obstacle& ob, const std::array<double, 2>& p0,
                      const std::array<double, 2>& p1, double tau0, double tau1) {
  if (ob.shape == ObstacleShape::kDisk) {  // relative motion: straight as well
    const auto q0 = obstacle_point(ob, p0, tau0), q1 = obstacle_point(ob, p1, tau1);
    return origin_to_segment({p0[0] - q0[0], p0[1] - q0[1]}, {p1[0] - q1[0], p1[1] - q1[1]});
  }
  // Two segments in the plane: 0 if they cross, else the least of the four end-to-segment
  // distances.
  const double c1 = cross(p0, p1, ob.from), c2 = cross(p0, p1, ob.to);
  const double c3 = cross(ob.from, ob.to, p0), c4 = cross(ob.from, ob.to, p1);
  if (((c1 > 0) != (c2 > 0)) && ((c3 > 0) != (c4 > 0))) return 0.0;
  auto to_segment = [](const std::array<double, 2>& x, const std::array<double, 2>& a,
                       const std::array<double, 2>& b) {
    return origin_to_segment({a[0] - x[0], a[1] - x[1]}, {b[0] - x[0], b[1] - x[1]});
  };
  return std::min({to_segment(p0, ob.from, ob.to), to_segment(p1, ob.from, ob.to),
                   to_segment(ob.from, p0, p1), to_segment(ob.to, p0, p1)});
}

void complete_obstacle_unknowns(const Layout& L, VectorRef z) {
  complete_obstacle_paths(L, z);
  for (int p = 0; p < L.num_pairs(); ++p) {
    if (!L.is_wall_pair(p)) continue;
    const Obstacle& ob = L.obstacle(p);
    const int i = L.pair(p).i;
    const double dx = ob.to[0] - ob.from[0], dy = ob.to[1] - ob.from[1], len = std::hypot(dx, dy);
    for (int t = 1; t <= L.steps(); ++t) {
      const int k = L.wall_parameter_index(p, t);
      if (k < 0) continue;
      const std::array<double, 2> c{L.state(i, t, kX).value(z), L.state(i, t, kY).value(z)};
      const double s = wall_projection(ob, c);
      z[k] = s;
      // N . d / |d| at the projection: 0 inside, the multiplier's value at an end.
      const double along = ((ob.from[0] + s * dx - c[0]) * dx + (ob.from[1] + s * dy - c[1]) * dy) / len;
      z[L.wall_low_index(p, t)] = std::max(0.0, along);
      z[L.wall_high_index(p, t)] = std::max(0.0, -along);
    }
  }
}

}  // namespace disco
