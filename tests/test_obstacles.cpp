// Obstacles (core/model/obstacles.h): the scene file's `obstacles`, a wall's nearest point
// as MPCC rows, the adaptive plan's windows, and solved scenes checked from their solution
// files against geometry computed here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/config/settings.h"
#include "core/model/gap.h"
#include "core/model/obstacle_path.h"
#include "core/model/obstacles.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "core/model/solution.h"
#include "core/util/errors.h"
#include "tests/test_support_messages.h"
#include "search/guess.h"
#include "search/solve_scene.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

// One robot (radius 0.5) at the origin with a target, one object at (3, 0), and `obstacles`.
std::string scene_text(const std::string& obstacles) {
  return "scenario: s\nsteps: 10\n"
         "robots:\n"
         "  - {name: a, radius: 0.5, mass: 1, mu: 0.2, force_max: 5, start: {x: 0, y: 0}, "
         "target: {x: 1}}\n"
         "objects:\n"
         "  - {name: coin, radius: 0.3, mass: 0.5, mu: 0.3, start: {x: 3, y: 0}}\n"
         "obstacles:\n" + obstacles;
}

using test_support::scene_error_of;
std::string error_of(const std::string& text) { return scene_error_of(text); }

TEST(ObstacleScene, DisksWallsAndTheirPairsAreRead) {
  const Scene s = parse_scene(
      scene_text("  - {name: post, disk: {x: 0, y: 3, radius: 0.4}, mode: contact, mu: 0.5}\n"
                 "  - {name: wall, wall: {from: [-2, -2], to: [2, -2], thickness: 0.2}}\n"
                 "  - {name: runner, disk: {x: 5, y: 5, radius: 0.2, vx: -1, vy: 0}, safe_distance: 0.1}\n"),
      "s.yaml");
  ASSERT_EQ(s.obstacles.size(), 3u);
  EXPECT_EQ(s.obstacles[0].shape, ObstacleShape::kDisk);
  EXPECT_EQ(s.obstacles[0].radius, 0.4);
  EXPECT_FALSE(s.obstacles[0].moves());
  EXPECT_EQ(s.obstacles[1].shape, ObstacleShape::kWall);
  EXPECT_EQ(s.obstacles[1].radius, 0.1) << "a wall's radius is half its thickness";
  EXPECT_EQ(s.obstacles[1].to[0], 2.0);
  EXPECT_TRUE(s.obstacles[2].moves());
  EXPECT_EQ(s.obstacles[2].velocity[0], -1.0);
  // A pair per (disk, obstacle), in obstacle order.
  ASSERT_EQ(s.obstacle_pairs.size(), 6u);
  const Pair& robot_post = s.obstacle_pairs[0];
  EXPECT_EQ(robot_post.i, 0);
  EXPECT_EQ(robot_post.j, 0);
  EXPECT_EQ(robot_post.mode, PairMode::kContact) << "the obstacle's own mode";
  EXPECT_EQ(robot_post.mu, 0.5);
  EXPECT_EQ(s.obstacle_pairs[2].mode, PairMode::kAvoid) << "robot-wall: the pairs default";
  EXPECT_EQ(s.obstacle_pairs[3].mode, PairMode::kContact) << "object-wall: contact, as object pairs";
  EXPECT_EQ(s.obstacle_pairs[5].mode, PairMode::kAvoid) << "a moving obstacle: avoid";
  EXPECT_EQ(s.obstacle_pairs[5].safe_distance, 0.1);
}

