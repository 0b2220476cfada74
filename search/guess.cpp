#include "search/guess.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "core/model/bounds.h"
#include "core/model/contact_friction.h"
#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/obstacles.h"
#include "core/model/lower_bound.h"
#include "core/util/check.h"
#include "core/util/numbers.h"
#include "search/trajectory.h"

namespace disco {
namespace {

constexpr double kPi = std::numbers::pi;

double smoothstep(double tau) { return tau * tau * (3.0 - 2.0 * tau); }
// tau with smoothstep(tau) = w, for w in [0, 1].
double inverse_smoothstep(double w) { return 0.5 - std::sin(std::asin(1.0 - 2.0 * w) / 3.0); }


}  // namespace

namespace {

// complete_guess for paths in model units (`length` 1) or in SI (`length` the unit of
// length), at the horizon T in model units.
Vector complete_paths(const RobotProblem& problem, const Paths& paths, double length, double T) {
  const Layout& layout = problem.layout();
  const Scene& s = layout.model_scene();
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  DISCO_CHECK(static_cast<int>(paths.size()) == nr, "one path per robot");
  const double h = T / N;
  // The states in model units: t = 0 is the start (a constant of the model, exact).
  std::vector<std::vector<State>> q(nr, std::vector<State>(N + 1));
  for (int i = 0; i < nr; ++i) {
    DISCO_CHECK(static_cast<int>(paths[i].size()) == N + 1, "a path has N + 1 poses");
    q[i][0] = s.robots[i].start;
    for (int t = 1; t <= N; ++t) {
      q[i][t][kX] = paths[i][t][0] / length;
      q[i][t][kY] = paths[i][t][1] / length;
      q[i][t][kPhi] = paths[i][t][2];  // angles are unitless
    }
  }
  Vector z = Vector::Zero(problem.program().num_variables());
  z[layout.horizon_index()] = T;
  for (int i = 0; i < nr; ++i)
    for (int t = 1; t <= N; ++t) {
      q[i][t][kVx] = (q[i][t][kX] - q[i][t - 1][kX]) / h;
      q[i][t][kVy] = (q[i][t][kY] - q[i][t - 1][kY]) / h;
      q[i][t][kOmega] = (q[i][t][kPhi] - q[i][t - 1][kPhi]) / h;
      if (!layout.rotates(i)) q[i][t][kPhi] = q[i][0][kPhi], q[i][t][kOmega] = 0.0;
      for (int c = 0; c < kStateSize; ++c)
        if (const int k = layout.state_index(i, t, c); k >= 0) z[k] = q[i][t][c];
    }
  // Floor friction opposing v^{t+1}, and the force that balances momentum.
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    for (int t = 0; t < N; ++t) {
      const double vx = q[i][t + 1][kVx], vy = q[i][t + 1][kVy];
      double friction[2] = {0.0, 0.0};
      if (layout.has_floor_friction(i)) {
        const FrictionVertex v = most_opposed_vertex(rb.friction_edges, vx, vy);
        const bool moving = std::hypot(vx, vy) > 1e-12;
        const double beta = moving ? rb.mu * rb.mass * s.gravity : 0.0;
        const std::array<double, 2> d = friction_direction(v.k, rb.friction_edges);
        z[layout.beta_index(i, t, v.k)] = beta;
        z[layout.floor_gamma_index(i, t)] = std::max(0.0, -v.dot);
        friction[0] = beta * d[0];
        friction[1] = beta * d[1];
      }
      double f[2];
      for (int a = 0; a < 2; ++a) {
        const int vel = a == 0 ? kVx : kVy;
        f[a] = rb.mass * (q[i][t + 1][vel] - q[i][t][vel]) / h - friction[a];
      }
      const auto& idx = layout.force_indices(i, t);
      if (rb.force_dims == 0) continue;  // an object: pushed, not driven
      if (rb.force_dims == 2) {
        for (int a = 0; a < 2; ++a) z[idx[a]] = std::clamp(f[a], -rb.force_max, rb.force_max);
      } else {
        const double along = f[0] * rb.force_axis[0] + f[1] * rb.force_axis[1];
        z[idx[0]] = std::clamp(along, -rb.force_max, rb.force_max);
      }
    }
  }
  // Gaps from the positions (a wall's nearest point first); contact multipliers zero but
  // gamma = |v_T|.
  complete_obstacle_unknowns(layout, z);
  for (int p = 0; p < layout.num_pairs(); ++p) {
    for (int t = 1; t <= N; ++t)
      if (layout.has_gap(p, t)) z[layout.gap_index(p, t)] = centre_gap(layout, z, p, t);
    if (!layout.has_contact_friction(p)) continue;
    for (int t = 0; t < N; ++t)
      if (layout.has_contact(p, t))
        z[layout.contact_gamma_index(p, t)] = std::abs(sliding_velocity(layout, z, p, t));
  }
  return z;
}

}  // namespace

Vector complete_guess(const RobotProblem& problem, const Paths& paths, double seconds) {
  return complete_paths(problem, paths, problem.units().length, seconds / problem.units().time);
}

double StraightMove::length() const { return std::hypot(to[0] - from[0], to[1] - from[1]); }

