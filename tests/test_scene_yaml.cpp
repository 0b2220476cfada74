// Tests for the scene file reader (core/model/scene_yaml.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "tests/test_support_messages.h"

namespace disco {
namespace {

const char* const kFile = "scene.yaml";

// Every line number used below is the line in this text (1-based).
const char* const kBase = R"(scenario: two_robots
description: "test scene"
steps: 20
gravity: 9.81
defaults:
  radius: 0.5
  mu: 0.2
robots:
  - name: r1
    mass: 1.0
    force_max: 5.0
    start: {x: 0, y: 0}
    target: {x: 10, y: [-0.1, 0.1], vx: 0}
  - name: r2
    radius: 0.25
    mass: 2.0
    mu: 0.1
    force_max: 4.0
    start: {x: 0, y: 2}
pairs:
  mode: avoid
)";

// kBase with the first occurrence of `from` replaced by `to` (which must exist).
std::string with(const std::string& from, const std::string& to, std::string text = kBase) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos)
    ADD_FAILURE() << "test bug: '" << from << "' not in the scene";
  else
    text.replace(at, from.size(), to);
  return text;
}

// The message of the InputError that parsing `text` throws ("" if none is thrown).
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, kFile, overrides);
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "";
}

// The message must start with "scene.yaml:LINE: key 'KEY': " and contain `fragment`.
void expect_error(const std::string& text, int line, const std::string& key,
                  const std::string& fragment, const std::vector<std::string>& overrides = {}) {
  const std::string msg = error_of(text, overrides);
  const std::string where =
      std::string(kFile) + ":" + std::to_string(line) + ": key '" + key + "': ";
  test_support::expect_prefix(msg, where, fragment);
}

// Same, for an error located in an override: "--set: key 'KEY': ".
void expect_set_error(const std::string& text, const std::vector<std::string>& overrides,
                      const std::string& key, const std::string& fragment) {
  const std::string msg = error_of(text, overrides);
  const std::string where = "--set: key '" + key + "': ";
  test_support::expect_prefix(msg, where, fragment);
}

using test_support::temp_path;

TEST(SceneYaml, BaseSceneIsValid) {
  const Scene s = parse_scene(kBase, kFile);
  EXPECT_EQ(s.name, "two_robots");
  EXPECT_EQ(s.source, kFile);
  ASSERT_EQ(s.robots.size(), 2u);
  ASSERT_EQ(s.pairs.size(), 1u);
}