TEST(ObstacleScene, BadObstaclesAreErrorsNamingFileLineAndKey) {
  // (obstacle entry, message)
  const std::pair<std::string, std::string> cases[] = {
      {"{name: w, wall: {from: [1, 2], to: [1, 2]}}",
       "s.yaml:8: key 'obstacles[0].wall.to': a wall needs two distinct ends (got a wall of "
       "length 0); for a round post use 'disk'"},
      {"{name: w, wall: {from: [-1, 0.4], to: [1, 0.4], thickness: 0.2}}",
       "s.yaml:4: key 'robots[0].start': robot 'a' and obstacle 'w' overlap at the start: the "
       "centre is 0.4 from the obstacle's centre line, less than R + R_obstacle = 0.6"},
      {"{name: p, disk: {x: 0, y: 0.605, radius: 0.1}}",
       "s.yaml:4: key 'robots[0].start': robot 'a' and obstacle 'p' (an avoid pair) start too "
       "close: the centre is 0.605 from the obstacle's centre, less than R + R_obstacle + "
       "safe_distance = 0.61 (move it, lower the obstacle's safe_distance or use mode contact)"},
      {"{name: p, disk: {x: 0, y: 3, radius: 0.1}, wall: {from: [0, 0], to: [1, 1]}}",
       "s.yaml:8: key 'obstacles[0]': an obstacle is either a 'disk' or a 'wall': give exactly "
       "one of them"},
      {"{name: p, disk: {x: 0, y: 3, radius: 0.1, vy: 1}, mode: contact}",
       "s.yaml:8: key 'obstacles[0].mode': a moving obstacle cannot be a contact obstacle (it "
       "could push, which disco does not model): use mode avoid"},
      {"{name: coin, disk: {x: 0, y: 3, radius: 0.1}}",
       "s.yaml:8: key 'obstacles[0].name': duplicate name 'coin' (already used by a robot or "
       "object)"},
      {"{name: p, disk: {x: 0, y: 3, radius: 0}}",
       "s.yaml:8: key 'obstacles[0].disk.radius': must be > 0 (got 0)"},
  };
  for (const auto& [entry, message] : cases)
    EXPECT_EQ(error_of(scene_text("  - " + entry + "\n")), message) << entry;
}

// A wall from (0, 0) to (2, 0), thickness 0.2, and one robot of radius 0.5 (3 steps).
Scene wall_scene() {
  Robot a = model_test::make_robot("a", 0.5, 1.0, 0.2, 5.0, 1.0, 2.0, 16);
  a.target.lower[kX] = a.target.upper[kX] = 1.0;
  Scene s = model_test::make_scene("wall", 3, {a});
  model_test::add_obstacle(s, model_test::wall("w", {0.0, 0.0}, {2.0, 0.0}, 0.1), PairMode::kContact);
  return s;
}

// The nearest point is found by its rows: at the exact projection (inside the wall and past
// either end) every row of the gap family is 0 and both complementarity products vanish, and
// the gap equals the distance to the capsule found by brute force.
TEST(WallProjection, TheExactNearestPointSatisfiesItsRowsInsideAndPastTheEnds) {
  const RobotProblem rp(wall_scene(), {Family::kGap});
  const Layout& L = rp.layout();
  const auto& P = rp.program();
  ASSERT_EQ(L.num_pairs(), 1);
  ASSERT_TRUE(L.is_wall_pair(0));
  const double R = rp.units().length;  // model units: positions below are in metres
  const std::vector<std::array<double, 2>> centres = {{1.2, 0.9}, {-0.7, 0.6}, {2.8, -0.9}};
  Vector z = Vector::Zero(P.num_variables());
  z[L.horizon_index()] = 1.0;
  for (int t = 1; t <= 3; ++t) {
    z[L.state_index(0, t, kX)] = centres[t - 1][0] / R;
    z[L.state_index(0, t, kY)] = centres[t - 1][1] / R;
  }
  complete_obstacle_unknowns(L, z);
  for (int t = 1; t <= 3; ++t) z[L.gap_index(0, t)] = centre_gap(L, z, 0, t);
  EXPECT_DOUBLE_EQ(z[L.wall_parameter_index(0, 2)], 0.0) << "past the first end";
  EXPECT_DOUBLE_EQ(z[L.wall_parameter_index(0, 3)], 1.0) << "past the second end";
  EXPECT_GT(z[L.wall_low_index(0, 2)], 0.1) << "the end's multiplier is active";
  Vector c(P.num_constraints());
  ASSERT_TRUE(P.constraints(z, c));
  for (int r = 0; r < P.num_constraints(); ++r) {
    if (P.constraint_lower()[r] == P.constraint_upper()[r]) {
      EXPECT_NEAR(c[r], P.constraint_lower()[r], 1e-12) << "row " << r;
    }
  }
  for (const auto& pr : P.complementarity_pairs())
    EXPECT_NEAR(side_value(pr.g, z, c) * side_value(pr.h, z, c), 0.0, 1e-12);
  for (int t = 1; t <= 3; ++t) {
    double nearest = kInf;  // the capsule's core by brute force
    for (int k = 0; k <= 200000; ++k) {
      const double x = 2.0 * k / 200000;
      nearest = std::min(nearest, std::hypot(centres[t - 1][0] - x, centres[t - 1][1]));
    }
    EXPECT_NEAR(z[L.gap_index(0, t)] * R, nearest - 0.5 - 0.1, 1e-9) << "state " << t;
  }
}

