// Trajectories to start from (search/trajectory.h): resampling, reading a solution file
// against a scene, and the starts that use them (--guess, coarse to fine:
// search/solve_scene.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "core/model/solution.h"
#include "core/util/errors.h"
#include "search/guess.h"
#include "search/solve_scene.h"
#include "search/trajectory.h"

namespace disco {
namespace {

using json = nlohmann::json;

Scene swap_scene(int steps) {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/two_robots_swap_avoid.yaml",
                    {"steps=" + std::to_string(steps)});
}

// The solution document of the detour-left guess of `scene` at `seconds` (not a solution
// of the model: any point has a trajectory).
json detour_document(const RobotProblem& problem, double seconds, Vector* z_out = nullptr) {
  const Vector z = complete_guess(problem, detour_paths(problem.scene(), +1), seconds);
  if (z_out != nullptr) *z_out = z;
  SolutionInfo info;
  info.status = MpccStatus::kSolved;
  return solution_json(problem, z, info);
}

// The message of the InputError `f` throws, or "" (a test failure) if it throws none.
template <class F>
std::string input_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(Trajectory, ResamplingInterpolatesLinearlyAtTheSameFractionAndKeepsBothEnds) {
  // A path of 4 steps along x = t^2 (a parabola: interpolation is exact only at the old
  // states), y = 3 t, phi = -t.
  std::vector<Pose> path;
  for (int t = 0; t <= 4; ++t) path.push_back({double(t * t), 3.0 * t, -double(t)});
  const Paths out = resample({path}, 8);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].size(), 9u);
  for (int t = 0; t <= 8; ++t) {
    const double u = t / 2.0;  // the old continuous step
    const int k = std::min(3, int(std::floor(u)));
    const double x = k * k + (u - k) * ((k + 1) * (k + 1) - k * k);
    EXPECT_DOUBLE_EQ(out[0][t][0], x) << t;
    EXPECT_DOUBLE_EQ(out[0][t][1], 1.5 * t) << t;
    EXPECT_DOUBLE_EQ(out[0][t][2], -u) << t;
  }
  // To the same steps: the path itself; to fewer: its ends exactly.
  EXPECT_EQ(resample({path}, 4)[0], path);
  const Paths coarse = resample({path}, 3);
  EXPECT_EQ(coarse[0].front(), path.front());
  EXPECT_EQ(coarse[0].back(), path.back());
}