TEST(SceneYaml, FullRoundTrip) {
  const char* text = R"(scenario: full.scene-1
description: "all keys"
steps: 50
gravity: 10
defaults:
  radius: 0.5
  mu: 0.1
  K: 8
robots:
  - name: a
    mass: 2.0
    force_max: 5.0
    start: {x: 0, y: 0, phi: 0.5, vx: 1, vy: 2, omega: 3}
    target: {x: 10, y: [-0.1, 0.1], phi: [~, 1], vx: [0, null], vy: 0}
  - name: b
    radius: 0.25
    mass: 1.0
    inertia: 0.3
    mu: 0.2
    damping: 0.07
    force_max: 3.0
    force_dims: 1
    force_axis: [3, 4]
    K: 5
    start: {x: 2, y: 0}
  - name: c
    mass: 1.0
    force_max: 2.0
    start: {x: 0, y: 3}
pairs:
  mode: contact
  safe_distance: 0.05
  mu: 0.4
  overrides:
    - robots: [c, a]
      mode: avoid
    - robots: [b, c]
      safe_distance: 0.2
      mu: 0.1
)";
  const Scene s = parse_scene(text, "full.yaml");
  EXPECT_EQ(s.name, "full.scene-1");
  EXPECT_EQ(s.source, "full.yaml");
  EXPECT_EQ(s.steps, 50);
  EXPECT_DOUBLE_EQ(s.gravity, 10.0);
  ASSERT_EQ(s.robots.size(), 3u);

  const Robot& a = s.robots[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_DOUBLE_EQ(a.radius, 0.5);  // from defaults
  EXPECT_DOUBLE_EQ(a.mass, 2.0);
  EXPECT_DOUBLE_EQ(a.inertia, 0.5 * 2.0 * 0.25);  // uniform disk
  EXPECT_DOUBLE_EQ(a.mu, 0.1);
  EXPECT_DOUBLE_EQ(a.damping, 0.05);  // 0.1 * radius
  EXPECT_DOUBLE_EQ(a.force_max, 5.0);
  EXPECT_EQ(a.force_dims, 2);
  EXPECT_DOUBLE_EQ(a.force_axis[0], 1.0);
  EXPECT_DOUBLE_EQ(a.force_axis[1], 0.0);
  EXPECT_EQ(a.friction_edges, 8);  // from defaults
  const State start{0, 0, 0.5, 1, 2, 3};
  EXPECT_EQ(a.start, start);
  EXPECT_DOUBLE_EQ(a.target.lower[kX], 10);
  EXPECT_DOUBLE_EQ(a.target.upper[kX], 10);
  EXPECT_DOUBLE_EQ(a.target.lower[kY], -0.1);
  EXPECT_DOUBLE_EQ(a.target.upper[kY], 0.1);
  EXPECT_EQ(a.target.lower[kPhi], -kInf);
  EXPECT_DOUBLE_EQ(a.target.upper[kPhi], 1);
  EXPECT_DOUBLE_EQ(a.target.lower[kVx], 0);
  EXPECT_EQ(a.target.upper[kVx], kInf);
  EXPECT_DOUBLE_EQ(a.target.lower[kVy], 0);
  EXPECT_DOUBLE_EQ(a.target.upper[kVy], 0);
  EXPECT_EQ(a.target.lower[kOmega], -kInf);
  EXPECT_EQ(a.target.upper[kOmega], kInf);

  const Robot& b = s.robots[1];
  EXPECT_DOUBLE_EQ(b.radius, 0.25);
  EXPECT_DOUBLE_EQ(b.inertia, 0.3);
  EXPECT_DOUBLE_EQ(b.mu, 0.2);
  EXPECT_DOUBLE_EQ(b.damping, 0.07);
  EXPECT_EQ(b.force_dims, 1);
  EXPECT_DOUBLE_EQ(b.force_axis[0], 0.6);
  EXPECT_DOUBLE_EQ(b.force_axis[1], 0.8);
  EXPECT_EQ(b.friction_edges, 5);
  const State b_start{2, 0, 0, 0, 0, 0};
  EXPECT_EQ(b.start, b_start);
  for (int c = 0; c < kStateSize; ++c) {  // no target: everything free
    EXPECT_EQ(b.target.lower[c], -kInf);
    EXPECT_EQ(b.target.upper[c], kInf);
  }
  const Robot& c = s.robots[2];
  EXPECT_DOUBLE_EQ(c.inertia, 0.5 * 1.0 * 0.25);
  EXPECT_EQ(c.friction_edges, 8);

  ASSERT_EQ(s.pairs.size(), 3u);
  const int expect_ij[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(s.pairs[k].i, expect_ij[k][0]);
    EXPECT_EQ(s.pairs[k].j, expect_ij[k][1]);
  }
  EXPECT_EQ(s.pairs[0].mode, PairMode::kContact);  // default
  EXPECT_DOUBLE_EQ(s.pairs[0].safe_distance, 0.05);
  EXPECT_DOUBLE_EQ(s.pairs[0].mu, 0.4);
  EXPECT_EQ(s.pairs[1].mode, PairMode::kAvoid);  // override [c, a]
  EXPECT_DOUBLE_EQ(s.pairs[1].safe_distance, 0.05);
  EXPECT_DOUBLE_EQ(s.pairs[1].mu, 0.4);
  EXPECT_EQ(s.pairs[2].mode, PairMode::kContact);  // override [b, c]
  EXPECT_DOUBLE_EQ(s.pairs[2].safe_distance, 0.2);
  EXPECT_DOUBLE_EQ(s.pairs[2].mu, 0.1);
}

