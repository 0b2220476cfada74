#include "core/model/layout.h"

#include <cmath>

#include "core/model/obstacle_path.h"
#include "core/model/obstacles.h"
#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {

Layout::Layout(const Scene& s, const ModelPlan& plan, PolynomialProgram& P) : scene_(s) {
  const int N = s.steps;
  const int nr = static_cast<int>(s.robots.size());
  const int np = static_cast<int>(s.pairs.size() + s.obstacle_pairs.size());
  DISCO_CHECK(static_cast<int>(plan.rotates.size()) == nr, "a plan entry per robot");
  DISCO_CHECK(static_cast<int>(plan.pairs.size()) == np, "a plan entry per pair and obstacle pair");
  robots_.resize(nr);
  pairs_.resize(np);
  momentum_.assign(nr, std::vector<std::array<int, 3>>(N, {-1, -1, -1}));

  t_f_ = P.add_variable(0.0, kInf, 1.0);
  for (int i = 0; i < nr; ++i) {
    robots_[i].rotates = plan.rotates[i];
    robots_[i].state.assign(N + 1, {-1, -1, -1, -1, -1, -1});
    robots_[i].force.resize(N);
    if (s.robots[i].mu > 0) robots_[i].beta.resize(N);
  }
  // Which states carry a gap unknown and which intervals carry contact unknowns.
  std::vector<std::vector<bool>> gap_at(np, std::vector<bool>(N + 1, false));
  std::vector<std::vector<bool>> contact_at(np, std::vector<bool>(N, false));
  for (int p = 0; p < np; ++p) {
    const PairPlan& w = plan.pairs[p];
    DISCO_CHECK(w.empty() || (1 <= w.first && w.last <= N), "a window lies within 1..N");
    auto& v = pairs_[p];
    v.friction = w.friction;
    v.gap.assign(N + 1, -1);
    for (auto* index : {&v.s, &v.low, &v.high, &v.q[0], &v.q[1]}) index->assign(N + 1, -1);
    for (auto* index : {&v.cn, &v.a1, &v.a2, &v.gamma}) index->assign(N, -1);
    if (w.empty()) continue;
    const bool contact = pair(p).mode == PairMode::kContact;
    for (int t = std::max(1, contact ? w.first - 1 : w.first); t <= w.last; ++t) gap_at[p][t] = true;
    if (contact)
      for (int t = w.first - 1; t < w.last; ++t) contact_at[p][t] = true;
  }

  // Unknowns in time order (interval t, then the state it leads to), which
  // keeps the KKT matrix banded in time.
  for (int t = 0; t < N; ++t) {
    for (int i = 0; i < nr; ++i) {
      const Robot& rb = s.robots[i];
      auto& v = robots_[i];
      for (int a = 0; a < rb.force_dims; ++a) v.force[t].push_back(P.add_variable(-kInf, kInf));
      if (rb.mu > 0) {
        for (int k = 0; k < rb.friction_edges; ++k) v.beta[t].push_back(P.add_variable(0, kInf));
        v.gamma.push_back(P.add_variable(0, kInf));
      }
    }
    for (int p = 0; p < np; ++p) {
      if (!contact_at[p][t]) continue;
      auto& v = pairs_[p];
      v.cn[t] = P.add_variable(0, kInf);
      if (!v.friction) continue;
      v.a1[t] = P.add_variable(0, kInf);
      v.a2[t] = P.add_variable(0, kInf);
      v.gamma[t] = P.add_variable(0, kInf);
    }
    for (int i = 0; i < nr; ++i)
      for (int c = 0; c < kStateSize; ++c)
        if (robots_[i].rotates || (c != kPhi && c != kOmega))
          robots_[i].state[t + 1][c] = P.add_variable(-kInf, kInf);
    // A contact pair's gap is >= 0 at every state: in the full model each is a
    // side of its pair with c_n; at the first state of a window it is not, and
    // without the bound its row (rho + R)^2 = |d|^2 would admit rho + R = -|d|.
    for (int p = 0; p < np; ++p) {
      if (!gap_at[p][t + 1]) continue;
      auto& v = pairs_[p];
      v.gap[t + 1] = P.add_variable(pair(p).mode == PairMode::kContact ? 0.0 : -kInf, kInf);
      if (follows_path(p))
        for (int a = 0; a < 2; ++a) v.q[a][t + 1] = P.add_variable(-kInf, kInf);
      if (!is_wall_pair(p)) continue;
      v.s[t + 1] = P.add_variable(0.0, 1.0, 0.5);
      v.low[t + 1] = P.add_variable(0.0, kInf);
      v.high[t + 1] = P.add_variable(0.0, kInf);
    }
  }
}

int Layout::state_index(int robot, int t, int component) const {
  return t == 0 ? -1 : robots_[robot].state[t][component];
}