TEST(ObstaclePlan, OnlyObstaclesWithinReachGetAWindow) {
  Scene s = wall_scene();
  model_test::add_obstacle(s, model_test::post("far", {40.0, 40.0}, 1.0), PairMode::kAvoid);
  model_test::add_obstacle(s, model_test::post("runner", {20.0, 2.0}, 0.5, {-20.0, 0.0}), PairMode::kAvoid);
  // T_max 1 s: the robot (5 N, 1 kg) moves well under 5 m; the runner gets to it by then.
  const RobotProblem rp(s, ModelOptions{true, 1.0});
  const auto& w = rp.plan().pairs;
  ASSERT_EQ(w.size(), 3u);
  EXPECT_FALSE(w[0].empty()) << "the wall is within reach";
  EXPECT_TRUE(w[1].empty()) << "a post 55 m away is not";
  EXPECT_FALSE(w[2].empty()) << "the runner comes within reach";
  EXPECT_GT(w[2].first, 1) << "but not at once: it starts 19 m away";
}

// The solution file's disk at state k against obstacle `ob` at time t_k: the centre's
// distance to the obstacle's core, computed here from the file's numbers.
// The waypoints of a solution file's obstacle.
std::vector<Waypoint> file_path(const nlohmann::json& ob) {
  std::vector<Waypoint> path;
  for (const auto& w : ob["path"]) path.push_back({w["t"], {w["x"], w["y"]}});
  return path;
}

// A disk on waypoints is where its path (core/model/obstacle_path.h, tested on its own in
// tests/test_obstacle_path.cpp) through the file's waypoints puts it.
double core_distance(const nlohmann::json& rob, const nlohmann::json& ob, int k, double t) {
  const double x = rob["x"][k], y = rob["y"][k];
  if (ob["shape"] == "disk" && ob.contains("path")) {
    const auto c = path_point(file_path(ob), t);
    return std::hypot(x - c[0], y - c[1]);
  }
  if (ob["shape"] == "disk") {
    const double cx = double(ob["centre"][0]) + t * double(ob["velocity"][0]);
    const double cy = double(ob["centre"][1]) + t * double(ob["velocity"][1]);
    return std::hypot(x - cx, y - cy);
  }
  const double ax = ob["from"][0], ay = ob["from"][1], bx = ob["to"][0], by = ob["to"][1];
  const double s = std::clamp(((x - ax) * (bx - ax) + (y - ay) * (by - ay)) /
                                  ((bx - ax) * (bx - ax) + (by - ay) * (by - ay)),
                              0.0, 1.0);
  return std::hypot(x - ax - s * (bx - ax), y - ay - s * (by - ay));
}

nlohmann::json solve_file(const std::string& name) {
  const Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + name);
  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  EXPECT_TRUE(run.solved()) << to_string(run.info.status);
  if (!run.solved()) return {};
  return solution_json(*run.problem, run.z, run.info);
}

