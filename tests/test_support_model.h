// Test-only helpers shared by the robot-model tests (derivatives, threads,
// physics). Header-only; everything inline.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/model/robot_problem.h"
#include "core/model/scene.h"
#include "core/util/numbers.h"

namespace disco::model_test {

// A lone robot spinning at the start (omega 0.1 rad/s) that must end at phi = 1 rad: damping
// stops it 0.025 rad on (omega_0 I / (sigma_d M g)), so no feasible point exists at any
// horizon, for a reason the input checks do not cover (core/model/reachability.h).
inline constexpr const char* kSpinShortScene = R"(
scenario: spin_short
steps: 10
defaults: {radius: 0.5, mass: 1.0, mu: 0.2, force_max: 5.0, K: 8}
robots:
  - name: a
    start: {x: 0, y: 0, omega: 0.1}
    target: {x: 2, y: 2, phi: 1.0, vx: 0, vy: 0}
  - name: b
    start: {x: 0, y: 3}
    target: {x: 3, y: 0, vx: 0, vy: 0}
)";

// A robot in SI units with the parser's defaults (inertia 0.5 M R^2,
// damping 0.1 R), at rest at (x, y).
inline Robot make_robot(const std::string& name, double radius, double mass, double mu,
                        double force_max, double x, double y, int K = 6) {
  Robot r;
  r.name = name;
  r.radius = radius;
  r.mass = mass;
  r.inertia = 0.5 * mass * radius * radius;
  r.mu = mu;
  r.damping = 0.1 * radius;
  r.force_max = force_max;
  r.friction_edges = K;
  r.start = {x, y, 0.0, 0.0, 0.0, 0.0};
  return r;
}

inline Pair make_pair(int i, int j, PairMode mode, double mu, double safe_distance) {
  Pair p;
  p.i = i;
  p.j = j;
  p.mode = mode;
  p.mu = mu;
  p.safe_distance = safe_distance;
  return p;
}

// A scene with one pair per robot pair i < j, all of `mode`.
inline Scene make_scene(const std::string& name, int steps, std::vector<Robot> robots,
                        PairMode mode = PairMode::kContact, double pair_mu = 0.3,
                        double safe_distance = 0.01) {
  Scene s;
  s.name = name;
  s.source = "test";
  s.steps = steps;
  s.gravity = 9.81;
  s.robots = std::move(robots);
  const int n = static_cast<int>(s.robots.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) s.pairs.push_back(make_pair(i, j, mode, pair_mu, safe_distance));
  return s;
}

// Two robots in contact mode heading for each other along x (slightly offset), each to the
// other's start at rest: the elastic NLP of such a scene has bilinear complementarity terms
// (an indefinite Hessian) and contact forces.
inline Scene two_robots_meeting_in_contact(int steps) {
  Robot a = make_robot("a", 0.5, 1.0, 0.2, 5.0, 0.0, 0.0, 4);
  Robot b = make_robot("b", 0.45, 1.2, 0.25, 6.0, 3.0, 0.3, 5);
  a.target.lower = {3, 0.3, -kInf, 0, 0, -kInf};
  a.target.upper = {3, 0.3, kInf, 0, 0, kInf};
  b.target.lower = {0, 0, -kInf, 0, 0, -kInf};
  b.target.upper = {0, 0, kInf, 0, 0, kInf};
  return make_scene("two_contact", steps, {a, b}, PairMode::kContact, 0.3);
}

// Appends obstacle `ob` to `s` with a pair (mode, mu, d_s) for every disk.
inline void add_obstacle(Scene& s, const Obstacle& ob, PairMode mode, double mu = 0.3,
                         double safe_distance = 0.01) {
  const int j = static_cast<int>(s.obstacles.size());
  s.obstacles.push_back(ob);
  for (int i = 0; i < static_cast<int>(s.robots.size()); ++i)
    s.obstacle_pairs.push_back(make_pair(i, j, mode, mu, safe_distance));
}

inline Obstacle wall(const std::string& name, std::array<double, 2> from, std::array<double, 2> to,
                     double half_thickness = 0.0) {
  Obstacle o;
  o.name = name;
  o.shape = ObstacleShape::kWall;
  o.from = from;
  o.to = to;
  o.radius = half_thickness;
  return o;
}

