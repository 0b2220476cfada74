// Outcomes of whole solves that are not optima: infeasible scenes end with
// status "infeasible" (never a crash, a hang or a false "solved").
#include <gtest/gtest.h>

#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "search/solve_scene.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

TEST(SolveOutcomes, ASpinningRobotThatDampingStopsShortOfItsPhiTargetIsInfeasible) {
  const Scene scene = parse_scene(model_test::kSpinShortScene, "spin_short.yaml");
  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  EXPECT_FALSE(run.solved());
  EXPECT_EQ(run.info.status, MpccStatus::kInfeasible);
  EXPECT_EQ(run.z.size(), 0);
  // Three feasibility attempts, the horizon doubling, each on a model built
  // for its own horizon (the adaptive model's T_max, core/model/model_plan.h).
  const double T0 = feasibility_horizon(*run.problem, reduction_settings(Settings::load(default_settings_path())));
  ASSERT_EQ(run.result.solves.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(run.result.solves[k].bound, T0 * (1 << k));
  EXPECT_EQ(run.problem->options().horizon_max, run.result.solves[2].bound);
}

TEST(SolveOutcomes, ForceAxisThatCannotReachTheTargetIsRejectedBeforeSolving) {
  // D_ef = 1 along x, target off the x axis: no force can move the robot in y, and the scene
  // says so before any solve (core/model/reachability.h).
  try {
    parse_scene(R"(
scenario: off_axis
steps: 10
robots:
  - name: a
    radius: 0.5
    mass: 1.0
    mu: 0.2
    force_max: 5.0
    force_dims: 1
    K: 8
    start: {x: 0, y: 0}
    target: {x: 3, y: 1, vx: 0, vy: 0}
)",
                "off_axis.yaml");
    FAIL() << "an off-axis target was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("off_axis.yaml:13: key 'robots[0].target': unreachable: robot 'a'"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace disco
