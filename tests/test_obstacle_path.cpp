// A disk obstacle on waypoints (core/model/obstacle_path.h): the clamped spline against
// values worked out by hand and against its own defining properties (through the waypoints,
// at rest at both ends, C^2 where pieces meet, derivatives equal to finite differences, the
// range exact); the scene file's `path` and its bad inputs. A solved scene with a sentry on
// waypoints is checked in tests/test_obstacles.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/model/obstacle_path.h"
#include "core/model/obstacles.h"
#include "core/model/scene_yaml.h"
#include "tests/test_support_messages.h"

namespace disco {
namespace {

const std::vector<Waypoint> kPath = {
    {0.5, {0.0, 1.0}}, {1.0, {2.0, -1.0}}, {2.5, {1.0, 3.0}}, {3.0, {-1.0, 0.0}}, {4.2, {0.5, 0.5}}};

// Two waypoints: the cubic with zero slope at both ends is P0 + (P1 - P0)(3s^2 - 2s^3),
// s = (t - t0) / (t1 - t0). Three equally spaced with values 0, 1, 0 (knots 0, 1, 2): the
// clamped system 2M0 + M1 = 6, M0 + 4M1 + M2 = -12, M1 + 2M2 = 6 gives M = (6, -6, 6), the
// same cubic on [0, 1] and its mirror on [1, 2].
TEST(ObstaclePath, MatchesSplinesWorkedOutByHand) {
  const PathCoordinate two({{1.0, {2.0, 0.0}}, {3.0, {5.0, 0.0}}}, 0);
  for (double t : {1.0, 1.3, 2.0, 2.7, 3.0}) {
    const double s = (t - 1.0) / 2.0;
    const auto v = two.eval(t);
    EXPECT_NEAR(v[0], 2.0 + 3.0 * (3 * s * s - 2 * s * s * s), 1e-14) << t;
    EXPECT_NEAR(v[1], 3.0 * (6 * s - 6 * s * s) / 2.0, 1e-14) << t;
  }
  const PathCoordinate hat({{0.0, {0.0, 0.0}}, {1.0, {0.0, 1.0}}, {2.0, {0.0, 0.0}}}, 1);
  for (double s : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(hat.eval(s)[0], 3 * s * s - 2 * s * s * s, 1e-14) << s;
    EXPECT_NEAR(hat.eval(2.0 - s)[0], 3 * s * s - 2 * s * s * s, 1e-14) << s;
    if (s > 0) EXPECT_NEAR(hat.eval(s)[2], 6.0 - 12.0 * s, 1e-13) << s;  // at t_0: at rest, 0
  }
}

TEST(ObstaclePath, PassesItsWaypointsAndRestsAtBothEnds) {
  for (int a = 0; a < 2; ++a) {
    const PathCoordinate Q(kPath, a);
    for (const Waypoint& w : kPath) EXPECT_NEAR(Q.eval(w.t)[0], w.p[a], 1e-13) << w.t;
    // Waits at the first waypoint, stays at the last, slope 0 at both.
    for (double t : {-1.0, 0.0, 0.5}) EXPECT_EQ(Q.eval(t)[0], kPath.front().p[a]);
    for (double t : {4.2, 5.0, 100.0}) EXPECT_NEAR(Q.eval(t)[0], kPath.back().p[a], 1e-13);
    EXPECT_NEAR(Q.eval(0.5 + 1e-9)[1], 0.0, 1e-7);
    EXPECT_NEAR(Q.eval(4.2 - 1e-9)[1], 0.0, 1e-7);
    EXPECT_EQ(path_point(kPath, 2.5)[a], Q.eval(2.5)[0]);
  }
}

// Where two pieces meet, value, slope and curvature agree from both sides (to the size of a
// 1e-9 step); inside a piece the derivatives equal central finite differences.
TEST(ObstaclePath, IsTwiceDifferentiableAndItsDerivativesAreExact) {
  for (int a = 0; a < 2; ++a) {
    const PathCoordinate Q(kPath, a);
    for (std::size_t k = 1; k + 1 < kPath.size(); ++k) {
      const auto left = Q.eval(kPath[k].t - 1e-9), right = Q.eval(kPath[k].t + 1e-9);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(left[d], right[d], 1e-6) << "waypoint " << k << ", derivative " << d;
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.5, 4.2);
    for (int n = 0; n < 50; ++n) {
      const double t = u(rng), e = 1e-6;
      const auto v = Q.eval(t), lo = Q.eval(t - e), hi = Q.eval(t + e);
      EXPECT_NEAR(v[1], (hi[0] - lo[0]) / (2 * e), 1e-7) << t;
      EXPECT_NEAR(v[2], (hi[1] - lo[1]) / (2 * e), 1e-6) << t;
    }
  }
}

// range() over an interval holds every sample of it, and its ends are reached (up to the
// samples' spacing).
TEST(ObstaclePath, RangeIsExact) {
  const PathCoordinate Q(kPath, 1);
  for (const auto [t0, t1] : {std::pair{0.0, 5.0}, {0.7, 1.9}, {2.6, 2.9}, {1.0, 1.0}, {4.0, 6.0}}) {
    const auto r = Q.range(t0, t1);
    double lo = 1e300, hi = -1e300;
    for (int m = 0; m <= 20000; ++m) {
      const double v = Q.eval(t0 + (t1 - t0) * m / 20000.0)[0];
      EXPECT_GE(v, r[0] - 1e-12);
      EXPECT_LE(v, r[1] + 1e-12);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    EXPECT_NEAR(r[0], lo, 1e-6) << t0 << ".." << t1;
    EXPECT_NEAR(r[1], hi, 1e-6) << t0 << ".." << t1;
  }
}

// One robot going 6 m along x, and `obstacle` (an obstacles entry), line 5 of the file.
std::string path_scene(const std::string& obstacle) {
  return "scenario: s\nsteps: 10\n"
         "robots:\n"
         "  - {name: a, radius: 0.3, mass: 1, mu: 0.2, force_max: 5, start: {x: -3, y: 0}, target: {x: 3}}\n"
         "obstacles:\n"
         "  - " + obstacle + "\n";
}

TEST(ObstaclePathScene, APathIsReadAndItsPairsAvoid) {
  const Scene s = parse_scene(
      path_scene("{name: sentry, disk: {radius: 0.4, path: [{t: 0.5, x: 0, y: -1.5}, {t: 1, x: 0, y: 1.5}]}}"),
      "s.yaml");
  ASSERT_EQ(s.obstacles.size(), 1u);
  const Obstacle& ob = s.obstacles[0];
  ASSERT_EQ(ob.path.size(), 2u);
  EXPECT_EQ(ob.path[1].t, 1.0);
  EXPECT_EQ(ob.path[1].p[1], 1.5);
  EXPECT_TRUE(ob.moves());
  EXPECT_EQ(ob.from[1], -1.5) << "at t = 0 it waits at its first waypoint";
  EXPECT_EQ(obstacle_centre(ob, 0.0)[1], -1.5);
  EXPECT_EQ(s.obstacle_pairs[0].mode, PairMode::kAvoid);
}

TEST(ObstaclePathScene, BadPathsAreErrorsNamingFileLineAndKey) {
  const std::pair<std::string, std::string> cases[] = {
      {"{name: p, disk: {radius: 0.4, path: [{t: 0, x: 0, y: 2}]}}",
       "s.yaml:6: key 'obstacles[0].disk.path': must be a sequence of at least two waypoints "
       "{t, x, y} (got 1)"},
      {"{name: p, disk: {radius: 0.4, path: [{t: 1, x: 0, y: 2}, {t: 1, x: 0, y: 3}]}}",
       "s.yaml:6: key 'obstacles[0].disk.path[1].t': waypoint times must increase (got 1 after 1)"},
      {"{name: p, disk: {radius: 0.4, path: [{t: 0, x: 0, y: 2}, {x: 1, y: 3}]}}",
       "s.yaml:6: key 'obstacles[0].disk.path[1].t': is required but missing"},
      {"{name: p, disk: {radius: 0.4, path: [{t: -1, x: 0, y: 2}, {t: 1, x: 1, y: 3}]}}",
       "s.yaml:6: key 'obstacles[0].disk.path[0].t': must be >= 0 (got -1)"},
      {"{name: p, disk: {radius: 0.4, x: 0, path: [{t: 0, x: 0, y: 2}, {t: 1, x: 1, y: 3}]}}",
       "s.yaml:6: key 'obstacles[0].disk.x': a disk that follows a path starts at its first "
       "waypoint and moves along it: give either 'path' or 'x', 'y' (and 'vx', 'vy'), not both"},
      {"{name: p, disk: {radius: 0.4, path: [{t: 0, x: -3, y: 0.5}, {t: 1, x: 1, y: 3}]}}",
       "s.yaml:4: key 'robots[0].start': robot 'a' and obstacle 'p' overlap at the start: the "
       "centre is 0.5 from the obstacle's centre, less than R + R_obstacle = 0.7"},
      {"{name: p, disk: {radius: 0.4, path: [{t: 0, x: -3, y: 0.705}, {t: 1, x: 1, y: 3}]}}",
       "s.yaml:4: key 'robots[0].start': robot 'a' and obstacle 'p' (an avoid pair) start too "
       "close: the centre is 0.705 from the obstacle's centre, less than R + R_obstacle + "
       "safe_distance = 0.71 (move it, lower the obstacle's safe_distance or use mode contact)"},
      {"{name: p, disk: {radius: 0.4, path: [{t: 0, x: 0, y: 2}, {t: 1, x: 1, y: 3}]}, mode: contact}",
       "s.yaml:6: key 'obstacles[0].mode': a moving obstacle cannot be a contact obstacle (it "
       "could push, which disco does not model): use mode avoid"},
  };
  for (const auto& [entry, message] : cases)
    EXPECT_EQ(test_support::scene_error_of(path_scene(entry)), message) << entry;
}

}  // namespace
}  // namespace disco