TEST(SceneYaml, BuiltInDefaults) {
  const char* text = R"(scenario: one
steps: 1
robots:
  - {name: r, radius: 1, mass: 1, mu: 0, force_max: 1, start: {x: 0, y: 0}, target: {x: 1}}
)";
  const Scene s = parse_scene(text, kFile);
  EXPECT_DOUBLE_EQ(s.gravity, 9.81);
  EXPECT_EQ(s.robots[0].force_dims, 2);
  EXPECT_EQ(s.robots[0].friction_edges, 16);
  EXPECT_DOUBLE_EQ(s.robots[0].damping, 0.1);
  EXPECT_TRUE(s.pairs.empty());
}

TEST(SceneYaml, PairDefaults) {
  const Scene s = parse_scene(with("pairs:\n  mode: avoid\n", ""), kFile);
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].mode, PairMode::kAvoid);
  EXPECT_DOUBLE_EQ(s.pairs[0].safe_distance, 0.01);
  EXPECT_DOUBLE_EQ(s.pairs[0].mu, 0.3);
  // An empty pairs section is the same.
  EXPECT_DOUBLE_EQ(parse_scene(with("  mode: avoid\n", ""), kFile).pairs[0].mu, 0.3);
}

TEST(SceneYaml, Overrides) {
  const Scene s = parse_scene(
      kBase, kFile,
      {"steps=25", "robots.0.mass=2", "defaults.K=8",
       "pairs.overrides=[{robots: [r2, r1], mode: contact}]", "robots.1.target={x: [1, ~]}"});
  EXPECT_EQ(s.steps, 25);
  EXPECT_DOUBLE_EQ(s.robots[0].mass, 2.0);
  EXPECT_DOUBLE_EQ(s.robots[0].inertia, 0.5 * 2.0 * 0.25);
  EXPECT_EQ(s.robots[0].friction_edges, 8);
  EXPECT_EQ(s.robots[1].friction_edges, 8);
  EXPECT_EQ(s.pairs[0].mode, PairMode::kContact);
  EXPECT_DOUBLE_EQ(s.robots[1].target.lower[kX], 1);
  EXPECT_EQ(s.robots[1].target.upper[kX], kInf);
}

TEST(SceneYaml, OverridesCreateSectionsAndAppend) {
  const char* text = R"(scenario: one
steps: 3
robots:
  - {name: r, radius: 1, mass: 1, mu: 0, force_max: 1, start: {x: 0, y: 0}, target: {x: 1}}
)";
  const Scene s = parse_scene(
      text, kFile,
      {"pairs.mode=contact", "gravity=2",
       "robots.1={name: q, radius: 1, mass: 1, mu: 0, force_max: 1, start: {x: 2, y: 0}}"});
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robots[1].name, "q");
  EXPECT_DOUBLE_EQ(s.gravity, 2);
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].mode, PairMode::kContact);
}

TEST(SceneYaml, OverrideErrors) {
  expect_set_error(kBase, {"steps"}, "steps", "KEY=VALUE");
  expect_set_error(kBase, {"robots..mass=1"}, "robots..mass", "malformed key");
  expect_set_error(kBase, {"robots.r1.mass=1"}, "robots.r1.mass", "must be an index");
  expect_set_error(kBase, {"robots.5.mass=1"}, "robots.5.mass", "out of range");
  expect_set_error(kBase, {"steps.x=1"}, "steps.x", "single value");
  expect_set_error(kBase, {"steps=[1, 2"}, "steps", "cannot parse");
  expect_set_error(kBase, {"steps=0"}, "steps", "must be >= 1");
  expect_set_error(kBase, {"robots.0.mass=-1"}, "robots.0.mass", "must be > 0");
  expect_set_error(kBase, {"robots.0.mass=abc"}, "robots.0.mass", "must be a number");
  expect_set_error(kBase, {"robots.0.masss=1"}, "robots.0.masss", "unknown key");
  expect_set_error(kBase, {"robots.0.start={x: 0, y: abc}"}, "robots.0.start.y",
                   "must be a number");
  expect_set_error(kBase, {"defaults.K=2"}, "defaults.K", "must be >= 3");
  expect_set_error(kBase, {"robots.0.force_max=1"}, "robots.0.force_max", "too weak");
  // A later override of a parent wins over an earlier one below it.
  expect_set_error(kBase, {"robots.0.mass=2", "robots.0={name: r1}"}, "robots.0.mass", "required");
  // An untouched key keeps its file location even when overrides are present.
  expect_error(with("mass: 2.0", "mass: -2.0"), 16, "robots[1].mass", "must be > 0",
               {"robots.0.mass=2"});
}