StraightMove straight_move(const Robot& rb) {
  return {{rb.start[kX], rb.start[kY], rb.start[kPhi]}, target_pose(rb)};
}

namespace {

// The closest approach of two straight moves timed alike: b − a = d0 + w D, D the relative
// motion; w in [0, 1] (0.5 without relative motion, DD = 0), r = d0 + w D at w.
struct Approach {
  double Dx = 0.0, Dy = 0.0, DD = 0.0, w = 0.5, rx = 0.0, ry = 0.0, closest = 0.0;
};
Approach closest_approach(const StraightMove& a, const StraightMove& b) {
  Approach c;
  const double d0x = b.from[0] - a.from[0], d0y = b.from[1] - a.from[1];
  c.Dx = (b.to[0] - a.to[0]) - d0x, c.Dy = (b.to[1] - a.to[1]) - d0y;
  c.DD = c.Dx * c.Dx + c.Dy * c.Dy;
  if (c.DD > 0.0) c.w = std::clamp(-(d0x * c.Dx + d0y * c.Dy) / c.DD, 0.0, 1.0);
  c.rx = d0x + c.w * c.Dx, c.ry = d0y + c.w * c.Dy;
  c.closest = std::hypot(c.rx, c.ry);
  return c;
}

// The closest approach of a's straight path to a fixed obstacle: the distance from a point
// moving along a segment to a point or a segment is convex in the fraction w, so a ternary
// search finds its least. (rx, ry) points from a's centre to the obstacle's nearest point.
Approach closest_approach(const StraightMove& a, const Obstacle& ob) {
  auto at = [&](double w) {
    return std::array<double, 2>{a.from[0] + w * (a.to[0] - a.from[0]), a.from[1] + w * (a.to[1] - a.from[1])};
  };
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 100; ++k) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (obstacle_distance(ob, at(m1), 0.0) <= obstacle_distance(ob, at(m2), 0.0)) hi = m2;
    else lo = m1;
  }
  Approach c;
  c.w = 0.5 * (lo + hi);
  const auto p = at(c.w);
  const auto q = obstacle_point(ob, p, 0.0);
  c.rx = q[0] - p[0], c.ry = q[1] - p[1];
  c.closest = std::hypot(c.rx, c.ry);
  return c;
}

}  // namespace

std::vector<Conflict> conflicts(const Scene& scene) {
  std::vector<Conflict> out;
  for (const Pair& p : scene.pairs) {
    const Approach c =
        closest_approach(straight_move(scene.robots[p.i]), straight_move(scene.robots[p.j]));
    if (!(c.DD > 0.0)) continue;  // no relative motion: the start distance stays, and it is valid
    const double w = c.w, closest = c.closest, Dx = c.Dx, Dy = c.Dy, DD = c.DD;
    const double clearance = disco::clearance(scene, p);
    // Touching at the start is allowed: a relative margin keeps roundoff out.
    if (!(closest < clearance * (1.0 - 1e-12))) continue;
    const double len = std::sqrt(DD);
    out.push_back({p.i, p.j, w, -Dy / len, Dx / len, clearance, p.mode});
  }
  return out;
}

