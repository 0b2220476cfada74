#include "core/model/reachability.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/obstacles.h"
#include "core/util/errors.h"

namespace disco {
namespace {

constexpr double kTol = 1e-12;  // relative, as the parser's start-overlap checks

// The range of a x + b y over the box [lo_x, hi_x] x [lo_y, hi_y] (bounds may be infinite).
std::pair<double, double> range(double a, double b, double lo_x, double hi_x, double lo_y, double hi_y) {
  auto term = [](double c, double lo, double hi) -> std::pair<double, double> {
    if (c == 0.0) return {0.0, 0.0};
    const double p = c * lo, q = c * hi;
    return {std::min(p, q), std::max(p, q)};
  };
  const auto [l1, h1] = term(a, lo_x, hi_x);
  const auto [l2, h2] = term(b, lo_y, hi_y);
  return {l1 + l2, h1 + h2};
}

bool outside(double v, std::pair<double, double> r) {
  const double tol = kTol * (1.0 + std::abs(v));
  return v < r.first - tol || v > r.second + tol;
}

std::string interval(double lo, double hi) {
  if (lo == hi) return fmt::format("= {:g}", lo);
  return fmt::format("in [{:g}, {:g}]", lo, hi);
}

bool has_contact_pair(const Scene& scene, int r) {
  for (const Pair& p : scene.pairs)
    if (p.mode == PairMode::kContact && (p.i == r || p.j == r)) return true;
  return false;
}

// A contact pair with a disk, or with an obstacle: an obstacle's contact forces can turn a
// robot (friction at the rim) and push it across its axis (the normal of a slanted wall),
// though never set a disk at rest moving (it has no force of its own).
bool touches_anything(const Scene& scene, int r) {
  for (const Pair& p : scene.obstacle_pairs)
    if (p.mode == PairMode::kContact && p.i == r) return true;
  return has_contact_pair(scene, r);
}

// The robot's floor friction is symmetric about the line along `u` (none, or a
// polygon symmetric about it).
bool polygon_symmetric_about(const Robot& rb, double ux, double uy) {
  return rb.mu == 0.0 || friction_polygon_symmetric_about(rb.friction_edges, ux, uy);
}

std::string quoted(const Robot& r) { return "'" + printable(r.name, kEchoLimit) + "'"; }

std::string who(const Scene& scene, int r) { return disk_name(scene.robots[r]); }

void off_axis(const Scene& scene, int r, std::vector<Unreachable>& out) {
  const Robot& rb = scene.robots[r];
  const double ux = rb.force_axis[0], uy = rb.force_axis[1];
  const double nx = -uy, ny = ux;  // across the axis
  const State& s = rb.start;
  if (rb.force_dims != 1 || touches_anything(scene, r) || nx * s[kVx] + ny * s[kVy] != 0.0 ||
      !polygon_symmetric_about(rb, ux, uy))
    return;
  const auto& lo = rb.target.lower;
  const auto& hi = rb.target.upper;
  const std::string why = fmt::format(
      "{} is driven along its force_axis ({:g}, {:g}) only, and nothing can push it (no contact "
      "pair with a disk or an obstacle) nor drive it across that axis (floor friction only "
      "opposes motion)",
      who(scene, r), ux, uy);
  const double c = nx * s[kX] + ny * s[kY];
  if (outside(c, range(nx, ny, lo[kX], hi[kX], lo[kY], hi[kY]))) {
    std::string stays, needs;
    if (ny == 0.0) {
      stays = fmt::format("x stays at its start {:g} m", s[kX]);
      needs = "x " + interval(lo[kX], hi[kX]);
    } else if (nx == 0.0) {
      stays = fmt::format("y stays at its start {:g} m", s[kY]);
      needs = "y " + interval(lo[kY], hi[kY]);
    } else {
      stays = fmt::format("it stays on the line through its start ({:g}, {:g}) along that axis",
                          s[kX], s[kY]);
      needs = "x " + interval(lo[kX], hi[kX]) + ", y " + interval(lo[kY], hi[kY]) +
              ", which misses that line";
    }
    out.push_back({Unreachable::Rule::kOffAxis, r, -1,
                   why + ", so " + stays + "; its target needs " + needs});
  }
  if (outside(0.0, range(nx, ny, lo[kVx], hi[kVx], lo[kVy], hi[kVy])))
    out.push_back({Unreachable::Rule::kOffAxis, r, -1,
                   why + ", so its velocity across the axis stays 0; its target needs vx " +
                       interval(lo[kVx], hi[kVx]) + ", vy " + interval(lo[kVy], hi[kVy])});
}

void no_turn(const Scene& scene, int r, std::vector<Unreachable>& out) {
  const Robot& rb = scene.robots[r];
  if (touches_anything(scene, r) || rb.start[kOmega] != 0.0) return;
  const std::string why = who(scene, r) +
                          " cannot turn: nothing touches it (no contact pair with a disk or an "
                          "obstacle), its force acts at "
                          "its centre and the floor's only torque is the damping -sigma_d M g omega";
  const auto& lo = rb.target.lower;
  const auto& hi = rb.target.upper;
  if (outside(rb.start[kPhi], {lo[kPhi], hi[kPhi]}))
    out.push_back({Unreachable::Rule::kNoTurn, r, -1,
                   fmt::format("{}, so phi stays at its start {:g} rad; its target needs phi {}", why,
                               rb.start[kPhi], interval(lo[kPhi], hi[kPhi]))});
  if (outside(0.0, {lo[kOmega], hi[kOmega]}))
    out.push_back({Unreachable::Rule::kNoTurn, r, -1,
                   why + ", so omega stays 0; its target needs omega " + interval(lo[kOmega], hi[kOmega])});
}

void untouched(const Scene& scene, int r, std::vector<Unreachable>& out) {
  const Robot& rb = scene.robots[r];
  const State& s = rb.start;
  if (!rb.object || has_contact_pair(scene, r) || s[kVx] != 0.0 || s[kVy] != 0.0 || s[kOmega] != 0.0)
    return;
  const auto& lo = rb.target.lower;
  const auto& hi = rb.target.upper;
  for (int c : {kX, kY, kVx, kVy}) {  // phi and omega: no_turn
    const double v = c < kVx ? s[c] : 0.0;
    if (!outside(v, {lo[c], hi[c]})) continue;
    out.push_back({Unreachable::Rule::kUntouched, r, -1,
                   fmt::format("{} has no force of its own and nothing can push it (no contact "
                               "pair with a robot or object), so it stays at rest at its start; "
                               "its target needs {} {}, "
                               "the start has {:g}",
                               who(scene, r), kStateNames[c], interval(lo[c], hi[c]), v)});
    return;
  }
}

void overlap(const Scene& scene, const Pair& p, std::vector<Unreachable>& out) {
  const Robot& a = scene.robots[p.i];
  const Robot& b = scene.robots[p.j];
  const auto& la = a.target.lower;
  const auto& ha = a.target.upper;
  const auto& lb = b.target.lower;
  const auto& hb = b.target.upper;
  const double dx = std::max(std::abs(hb[kX] - la[kX]), std::abs(ha[kX] - lb[kX]));
  const double dy = std::max(std::abs(hb[kY] - la[kY]), std::abs(ha[kY] - lb[kY]));
  const double farthest = std::hypot(dx, dy);
  const bool avoid = p.mode == PairMode::kAvoid;
  const double needed = clearance(scene, p);
  if (!(farthest < needed * (1.0 - kTol))) return;
  out.push_back({Unreachable::Rule::kOverlap, p.j, p.i,
                 fmt::format("{} ({} pair): their targets keep their centres at "
                             "most {:g} m apart, less than R_i + R_j{} = {:g} m",
                             disk_pair_names(a, b), avoid ? "an avoid" : "a contact", farthest,
                             avoid ? " + safe_distance" : "", needed)});
}

void in_obstacle(const Scene& scene, const Pair& p, std::vector<Unreachable>& out) {
  const Obstacle& ob = scene.obstacles[p.j];
  if (ob.moves()) return;
  const Robot& a = scene.robots[p.i];
  const auto& lo = a.target.lower;
  const auto& hi = a.target.upper;
  double farthest = 0.0;
  for (double x : {lo[kX], hi[kX]})
    for (double y : {lo[kY], hi[kY]})
      farthest = std::max(farthest, std::isfinite(x) && std::isfinite(y)
                                        ? obstacle_distance(ob, {x, y}, 0.0)
                                        : std::numeric_limits<double>::infinity());
  const bool avoid = p.mode == PairMode::kAvoid;
  const double needed = obstacle_clearance(scene, p);
  if (!(farthest < needed * (1.0 - kTol))) return;
  out.push_back({Unreachable::Rule::kInObstacle, p.i, -1,
                 fmt::format("{} and obstacle '{}' ({} pair): its target keeps its centre at most "
                             "{:g} m from the obstacle's {}, less than R + R_obstacle{} = {:g} m",
                             who(scene, p.i), printable(ob.name, kEchoLimit),
                             avoid ? "an avoid" : "a contact", farthest,
                             ob.shape == ObstacleShape::kWall ? "centre line" : "centre",
                             avoid ? " + safe_distance" : "", needed)});
}

}  // namespace

std::vector<Unreachable> unreachable_targets(const Scene& scene) {
  std::vector<Unreachable> out;
  for (int r = 0; r < static_cast<int>(scene.robots.size()); ++r) {
    off_axis(scene, r, out);
    untouched(scene, r, out);
    no_turn(scene, r, out);
  }
  for (const Pair& p : scene.pairs) overlap(scene, p, out);
  for (const Pair& p : scene.obstacle_pairs) in_obstacle(scene, p, out);
  return out;
}

std::string disk_name(const Robot& r) { return (r.object ? "object " : "robot ") + quoted(r); }

std::string disk_pair_names(const Robot& a, const Robot& b) {
  if (a.object != b.object) return disk_name(a) + " and " + disk_name(b);
  return (a.object ? "objects " : "robots ") + quoted(a) + " and " + quoted(b);
}

bool has_any_target(const Scene& scene) {
  for (const Robot& rb : scene.robots)
    for (int c = 0; c < kStateSize; ++c)
      if (std::isfinite(rb.target.lower[c]) || std::isfinite(rb.target.upper[c])) return true;
  return false;
}

}  // namespace disco
