#include "core/model/model_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "core/model/floor_friction.h"
#include "core/model/gap.h"
#include "core/model/obstacles.h"
#include "core/util/check.h"

namespace disco {
namespace {

// A rounded box: the points within `radius` of the box [lo, hi] (a point when
// lo = hi; the plane when a side or the radius is infinite).
struct RoundedBox {
  std::array<double, 2> lo, hi;
  double radius;
};

// A lower bound on the distance between a point of `a` and a point of `b`,
// less the rounding error of computing it: kRoundoff times the magnitudes
// involved (coordinates of 1e160 m leave no digits for a 1 m gap).
constexpr double kRoundoff = 1e-9;
double distance_bound(const RoundedBox& a, const RoundedBox& b) {
  std::array<double, 2> gap;
  double scale = a.radius + b.radius;
  for (int k = 0; k < 2; ++k) {
    gap[k] = std::max({0.0, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k]});
    if (std::isnan(gap[k])) return -kInf;  // inf - inf: unbounded on both sides
    for (double v : {a.lo[k], a.hi[k], b.lo[k], b.hi[k]})
      if (std::isfinite(v)) scale = std::max(scale, std::abs(v));
  }
  return std::hypot(gap[0], gap[1]) - a.radius - b.radius - kRoundoff * scale;  // hypot: no overflow
}

// The largest speed in a target velocity box (infinite if unbounded).
double largest_speed(const StateBox& box) {
  double squared = 0.0;
  for (int c : {kVx, kVy}) {
    const double m = std::max(std::abs(box.lower[c]), std::abs(box.upper[c]));
    squared += m * m;
  }
  return std::sqrt(squared);
}

}  // namespace

std::vector<int> contact_components(const Scene& s) {
  std::vector<int> label(s.robots.size());
  std::iota(label.begin(), label.end(), 0);
  auto root = [&](int i) {
    while (label[i] != i) i = label[i] = label[label[i]];
    return i;
  };
  for (const Pair& p : s.pairs)
    if (p.mode == PairMode::kContact) label[root(p.j)] = root(p.i);
  for (int i = 0; i < static_cast<int>(label.size()); ++i) label[i] = root(i);
  return label;
}

std::vector<std::vector<double>> speed_bounds(const Scene& s, double h) {
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  const std::vector<int> comp = contact_components(s);
  std::vector<int> size(nr, 0);
  for (int c : comp) ++size[c];
  // A disk in contact with an obstacle takes the energy bound too: the obstacle's
  // impulses only dissipate (fixed and convex: core/model/obstacles.h), but with
  // friction they can turn spin into speed, which the one-robot bound leaves out.
  for (const Pair& p : s.obstacle_pairs)
    if (p.mode == PairMode::kContact) size[comp[p.i]] = std::max(size[comp[p.i]], 2);
  // Per component: G^2 and the start energy e0^2.
  std::vector<double> G2(nr, 0.0), e2(nr, 0.0);
  // M a = Fbar - mu M g cos(pi / K): the largest net push along the motion.
  // An object (no force) gets 0: its floor friction only takes energy away.
  auto net_push = [&](const Robot& rb) {
    if (rb.object) return 0.0;
    return rb.push_bound() - rb.mu * rb.mass * s.gravity * least_dissipation_ratio(rb.friction_edges);
  };
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    const double F = net_push(rb);
    DISCO_CHECK(F > 0 || rb.object, "F_max > mu M g (the parser's rule)");
    G2[comp[i]] += F * F / rb.mass;
    e2[comp[i]] += rb.mass * (rb.start[kVx] * rb.start[kVx] + rb.start[kVy] * rb.start[kVy]) +
                   rb.inertia * rb.start[kOmega] * rb.start[kOmega];
  }
  std::vector<std::vector<double>> energy(nr);  // e^s of component roots
  for (int c = 0; c < nr; ++c) {
    if (size[c] < 2) continue;
    const double hG = h * std::sqrt(G2[c]);
    energy[c].resize(N + 1);
    energy[c][0] = std::sqrt(e2[c]);
    for (int t = 0; t < N; ++t) energy[c][t + 1] = hG + std::hypot(hG, energy[c][t]);
  }
  std::vector<std::vector<double>> u(nr, std::vector<double>(N + 1));
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    if (size[comp[i]] >= 2) {
      for (int t = 0; t <= N; ++t) u[i][t] = energy[comp[i]][t] / std::sqrt(rb.mass);
      continue;
    }
    const double a = net_push(rb) / rb.mass, b = (rb.push_bound() + rb.mu * rb.mass * s.gravity) / rb.mass;
    const double v0 = std::hypot(rb.start[kVx], rb.start[kVy]), vT = largest_speed(rb.target);
    for (int t = 0; t <= N; ++t) u[i][t] = std::min(v0 + t * h * a, vT + (N - t) * h * b);
  }
  return u;
}

int ModelPlan::pair_states() const {
  int n = 0;
  for (const PairPlan& w : pairs) n += w.empty() ? 0 : w.last - w.first + 1;
  return n;
}

int ModelPlan::turning_robots() const {
  return static_cast<int>(std::count(rotates.begin(), rotates.end(), true));
}