TEST(Trajectory, ASolutionFileOfTheSameSceneGivesItsOwnPathsAndHorizon) {
  const Scene scene = swap_scene(12);
  const RobotProblem problem(scene, ModelOptions{});
  Vector z;
  const json doc = detour_document(problem, 3.0, &z);
  const Trajectory t = trajectory_from_solution(json::parse(doc.dump()), scene, "f.json");
  EXPECT_EQ(t.source, "f.json");
  EXPECT_DOUBLE_EQ(t.seconds, 3.0);
  const Paths want = paths_of(problem, z);
  ASSERT_EQ(t.paths.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    for (int s = 0; s <= scene.steps; ++s)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(t.paths[i][s][d], want[i][s][d], 1e-12) << i << " " << s;
}

TEST(Trajectory, ASolutionAtOtherStepsIsResampledToTheScenesSteps) {
  const Scene coarse = swap_scene(6), fine = swap_scene(12);
  const RobotProblem problem(coarse, ModelOptions{});
  Vector z;
  const json doc = detour_document(problem, 3.0, &z);
  const Trajectory t = trajectory_from_solution(doc, fine, "coarse.json");
  const Paths old = paths_of(problem, z);
  ASSERT_EQ(t.paths[0].size(), 13u);
  for (std::size_t i = 0; i < old.size(); ++i)
    for (int s = 0; s <= 6; ++s)  // every second fine state is a coarse one
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(t.paths[i][2 * s][d], old[i][s][d], 1e-12);
}

TEST(Trajectory, AFileThatDoesNotMatchTheSceneIsAnInputErrorSayingHow) {
  const Scene scene = swap_scene(8);
  const RobotProblem problem(scene, ModelOptions{});
  const json good = detour_document(problem, 3.0);

  json renamed = good;
  renamed["robots"][0]["name"] = "alice";
  std::string m = input_error([&] { trajectory_from_solution(renamed, scene, "g.json"); });
  EXPECT_NE(m.find("--guess g.json: its robots do not match scene 'two_robots_swap_avoid'"),
            std::string::npos) << m;
  EXPECT_NE(m.find("robot 1 is 'alice' there, '" + scene.robots[0].name + "' in the scene"),
            std::string::npos) << m;

  json fewer = good;
  fewer["robots"].erase(1);
  m = input_error([&] { trajectory_from_solution(fewer, scene, "g.json"); });
  EXPECT_NE(m.find("1 there (" + scene.robots[0].name + "), 2 in the scene"), std::string::npos) << m;

  json moved = good;
  moved["robots"][1]["x"][0] = moved["robots"][1]["x"][0].get<double>() + 0.5;
  m = input_error([&] { trajectory_from_solution(moved, scene, "g.json"); });
  EXPECT_NE(m.find("robot '" + scene.robots[1].name + "' starts at"), std::string::npos) << m;

  json none = good;
  none["T_f"] = nullptr;
  none["status"] = "infeasible";
  m = input_error([&] { trajectory_from_solution(none, scene, "g.json"); });
  EXPECT_NE(m.find("holds no trajectory (T_f is null, status infeasible)"), std::string::npos) << m;

  json short_x = good;
  short_x["robots"][0]["x"].erase(0);
  m = input_error([&] { trajectory_from_solution(short_x, scene, "g.json"); });
  EXPECT_NE(m.find("'x' must be an array of N_t + 1 = 9 numbers"), std::string::npos) << m;

  m = input_error([&] { trajectory_from_solution(json::array(), scene, "g.json"); });
  EXPECT_NE(m.find("not a solution file"), std::string::npos) << m;
  m = input_error([&] { read_guess_file("/no/such/file.json", scene); });
  EXPECT_NE(m.find("--guess /no/such/file.json: cannot be read"), std::string::npos) << m;
}

TEST(Trajectory, AStartFromASolutionAtOtherStepsIsCertifiedAndBeginsAtTheSlackedHorizon) {
  const Settings settings = Settings::load(default_settings_path());
  const ReductionSettings schedule = reduction_settings(settings);
  // A certified solution at 8 steps, then a start from it at 16.
  const Scene coarse = swap_scene(8), fine = swap_scene(16);
  const SceneSolve first = solve_scene(coarse, settings);
  ASSERT_TRUE(first.solved());
  const json doc = solution_json(*first.problem, first.z, first.info);
  StartSpec start = make_start(fine, 1, 0, schedule, elastic_settings(settings));
  start = with_guess(start, trajectory_from_solution(doc, fine, "first"));
  const SceneSolve run = solve_scene(fine, settings, start);
  ASSERT_TRUE(run.solved());
  EXPECT_LE(run.info.certificate.max_violation, elastic_settings(settings).violation_tol);
  EXPECT_LE(run.info.certificate.max_complementarity,
            elastic_settings(settings).complementarity_tol);
  ASSERT_FALSE(run.result.solves.empty());
  EXPECT_EQ(run.result.solves.front().kind, SolveKind::kFeasibility);
  EXPECT_DOUBLE_EQ(run.result.solves.front().bound, (1.0 + schedule.guess_slack) * first.T_f());
}

TEST(Trajectory, ACoarseToFineStartSolvesFewerStepsFirstAndNeverTakesACoarseBest) {
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("feasibility.coarse_fraction=0.5");
  const Scene scene = swap_scene(12);
  const ReductionSettings schedule = reduction_settings(settings);
  EXPECT_EQ(coarse_steps(scene, schedule), 6);
  const StartSpec start = make_start(scene, 1, 0, schedule, elastic_settings(settings));
  EXPECT_NE(start.describe().find("coarse 0.50 N_t first"), std::string::npos) << start.describe();
  int logged_coarse = 0;
  const SceneSolve run = solve_scene(scene, settings, start, 0.0, [&](const SolveRecord& r) {
    if (r.coarse) ++logged_coarse;
  });
  ASSERT_TRUE(run.solved());
  const auto& solves = run.result.solves;
  ASSERT_GT(logged_coarse, 0);
  int coarse = 0, iterations = 0;
  for (std::size_t k = 0; k < solves.size(); ++k) {
    if (solves[k].coarse) {
      EXPECT_EQ(int(k), coarse) << "the coarse solves come first";
      EXPECT_FALSE(solves[k].improved);
      ++coarse;
    }
    iterations += solves[k].iterations;
  }
  EXPECT_EQ(coarse, logged_coarse);
  ASSERT_LT(coarse, int(solves.size()));
  EXPECT_EQ(iterations, run.result.iterations);
  // The fine stage began from the coarse answer: its first solve is a feasibility solve at
  // (1 + guess_slack) times a coarse T_f that the coarse stage certified.
  const SolveRecord& first_fine = solves[coarse];
  EXPECT_EQ(first_fine.kind, SolveKind::kFeasibility);
  bool from_a_coarse_best = false;
  for (int k = 0; k < coarse; ++k)
    if (solves[k].status == MpccStatus::kSolved &&
        std::abs(first_fine.bound - (1.0 + schedule.guess_slack) * solves[k].T_f) < 1e-12)
      from_a_coarse_best = true;
  EXPECT_TRUE(from_a_coarse_best);
  // The history is the fine stage's bests, on the start's clock (after the coarse stage).
  ASSERT_FALSE(run.result.history.empty());
  double coarse_seconds = 0.0;
  for (int k = 0; k < coarse; ++k) coarse_seconds += solves[k].seconds;
  EXPECT_GE(run.result.history.front().seconds, coarse_seconds);
  EXPECT_EQ(run.result.history.back().value, run.T_f());

  // A fraction that leaves no fewer steps: no coarse stage.
  settings.apply_override("feasibility.coarse_fraction=0.99");
  EXPECT_EQ(coarse_steps(scene, reduction_settings(settings)), 0);
}

}  // namespace
}  // namespace disco