TEST(SceneYaml, MissingFile) {
  const std::string path = temp_path("does_not_exist.yaml");
  std::filesystem::remove(path);
  try {
    load_scene(path);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
  }
}

TEST(SceneYaml, LoadFromFile) {
  const std::string path = temp_path("scene.yaml");
  {
    std::ofstream out(path);
    out << kBase;
  }
  const Scene s = load_scene(path, {"steps=7"});
  EXPECT_EQ(s.source, path);
  EXPECT_EQ(s.steps, 7);
  {
    std::ofstream out(path);
    out << with("mass: 1.0", "mass: 0");
  }
  try {
    load_scene(path);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":10: key 'robots[0].mass': ", 0), 0u) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(SceneYaml, SyntaxError) {
  const std::string msg = error_of(with("  mu: 0.2", "  mu: [0.2"));
  EXPECT_EQ(msg.rfind("scene.yaml:", 0), 0u) << msg;
  EXPECT_NE(msg.find("YAML syntax error"), std::string::npos) << msg;
  const std::string msg2 = error_of("scenario: a\nsteps: 3\n  bad: indent\n");
  EXPECT_EQ(msg2.rfind("scene.yaml:3:", 0), 0u) << msg2;
}

TEST(SceneYaml, NestingTooDeep) {
  // Past yaml-cpp's depth limit (500 in Debian's build) its own message is "bad file".
  const std::string deep = std::string(3000, '[') + std::string(3000, ']');
  const std::string msg = error_of("scenario: a\nsteps: " + deep + "\n");
  EXPECT_EQ(msg.rfind("scene.yaml:2: YAML syntax error: nesting too deep (", 0), 0u) << msg;
  expect_set_error(kBase, {"steps=" + deep}, "steps", "' as YAML: nesting too deep (");
}

TEST(SceneYaml, NotAMapping) {
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
  EXPECT_EQ(error_of("- a\n- b\n").rfind("scene.yaml:1: ", 0), 0u);
  EXPECT_NE(error_of("- a\n- b\n").find("must be a YAML mapping"), std::string::npos);
}

TEST(SceneYaml, UnknownKeys) {
  expect_error(with("gravity: 9.81", "gravty: 9.81"), 4, "gravty",
               "allowed: scenario, description, steps, gravity, defaults, robots, objects, obstacles, pairs");
  expect_error(with("    mass: 1.0", "    masss: 1.0"), 10, "robots[0].masss",
               "unknown key (allowed: name, radius, mass");
  expect_error(with("{x: 0, y: 2}", "{x: 0, y: 2, z: 1}"), 19, "robots[1].start.z",
               "allowed: x, y, phi, vx, vy, omega");
  expect_error(with("vx: 0}", "vx: 0, v: 1}"), 13, "robots[0].target.v", "unknown key");
  expect_error(with("  mu: 0.2", "  name: r"), 7, "defaults.name",
               "allowed: radius, mass, inertia");
  expect_error(with("  mode: avoid", "  mod: avoid"), 21, "pairs.mod",
               "allowed: mode, safe_distance, mu, overrides");
  expect_error(with("  mode: avoid",
                    "  overrides:\n    - robots: [r1, r2]\n      mu: 1\n"
                    "      kind: x"),
               24, "pairs.overrides[0].kind", "allowed: robots, mode, safe_distance, mu");
}

TEST(SceneYaml, DuplicateKey) {
  expect_error(with("    mass: 2.0", "    mass: 2.0\n    mass: 3.0"), 17, "robots[1].mass",
               "duplicate key");
}