namespace {

// 0 at tau = 0 and 1, 1 at peak, C^1 (sin^2 on each side).
double bump(double tau, double peak) {
  const double u = tau <= peak ? tau / peak : (1.0 - tau) / (1.0 - peak);
  const double s = std::sin(0.5 * kPi * u);
  return s * s;
}

// Offsets of force_dims 1 robots onto their force axis.
void project(const Robot& rb, double& ox, double& oy) {
  if (rb.force_dims != 1) return;
  const double along = ox * rb.force_axis[0] + oy * rb.force_axis[1];
  ox = along * rb.force_axis[0];
  oy = along * rb.force_axis[1];
}

// The paths with timing warp `warp` (tau -> s) and offsets added by `offset`
bool position_free(const Robot& rb) {
  for (int c : {kX, kY})
    if (std::isfinite(rb.target.lower[c]) || std::isfinite(rb.target.upper[c])) return false;
  return true;
}

// Pushers (see the header): robot i pushes object pusher_of[i] (-1: none).
std::vector<int> pushed_objects(const Scene& scene) {
  const int n = static_cast<int>(scene.robots.size());
  std::vector<int> pushes(n, -1);
  for (int i = 0; i < n; ++i) {
    const Robot& rb = scene.robots[i];
    if (rb.object || !position_free(rb)) continue;
    double nearest = kInf;
    for (const Pair& p : scene.pairs) {
      if (p.mode != PairMode::kContact || (p.i != i && p.j != i)) continue;
      const int o = p.i == i ? p.j : p.i;
      const Robot& ob = scene.robots[o];
      if (!ob.object || straight_move(ob).length() == 0.0) continue;
      const double d = std::hypot(ob.start[kX] - rb.start[kX], ob.start[kY] - rb.start[kY]);
      if (d < nearest) nearest = d, pushes[i] = o;
    }
  }
  return pushes;
}

using Point = std::array<double, 2>;
template <class P>
Point position(const P& p) {
  return {p[kX], p[kY]};
}
double distance(const Point& a, const Point& b) { return std::hypot(b[0] - a[0], b[1] - a[1]); }

// Robot i's contact point straight behind object o at the start and at the end of its move.
std::pair<Point, Point> contact_points(const Scene& scene, int i, int o) {
  const StraightMove move = straight_move(scene.robots[o]);
  const double L = move.length(), R = scene.robots[i].radius + scene.robots[o].radius;
  const double ux = (move.to[kX] - move.from[kX]) / L, uy = (move.to[kY] - move.from[kY]) / L;
  return {{move.from[kX] - R * ux, move.from[kY] - R * uy}, {move.to[kX] - R * ux, move.to[kY] - R * uy}};
}

// One leg of a queued pusher's way: (from, to), and the object it pushes (-1: a way between).
struct Leg {
  Point from, to;
  int object;
};
struct QueuedWays {
  std::vector<std::vector<Leg>> legs;  // per robot; empty for one push_the_rest leaves alone
  std::vector<char> to_target;         // the robot ends its way at its own target
};

// The plan of push_the_rest (below): which robots push which objects one after the other.
QueuedWays queued_ways(const Scene& scene, const std::vector<int>& pushes) {
  const int n = static_cast<int>(scene.robots.size());
  std::vector<std::vector<int>> queue(n);
  std::vector<int> team_size(n, 0);
  for (int i = 0; i < n; ++i)
    if (pushes[i] >= 0) ++team_size[pushes[i]];
  for (int i = 0; i < n; ++i)
    if (pushes[i] >= 0 && team_size[pushes[i]] == 1) queue[i].push_back(pushes[i]);
  // Each moving object still without a pusher joins the queue of the contact partner i with
  // the least cost(i, o) (kInf: not a candidate); returns that partner, or -1.
  const auto queue_unpushed = [&](int o, auto&& cost) {
    const Robot& ob = scene.robots[o];
    if (!ob.object || team_size[o] > 0 || straight_move(ob).length() == 0.0) return -1;
    int best = -1;
    double least = kInf;
    for (const Pair& p : scene.pairs) {
      if (p.mode != PairMode::kContact || (p.i != o && p.j != o)) continue;
      const int i = p.i == o ? p.j : p.i;
      const double c = cost(i, o);
      if (c < least) least = c, best = i;
    }
    if (best >= 0) queue[best].push_back(o), team_size[o] = 1;
    return best;
  };
  for (int o = 0; o < n; ++o)  // to a lone pusher, the one whose last object ends nearest
    queue_unpushed(o, [&](int i, int obj) {
      if (queue[i].empty()) return kInf;
      return distance(position(straight_move(scene.robots[queue[i].back()]).to), position(scene.robots[obj].start));
    });
  QueuedWays ways{std::vector<std::vector<Leg>>(n), std::vector<char>(n, 0)};
  for (int o = 0; o < n; ++o) {  // to a robot with a target, the one whose way it lengthens least
    const int taker = queue_unpushed(o, [&](int i, int obj) {
      const Robot& rb = scene.robots[i];
      if (rb.object || rb.force_dims == 1 || position_free(rb)) return kInf;
      const Point from = queue[i].empty() ? position(rb.start) : contact_points(scene, i, queue[i].back()).second;
      const Point target = position(straight_move(rb).to);
      const auto [behind, done] = contact_points(scene, i, obj);
      return distance(from, behind) + straight_move(scene.robots[obj]).length() + distance(done, target) -
             distance(from, target);
    });
    if (taker >= 0) ways.to_target[taker] = 1;
  }
  for (int i = 0; i < n; ++i) {
    if (queue[i].size() < 2 && !ways.to_target[i]) continue;
    Point at = position(scene.robots[i].start);
    for (int o : queue[i]) {
      const auto [behind, done] = contact_points(scene, i, o);
      ways.legs[i].push_back({at, behind, -1});
      ways.legs[i].push_back({behind, done, o});
      at = done;
    }
    if (ways.to_target[i]) ways.legs[i].push_back({at, position(straight_move(scene.robots[i]).to), -1});
  }
  return ways;
}

// Objects left without a pusher by pushed_objects() (more moving objects than pushers):
// each is added to the queue of the lone pusher (the only one of its object) whose last
// object ends nearest to it. An object that still has none (no robot without a position
// target can push it) is taken on the way by the robot with a position target whose way
// it lengthens least: the way from where the robot's queue leaves it to the contact point
// behind the object, the object's move, and the way from there to the robot's target,
// less the way straight from the first to the last. A pusher with a queue pushes its objects
// one after the other: it goes straight to the contact point straight behind the next object
// while every object waits, pushes it to its target (smoothstep), and goes on, a robot with
// a target at last to its target; each leg takes a share of the horizon in proportion to its
// length. An object waits at its start before its push and rests at its target after it.
void push_the_rest(const Scene& scene, const std::vector<int>& pushes, Paths& paths) {
  const int N = scene.steps, n = static_cast<int>(scene.robots.size());
  const QueuedWays ways = queued_ways(scene, pushes);
  for (int i = 0; i < n; ++i) {
    const std::vector<Leg>& legs = ways.legs[i];
    if (legs.empty()) continue;
    std::vector<double> ends;  // the share of the horizon at each leg's end
    double total = 0.0;
    for (const Leg& l : legs) ends.push_back(total += distance(l.from, l.to));
    for (double& e : ends) e /= total;
    for (int t = 1; t <= N; ++t) {
      const double tau = static_cast<double>(t) / N;
      std::size_t k = 0;
      while (k + 1 < legs.size() && tau > ends[k]) ++k;
      const double begin = k == 0 ? 0.0 : ends[k - 1];
      const double w = ends[k] > begin ? smoothstep(std::clamp((tau - begin) / (ends[k] - begin), 0.0, 1.0)) : 1.0;
      const Leg& l = legs[k];
      paths[i][t][kX] = l.from[0] + w * (l.to[0] - l.from[0]);
      paths[i][t][kY] = l.from[1] + w * (l.to[1] - l.from[1]);
      for (std::size_t m = 0; m < legs.size(); ++m) {
        const int o = legs[m].object;
        if (o < 0) continue;
        const StraightMove move = straight_move(scene.robots[o]);
        const double f = m < k ? 1.0 : m == k ? w : 0.0;
        for (int c : {kX, kY, kPhi}) paths[o][t][c] = move.from[c] + f * (move.to[c] - move.from[c]);
      }
    }
    for (const Leg& l : legs)  // every object pushed in its target
      if (l.object >= 0) paths[l.object][N] = straight_move(scene.robots[l.object]).to;
    if (ways.to_target[i]) paths[i][N] = straight_move(scene.robots[i]).to;
  }
}

// Robots push the objects they are assigned (pushed_objects): each goes straight to its
// contact point behind the object (the m-th of k pushers at angle (m - (k - 1) / 2) pi / 4
// from straight behind), while the object waits, then moves with it, touching.
void follow_objects(const Scene& scene, Paths& paths) {
  const int N = scene.steps, n = static_cast<int>(scene.robots.size());
  const std::vector<int> pushes = pushed_objects(scene);
  for (int o = 0; o < n; ++o) {
    std::vector<int> team;
    for (int i = 0; i < n; ++i)
      if (pushes[i] == o) team.push_back(i);
    if (team.empty()) continue;
    const Robot& ob = scene.robots[o];
    const StraightMove move = straight_move(ob);
    const double L = move.length(), ux = (move.to[kX] - move.from[kX]) / L,
                 uy = (move.to[kY] - move.from[kY]) / L;
    std::vector<std::array<double, 2>> offset(team.size());
    double approach = 0.0;  // the largest way to a contact point
    for (std::size_t m = 0; m < team.size(); ++m) {
      const Robot& rb = scene.robots[team[m]];
      const double angle = (static_cast<double>(m) - 0.5 * (team.size() - 1.0)) * kPi / 4.0;
      const double c = std::cos(angle), sn = std::sin(angle), R = rb.radius + ob.radius;
      offset[m] = {-R * (c * ux - sn * uy), -R * (sn * ux + c * uy)};
      approach = std::max(approach, std::hypot(move.from[kX] + offset[m][0] - rb.start[kX],
                                               move.from[kY] + offset[m][1] - rb.start[kY]));
    }
    // The share of the horizon spent reaching the object, in proportion to the ways.
    const double a = std::min(0.5, approach / (approach + L));
    const std::vector<Pose> own = paths[o];
    for (int t = 1; t < N; ++t) {
      const double tau = static_cast<double>(t) / N;
      if (tau <= a) {
        paths[o][t] = own[0];
      } else {
        paths[o][t] = pose_at(own, N * (tau - a) / (1.0 - a));
      }
      for (std::size_t m = 0; m < team.size(); ++m) {
        const Robot& rb = scene.robots[team[m]];
        Pose& q = paths[team[m]][t];
        if (tau < a) {
          const double w = smoothstep(tau / a);
          q[kX] = rb.start[kX] + w * (move.from[kX] + offset[m][0] - rb.start[kX]);
          q[kY] = rb.start[kY] + w * (move.from[kY] + offset[m][1] - rb.start[kY]);
        } else {
          q[kX] = paths[o][t][kX] + offset[m][0];
          q[kY] = paths[o][t][kY] + offset[m][1];
        }
      }
    }
    for (std::size_t m = 0; m < team.size(); ++m) {  // the free end: behind the object's target
      paths[team[m]][N][kX] = move.to[kX] + offset[m][0];
      paths[team[m]][N][kY] = move.to[kY] + offset[m][1];
    }
  }
  push_the_rest(scene, pushes, paths);
}

// The point at the share w in [0, 1] of the length of `way`.
std::array<double, 2> point_along(const Way& way, double w) {
  // A straight way: the straight move's own arithmetic, so obstacle-free guesses stay the
  // same to the last bit (a roundoff change moved paper B1 start 0 to another optimum).
  if (way.size() == 2)
    return {way[0][0] + w * (way[1][0] - way[0][0]), way[0][1] + w * (way[1][1] - way[0][1])};
  double total = 0.0;
  for (std::size_t k = 1; k < way.size(); ++k)
    total += std::hypot(way[k][0] - way[k - 1][0], way[k][1] - way[k - 1][1]);
  double left = w * total;
  for (std::size_t k = 1; k < way.size(); ++k) {
    const double len = std::hypot(way[k][0] - way[k - 1][0], way[k][1] - way[k - 1][1]);
    if (left <= len && len > 0.0) {
      const double f = left / len;
      return {way[k - 1][0] + f * (way[k][0] - way[k - 1][0]), way[k - 1][1] + f * (way[k][1] - way[k - 1][1])};
    }
    left -= len;
  }
  return way.back();
}

// (robot, tau, &ox, &oy); the t = N point is the target point.
template <class Warp, class Offset>
Paths build_paths(const Scene& scene, bool meet_turners, Warp&& warp, Offset&& offset) {
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  Paths paths(nr, std::vector<Pose>(N + 1));
  const std::vector<Meeting> meets = meet_turners ? meetings(scene) : std::vector<Meeting>{};
  // The turners' meetings ("Turners" in the header): i towards j, j towards i.
  auto meet_offset = [&](int robot, double tau, double& ox, double& oy) {
    for (const Meeting& m : meets) {
      if (robot != m.i && robot != m.j) continue;
      const double peak = std::clamp(inverse_smoothstep(m.w), 0.15, 0.85);
      const double a = bump(tau, peak) * (robot == m.i ? m.shift_i : -m.shift_j);
      ox += a * m.ux;
      oy += a * m.uy;
    }
  };
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = scene.robots[i];
    const StraightMove m = straight_move(rb);
    const Way way = way_around_obstacles(scene, i);
    paths[i][0] = m.from;
    for (int t = 1; t < N; ++t) {
      const double tau = static_cast<double>(t) / N;
      const double w = smoothstep(std::clamp(warp(i, tau), 0.0, 1.0));
      double ox = 0.0, oy = 0.0;
      offset(i, tau, ox, oy);
      meet_offset(i, tau, ox, oy);
      project(rb, ox, oy);
      const auto at = point_along(way, w);
      paths[i][t][kX] = at[0] + ox;
      paths[i][t][kY] = at[1] + oy;
      paths[i][t][kPhi] = m.from[kPhi] + w * (m.to[kPhi] - m.from[kPhi]);
    }
    paths[i][N] = m.to;
  }
  follow_objects(scene, paths);
  return paths;
}

}  // namespace