// Every state keeps the avoid clearance from every obstacle (R + R_o + d_s, less the
// certificate's tolerance); between two states (moving straight, sampled), computed from the
// file alone, no point overlaps a wall, and none comes nearer a disk obstacle's centre than
// sqrt(0.19) (R + R_o): what the swept rows promise (core/model/swept.h: a disk goes round a
// post, never over it, but may cut into it between the states; the solution file reports
// that as swept_gap).
void expect_clear(const nlohmann::json& sol) {
  const double h = sol["h"];
  for (const auto& rob : sol["robots"])
    for (const auto& ob : sol["obstacles"]) {
      const double touch = double(rob["radius"]) + double(ob["radius"]);
      const int n = static_cast<int>(rob["x"].size());
      for (int k = 0; k < n; ++k) {
        EXPECT_GE(core_distance(rob, ob, k, k * h), touch + 0.01 - 1e-6)
            << rob["name"] << " and " << ob["name"] << " at state " << k;
        if (k + 1 == n) continue;
        for (int m = 1; m < 20; ++m) {
          const double f = m / 20.0;
          nlohmann::json between = {{"x", {double(rob["x"][k]) * (1 - f) + double(rob["x"][k + 1]) * f}},
                                    {"y", {double(rob["y"][k]) * (1 - f) + double(rob["y"][k + 1]) * f}}};
          const double promised = ob["shape"] == "disk" ? std::sqrt(0.19) * touch : touch;
          EXPECT_GE(core_distance(between, ob, 0, (k + f) * h), promised - 1e-6)
              << rob["name"] << " and " << ob["name"] << " between states " << k << " and " << k + 1;
        }
      }
    }
}

// Between two states (core/model/obstacles.h): a straight move through a wall has distance
// 0; one past a wall's end, the distance to the end; a disk crossing a moving disk's way
// behind it, the least distance of the relative motion.
TEST(SweptDistance, FindsWhatTheStatesMiss) {
  const Obstacle w = model_test::wall("w", {0.0, -1.0}, {0.0, 1.0});
  EXPECT_EQ(swept_distance(w, {-1.0, 0.5}, {1.0, 0.3}, 0.0, 0.1), 0.0) << "through the wall";
  EXPECT_NEAR(swept_distance(w, {-1.0, 2.0}, {1.0, 2.0}, 0.0, 0.1), 1.0, 1e-15) << "past its end";
  EXPECT_NEAR(swept_distance(w, {0.5, -3.0}, {0.5, 3.0}, 0.0, 0.1), 0.5, 1e-15) << "along it";
  // A post moving up at 1 m/s from (0, -1); a disk going right from (-1, 0) to (1, 0) in 1 s:
  // relative motion from (-1, 1) to (1, 0), nearest the origin at (-0.2, 0.6)... computed:
  const Obstacle runner = model_test::post("r", {0.0, -1.0}, 0.1, {0.0, 1.0});
  const double ex = -1.0 + 2.0 * 0.6, ey = 1.0 - 0.6;  // s = 0.6 minimises |(-1 + 2s, 1 - s)|
  EXPECT_NEAR(swept_distance(runner, {-1.0, 0.0}, {1.0, 0.0}, 0.0, 1.0), std::hypot(ex, ey), 1e-15);
}

// A robot boxed in by four thin walls, its target outside. The pair rows hold at the
// states only, so without the swept rows (core/model/swept.h) it jumped a wall in one step
// at 20 steps and the box was "solved". Now no step crosses a wall, at any N_t: at 5 steps
// a step may be 1.3 m long (h = 0.43 s at the first horizon, 3 m/s), far more than a
// wall's 0.35 m clearance.
TEST(ObstacleSolve, WallsThatCloseTheOnlyWayMakeTheSceneInfeasibleAtAnySteps) {
  for (int steps : {5, 40}) {
    Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/stress/walled_in.yaml");
    scene.steps = steps;
    const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
    EXPECT_EQ(run.info.status, MpccStatus::kInfeasible) << steps << " steps: " << to_string(run.info.status);
  }
}