TEST(SceneYaml, MissingRequiredKeys) {
  expect_error(with("scenario: two_robots\n", ""), 1, "scenario", "required");
  expect_error(with("steps: 20\n", ""), 1, "steps", "required");
  const std::string no_robots = "scenario: a\nsteps: 3\n";
  expect_error(no_robots, 1, "robots", "required");
  expect_error(with("  - name: r2\n", "  - inertia: 1\n"), 14, "robots[1].name", "required");
  expect_error(with("    mass: 1.0\n", ""), 9, "robots[0].mass", "required");
  expect_error(with("  radius: 0.5\n", ""), 8, "robots[0].radius", "required");
  expect_error(with("  mu: 0.2\n", ""), 8, "robots[0].mu", "required");
  expect_error(with("    force_max: 4.0\n", ""), 14, "robots[1].force_max", "required");
  expect_error(with("    start: {x: 0, y: 2}\n", ""), 14, "robots[1].start", "required");
  expect_error(with("{x: 0, y: 2}", "{y: 2}"), 19, "robots[1].start.x", "required");
  expect_error(with("{x: 0, y: 2}", "{x: 0}"), 19, "robots[1].start.y", "required");
  expect_error(with("  mode: avoid", "  overrides:\n    - mode: contact"), 22,
               "pairs.overrides[0].robots", "required");
}

TEST(SceneYaml, WrongTypes) {
  expect_error(with("radius: 0.25", "radius: abc"), 15, "robots[1].radius",
               "must be a number (got 'abc')");
  expect_error(with("steps: 20", "steps: 2.5"), 3, "steps", "must be an integer (got '2.5')");
  expect_error("scenario: a\nsteps: 3\nrobots: 3\n", 3, "robots", "must be a sequence");
  expect_error("scenario: a\nsteps: 3\nrobots: []\n", 3, "robots", "at least one robot");
  expect_error(with("mass: 2.0", "mass: \"2.0\""), 16, "robots[1].mass",
               "must be a number (got the quoted string \"2.0\")");
  expect_error(with("mass: 2.0", "mass: [2]"), 16, "robots[1].mass", "got a sequence");
  expect_error(with("mass: 2.0", "mass:"), 16, "robots[1].mass", "got null");
  expect_error(with("    mu: 0.1", "    force_dims: two"), 17, "robots[1].force_dims",
               "must be an integer");
  expect_error(with("    mu: 0.1", "    K: 3.5"), 17, "robots[1].K", "must be an integer");
  expect_error(with("    mu: 0.1", "    force_axis: [1]"), 17, "robots[1].force_axis", "2-vector");
  expect_error(with("    mu: 0.1", "    force_axis: [1, a]"), 17, "robots[1].force_axis[1]",
               "must be a number");
  expect_error(with("{x: 0, y: 2}", "5"), 19, "robots[1].start", "must be a mapping");
  expect_error(with("vx: 0}", "vx: {a: 1}}"), 13, "robots[0].target.vx",
               "must be a number or a box");
  expect_error(with("vx: 0}", "vx: [0, 1, 2]}"), 13, "robots[0].target.vx", "[lo, hi]");
  expect_error(with("vx: 0}", "vx: [0, b]}"), 13, "robots[0].target.vx[1]", "must be a number");
  expect_error(with("pairs:\n  mode: avoid\n", "pairs: 3\n"), 20, "pairs", "must be a mapping");
  expect_error(with("  mode: avoid", "  overrides: 5"), 21, "pairs.overrides", "sequence");
  expect_error(with("  mode: avoid", "  mode: sideways"), 21, "pairs.mode", "'avoid' or 'contact'");
  expect_error(with("  mode: avoid", "  overrides:\n    - robots: r1"), 22,
               "pairs.overrides[0].robots", "two robot or object names");
  expect_error(with("scenario: two_robots", "scenario: two robots"), 1, "scenario",
               "letters, digits");
  expect_error(with("name: r2", "name: [r2]"), 14, "robots[1].name", "must be text");
  expect_error("scenario: a\nsteps: 3\nrobots:\n  - 7\n", 4, "robots[0]", "must be a mapping");
  expect_error(with("defaults:\n  radius: 0.5\n  mu: 0.2\n", "defaults: 1\n"), 5, "defaults",
               "must be a mapping");
}

TEST(SceneYaml, NonFiniteNumbers) {
  expect_error(with("mass: 2.0", "mass: .inf"), 16, "robots[1].mass", "finite");
  expect_error(with("    mu: 0.1", "    mu: .nan"), 17, "robots[1].mu", "finite");
  expect_error(with("{x: 0, y: 2}", "{x: -.inf, y: 2}"), 19, "robots[1].start.x", "finite");
  expect_error(with("y: [-0.1, 0.1]", "y: [-0.1, .inf]"), 13, "robots[0].target.y[1]", "finite");
}