std::vector<Meeting> meetings(const Scene& scene) {
  const int n = static_cast<int>(scene.robots.size());
  // Straight paths that cross in a contact pair touch; crossing in an avoid pair, they do not.
  std::vector<char> in_contact(n, 0);
  for (const Conflict& c : conflicts(scene))
    if (c.mode == PairMode::kContact) in_contact[c.i] = in_contact[c.j] = 1;
  const std::vector<int> pushes = pushed_objects(scene);
  std::vector<Meeting> out;
  for (int i = 0; i < n; ++i) {
    const Robot& rb = scene.robots[i];
    if (rb.object || in_contact[i] || pushes[i] >= 0 || rb.start[kOmega] != 0.0 ||
        target_pose(rb)[kPhi] == rb.start[kPhi])
      continue;
    const StraightMove a = straight_move(rb);
    double best = std::numeric_limits<double>::infinity();
    Meeting meet;
    // Robots first; objects only when no robot is a contact partner.
    for (const bool objects : {false, true}) {
      if (std::isfinite(best)) break;
      for (const Pair& p : scene.pairs) {
        if (p.mode != PairMode::kContact || (p.i != i && p.j != i)) continue;
        const int j = p.i == i ? p.j : p.i;
        if (scene.robots[j].object != objects) continue;
        const Approach c = closest_approach(a, straight_move(scene.robots[j]));
        if (!(c.closest < best) || !(c.closest > 0.0)) continue;
        best = c.closest;
        const double excess = c.closest - disco::clearance(scene, p);
        meet = {i, j, c.w, c.rx / c.closest, c.ry / c.closest, objects ? excess : 0.5 * excess,
                objects ? 0.0 : 0.5 * excess};
      }
    }
    // Else the closest fixed contact obstacle: rubbing it turns the robot too.
    const bool disk_partner = std::isfinite(best);
    for (const Pair& p : scene.obstacle_pairs) {
      const Obstacle& ob = scene.obstacles[p.j];
      if (disk_partner || p.i != i || p.mode != PairMode::kContact || ob.moves()) continue;
      const Approach c = closest_approach(a, ob);
      if (!(c.closest < best) || !(c.closest > 0.0)) continue;
      best = c.closest;
      meet = {i, -1, c.w, c.rx / c.closest, c.ry / c.closest, c.closest - obstacle_clearance(scene, p), 0.0};
      meet.obstacle = p.j;
    }
    // Two turners that are each other's partner meet once (each moved half, not twice).
    const bool met = std::any_of(out.begin(), out.end(), [&](const Meeting& m) {
      return m.i == meet.j && m.j == meet.i;
    });
    if (std::isfinite(best) && meet.shift_i > 0.0 && !met) out.push_back(meet);
  }
  return out;
}

