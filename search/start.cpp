#include "search/start.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "core/model/lower_bound.h"
#include "core/util/check.h"
#include "core/util/numbers.h"

// How the starts are made.
//
// Parameters. Start `index` >= 1 draws, in this fixed order, from a
// std::mt19937_64 (fully specified by the standard) seeded with FNV-1a over
// (seed, scene name, index, stream 0): horizon_factor, rate, grow, shrink,
// perturbation, zeta, min_rate, T_scale, margin (the last three were added
// later, after the others, so that those keep their values). Uniform reals are made here
// from the generator's bits (std::uniform_real_distribution is
// implementation-defined), so a start is the same with any standard library.
// Every draw is made whatever the kind, so the kind never shifts the other
// parameters.
//
// Kinds. With a conflicting pair (below), (index - 1) % 5 = 0: detour left,
// 1: detour right, 2: yield, 3: perturbed, 4: perturbed feasible (detours
// first: on the paper's A3/A4 they reached the best optima, perturbed starts
// rarely did; under a time budget the first starts are the ones that run).
// Without one (detours and yields would be the straight guess), perturbed and
// perturbed feasible alternate: (index - 1) % 2 = 0: perturbed, 1: perturbed
// feasible.
//
// Paths. Every guess is a set of position paths, completed into a full model
// point by RobotProblem::guess_from_paths. The straight path of a robot goes
// from its start to the nearest point of its target box along the smoothstep
// w(tau) = tau^2 (3 - 2 tau), tau = t / N. Every offset added here vanishes at
// t = 0 and t = N, and the point at t = N is set to the target point exactly.
// A robot with force_dims 1 cannot push sideways: its offsets are projected on
// its force axis (only its timing along the axis changes).
//
// Conflicts. A pair (i, j) conflicts when, on the straight paths (which share
// the same timing, so p_j - p_i = d0 + w (dN - d0) is linear in w), the centre
// distance drops below R_i + R_j (+ d_s for an avoid pair).
//
// Detour. For every conflicting pair, with D = dN - d0 (the relative motion of
// j seen from i) and n = D turned +90 degrees (unit): i is moved by
// +side B n b(tau), j by -side B n b(tau), with B = R_i + R_j (+ d_s) and b a
// smooth bump, 0 at tau = 0 and 1, peaking (b = 1) at the straight paths'
// closest approach. So the lateral offset (p_j - p_i) . n changes by
// -2 side B at the peak: side +1 (left) puts each robot on the other's left
// (relative to their relative motion), side -1 (right) on its right. The
// offsets of the two sides are exact mirror images; pairs' offsets add up.
//
// Perturbed. Per robot: a lateral offset p L l(tau) along its path's normal
// (L = path length; a robot that does not move gets p R in x and in y
// independently, R its radius), with l = sum_k a_k sin(k pi tau) / sum |a_k|,
// k = 1..3, a_k uniform in [-1, 1]; and a timing warp s(tau) = tau +
// p sum_k c_k sin(k pi tau) / (k pi), k = 1..2, c_k in [-1, 1], along the path
// (w(s(tau)) replaces w(tau)), monotone since s' >= 1 - 2 p > 0 for p < 0.5.
// The shape's random numbers come from stream 1 of the start's generator.
//
// Yield. Prioritised planning with waits: the robots, in a random order
// (Fisher-Yates on stream 1), each keep their straight path and smoothstep
// timing but wait at the start for a fraction d of the horizon, then move on
// w((tau - d) / (1 - d)). Each robot takes the smallest d in 0, 0.01, ..., 0.6
// for which its centre distance to every robot placed before it, over 8 N
// samples of tau, stays at least `margin` (drawn in [1, 1.5]) times the pair's
// clearance; if none does, the d with the largest smallest distance. So at a
// crossing one robot goes first and the other waits for it, the class of
// solution a straight or detour guess rarely reaches.
//
// Perturbed feasible. The guess is the straight one; the perturbation (step
// 1b of objective_reduction.h) takes each robot's path from the feasible
// point, (x, y, phi) at t = 0..N (t = 0 the start), and re-times it: state t
// of the new path is the old path at the continuous step N s(t / N), linearly
// interpolated between the neighbouring states, with s(tau) = tau + p sum_k
// c_k sin(k pi tau) / (k pi), k = 1..2, c_k uniform in [-1, 1] per robot
// (stream 1), p = perturbation: s(0) = 0, s(1) = 1, s' >= 1 - 2 p > 0. The
// t = N state is the feasible end state exactly (in the target box). Robots get
// different warps, so their relative timing changes too. Velocities,
// friction, forces and gaps follow from the new positions
// (RobotProblem::guess_from_paths) for the horizon T_scale times the feasible
// one.
//
// Weak robots. The smoothstep asks for accelerations up to 6 L / T^2 (at both
// ends). A robot whose own acceleration along its move, a_1 = (push -
// friction) / M (core/model/lower_bound.h), is smaller at the horizon T cannot
// follow it: a robot barely stronger than its floor friction. From such a
// guess the feasibility solve settled on stop-and-go paths (the robot at rest
// at inner steps, where the friction complementarity is biactive and leaving
// the stop needs a jump of the friction to mu M g), local optima the reduction
// never left: configs/stress/weak_force.yaml (F_max = 1.001 mu M g) ended at
// 34.03 s, 5.3 % above its 32.33 s optimum. In the guess of a straight start
// (start 0, what `disco solve` runs), at a horizon T from the move's minimum
// time up to sqrt(6 L / a_1), such a robot moves on the timing of its own
// fastest move in the model's steps, stretched to T: the distance after step t
// is the share sum_{k<=t} v_k / sum_{k<=N} v_k of the velocity profile v_k =
// min(a_1 k, a_2 (N - k)), a_2 = (push + friction) / M (v_k = a_1 k without a
// stop at the end); its velocity changes stay within a_1 h and a_2 h whenever
// T is at least the move's minimum time in N steps, and it ends at rest
// exactly. (The
// continuous bang-bang timing brakes within the last step, which positions at
// the steps cannot show: from it the first feasibility solve failed.)
// weak_force then reaches 32.33 s in 2 solves. Without such a robot the
// straight guess is RobotProblem::straight_line_guess, bit for bit as before.
// At the default horizon (1.5 times the slowest robot's time) the smoothstep
// is too fast for a robot with push < 2 friction along its move: the paper's
// robots (push 1.52 friction) but none of the other configs/scenarios/
// (tests/test_start.cpp checks). Measured on the paper scenes, start 0 alone
// (`disco solve`, one thread), smoothstep -> own timing: A1, A2, A3 the same
// T_f (83 / 107, 61 / 71, 421 / 424 iterations), A4 unchanged (no weak robot at
// its horizon), B1 9.8177 -> 9.8058 s (57 -> 108 s), B2 9.8709 -> 9.8227 s
// (50 s), B3 10.1318 -> 10.1338 s (157 -> 42 s). Other kinds keep the
// smoothstep, so the search's other starts are as before.