TEST(SceneYaml, Ranges) {
  expect_error(with("radius: 0.25", "radius: 0"), 15, "robots[1].radius", "must be > 0 (got 0)");
  expect_error(with("  radius: 0.5", "  radius: -0.5"), 6, "defaults.radius", "must be > 0");
  expect_error(with("mass: 2.0", "mass: -1"), 16, "robots[1].mass", "must be > 0 (got -1)");
  expect_error(with("    mu: 0.1", "    inertia: 0"), 17, "robots[1].inertia", "must be > 0");
  expect_error(with("    mu: 0.1", "    mu: -0.1"), 17, "robots[1].mu", "must be >= 0 (got -0.1)");
  expect_error(with("    mu: 0.1", "    damping: -1"), 17, "robots[1].damping", "must be >= 0");
  expect_error(with("force_max: 4.0", "force_max: 0"), 18, "robots[1].force_max", "must be > 0");
  expect_error(with("    mu: 0.1", "    force_dims: 3"), 17, "robots[1].force_dims",
               "must be 1 or 2");
  expect_error(with("    mu: 0.1", "    force_dims: 0"), 17, "robots[1].force_dims",
               "must be 1 or 2");
  expect_error(with("    mu: 0.1", "    force_axis: [0, 0.0]"), 17, "robots[1].force_axis",
               "zero vector");
  expect_error(with("    mu: 0.1", "    K: 2"), 17, "robots[1].K", "must be >= 3 (got 2)");
  expect_error(with("steps: 20", "steps: 0"), 3, "steps", "must be >= 1 (got 0)");
  expect_error(with("gravity: 9.81", "gravity: 0"), 4, "gravity", "must be > 0");
  expect_error(with("  mode: avoid", "  safe_distance: -0.1"), 21, "pairs.safe_distance",
               "must be >= 0");
  expect_error(with("  mode: avoid", "  mu: -1"), 21, "pairs.mu", "must be >= 0");
  expect_error(with("  mode: avoid",
                    "  overrides:\n    - robots: [r1, r2]\n"
                    "      safe_distance: -1"),
               23, "pairs.overrides[0].safe_distance", "must be >= 0");
}

TEST(SceneYaml, DuplicateRobotName) {
  expect_error(with("name: r2", "name: r1"), 14, "robots[1].name",
               "duplicate name 'r1' (already used by robots[0])");
}

TEST(SceneYaml, PairOverrideErrors) {
  expect_error(with("  mode: avoid", "  overrides:\n    - robots: [r1, r3]"), 22,
               "pairs.overrides[0].robots[1]", "unknown robot or object name 'r3'");
  expect_error(with("  mode: avoid", "  overrides:\n    - robots: [r2, r2]"), 22,
               "pairs.overrides[0].robots", "two distinct robots or objects");
  expect_error(with("  mode: avoid",
                    "  overrides:\n    - robots: [r1, r2]\n"
                    "    - robots: [r2, r1]\n      mode: contact"),
               23, "pairs.overrides[1].robots", "already set by pairs.overrides[0]");
}

TEST(SceneYaml, StartOverlap) {
  // Centre distance 0.5 < 0.5 + 0.25: names both robots.
  expect_error(with("{x: 0, y: 2}", "{x: 0.5, y: 0}"), 19, "robots[1].start",
               "robots 'r1' and 'r2' overlap at the start");
  // Exactly touching is allowed for a contact pair ...
  const std::string touching = with("{x: 0, y: 2}", "{x: 0.75, y: 0}");
  EXPECT_NO_THROW(parse_scene(with("mode: avoid", "mode: contact", touching), kFile));
  // ... but an avoid pair needs the safe distance on top.
  expect_error(touching, 19, "robots[1].start", "R_i + R_j + safe_distance = 0.76");
  EXPECT_NO_THROW(parse_scene(with("{x: 0, y: 2}", "{x: 0.76, y: 0}"), kFile));
  EXPECT_NO_THROW(parse_scene(touching, kFile, {"pairs.safe_distance=0"}));
  // A start set by an override is named in the message.
  expect_error(kBase, 19, "robots[1].start",
               "overlap at the start: centre distance 0.5 < R_i + "
               "R_j = 0.75 (with --set robots.1.start.x, robots.1.start.y)",
               {"robots.1.start.x=0.5", "robots.1.start.y=0"});
}