inline Obstacle post(const std::string& name, std::array<double, 2> centre, double radius,
                     std::array<double, 2> velocity = {0.0, 0.0}) {
  Obstacle o;
  o.name = name;
  o.from = o.to = centre;
  o.radius = radius;
  o.velocity = velocity;
  return o;
}

// A disk obstacle that follows `path` (core/model/obstacle_path.h).
inline Obstacle sentry(const std::string& name, double radius, std::vector<Waypoint> path) {
  Obstacle o;
  o.name = name;
  o.from = o.to = path.front().p;
  o.radius = radius;
  o.path = std::move(path);
  return o;
}

// Direction d_k of the floor-friction polygon (core/model/floor_friction.h).
inline std::array<double, 2> edge_direction(int k, int K) {
  const double a = 2.0 * std::numbers::pi * k / K;
  return {std::cos(a), std::sin(a)};
}

// How well a point satisfies a model, computed here from the public Nlp and
// Mpcc interfaces (independent of core/elastic's certify()).
struct Residuals {
  double equality = 0.0;       // max |c_r - c_lo_r| over rows with c_lo == c_hi
  double inequality = 0.0;     // max excess of the other rows over their bounds
  double bounds = 0.0;         // max excess of z over its bounds
  double side_negative = 0.0;  // max(-G_i, -H_i, 0) over the pairs
  double complementarity = 0.0;  // max |min(G_i, H_i)| over the pairs
  int worst_equality_row = -1;
  int worst_pair = -1;
  double worst() const {
    return std::max({equality, inequality, bounds, side_negative, complementarity});
  }
};

inline Residuals residuals(const Mpcc& mpcc, const Eigen::VectorXd& z) {
  Residuals out;
  Eigen::VectorXd c(mpcc.num_constraints());
  if (!mpcc.constraints(z, c)) {
    out.equality = kInf;
    return out;
  }
  const auto& lo = mpcc.constraint_lower();
  const auto& hi = mpcc.constraint_upper();
  for (int r = 0; r < c.size(); ++r) {
    if (lo[r] == hi[r]) {
      const double e = std::abs(c[r] - lo[r]);
      if (e > out.equality) out.equality = e, out.worst_equality_row = r;
    } else {
      out.inequality = std::max({out.inequality, lo[r] - c[r], c[r] - hi[r]});
    }
  }
  for (int k = 0; k < z.size(); ++k)
    out.bounds = std::max({out.bounds, mpcc.variable_lower()[k] - z[k],
                           z[k] - mpcc.variable_upper()[k]});
  const auto& pairs = mpcc.complementarity_pairs();
  for (int i = 0; i < static_cast<int>(pairs.size()); ++i) {
    const double g = side_value(pairs[i].g, z, c), h = side_value(pairs[i].h, z, c);
    out.side_negative = std::max({out.side_negative, -g, -h});
    const double m = std::abs(std::min(g, h));
    if (m > out.complementarity) out.complementarity = m, out.worst_pair = i;
  }
  return out;
}

// The value of one constraint row at z.
inline double row_value(const Nlp& nlp, const Eigen::VectorXd& z, int r) {
  Eigen::VectorXd c(nlp.num_constraints());
  nlp.constraints(z, c);
  return c[r];
}

// Converts SI values to the model units of a RobotProblem (core/model/units.h).
struct ToModel {
  Units u;
  double length(double v) const { return v / u.length; }
  double time(double v) const { return v / u.time; }
  double velocity(double v) const { return v / u.velocity(); }
  double omega(double v) const { return v * u.time; }
  double force(double v) const { return v / u.force(); }
  // c_n and alpha: the impulse is h c_n N with N a length, so [c_n] = force / length.
  double contact_multiplier(double v) const { return v * u.length / u.force(); }
  // The contact-friction gamma matches v_T = T . v, a length times a velocity.
  double contact_gamma(double v) const { return v / (u.length * u.velocity()); }
};

}  // namespace disco::model_test