// Paper B1's crossing with a post at the centre, at 5 steps (a step is up to ~2.5 m long,
// more than the post's clearance R = R_i + R_o = 1.1 m). Without swept rows for disk
// obstacles a robot stepped through the post's centre (swept_gap -1.1 m: -R). The row
// (core/model/swept.h) keeps every straight step off the centre: with both ends at least R
// away, by at least sqrt(1 - 0.9^2) R = 0.436 R, computed here from the file.
TEST(ObstacleSolve, AFewLongStepsGoRoundAPostNotOverIt) {
  Scene scene = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/post_crossing.yaml");
  scene.steps = 5;
  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  ASSERT_TRUE(run.solved()) << to_string(run.info.status);
  const nlohmann::json sol = solution_json(*run.problem, run.z, run.info);
  const auto& post = sol["obstacles"][0];
  ASSERT_EQ(post["shape"], "disk");
  const double cx = post["centre"][0], cy = post["centre"][1];
  for (const auto& rob : sol["robots"]) {
    const double R = double(rob["radius"]) + double(post["radius"]);
    for (std::size_t k = 0; k + 1 < rob["x"].size(); ++k) {
      const double ax = double(rob["x"][k]) - cx, ay = double(rob["y"][k]) - cy;
      const double dx = double(rob["x"][k + 1]) - double(rob["x"][k]), dy = double(rob["y"][k + 1]) - double(rob["y"][k]);
      const double dd = dx * dx + dy * dy;  // 0 where the robot rests
      const double s = dd > 0 ? std::clamp(-(ax * dx + ay * dy) / dd, 0.0, 1.0) : 0.0;
      EXPECT_GE(std::hypot(ax + s * dx, ay + s * dy), std::sqrt(1.0 - 0.81) * R - 1e-6)
          << rob["name"] << ", step " << k;
    }
  }
}

double way_length(const Way& way) {
  double L = 0.0;
  for (std::size_t k = 1; k < way.size(); ++k) L += std::hypot(way[k][0] - way[k - 1][0], way[k][1] - way[k - 1][1]);
  return L;
}

// The guesses' way around fixed obstacles (search/guess.h): through the doorway's door with
// every leg clear of both walls; around a post within 1 % of the shortest way (a tangent,
// an arc, a tangent: computed here); straight where nothing is in the way or no way leads
// out of a closed box.
TEST(WayAroundObstacles, GoesThroughTheDoorAroundAPostAndStraightWhenClosedIn) {
  const Scene door = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/doorway.yaml");
  const Way way = way_around_obstacles(door, 0);
  ASSERT_GE(way.size(), 3u) << "the straight move crosses the upper wall";
  EXPECT_EQ(way.front(), (std::array<double, 2>{-2.0, 2.0}));
  EXPECT_EQ(way.back(), (std::array<double, 2>{2.0, 1.5}));
  const double need = 0.3 + 0.05 + 0.01;  // R + half the thickness + d_s
  for (std::size_t k = 1; k < way.size(); ++k) {
    for (const Obstacle& ob : door.obstacles)
      EXPECT_GE(swept_distance(ob, way[k - 1], way[k], 0.0, 0.0), need) << ob.name << ", leg " << k;
    if (way[k - 1][0] < 0.0 && way[k][0] >= 0.0) {
      const double f = -way[k - 1][0] / (way[k][0] - way[k - 1][0]);
      EXPECT_LT(std::abs(way[k - 1][1] + f * (way[k][1] - way[k - 1][1])), 0.5 - need) << "in the door";
    }
  }

  Robot a = model_test::make_robot("a", 0.4, 1.0, 0.2, 5.0, -3.0, 0.0);
  a.target.lower[kX] = a.target.upper[kX] = 3.0;
  a.target.lower[kY] = a.target.upper[kY] = 0.0;
  Scene post = model_test::make_scene("post", 10, {a});
  EXPECT_EQ(way_around_obstacles(post, 0).size(), 2u) << "no obstacle: straight";
  model_test::add_obstacle(post, model_test::post("p", {0.0, 0.0}, 0.09), PairMode::kAvoid);
  const double c = 0.4 + 0.09 + 0.01, d = 3.0;
  const double shortest = 2.0 * std::sqrt(d * d - c * c) + c * (std::numbers::pi - 2.0 * std::acos(c / d));
  const Way round = way_around_obstacles(post, 0);
  EXPECT_GE(way_length(round), shortest * (1 - 1e-12));
  EXPECT_LE(way_length(round), shortest * 1.01);

  const Scene box = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/stress/walled_in.yaml");
  EXPECT_EQ(way_around_obstacles(box, 0).size(), 2u) << "no way out: straight";
}