Way way_around_obstacles(const Scene& scene, int robot) {
  const Robot& rb = scene.robots[robot];
  const StraightMove m = straight_move(rb);
  const std::array<double, 2> from{m.from[kX], m.from[kY]}, to{m.to[kX], m.to[kY]};
  // The fixed obstacles and this disk's clearance from each.
  std::vector<std::pair<const Obstacle*, double>> fixed;
  for (const Pair& p : scene.obstacle_pairs) {
    const Obstacle& ob = scene.obstacles[p.j];
    if (p.i == robot && !ob.moves()) fixed.emplace_back(&ob, obstacle_clearance(scene, p));
  }
  auto clear = [&](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    for (const auto& [ob, c] : fixed)
      if (swept_distance(*ob, a, b, 0.0, 0.0) < c) return false;
    return true;
  };
  if (fixed.empty() || clear(from, to) || rb.force_dims == 1) return {from, to};
  // Corners around each obstacle at kWayMargin times the clearance: 8 around a post's
  // centre; 5 around each end of a wall (straight on, 45 and 90 degrees to either side).
  std::vector<std::array<double, 2>> node{from, to};
  for (const auto& [ob, c] : fixed) {
    const double r = kWayMargin * c;
    auto around = [&](const std::array<double, 2>& centre, double ux, double uy, const std::vector<double>& angles) {
      for (double a : angles)
        node.push_back({centre[0] + r * (std::cos(a) * ux - std::sin(a) * uy),
                        centre[1] + r * (std::sin(a) * ux + std::cos(a) * uy)});
    };
    if (ob->shape == ObstacleShape::kDisk) {
      around(ob->from, 1.0, 0.0, {0, kPi / 4, kPi / 2, 3 * kPi / 4, kPi, 5 * kPi / 4, 3 * kPi / 2, 7 * kPi / 4});
    } else {
      const double dx = ob->to[0] - ob->from[0], dy = ob->to[1] - ob->from[1], len = std::hypot(dx, dy);
      const std::vector<double> fan{0, kPi / 4, -kPi / 4, kPi / 2, -kPi / 2};
      around(ob->to, dx / len, dy / len, fan);
      around(ob->from, -dx / len, -dy / len, fan);
    }
  }
  const int n = static_cast<int>(node.size());
  std::vector<bool> usable(n, true);
  for (int k = 2; k < n; ++k)
    for (const auto& [ob, c] : fixed)
      if (obstacle_distance(*ob, node[k], 0.0) < c) usable[k] = false;
  // Dijkstra on the visibility graph of the usable corners (n is small: O(n^2) edges).
  std::vector<double> dist(n, kInf);
  std::vector<int> prev(n, -1);
  std::vector<bool> done(n, false);
  dist[0] = 0.0;
  for (int round = 0; round < n; ++round) {
    int u = -1;
    for (int k = 0; k < n; ++k)
      if (!done[k] && usable[k] && std::isfinite(dist[k]) && (u < 0 || dist[k] < dist[u])) u = k;
    if (u < 0 || u == 1) break;
    done[u] = true;
    for (int v = 0; v < n; ++v) {
      if (done[v] || !usable[v]) continue;
      const double d = dist[u] + std::hypot(node[v][0] - node[u][0], node[v][1] - node[u][1]);
      if (d < dist[v] && clear(node[u], node[v])) dist[v] = d, prev[v] = u;
    }
  }
  if (prev[1] < 0) return {from, to};  // no way round: closed in
  Way way;
  for (int k = 1; k >= 0; k = prev[k]) way.push_back(node[k]);
  std::reverse(way.begin(), way.end());
  return way;
}

