// The homotopy class of a trajectory (search/homotopy.h): turn, order and touch per pair, on
// paths made here; and the detour starts that enumerate the side patterns (search/start.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <set>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "search/guess.h"
#include "search/homotopy.h"
#include "test_support_model.h"

namespace disco {
namespace {

using model_test::make_robot;
using model_test::make_scene;

// Robot paths of N steps from a function tau -> (x, y).
template <class F>
std::vector<Pose> path(int N, F f) {
  std::vector<Pose> p;
  for (int t = 0; t <= N; ++t) {
    const auto [x, y] = f(static_cast<double>(t) / N);
    p.push_back({x, y, 0.0});
  }
  return p;
}

TEST(Homotopy, CrossingRobotsTurnTheWayTheirOrderSaysAndTheFirstIsNamed) {
  // a crosses from west to east at constant speed; b from south to north, starting later:
  // a is through the crossing first, so b - a turns clockwise.
  const int N = 40;
  const Scene scene = make_scene("cross", N, {make_robot("a", 0.3, 1, 0.2, 5, -2, 0),
                                              make_robot("b", 0.3, 1, 0.2, 5, 0, -2)},
                                 PairMode::kAvoid, 0.0, 0.0);
  auto a = path(N, [](double t) { return std::pair{-2.0 + 4.0 * t, 0.0}; });
  auto late = [](double t) { return std::pair{0.0, -2.0 + 4.0 * std::clamp((t - 0.3) / 0.7, 0.0, 1.0)}; };
  HomotopyClass c = homotopy_class(scene, {a, path(N, late)});
  ASSERT_EQ(c.pairs.size(), 1u);
  EXPECT_EQ(c.pairs[0].turn, "cw");
  EXPECT_EQ(c.pairs[0].first, 0);
  EXPECT_FALSE(c.pairs[0].touch);
  EXPECT_TRUE(c.decided());
  EXPECT_EQ(c.key(scene), "a/b cw, a first");
  // b goes first instead (a starts late): the other turn, b first.
  auto a_late = path(N, [](double t) { return std::pair{-2.0 + 4.0 * std::clamp((t - 0.3) / 0.7, 0.0, 1.0), 0.0}; });
  auto b = path(N, [](double t) { return std::pair{0.0, -2.0 + 4.0 * t}; });
  c = homotopy_class(scene, {a_late, b});
  EXPECT_EQ(c.key(scene), "a/b ccw, b first");
  // Together through the crossing: they run through each other; the paths decide nothing.
  c = homotopy_class(scene, {a, b});
  EXPECT_EQ(c.pairs[0].turn, "?");
  EXPECT_FALSE(c.decided());
  // Far apart: no pair within reach, the empty class.
  auto far = path(N, [](double t) { return std::pair{8.0, -2.0 + 4.0 * t}; });
  EXPECT_TRUE(homotopy_class(scene, {a, far}).pairs.empty());
}

TEST(Homotopy, AContactPairThatReachesItsClearanceTouchesAnAvoidPairNever) {
  const int N = 40;
  auto still = path(N, [](double) { return std::pair{0.0, 0.0}; });
  auto by = path(N, [](double t) { return std::pair{-2.0 + 4.0 * t, 0.6}; });  // 0.6 = R + R
  for (PairMode mode : {PairMode::kContact, PairMode::kAvoid}) {
    const Scene scene = make_scene("rub", N, {make_robot("a", 0.3, 1, 0.2, 5, 0, 0),
                                              make_robot("b", 0.3, 1, 0.2, 5, -2, 0.6)},
                                   mode, 0.3, 0.0);
    const HomotopyClass c = homotopy_class(scene, {still, by});
    ASSERT_EQ(c.pairs.size(), 1u);
    EXPECT_EQ(c.pairs[0].turn, "cw");  // b passes a's north side going east
    EXPECT_EQ(c.pairs[0].touch, mode == PairMode::kContact);
    EXPECT_EQ(c.pairs[0].first, 1);  // a does not move: b is farther along its path
  }
}

TEST(Homotopy, TheTwoDetoursOfASwapAreOppositeClassesAndStraightDecidesNone) {
  const Scene scene = load_scene(
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/two_robots_swap_avoid.yaml", {"steps=20"});
  const HomotopyClass left = homotopy_class(scene, detour_paths(scene, +1));
  const HomotopyClass right = homotopy_class(scene, detour_paths(scene, -1));
  ASSERT_EQ(left.pairs.size(), 1u);
  ASSERT_EQ(right.pairs.size(), 1u);
  EXPECT_TRUE(left.decided() && right.decided());
  EXPECT_NE(left.pairs[0].turn, right.pairs[0].turn);
  EXPECT_NE(left.pairs[0].turn, "none");
  EXPECT_NE(right.pairs[0].turn, "none");
  StartSpec straight;  // the straight guess: the robots run through each other
  EXPECT_EQ(homotopy_class(scene, guess_paths(scene, straight)).pairs[0].turn, "?");
  const nlohmann::json j = left.to_json(scene);
  EXPECT_EQ(j["key"], left.key(scene));
  EXPECT_EQ(j["pairs"][0]["pair"], "left/right");
}

TEST(Homotopy, DetourStartsEnumerateEverySidePatternOfAFewConflictingPairs) {
  // Three robots on a circle, each crossing to the opposite point through the centre (their
  // straight paths conflict pairwise).
  std::vector<Robot> robots;
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 3.0;
    robots.push_back(make_robot(std::string(1, char('a' + i)), 0.3, 1, 0.2, 5, 1.5 * std::cos(a),
                                1.5 * std::sin(a)));
    robots[i].target.lower[kX] = robots[i].target.upper[kX] = -1.5 * std::cos(a);
    robots[i].target.lower[kY] = robots[i].target.upper[kY] = -1.5 * std::sin(a);
  }
  const Scene scene = make_scene("triangle", 20, robots, PairMode::kAvoid, 0.0, 0.01);
  const int k = static_cast<int>(conflicts(scene).size());
  ASSERT_GE(k, 2);
  ASSERT_LE(k, kEnumeratedPairs);
  const Settings settings = Settings::load(default_settings_path());
  std::set<std::uint64_t> patterns;
  std::set<std::string> classes;
  int detours = 0;
  for (int index = 1; detours < (1 << k); ++index) {
    const StartSpec s = make_start(scene, 1, index, reduction_settings(settings),
                                   elastic_settings(settings));
    if (s.guess != GuessKind::kDetour) continue;
    if (detours == 0) {  // all left first, then all right
      EXPECT_EQ(s.detour_side, +1);
    }
    if (detours == 1) {
      EXPECT_EQ(s.detour_side, -1);
    }
    ++detours;
    patterns.insert(s.detour_pattern);
    classes.insert(homotopy_class(scene, guess_paths(scene, s)).key(scene));
  }
  EXPECT_EQ(patterns.size(), std::size_t{1} << k) << "every pattern once in the first 2^k";
  EXPECT_GE(classes.size(), 2u);
  // Paper A3 has more conflicting pairs than are enumerated: its mixed patterns are drawn,
  // and the first two detours are still all left and all right.
  const Scene a3 = load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/paper/A3.yaml", {});
  EXPECT_GT(static_cast<int>(conflicts(a3).size()), kEnumeratedPairs);
  const auto base = reduction_settings(settings);
  EXPECT_EQ(make_start(a3, 1, 1, base, elastic_settings(settings)).detour_side, +1);
  EXPECT_EQ(make_start(a3, 1, 2, base, elastic_settings(settings)).detour_side, -1);
}

}  // namespace
}  // namespace disco