TEST(SceneYaml, TooWeakToMove) {
  // 0.1 * 2 * 9.81 = 1.962 N of floor friction.
  expect_error(with("force_max: 4.0", "force_max: 1.962"), 18, "robots[1].force_max",
               "robot 'r2' is too weak to move: force_max = 1.962 N must exceed "
               "mu * mass * gravity = 0.1 * 2 * 9.81 = 1.962 N");
  // A force_max from defaults is reported where it is written.
  expect_error(with("    force_max: 5.0\n", "", with("  mu: 0.2\n", "  mu: 0.2\n  force_max: 1\n")),
               8, "defaults.force_max", "robot 'r1' is too weak");
}

TEST(SceneYaml, TargetBoxOrder) {
  expect_error(with("y: [-0.1, 0.1]", "y: [0.1, -0.1]"), 13, "robots[0].target.y",
               "lower bound 0.1 > upper bound -0.1");
  const Scene s = parse_scene(with("vx: 0}", "vx: [~, ~], phi: ~}"), kFile);
  EXPECT_EQ(s.robots[0].target.lower[kVx], -kInf);
  EXPECT_EQ(s.robots[0].target.upper[kPhi], kInf);
}

// Found by tests/fuzz/scene_fuzz.cpp: messages echoed raw control bytes (a newline, NUL,
// ESC) from the input and had no bound on their length.
TEST(SceneYaml, ControlBytesInMessagesAreEscaped) {
  expect_error(with("scenario: two_robots", "scenario: \"two\\nrobots\\0\""), 1, "scenario",
               "(got the quoted string \"two\\nrobots\\x00\")");
  expect_error(with("gravity: 9.81", std::string("gra\x01vity: 9.81")), 4, "gra\\x01vity",
               "unknown key");
  const std::string syntax = error_of(with("scenario: two_robots", "scenario: \"a\\\x1b\""));
  EXPECT_EQ(syntax.rfind("scene.yaml:1: YAML syntax error: ", 0), 0u) << syntax;
  EXPECT_NE(syntax.find("\\x1b"), std::string::npos) << syntax;
  for (char c : syntax) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << syntax;
  expect_set_error(kBase, {"ste\tps.x=1"}, "ste\\tps", "unknown key");
}

TEST(SceneYaml, LongEchoesAreCut) {
  const std::string value(5000, 'a');
  const std::string msg = error_of(with("mass: 2.0", "mass: " + value));
  EXPECT_NE(msg.find("(got '" + std::string(80, 'a') + "... (5000 bytes)')"), std::string::npos)
      << msg;
  const std::string key = error_of(with("gravity: 9.81", std::string(1000, 'k') + ": 9.81"));
  EXPECT_EQ(key.rfind("scene.yaml:4: key '" + std::string(160, 'k') + "... (1000 bytes)': ", 0),
            0u)
      << key;
  const std::string value_set = error_of(kBase, {"robots.0.mass=[" + value});
  const std::string cut = "cannot parse the value '[" + std::string(79, 'a') + "... (5001 bytes)'";
  EXPECT_NE(value_set.find(cut), std::string::npos) << value_set;
  for (const std::string* m : {&msg, &key, &value_set}) EXPECT_LT(m->size(), 500u) << *m;
}

TEST(SceneYaml, OverridesBelowAKeyAreNamedOnce) {
  // pairs.extra.b.c=1 creates pairs.extra.b and sets its c: one override, named once.
  expect_error(with("  mode: avoid", "  mode: avoid\n  extra: {a: 1}"), 22, "pairs.extra",
               "unknown key (allowed: mode, safe_distance, mu, overrides) "
               "(with --set pairs.extra.b.c, pairs.extra.d)",
               {"pairs.extra.b.c=1", "pairs.extra.d=2"});
}

}  // namespace
}  // namespace disco