Paths detour_paths(const Scene& scene, int side) {
  return detour_paths(scene, side > 0 ? 0u : ~std::uint64_t{0});
}

Paths detour_paths(const Scene& scene, std::uint64_t pattern, bool meet_turners) {
  const std::vector<Conflict> cs = conflicts(scene);
  auto straight = [](int, double tau) { return tau; };
  auto offset = [&](int robot, double tau, double& ox, double& oy) {
    for (std::size_t k = 0; k < cs.size(); ++k) {
      const Conflict& c = cs[k];
      if (robot != c.i && robot != c.j) continue;
      const double side = k < 64 && (pattern >> k & 1u) ? -1.0 : 1.0;
      // Peak at the closest approach, kept away from the ends.
      const double peak = std::clamp(inverse_smoothstep(c.w), 0.15, 0.85);
      const double a = side * c.clearance * bump(tau, peak) * (robot == c.i ? 1.0 : -1.0);
      ox += a * c.nx;
      oy += a * c.ny;
    }
  };
  return build_paths(scene, meet_turners, straight, offset);
}

Paths yield_paths(const Scene& scene, const StartSpec& start) {
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  std::vector<int> order = start.yield_order;
  if (order.empty()) {  // drawn: Fisher-Yates with our own uniform draws
    std::mt19937_64 g = start_generator(start.seed, scene.name, start.index, 1);
    order.resize(nr);
    for (int i = 0; i < nr; ++i) order[i] = i;
    for (int i = nr - 1; i > 0; --i)
      std::swap(order[i], order[std::min(i, static_cast<int>((i + 1) * uniform01(g)))]);
  }
  DISCO_CHECK(static_cast<int>(order.size()) == nr, "a yield order lists every robot once");
  std::vector<double> clearance(nr * nr, -1.0);  // < 0: the pair does not interact
  for (const Pair& p : scene.pairs)
    clearance[p.i * nr + p.j] = clearance[p.j * nr + p.i] = disco::clearance(scene, p);
  std::vector<StraightMove> moves(nr);
  for (int i = 0; i < nr; ++i) moves[i] = straight_move(scene.robots[i]);
  std::vector<double> delay(nr, 0.0);
  auto at = [&](int i, double d, double tau, int c) {
    const double w = smoothstep(std::clamp((tau - d) / (1.0 - d), 0.0, 1.0));
    return moves[i].from[c] + w * (moves[i].to[c] - moves[i].from[c]);
  };
  const int samples = 8 * N;
  for (int k = 0; k < nr; ++k) {
    const int i = order[k];
    double best_d = 0.0, best_ratio = -1.0;
    for (int step = 0; step <= 60; ++step) {
      const double d = 0.01 * step;
      double ratio = kInf;  // smallest distance / clearance against the robots placed
      for (int q = 0; q < k; ++q) {
        const int j = order[q];
        if (clearance[i * nr + j] < 0) continue;
        for (int m = 0; m <= samples; ++m) {
          const double tau = static_cast<double>(m) / samples;
          const double dist = std::hypot(at(i, d, tau, kX) - at(j, delay[j], tau, kX),
                                         at(i, d, tau, kY) - at(j, delay[j], tau, kY));
          ratio = std::min(ratio, dist / clearance[i * nr + j]);
        }
      }
      if (ratio > best_ratio) best_d = d, best_ratio = ratio;
      if (ratio >= start.margin) break;
    }
    delay[i] = best_d;
  }
  auto warp = [&](int robot, double tau) {
    return std::clamp((tau - delay[robot]) / (1.0 - delay[robot]), 0.0, 1.0);
  };
  auto no_offset = [](int, double, double&, double&) {};
  return build_paths(scene, start.meet_turners, warp, no_offset);
}