Affine Layout::state(int robot, int t, int component) const {
  const int k = state_index(robot, t, component);
  if (k >= 0) return Affine::variable(k);
  // The start, or phi and omega (= phi^0, 0) of a robot that does not turn.
  return Affine(scene_.robots[robot].start[component]);
}

Affine Layout::force(int robot, int t, int axis) const {
  const Robot& rb = scene_.robots[robot];
  const auto& f = robots_[robot].force[t];
  if (rb.force_dims == 0) return Affine(0.0);  // an object: no force of its own
  if (rb.force_dims == 2) return Affine::variable(f[axis]);
  return Affine::variable(f[0], rb.force_axis[axis]);
}

Affine Layout::beta(int robot, int t, int k) const {
  return Affine::variable(beta_index(robot, t, k));
}
Affine Layout::floor_gamma(int robot, int t) const {
  return Affine::variable(floor_gamma_index(robot, t));
}
int Layout::beta_index(int robot, int t, int k) const {
  DISCO_CHECK(has_floor_friction(robot), "beta of a robot without floor friction");
  return robots_[robot].beta[t][k];
}
int Layout::floor_gamma_index(int robot, int t) const {
  DISCO_CHECK(has_floor_friction(robot), "gamma of a robot without floor friction");
  return robots_[robot].gamma[t];
}

int Layout::momentum_row(int robot, int t, int axis) const {
  const int r = momentum_[robot][t][axis];
  DISCO_CHECK(r >= 0, "momentum rows are created by add_dynamics, before any impulse");
  return r;
}

const Obstacle& Layout::obstacle(int p) const {
  DISCO_CHECK(with_obstacle(p), "the obstacle of a pair of two disks");
  return scene_.obstacles[pair(p).j];
}

bool Layout::is_wall_pair(int p) const {
  return with_obstacle(p) && obstacle(p).shape == ObstacleShape::kWall;
}

double Layout::radius_sum(int p) const {
  const Pair& pr = pair(p);
  return scene_.robots[pr.i].radius + (with_obstacle(p) ? obstacle(p).radius : scene_.robots[pr.j].radius);
}

Affine Layout::wall_parameter(int p, int t) const {
  DISCO_CHECK(is_wall_pair(p), "the wall parameter of a pair without a wall");
  if (t > 0) {
    DISCO_CHECK(pairs_[p].s[t] >= 0, "the wall parameter outside the pair's window");
    return Affine::variable(pairs_[p].s[t]);
  }
  const Robot& rb = scene_.robots[pair(p).i];
  return Affine(wall_projection(obstacle(p), {rb.start[kX], rb.start[kY]}));
}

Affine Layout::other_state(int p, int t, int c) const {
  if (!with_obstacle(p)) return state(pair(p).j, t, c);
  const Obstacle& ob = obstacle(p);
  if (c == kPhi || c == kOmega) return Affine(0.0);
  const int a = c == kX || c == kVx ? 0 : 1;
  if (c == kVx || c == kVy) return Affine(ob.velocity[a]);
  if (ob.shape == ObstacleShape::kWall) return Affine(ob.from[a]) + (ob.to[a] - ob.from[a]) * wall_parameter(p, t);
  if (follows_path(p)) {
    if (t == 0) return Affine(path_point(ob.path, 0.0)[a]);
    DISCO_CHECK(pairs_[p].q[a][t] >= 0, "a path obstacle's centre outside the pair's window");
    return Affine::variable(pairs_[p].q[a][t]);
  }
  // A disk at from + tau v, tau = t h = t T_f / N: affine in T_f.
  Affine centre(ob.from[a]);
  if (ob.velocity[a] != 0.0 && t > 0) centre += Affine::variable(t_f_, ob.velocity[a] * t / scene_.steps);
  return centre;
}

int Layout::gap_index(int pair, int t) const { return t == 0 ? -1 : pairs_[pair].gap[t]; }

bool Layout::has_gap(int pair, int t) const { return t == 0 || pairs_[pair].gap[t] >= 0; }

Affine Layout::gap(int pair, int t) const {
  DISCO_CHECK(has_gap(pair, t), "the gap of a pair outside its window");
  if (t == 0) {
    const auto& a = scene_.robots[this->pair(pair).i].start;
    const double bx = other_state(pair, 0, kX).constant, by = other_state(pair, 0, kY).constant;
    return Affine(std::hypot(bx - a[kX], by - a[kY]) - radius_sum(pair));
  }
  return Affine::variable(pairs_[pair].gap[t]);
}

Affine Layout::centre_distance(int pair, int t) const { return gap(pair, t) + Affine(radius_sum(pair)); }

Affine Layout::normal(int p, int t, int axis) const {
  return other_state(p, t, axis) - state(pair(p).i, t, axis);
}

Affine Layout::tangent(int pair, int t, int axis) const {
  return axis == 0 ? -normal(pair, t, 1) : normal(pair, t, 0);
}

}  // namespace disco
