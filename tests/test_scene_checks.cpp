// Scenes that ask for nothing, or for a target out of reach for a reason the scene shows, are
// rejected before any solve (core/model/reachability.h, called by core/model/scene_yaml.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "core/model/reachability.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"

namespace disco {
namespace {

// One robot (K 16, mu 0.2) with the given extra robot keys; a second robot far away, with a
// target, in the given pair mode.
std::string scene_text(const std::string& robot_keys, const std::string& mode = "avoid",
                       const std::string& second_target = "{x: 20, y: 20}") {
  return "scenario: s\nsteps: 10\n"
         "defaults: {radius: 0.5, mass: 1.0, mu: 0.2, force_max: 5.0, K: 16}\n"
         "robots:\n"
         "  - name: a\n" + robot_keys +
         "  - name: b\n"
         "    start: {x: 20, y: 0}\n"
         "    target: " + second_target + "\n"
         "pairs: {mode: " + mode + "}\n";
}

// The InputError message for `text`, or "" if it loads.
std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "s.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneChecks, ASceneWithNoTargetAtAllIsAnError) {
  const std::string e = error_of(
      "scenario: s\nsteps: 10\n"
      "robots:\n"
      "  - {name: a, radius: 0.5, mass: 1, mu: 0.2, force_max: 5, start: {x: 0, y: 0}}\n"
      "  - {name: b, radius: 0.5, mass: 1, mu: 0.2, force_max: 5, start: {x: 3, y: 0}}\n");
  EXPECT_EQ(e, "s.yaml:4: key 'robots': no robot has a target (every target is missing or "
               "unbounded), so there is nothing to reach and T_f would be 0; give at least one "
               "robot a target") << e;
  // One bound on one robot is a target.
  EXPECT_EQ(error_of(scene_text("    start: {x: 0, y: 0}\n", "avoid", "{vx: 0}")), "");
}

TEST(SceneChecks, ATargetOffTheForceAxisOfARobotNothingCanPushIsUnreachable) {
  const std::string robot =
      "    force_dims: 1\n    force_axis: [1, 0]\n    start: {x: 0, y: 0}\n"
      "    target: {x: 3, y: 1, vx: 0, vy: 0}\n";
  const std::string e = error_of(scene_text(robot));
  EXPECT_NE(e.find("s.yaml:9: key 'robots[0].target': unreachable: robot 'a' is driven along its "
                   "force_axis (1, 0) only, and nothing can push it (no contact pair) nor drive it "
                   "across that axis (floor friction only opposes motion), so y stays at its start "
                   "0 m; its target needs y = 1"),
            std::string::npos) << e;
  // On the axis: fine. A contact partner could push it: not flagged.
  EXPECT_EQ(error_of(scene_text("    force_dims: 1\n    start: {x: 0, y: 0}\n"
                                "    target: {x: 3, y: 0, vx: 0, vy: 0}\n")), "");
  EXPECT_EQ(error_of(scene_text(robot, "contact")), "");
  // A velocity across the axis at T_f is out of reach too.
  const std::string v = error_of(scene_text("    force_dims: 1\n    start: {x: 0, y: 0}\n"
                                            "    target: {x: 3, y: 0, vy: 1}\n"));
  EXPECT_NE(v.find("so its velocity across the axis stays 0; its target needs vx in [-inf, inf], vy = 1"),
            std::string::npos) << v;
}

TEST(SceneChecks, AnAxisTheFrictionPolygonIsNotSymmetricAboutIsNotFlagged) {
  // Axis at 10 degrees, K 16 (vertices every 22.5 degrees): friction may push across it.
  const std::string robot =
      "    force_dims: 1\n    force_axis: [0.984807753012208, 0.17364817766693]\n"
      "    start: {x: 0, y: 0}\n    target: {x: 3, y: 3}\n";
  EXPECT_EQ(error_of(scene_text(robot)), "");
  // Without floor friction nothing acts across any axis.
  const std::string e = error_of(scene_text(robot + "    mu: 0\n"));
  EXPECT_NE(e.find("unreachable: robot 'a' is driven along its force_axis (0.984808, 0.173648) only"),
            std::string::npos) << e;
  EXPECT_NE(e.find("it stays on the line through its start (0, 0) along that axis"), std::string::npos) << e;
  // At a multiple of pi / K (here the y axis, 8 pi / 16): flagged.
  EXPECT_NE(error_of(scene_text("    force_dims: 1\n    force_axis: [0, 1]\n    start: {x: 0, y: 0}\n"
                                "    target: {x: 1, y: 3}\n"))
                .find("so x stays at its start 0 m; its target needs x = 1"),
            std::string::npos);
}

TEST(SceneChecks, APhiTargetOfARobotNothingCanTurnIsUnreachable) {
  const std::string robot = "    start: {x: 0, y: 0, phi: 0.5}\n    target: {x: 2, y: 2, phi: 1}\n";
  const std::string e = error_of(scene_text(robot));
  EXPECT_NE(e.find("s.yaml:7: key 'robots[0].target': unreachable: robot 'a' cannot turn: nothing "
                   "touches it (no contact pair), its force acts at its centre and the floor's only "
                   "torque is the damping -sigma_d M g omega, so phi stays at its start 0.5 rad; its "
                   "target needs phi = 1"),
            std::string::npos) << e;
  EXPECT_EQ(error_of(scene_text(robot, "contact")), "") << "a contact partner can turn it";
  EXPECT_EQ(error_of(scene_text("    start: {x: 0, y: 0, omega: 0.1}\n    target: {x: 2, y: 2, phi: 1}\n")),
            "") << "spinning at the start: not covered (the solve decides)";
  EXPECT_EQ(error_of(scene_text("    start: {x: 0, y: 0, phi: 0.5}\n    target: {phi: [0, 1]}\n")), "")
      << "the start's phi is in the target";
  EXPECT_NE(error_of(scene_text("    start: {x: 0, y: 0}\n    target: {x: 1, omega: 1}\n"))
                .find("so omega stays 0; its target needs omega = 1"),
            std::string::npos);
}

TEST(SceneChecks, TargetsThatKeepTwoRobotsTooCloseAreUnreachable) {
  // b's target within 0.8 m of a's: an avoid pair needs R + R + d_s = 1.01 m (d_s 0.01 by default).
  const std::string e = error_of(scene_text("    start: {x: 0, y: 0}\n    target: {x: 5, y: 5}\n",
                                            "avoid", "{x: 5.8, y: 5}"));
  EXPECT_NE(e.find("key 'robots[1].target': unreachable: robots 'a' and 'b' (an avoid pair): their "
                   "targets keep their centres at most 0.8 m apart, less than R_i + R_j + "
                   "safe_distance = 1.01 m"),
            std::string::npos) << e;
  // A contact pair may touch (1 m), not overlap.
  EXPECT_EQ(error_of(scene_text("    start: {x: 0, y: 0}\n    target: {x: 5, y: 5}\n", "contact",
                                "{x: 6, y: 5}")), "");
  EXPECT_NE(error_of(scene_text("    start: {x: 0, y: 0}\n    target: {x: 5, y: 5}\n", "contact",
                                "{x: 5.9, y: 5}")).find("(a contact pair)"),
            std::string::npos);
  // A box that lets them apart is fine.
  EXPECT_EQ(error_of(scene_text("    start: {x: 0, y: 0}\n    target: {x: 5, y: 5}\n", "avoid",
                                "{x: [5, 9], y: 5}")), "");
}

TEST(SceneChecks, EveryShippedSceneThatCanBeSolvedLoads) {
  const std::set<std::string> unreachable = {"unreachable_target.yaml", "off_axis_target.yaml",
                                             "overlapping_targets.yaml"};
  int loaded = 0;
  for (const char* dir : {"configs/scenarios", "configs/stress"}) {
    for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(DISCO_SOURCE_DIR) + "/" + dir)) {
      if (e.path().extension() != ".yaml" || unreachable.count(e.path().filename().string())) continue;
      if (e.path().filename() == "too_weak.yaml") continue;  // rejected for its force_max
      EXPECT_NO_THROW(load_scene(e.path().string())) << e.path();
      ++loaded;
    }
  }
  EXPECT_GE(loaded, 25);
  for (const auto& name : unreachable)
    EXPECT_THROW(load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/stress/" + name), InputError) << name;
}

}  // namespace
}  // namespace disco