Paths perturbed_paths(const Scene& scene, const StartSpec& start) {
  const int nr = static_cast<int>(scene.robots.size());
  const double p = start.perturbation;
  std::mt19937_64 g = start_generator(start.seed, scene.name, start.index, 1);
  struct Shape {
    std::array<double, 3> lateral, second;  // second: y of a robot that does not move
    std::array<double, 2> timing;
  };
  std::vector<Shape> shapes(nr);
  for (Shape& s : shapes) {  // the same draws for every robot, moving or not
    for (double& a : s.lateral) a = uniform(g, -1.0, 1.0);
    for (double& a : s.second) a = uniform(g, -1.0, 1.0);
    for (double& c : s.timing) c = uniform(g, -1.0, 1.0);
  }
  auto profile = [](const std::array<double, 3>& a, double tau) {
    double sum = 0.0, norm = 0.0;
    for (int k = 0; k < 3; ++k) {
      sum += a[k] * std::sin((k + 1) * kPi * tau);
      norm += std::abs(a[k]);
    }
    return norm > 0.0 ? sum / norm : 0.0;
  };
  auto warp = [&](int robot, double tau) {
    double s = tau;
    for (int k = 0; k < 2; ++k)
      s += p * shapes[robot].timing[k] * std::sin((k + 1) * kPi * tau) / ((k + 1) * kPi);
    return s;
  };
  auto offset = [&](int robot, double tau, double& ox, double& oy) {
    const Robot& rb = scene.robots[robot];
    const StraightMove m = straight_move(rb);
    const double L = m.length();
    if (L > 1e-9 * rb.radius) {
      const double a = p * L * profile(shapes[robot].lateral, tau);
      ox += a * -(m.to[1] - m.from[1]) / L;
      oy += a * (m.to[0] - m.from[0]) / L;
    } else {
      ox += p * rb.radius * profile(shapes[robot].lateral, tau);
      oy += p * rb.radius * profile(shapes[robot].second, tau);
    }
  };
  return build_paths(scene, start.meet_turners, warp, offset);
}

Paths retimed_paths(const RobotProblem& problem, const StartSpec& start, const Vector& z) {
  const Scene& scene = problem.scene();  // SI
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  const double p = start.perturbation;
  std::mt19937_64 g = start_generator(start.seed, scene.name, start.index, 1);
  const Paths old = paths_of(problem, z);  // the feasible paths, SI
  Paths paths = old;
  for (int i = 0; i < nr; ++i) {
    std::array<double, 2> c;
    for (double& a : c) a = uniform(g, -1.0, 1.0);
    for (int t = 1; t < N; ++t) {
      const double tau = static_cast<double>(t) / N;
      double s = tau;
      for (int k = 0; k < 2; ++k) s += p * c[k] * std::sin((k + 1) * kPi * tau) / ((k + 1) * kPi);
      paths[i][t] = pose_at(old[i], N * std::clamp(s, 0.0, 1.0));
    }
  }
  return paths;
}

Vector smoothstep_guess(const RobotProblem& problem, double seconds, bool meet_turners) {
  // Made on the scene in model units, as the solver sees it: no round trip through SI.
  auto straight = [](int, double tau) { return tau; };
  auto no_offset = [](int, double, double&, double&) {};
  return complete_paths(problem,
                        build_paths(problem.layout().model_scene(), meet_turners, straight, no_offset),
                        1.0, seconds / problem.units().time);
}