namespace disco {
namespace {

using Paths = std::vector<std::vector<std::array<double, 3>>>;

constexpr double kPi = std::numbers::pi;

// FNV-1a, 64 bits, over an explicit little-endian byte sequence.
class Fnv1a {
 public:
  void byte(std::uint8_t b) {
    h_ ^= b;
    h_ *= 1099511628211ull;
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) byte(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void text(const std::string& s) {
    u64(s.size());
    for (char c : s) byte(static_cast<std::uint8_t>(c));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

// Stream 0: the start's parameters; stream 1: the shape of its guess.
std::mt19937_64 generator(std::uint64_t seed, const std::string& scene, int index,
                          std::uint64_t stream) {
  Fnv1a f;
  f.text("disco start");
  f.u64(seed);
  f.text(scene);
  f.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(index)));
  f.u64(stream);
  return std::mt19937_64(f.value());
}

// Uniform in [0, 1), from the top 53 bits.
double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& g, double lo, double hi) { return lo + (hi - lo) * uniform01(g); }

double smoothstep(double tau) { return tau * tau * (3.0 - 2.0 * tau); }
// tau with smoothstep(tau) = w, for w in [0, 1].
double inverse_smoothstep(double w) { return 0.5 - std::sin(std::asin(1.0 - 2.0 * w) / 3.0); }

// A robot's straight move: start and nearest target point (SI).
struct Move {
  std::array<double, 3> from, to;  // x, y, phi
  double length() const { return std::hypot(to[0] - from[0], to[1] - from[1]); }
};

Move straight_move(const Robot& rb) {
  Move m;
  for (int c : {kX, kY, kPhi}) {
    m.from[c] = rb.start[c];
    m.to[c] = std::clamp(rb.start[c], rb.target.lower[c], rb.target.upper[c]);
  }
  return m;
}

struct Conflict {
  int i = 0, j = 0;
  double w = 0.5;              // smoothstep fraction at the closest approach
  double nx = 0.0, ny = 0.0;   // unit normal of the relative motion
  double clearance = 0.0;      // R_i + R_j (+ d_s)
};

std::vector<Conflict> conflicts(const Scene& scene) {
  std::vector<Conflict> out;
  for (const Pair& p : scene.pairs) {
    const Move a = straight_move(scene.robots[p.i]), b = straight_move(scene.robots[p.j]);
    const double d0x = b.from[0] - a.from[0], d0y = b.from[1] - a.from[1];
    const double Dx = (b.to[0] - a.to[0]) - d0x, Dy = (b.to[1] - a.to[1]) - d0y;
    const double DD = Dx * Dx + Dy * Dy;
    if (!(DD > 0.0)) continue;  // no relative motion: the start distance stays, and it is valid
    const double w = std::clamp(-(d0x * Dx + d0y * Dy) / DD, 0.0, 1.0);
    const double closest = std::hypot(d0x + w * Dx, d0y + w * Dy);
    const double clearance = scene.robots[p.i].radius + scene.robots[p.j].radius +
                             (p.mode == PairMode::kAvoid ? p.safe_distance : 0.0);
    // Touching at the start is allowed: a relative margin keeps roundoff out.
    if (!(closest < clearance * (1.0 - 1e-12))) continue;
    const double len = std::sqrt(DD);
    out.push_back({p.i, p.j, w, -Dy / len, Dx / len, clearance});
  }
  return out;
}

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
// (robot, tau, &ox, &oy); the t = N point is the target point.
template <class Warp, class Offset>
Paths build_paths(const Scene& scene, Warp&& warp, Offset&& offset) {
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  Paths paths(nr, std::vector<std::array<double, 3>>(N + 1));
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = scene.robots[i];
    const Move m = straight_move(rb);
    paths[i][0] = m.from;
    for (int t = 1; t < N; ++t) {
      const double tau = static_cast<double>(t) / N;
      const double w = smoothstep(std::clamp(warp(i, tau), 0.0, 1.0));
      double ox = 0.0, oy = 0.0;
      offset(i, tau, ox, oy);
      project(rb, ox, oy);
      for (int c : {kX, kY, kPhi}) paths[i][t][c] = m.from[c] + w * (m.to[c] - m.from[c]);
      paths[i][t][kX] += ox;
      paths[i][t][kY] += oy;
    }
    paths[i][N] = m.to;
  }
  return paths;
}

Paths detour_paths(const Scene& scene, int side) {
  const std::vector<Conflict> cs = conflicts(scene);
  auto straight = [](int, double tau) { return tau; };
  auto offset = [&](int robot, double tau, double& ox, double& oy) {
    for (const Conflict& c : cs) {
      if (robot != c.i && robot != c.j) continue;
      // Peak at the closest approach, kept away from the ends.
      const double peak = std::clamp(inverse_smoothstep(c.w), 0.15, 0.85);
      const double a = side * c.clearance * bump(tau, peak) * (robot == c.i ? 1.0 : -1.0);
      ox += a * c.nx;
      oy += a * c.ny;
    }
  };
  return build_paths(scene, straight, offset);
}

Paths yield_paths(const Scene& scene, const StartSpec& start) {
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  std::mt19937_64 g = generator(start.seed, scene.name, start.index, 1);
  std::vector<int> order(nr);
  for (int i = 0; i < nr; ++i) order[i] = i;
  for (int i = nr - 1; i > 0; --i)  // Fisher-Yates with our own uniform draws
    std::swap(order[i], order[std::min(i, static_cast<int>((i + 1) * uniform01(g)))]);
  std::vector<double> clearance(nr * nr, -1.0);  // < 0: the pair does not interact
  for (const Pair& p : scene.pairs)
    clearance[p.i * nr + p.j] = clearance[p.j * nr + p.i] =
        scene.robots[p.i].radius + scene.robots[p.j].radius +
        (p.mode == PairMode::kAvoid ? p.safe_distance : 0.0);
  std::vector<Move> moves(nr);
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
  return build_paths(scene, warp, no_offset);
}

Paths perturbed_paths(const Scene& scene, const StartSpec& start) {
  const int nr = static_cast<int>(scene.robots.size());
  const double p = start.perturbation;
  std::mt19937_64 g = generator(start.seed, scene.name, start.index, 1);
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
    const Move m = straight_move(rb);
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
  return build_paths(scene, warp, offset);
}

// The feasible point's paths re-timed (see "Perturbed feasible" above).
Paths retimed_paths(const RobotProblem& problem, const StartSpec& start, const Vector& z) {
  const Scene& scene = problem.scene();  // SI
  const Layout& lay = problem.layout();
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  const double L = problem.units().length;
  const double p = start.perturbation;
  std::mt19937_64 g = generator(start.seed, scene.name, start.index, 1);
  Paths paths(nr, std::vector<std::array<double, 3>>(N + 1));
  for (int i = 0; i < nr; ++i) {
    std::array<double, 2> c;
    for (double& a : c) a = uniform(g, -1.0, 1.0);
    // The feasible path, SI.
    std::vector<std::array<double, 3>> old(N + 1);
    old[0] = {scene.robots[i].start[kX], scene.robots[i].start[kY], scene.robots[i].start[kPhi]};
    for (int t = 1; t <= N; ++t)
      old[t] = {lay.state(i, t, kX).value(z) * L, lay.state(i, t, kY).value(z) * L,
                lay.state(i, t, kPhi).value(z)};
    paths[i][0] = old[0];
    for (int t = 1; t < N; ++t) {
      const double tau = static_cast<double>(t) / N;
      double s = tau;
      for (int k = 0; k < 2; ++k) s += p * c[k] * std::sin((k + 1) * kPi * tau) / ((k + 1) * kPi);
      const double u = N * std::clamp(s, 0.0, 1.0);
      const int k = std::min(N - 1, static_cast<int>(std::floor(u)));
      const double f = u - k;
      for (int d = 0; d < 3; ++d) paths[i][t][d] = old[k][d] + f * (old[k + 1][d] - old[k][d]);
    }
    paths[i][N] = old[N];
  }
  return paths;
}

}  // namespace

