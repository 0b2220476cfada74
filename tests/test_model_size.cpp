// The size guard (core/model/model_size.h, core/config/solver_settings.h memory_limit): the counts it
// extrapolates are those of the model built at the scene's N_t, the estimate grows as a
// solve's memory does, a scene above model.memory_limit is refused before anything is
// built with a message naming where `steps` was given, and every shipped scene fits a
// small machine.
#include <gtest/gtest.h>

#include <climits>
#include <filesystem>
#include <set>
#include <string>

#include "core/util/machine.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_nlp.h"
#include "core/model/model_size.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "core/util/numbers.h"
#include "search/search_plan.h"
#include "test_support_messages.h"

namespace disco {
namespace {

using test_support::expect_prefix;

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

std::string scene_path(const std::string& name) {
  return std::string(DISCO_SOURCE_DIR) + "/configs/" + name;
}

// A one-robot scene; `steps` on line 2.
const char* kOneRobot =
    "scenario: big\n"
    "steps: 200000\n"
    "robots:\n"
    "  - {name: r1, radius: 0.5, mass: 1.0, mu: 0.2, force_max: 5.0, start: {x: 0, y: 0},\n"
    "     target: {x: 4, y: 0, vx: 0, vy: 0}}\n";

std::string error_of(const Scene& scene, const MemoryLimit& limit, int processes = 1) {
  try {
    check_model_size(scene, true, limit, processes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelSize, CountsAreThoseOfTheModelBuiltAtTheScenesSteps) {
  // The estimate counts from models at N_t = 2 and 3; here the models at N_t itself.
  for (const char* name :
       {"scenarios/one_robot_axis.yaml", "scenarios/three_robots_contact.yaml",
        "scenarios/paper/A4.yaml", "stress/twelve_robots.yaml", "stress/K_3.yaml",
        "stress/spin_short.yaml", "stress/forced_contact.yaml"}) {
    for (int steps : {1, 2, 7, 40}) {
      for (bool adaptive : {true, false}) {
        Scene scene = load_scene(scene_path(name));
        scene.steps = steps;
        const ModelSizeEstimate e = estimate_model_size(scene, adaptive);
        const RobotProblem built(scene, ModelOptions{adaptive, kInf});
        const ElasticNlp nlp(built.program(), ElasticFormulation::kLumped, 1.0);
        const std::string what = std::string(name) + " N_t = " + std::to_string(steps) +
                                 (adaptive ? " adaptive" : " full");
        EXPECT_EQ(e.steps, steps) << what;
        EXPECT_EQ(e.variables, nlp.num_variables()) << what;
        EXPECT_EQ(e.rows, nlp.num_constraints()) << what;
        EXPECT_EQ(e.nonzeros, nlp.jacobian_pattern().size() + nlp.hessian_pattern().size()) << what;
      }
    }
  }
}

TEST(ModelSize, EstimateGrowsWithStepsRobotsAndCoupling) {
  Scene one = load_scene(scene_path("scenarios/one_robot_axis.yaml"));
  auto bytes = [](Scene s, int steps) {
    s.steps = steps;
    return estimate_model_size(s, true).bytes;
  };
  // One robot: every step adds the same, so the part above the process doubles with N_t.
  const double base = bytes(one, 1000) - (bytes(one, 2000) - bytes(one, 1000));
  EXPECT_GT(base, 0.0);
  EXPECT_NEAR(bytes(one, 4000) - base, 4.0 * (bytes(one, 1000) - base), 1e-6 * bytes(one, 4000));
  // About 100 kB a step for one robot (a solve measured 68 to 73 kB; header table).
  const double per_step = (bytes(one, 2000) - bytes(one, 1000)) / 1000;
  EXPECT_GT(per_step, 60e3);
  EXPECT_LT(per_step, 120e3);
  // Three robots in contact need more per step than three times one robot.
  Scene three = load_scene(scene_path("scenarios/three_robots_contact.yaml"));
  EXPECT_GT(bytes(three, 1000) - base, 3.0 * (bytes(one, 1000) - base));
  // The full model is at least as big as the adaptive one.
  three.steps = 500;
  EXPECT_GE(estimate_model_size(three, false).bytes, estimate_model_size(three, true).bytes);
}

TEST(ModelSize, EstimatingBuildsNothingOfTheSceneSize) {
  // 2^31 - 1 steps: a model nobody could build, estimated at once.
  Scene scene = parse_scene(kOneRobot, "big.yaml");
  scene.steps = INT_MAX;
  const ModelSizeEstimate e = estimate_model_size(scene, true);
  EXPECT_GT(e.variables, 20.0 * INT_MAX);
  EXPECT_GT(e.bytes, 1e14);
}

TEST(ModelSize, RefusedAboveTheLimitNamingStepsFileLineAndEstimate) {
  const Scene scene = parse_scene(kOneRobot, "configs/big.yaml");
  const MemoryLimit limit{1.5 * kGiB, "configs/disco.yaml:51",
                          "auto = half of the machine's 3.0 GiB"};
  const std::string msg = error_of(scene, limit);
  expect_prefix(msg, "configs/big.yaml:2: key 'steps': the model would need about ", " GiB (");
  for (const char* piece : {"variables", "Jacobian and Hessian nonzeros", "N_t = 200000",
                            "1 robot and 0 pairs",
                            "above model.memory_limit = 1.5 GiB (configs/disco.yaml:51; auto = "
                            "half of the machine's 3.0 GiB)",
                            "lower steps or raise model.memory_limit"})
    EXPECT_NE(msg.find(piece), std::string::npos) << piece << "\n got: " << msg;
  // The estimate named is the estimate: about 19 GiB (100 kB a step).
  const double gib = estimate_model_size(scene, true).bytes / kGiB;
  EXPECT_GT(gib, 10.0);
  EXPECT_NE(msg.find(memory_text(gib * kGiB)), std::string::npos) << msg;
  // Below the limit: accepted, and the estimate returned.
  EXPECT_EQ(error_of(scene, MemoryLimit{2 * gib * kGiB, "x", ""}), "");
}

TEST(ModelSize, StepsFromAnOverrideAreNamedAsSet) {
  const Scene scene = parse_scene(kOneRobot, "configs/big.yaml", {"steps=300000"});
  const std::string msg = error_of(scene, MemoryLimit{kGiB, "--set", ""});
  expect_prefix(msg, "--set: key 'steps': the model would need", "N_t = 300000");
  EXPECT_NE(msg.find("above model.memory_limit = 1.0 GiB (--set)"), std::string::npos) << msg;
}

TEST(ModelSize, ASceneMadeInCodeIsNamedByItsSource) {
  Scene scene = parse_scene(kOneRobot, "configs/big.yaml");
  scene.steps_origin = {};
  const std::string msg = error_of(scene, MemoryLimit{kGiB, "x", ""});
  EXPECT_EQ(msg.rfind("configs/big.yaml: key 'steps': the model would need", 0), 0u) << msg;
}

TEST(ModelSize, ASearchsProcessesShareTheLimit) {
  Scene scene = parse_scene(kOneRobot, "big.yaml");
  scene.steps = 20000;
  const double need = estimate_model_size(scene, true).bytes;
  const MemoryLimit limit{1.5 * need, "configs/disco.yaml:51", ""};
  EXPECT_EQ(error_of(scene, limit, 1), "");
  const std::string msg = error_of(scene, limit, 2);
  EXPECT_NE(msg.find("shared by the 2 processes of this search on this machine"),
            std::string::npos)
      << msg;
}

Settings settings_with(const std::string& value) {
  return Settings::parse("model:\n  adaptive: true\n  memory_limit: " + value + "\n", "s.yaml");
}

TEST(MemoryLimit, AutoIsHalfThePhysicalMemoryANumberIsGiB) {
  const MemoryLimit a = memory_limit(settings_with("auto"));
  EXPECT_DOUBLE_EQ(a.bytes, 0.5 * physical_memory_bytes());
  EXPECT_EQ(a.where, "s.yaml:3");
  EXPECT_EQ(a.auto_meaning, "auto = half of the machine's " + memory_text(physical_memory_bytes()));
  EXPECT_GT(physical_memory_bytes(), 256.0 * (1 << 20));
  const MemoryLimit n = memory_limit(settings_with("2.5"));
  EXPECT_DOUBLE_EQ(n.bytes, 2.5 * kGiB);
  EXPECT_EQ(n.auto_meaning, "");
  Settings over = settings_with("auto");
  over.apply_override("model.memory_limit=0.25");
  EXPECT_DOUBLE_EQ(memory_limit(over).bytes, 0.25 * kGiB);
  EXPECT_EQ(memory_limit(over).where, "--set");
}

TEST(MemoryLimit, AnythingElseIsRefusedNamingFileLineAndKey) {
  for (const char* bad : {"0", "-1", "lots", "\"2 GiB\"", ".nan"}) {
    try {
      memory_limit(settings_with(bad));
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      expect_prefix(e.what(), "s.yaml:3: key 'model.memory_limit': ",
                    "must be 'auto' or a number of GiB > 0");
    }
  }
  EXPECT_THROW(memory_limit(Settings::parse("model:\n  adaptive: true\n", "s.yaml")), InputError);
  // The shipped settings file has the key.
  EXPECT_GT(memory_limit(Settings::load(default_settings_path())).bytes, 0.0);
}

// Every shipped scene fits a small CI machine: 4 GiB, auto = 2 GiB, shared by a search's
// two ranks (1 GiB each), benchmarks with their steps.
TEST(ModelSize, EveryShippedSceneFitsASmallMachine) {
  const MemoryLimit small{0.5 * 4 * kGiB, "a 4 GiB machine", "auto"};
  int checked = 0;
  for (const char* dir : {"scenarios", "stress"}) {
    for (const auto& e : std::filesystem::recursive_directory_iterator(scene_path(dir))) {
      if (e.path().extension() != ".yaml") continue;
      Scene scene;
      try {
        scene = load_scene(e.path().string());
      } catch (const InputError&) {
        continue;  // refused by the scene checks (tests/test_scene_checks.cpp)
      }
      EXPECT_EQ(error_of(scene, small, 2), "") << e.path();
      EXPECT_LT(estimate_model_size(scene, false).bytes, 0.5 * small.bytes / 2) << e.path();
      ++checked;
    }
  }
  EXPECT_GE(checked, 25);
  for (const char* bench : {"benchmarks/smoke.yaml", "benchmarks/paper.yaml"}) {
    for (const SceneJob& job : load_search_plan({scene_path(bench)}, 0, 1, {}).scenes) {
      EXPECT_EQ(error_of(job.scene, small, 2), "") << bench << " " << job.scene.name;
      ++checked;
    }
  }
  // steps_1000, the largest: about 100 MiB.
  const Scene big = load_scene(scene_path("stress/steps_1000.yaml"));
  EXPECT_LT(estimate_model_size(big, true).bytes, 128.0 * (1 << 20));
}

}  // namespace
}  // namespace disco