Vector straight_guess(const RobotProblem& problem, double seconds, bool meet_turners) {
  const Scene& scene = problem.scene();  // SI
  const int nr = static_cast<int>(scene.robots.size());
  std::vector<double> switch_at(nr, -1.0);  // < 0: the smoothstep
  bool any = false;
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = scene.robots[i];
    const auto m = straight_move_limits(rb, scene.gravity);
    if (!m || m->distance == 0.0) continue;
    const double a1 = m->accel(rb.mass), a2 = m->brake(rb.mass);
    // Only where the smoothstep asks too much and a feasible timing exists.
    if (!(a1 > 0.0) || 6.0 * m->distance / (seconds * seconds) <= a1 ||
        seconds < bang_bang_time(m->distance, a1, a2, m->stop_at_end))
      continue;
    switch_at[i] = m->stop_at_end ? a2 / (a1 + a2) : 1.0;
    any = true;
  }
  if (!any) return smoothstep_guess(problem, seconds, meet_turners);
  const int N = scene.steps;
  auto warp = [&](int robot, double tau) {
    const double s = switch_at[robot];
    if (s < 0.0) return tau;
    // Discrete: the distance after step t of the velocity profile min(a_1 k, a_2 (N - k)).
    const int t = static_cast<int>(std::lround(tau * N));
    double done = 0.0, all = 0.0;
    for (int k = 1; k <= N; ++k) {
      const double v = s < 1.0 ? std::min(k / s, (N - k) / (1.0 - s)) : k;
      all += v;
      if (k <= t) done += v;
    }
    return inverse_smoothstep(done / all);
  };
  auto no_offset = [](int, double, double&, double&) {};
  return complete_guess(problem, build_paths(scene, meet_turners, warp, no_offset), seconds);
}

Vector make_guess(const RobotProblem& problem, const StartSpec& start, double seconds) {
  switch (start.guess) {
    case GuessKind::kStraight: return straight_guess(problem, seconds, start.meet_turners);
    case GuessKind::kPerturbed:
      return complete_guess(problem, perturbed_paths(problem.scene(), start), seconds);
    case GuessKind::kDetour:
      return complete_guess(
          problem, detour_paths(problem.scene(), start.detour_pattern, start.meet_turners), seconds);
    case GuessKind::kPerturbedFeasible: return smoothstep_guess(problem, seconds, start.meet_turners);
    case GuessKind::kYield:
      return complete_guess(problem, yield_paths(problem.scene(), start), seconds);
    case GuessKind::kGiven: return complete_guess(problem, start.given.paths, seconds);
  }
  return smoothstep_guess(problem, seconds);
}

Paths guess_paths(const Scene& scene, const StartSpec& start) {
  switch (start.guess) {
    case GuessKind::kPerturbed: return perturbed_paths(scene, start);
    case GuessKind::kDetour: return detour_paths(scene, start.detour_pattern, start.meet_turners);
    case GuessKind::kYield: return yield_paths(scene, start);
    case GuessKind::kGiven: return start.given.paths;
    case GuessKind::kStraight:
    case GuessKind::kPerturbedFeasible: break;
  }
  auto straight = [](int, double tau) { return tau; };
  auto no_offset = [](int, double, double&, double&) {};
  return build_paths(scene, start.meet_turners, straight, no_offset);
}

std::optional<double> pushers_way_time(const Scene& scene) {
  const QueuedWays ways = queued_ways(scene, pushed_objects(scene));
  std::optional<double> longest;
  for (std::size_t i = 0; i < ways.legs.size(); ++i) {
    if (!ways.to_target[i]) continue;
    double total = 0.0;
    for (const Leg& l : ways.legs[i]) {
      std::optional<double> t;
      if (l.object >= 0) {
        t = pushed_move_time(scene, l.object);
      } else {  // the robot alone, from rest at the leg's start to rest at its end
        Robot leg = scene.robots[i];
        leg.start = State{l.from[0], l.from[1], leg.start[kPhi], 0.0, 0.0, 0.0};
        leg.target = StateBox{};
        leg.target.lower[kX] = leg.target.upper[kX] = l.to[0];
        leg.target.lower[kY] = leg.target.upper[kY] = l.to[1];
        leg.target.lower[kVx] = leg.target.upper[kVx] = leg.target.lower[kVy] = leg.target.upper[kVy] = 0.0;
        t = straight_move_time(leg, scene.gravity);
      }
      if (!t || !std::isfinite(*t)) return std::nullopt;
      total += *t;
    }
    longest = std::max(longest.value_or(0.0), total);
  }
  return longest;
}

Perturbation perturb_feasible(const RobotProblem& problem, const StartSpec& start,
                              const Vector& feasible) {
  DISCO_CHECK(feasible.size() == problem.program().num_variables(), "a model point");
  const double seconds = start.T_scale * problem.horizon(feasible);
  return {complete_guess(problem, retimed_paths(problem, start, feasible), seconds), seconds};
}

PerturbFunction make_perturbation(const RobotProblem& problem, const StartSpec& start) {
  // A scene that fixes T_f (objective energy) has no other horizon to perturb to.
  if (start.guess != GuessKind::kPerturbedFeasible || problem.horizon_is_fixed()) return {};
  return [&problem, start](const Vector& feasible) {
    return perturb_feasible(problem, start, feasible);
  };
}


}  // namespace disco