std::string to_string(GuessKind kind) {
  switch (kind) {
    case GuessKind::kStraight: return "straight";
    case GuessKind::kPerturbed: return "perturbed";
    case GuessKind::kDetour: return "detour";
    case GuessKind::kPerturbedFeasible: return "perturbed feasible";
    case GuessKind::kYield: return "yield";
  }
  return "unknown";
}

// The guess and its parameters, e.g. "detour left".
static std::string guess_text(const StartSpec& s) {
  std::string kind = to_string(s.guess);
  char buf[64];
  if (s.guess == GuessKind::kDetour) {
    kind += s.detour_side > 0 ? " left" : " right";
  } else if (s.guess == GuessKind::kPerturbed) {
    std::snprintf(buf, sizeof buf, " %.2f", s.perturbation);
    kind += buf;
  } else if (s.guess == GuessKind::kPerturbedFeasible) {
    std::snprintf(buf, sizeof buf, " %.2f, T x%.2f", s.perturbation, s.T_scale);
    kind += buf;
  } else if (s.guess == GuessKind::kYield) {
    std::snprintf(buf, sizeof buf, " margin %.2f", s.margin);
    kind += buf;
  }
  return kind;
}

nlohmann::json StartSpec::schedule_json() const {
  return {{"horizon_factor", schedule.horizon_factor}, {"rate", schedule.rate},
          {"grow", schedule.grow},                     {"shrink", schedule.shrink},
          {"min_rate", schedule.min_rate},             {"zeta", elastic.zeta}};
}