ModelPlan plan_model(const Scene& s, bool adaptive, double horizon_max) {
  const int N = s.steps, nr = static_cast<int>(s.robots.size());
  const int np = static_cast<int>(s.pairs.size());
  const int nall = np + static_cast<int>(s.obstacle_pairs.size());
  auto pair = [&](int p) -> const Pair& { return p < np ? s.pairs[p] : s.obstacle_pairs[p - np]; };
  ModelPlan plan;
  plan.rotates.assign(nr, true);
  plan.pairs.resize(nall);
  for (int p = 0; p < nall; ++p) {
    plan.pairs[p] = {1, N, pair(p).mode == PairMode::kContact};
    if (adaptive) plan.pairs[p].friction = plan.pairs[p].friction && pair(p).mu > 0;
  }
  if (!adaptive) return plan;

  // Pair windows from the reach regions (items 1-3 of the header).
  DISCO_CHECK(horizon_max > 0, "the largest horizon is positive");
  if (std::isfinite(horizon_max)) {
    const double h = horizon_max / N;
    const auto u = speed_bounds(s, h);
    // forward[i][t] = r_f(t), backward[i][t] = r_b(t).
    std::vector<std::vector<double>> forward(nr, std::vector<double>(N + 1, 0.0)), backward = forward;
    for (int i = 0; i < nr; ++i) {
      for (int t = 1; t <= N; ++t) forward[i][t] = forward[i][t - 1] + h * u[i][t];
      for (int t = N - 1; t >= 0; --t) backward[i][t] = backward[i][t + 1] + h * u[i][t + 1];
    }
    // The region of robot i's centre at state t: within r_f(t_f) of its start and r_b(t_b)
    // of its target box (t_f = t_b = t; a step's straight move from t - 1 to t lies in the
    // region with t_f = t, t_b = t - 1, both sets being convex and r_f growing, r_b shrinking).
    auto regions = [&](int i, int t_f, int t_b) {
      const Robot& rb = s.robots[i];
      const std::array<double, 2> start{rb.start[kX], rb.start[kY]};
      return std::array<RoundedBox, 2>{
          RoundedBox{start, start, forward[i][t_f]},
          RoundedBox{{rb.target.lower[kX], rb.target.lower[kY]},
                     {rb.target.upper[kX], rb.target.upper[kY]},
                     backward[i][t_b]}};
    };
    for (int p = 0; p < np; ++p) {
      const Pair& pr = s.pairs[p];
      const double R = s.robots[pr.i].radius + s.robots[pr.j].radius;
      const double reach = clearance(s, pr) + kReachMargin * R;
      int first = N + 1, last = 0;
      for (int t = 1; t <= N; ++t) {
        const auto a = regions(pr.i, t, t), b = regions(pr.j, t, t);
        double apart = -kInf;
        for (const auto& ra : a)
          for (const auto& rb : b) apart = std::max(apart, distance_bound(ra, rb));
        if (!(apart > reach)) first = std::min(first, t), last = t;  // NaN: keep
      }
      plan.pairs[p].first = first;
      plan.pairs[p].last = last;
    }
    // Obstacle pairs: the obstacle's place up to state t + 1 is within the box of its
    // segment (a wall) or of its way from tau = 0 to (t + 1) h (a disk; obstacle_box),
    // rounded by R_o. A pair keeps state t also where the move from t - 1 to t or from t to
    // t + 1 comes within reach (its region from t_f = t + 1 and t_b = t - 1 holds both), so
    // every such step carries the swept row (core/model/swept.h).
    for (int q = 0; q < static_cast<int>(s.obstacle_pairs.size()); ++q) {
      const Pair& pr = s.obstacle_pairs[q];
      const Obstacle& ob = s.obstacles[pr.j];
      const double reach = obstacle_clearance(s, pr) + kReachMargin * (s.robots[pr.i].radius + ob.radius);
      int first = N + 1, last = 0;
      for (int t = 1; t <= N; ++t) {
        const auto box = obstacle_box(ob, 0.0, std::min(t + 1, N) * h);
        const RoundedBox o{box[0], box[1], ob.radius};
        double apart = -kInf;
        for (const auto& ra : regions(pr.i, std::min(t + 1, N), t - 1)) apart = std::max(apart, distance_bound(ra, o));
        if (!(apart > reach)) first = std::min(first, t), last = t;
      }
      plan.pairs[np + q].first = first;
      plan.pairs[np + q].last = last;
    }
  }

  // Rotation (item 4).
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = s.robots[i];
    bool turned = rb.start[kOmega] != 0.0;
    for (int p = 0; p < nall; ++p) {
      const Pair& pr = pair(p);
      const bool member = pr.i == i || (p < np && pr.j == i);
      if (member && plan.pairs[p].friction && !plan.pairs[p].empty()) turned = true;
    }
    auto inside = [&](int c, double v) { return rb.target.lower[c] <= v && v <= rb.target.upper[c]; };
    const bool constants_allowed = inside(kPhi, rb.start[kPhi]) && inside(kOmega, 0.0);
    plan.rotates[i] = turned || !constants_allowed;
  }
  return plan;
}

}  // namespace disco