TEST(ObstacleSolve, DoorwayIsPassedThroughTheDoor) {
  const nlohmann::json sol = solve_file("doorway.yaml");
  ASSERT_FALSE(sol.is_null());
  expect_clear(sol);
  // The straight line crosses the wall at y = 1.75; the path crosses x = 0 in the door
  // (|y| < 0.5 - 0.05 - 0.3 between the walls' ends).
  const auto& r = sol["robots"][0];
  bool crossed = false;
  for (std::size_t k = 0; k + 1 < r["x"].size(); ++k) {
    const double x0 = r["x"][k], x1 = r["x"][k + 1];
    if (x0 < 0 && x1 >= 0) {
      const double y = double(r["y"][k]) + (double(r["y"][k + 1]) - double(r["y"][k])) * (-x0) / (x1 - x0);
      EXPECT_LT(std::abs(y), 0.15) << "crosses x = 0 at y = " << y;
      crossed = true;
    }
  }
  EXPECT_TRUE(crossed);
  EXPECT_GT(double(sol["T_f"]), double(sol["lower_bound"]) * 1.05) << "the detour costs time";
}

TEST(ObstacleSolve, ARobotCrossingAMovingObstacleNeverTouchesIt) {
  const nlohmann::json sol = solve_file("moving_crossing.yaml");
  ASSERT_FALSE(sol.is_null());
  expect_clear(sol);  // against the obstacle where it is at each t_k
  // Alone the robot would arrive at the obstacle's line when it passes: the answer waits
  // or goes round, so it takes longer than the robot's own lower bound.
  EXPECT_GT(double(sol["T_f"]), double(sol["lower_bound"]) * 1.02);
  const auto& r = sol["robots"][0];
  EXPECT_LT(double(r["x"][0]), 0.0);
  EXPECT_GT(double(r["x"].back()), 0.0) << "it crossed the obstacle's path";
}

// configs/scenarios/moving_path.yaml: a sentry patrols x = 0 between y = -1.5 and 1.5 on
// waypoints and crosses the robot's line when the robot alone would. The file's centres of
// the sentry at the states are its path's, and the robot keeps clear of it (expect_clear).
TEST(ObstacleSolve, ARobotCrossingASentryOnWaypointsKeepsClearOfIt) {
  const nlohmann::json sol = solve_file("moving_path.yaml");
  ASSERT_FALSE(sol.is_null());
  const auto& ob = sol["obstacles"][0];
  ASSERT_EQ(ob["path"].size(), 5u);
  const std::vector<Waypoint> path = file_path(ob);
  const double h = sol["h"];
  for (std::size_t k = 0; k < ob["x"].size(); ++k) {
    EXPECT_NEAR(double(ob["x"][k]), path_point(path, k * h)[0], 1e-12) << k;
    EXPECT_NEAR(double(ob["y"][k]), path_point(path, k * h)[1], 1e-12) << k;
  }
  expect_clear(sol);
  EXPECT_GT(double(sol["T_f"]), double(sol["lower_bound"]) * 1.02);
  const auto& r = sol["robots"][0];
  EXPECT_LT(double(r["x"][0]), 0.0);
  EXPECT_GT(double(r["x"].back()), 0.0) << "it crossed the sentry's way";
}

}  // namespace
}  // namespace disco