std::string StartSpec::describe() const {
  const std::string kind = guess_text(*this);
  char line[256];
  std::snprintf(line, sizeof line,
                "start %d: %s, horizon x%.2f, rate %.3f, grow %.2f, shrink %.2f, min rate %.4f, "
                "zeta %g",
                index, kind.c_str(), schedule.horizon_factor, schedule.rate, schedule.grow,
                schedule.shrink, schedule.min_rate, elastic.zeta);
  return line;
}

StartSpec make_start(const Scene& scene, std::uint64_t seed, int index,
                     const ReductionSettings& base_schedule, const ElasticSettings& base_elastic) {
  DISCO_CHECK(index >= 0, "start indices are >= 0");
  StartSpec s;
  s.index = index;
  s.seed = seed;
  s.schedule = base_schedule;
  s.elastic = base_elastic;
  if (index == 0) return s;  // the plain start: straight guess, settings as given

  std::mt19937_64 g = generator(seed, scene.name, index, 0);
  s.schedule.horizon_factor = uniform(g, 1.2, 3.0);
  s.schedule.rate = uniform(g, 0.02, 0.2);
  s.schedule.grow = uniform(g, 1.2, 2.0);
  s.schedule.shrink = uniform(g, 0.3, 0.7);
  const double perturbation = uniform(g, 0.05, 0.3);
  static constexpr double kZeta[3] = {1.0, 10.0, 100.0};  // uniform in log10(zeta)
  s.elastic.zeta = kZeta[std::min(2, static_cast<int>(3.0 * uniform01(g)))];
  // Added after the draws above: those keep their values.
  s.schedule.min_rate = uniform(g, 0.005, 0.02);
  const double T_scale = uniform(g, 0.8, 1.0);
  const double margin = uniform(g, 1.0, 1.5);

  enum { kPerturbedSlot, kLeft, kRight, kFeasibleSlot, kYieldSlot } slot;
  if (conflicts(scene).empty()) {
    slot = (index - 1) % 2 == 0 ? kPerturbedSlot : kFeasibleSlot;
  } else {
    static constexpr decltype(slot) kCycle[5] = {kLeft, kRight, kYieldSlot, kPerturbedSlot,
                                                 kFeasibleSlot};
    slot = kCycle[(index - 1) % 5];
  }
  switch (slot) {
    case kLeft:
    case kRight:
      s.guess = GuessKind::kDetour;
      s.detour_side = slot == kLeft ? +1 : -1;
      break;
    case kPerturbedSlot:
      s.guess = GuessKind::kPerturbed;
      s.perturbation = perturbation;
      break;
    case kFeasibleSlot:
      s.guess = GuessKind::kPerturbedFeasible;
      s.perturbation = perturbation;
      s.T_scale = T_scale;
      break;
    case kYieldSlot:
      s.guess = GuessKind::kYield;
      s.margin = margin;
      break;
  }
  return s;
}

namespace {

// The straight guess (see "Weak robots" above).
Vector straight_guess(const RobotProblem& problem, double seconds) {
  const Scene& scene = problem.scene();  // SI
  const int nr = static_cast<int>(scene.robots.size());
  std::vector<double> switch_at(nr, -1.0);  // < 0: the smoothstep
  bool any = false;
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = scene.robots[i];
    const auto m = robot_straight_move(rb, scene.gravity);
    if (!m || m->distance == 0.0) continue;
    const double a1 = (m->push - m->friction) / rb.mass, a2 = (m->push + m->friction) / rb.mass;
    // Only where the smoothstep asks too much and a feasible timing exists.
    if (!(a1 > 0.0) || 6.0 * m->distance / (seconds * seconds) <= a1 ||
        seconds < straight_move_time(m->distance, a1, a2, m->stop_at_end))
      continue;
    switch_at[i] = m->stop_at_end ? a2 / (a1 + a2) : 1.0;
    any = true;
  }
  if (!any) return problem.straight_line_guess(seconds);
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
  return problem.guess_from_paths(build_paths(scene, warp, no_offset), seconds);
}

}  // namespace

Vector make_guess(const RobotProblem& problem, const StartSpec& start, double seconds) {
  switch (start.guess) {
    case GuessKind::kStraight: return straight_guess(problem, seconds);
    case GuessKind::kPerturbed:
      return problem.guess_from_paths(perturbed_paths(problem.scene(), start), seconds);
    case GuessKind::kDetour:
      return problem.guess_from_paths(detour_paths(problem.scene(), start.detour_side), seconds);
    case GuessKind::kPerturbedFeasible: return problem.straight_line_guess(seconds);
    case GuessKind::kYield:
      return problem.guess_from_paths(yield_paths(problem.scene(), start), seconds);
  }
  return problem.straight_line_guess(seconds);
}

Perturbation perturb_feasible(const RobotProblem& problem, const StartSpec& start,
                              const Vector& feasible) {
  DISCO_CHECK(feasible.size() == problem.program().num_variables(), "a model point");
  const double seconds = start.T_scale * problem.horizon(feasible);
  return {problem.guess_from_paths(retimed_paths(problem, start, feasible), seconds), seconds};
}

PerturbFunction make_perturbation(const RobotProblem& problem, const StartSpec& start) {
  if (start.guess != GuessKind::kPerturbedFeasible) return {};
  return [&problem, start](const Vector& feasible) {
    return perturb_feasible(problem, start, feasible);
  };
}

}  // namespace disco
