// The paper's seven test problems (configs/scenarios/paper/, listed by
// configs/benchmarks/paper.yaml): the dimensions of Tables III and V, equal
// single-robot closed-form times (the paper's LB), valid bounds, straight paths
// that really conflict, and a smoke solve of the one-robot problems A1 and A2.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/lower_bound.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "search/search_plan.h"
#include "search/solve_scene.h"

namespace disco {
namespace {

struct PaperScene {
  const char* id;
  int robots, force_dims, steps, K;
  bool contact;      // set B (contact, mu 0.3) or set A (avoid, d_s 0.01)
  double paper_lb;   // Tables IV and VI
};

const std::vector<PaperScene>& paper_scenes() {
  static const std::vector<PaperScene> scenes = {
      {"A1", 1, 2, 100, 16, false, 8.94}, {"A2", 1, 1, 100, 16, false, 9.75},
      {"A3", 4, 2, 50, 8, false, 8.944},  {"A4", 6, 2, 50, 4, false, 8.94},
      {"B1", 2, 2, 100, 16, true, 8.94},  {"B2", 3, 2, 50, 16, true, 8.94},
      {"B3", 3, 2, 50, 16, true, 8.94},
  };
  return scenes;
}

std::string scene_path(const std::string& id) {
  return std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/paper/" + id + ".yaml";
}

Scene load_paper(const std::string& id) { return load_scene(scene_path(id)); }

// The robot's move: start -> its (exact) target point.
std::array<double, 2> move(const Robot& rb) {
  return {rb.target.lower[kX] - rb.start[kX], rb.target.lower[kY] - rb.start[kY]};
}

// Every robot's straight time, checked equal; returns the common time.
double common_straight_time(const Scene& scene) {
  const auto t0 = straight_move_time(scene.robots[0], scene.gravity);
  EXPECT_TRUE(t0.has_value());
  for (const auto& rb : scene.robots) {
    const auto t = straight_move_time(rb, scene.gravity);
    EXPECT_TRUE(t.has_value()) << scene.name << " " << rb.name;
    if (!t || !t0) continue;
    EXPECT_TRUE(std::isfinite(*t)) << scene.name << " " << rb.name;
    EXPECT_NEAR(*t, *t0, 1e-9 * *t0) << scene.name << " " << rb.name;
  }
  return t0.value_or(NAN);
}

// Minimum centre distance of robots i and j over their straight paths. All
// robots share one closed-form time and one smoothstep profile, so both are at
// the same fraction s of their moves: p_i(s) = p_i(0) + s d_i, and the distance
// |r + s v| (r = p_j(0) - p_i(0), v = d_j - d_i) is minimised over s in [0, 1].
double min_straight_distance(const Robot& a, const Robot& b, double* at_fraction = nullptr) {
  const auto da = move(a), db = move(b);
  const double rx = b.start[kX] - a.start[kX], ry = b.start[kY] - a.start[kY];
  const double vx = db[0] - da[0], vy = db[1] - da[1];
  const double vv = vx * vx + vy * vy;
  const double s = vv == 0.0 ? 0.0 : std::clamp(-(rx * vx + ry * vy) / vv, 0.0, 1.0);
  if (at_fraction) *at_fraction = s;
  return std::hypot(rx + s * vx, ry + s * vy);
}

TEST(PaperScenes, LoadWithThePapersDimensionsAndPairModes) {
  for (const auto& p : paper_scenes()) {
    SCOPED_TRACE(p.id);
    const Scene scene = load_paper(p.id);
    EXPECT_EQ(scene.name, std::string("paper_") + p.id);
    EXPECT_EQ(static_cast<int>(scene.robots.size()), p.robots);
    EXPECT_EQ(scene.steps, p.steps);
    for (const auto& rb : scene.robots) {
      EXPECT_EQ(rb.force_dims, p.force_dims) << rb.name;
      EXPECT_EQ(rb.friction_edges, p.K) << rb.name;
      // Rest to rest, to an exact point; phi and omega free.
      for (int k : {kVx, kVy}) EXPECT_EQ(rb.start[k], 0.0) << rb.name;
      for (int k : {kX, kY, kVx, kVy}) EXPECT_EQ(rb.target.lower[k], rb.target.upper[k]) << rb.name;
      for (int k : {kVx, kVy}) EXPECT_EQ(rb.target.lower[k], 0.0) << rb.name;
      for (int k : {kPhi, kOmega}) {
        EXPECT_EQ(rb.target.lower[k], -kInf) << rb.name;
        EXPECT_EQ(rb.target.upper[k], kInf) << rb.name;
      }
    }
    const size_t n = scene.robots.size();
    EXPECT_EQ(scene.pairs.size(), n * (n - 1) / 2);
    for (const auto& pair : scene.pairs) {
      if (p.contact) {
        EXPECT_EQ(pair.mode, PairMode::kContact);
        EXPECT_DOUBLE_EQ(pair.mu, 0.3);
      } else {
        EXPECT_EQ(pair.mode, PairMode::kAvoid);
        EXPECT_DOUBLE_EQ(pair.safe_distance, 0.01);
      }
    }
  }
}

TEST(PaperScenes, EveryRobotHasTheSameValidStraightTime) {
  for (const auto& p : paper_scenes()) {
    SCOPED_TRACE(p.id);
    const Scene scene = load_paper(p.id);
    const double t = common_straight_time(scene);
    // The straight move is each robot's optimum (D_ef 1 along the force axis,
    // D_ef 2 along a diagonal), so the closed form is a true single-robot bound.
    for (const auto& rb : scene.robots) {
      const auto d = move(rb);
      const double len = std::hypot(d[0], d[1]);
      ASSERT_GT(len, 0.0) << rb.name;
      EXPECT_TRUE(straight_move_is_optimal(rb, d[0] / len, d[1] / len)) << rb.name;
    }
    // Close to the paper's LB (force_max was solved for it).
    EXPECT_NEAR(t, p.paper_lb, 5e-3);
    EXPECT_DOUBLE_EQ(scene_reference_time(scene).value(), t);
    const auto lb = scene_lower_bound(scene);
    if (p.contact) {
      EXPECT_FALSE(lb.has_value()) << "every robot is pushable in set B";
    } else {
      ASSERT_TRUE(lb.has_value());
      EXPECT_DOUBLE_EQ(*lb, t);
    }
    const RobotProblem problem(scene);
    const ModelSize size = problem.size();
    std::printf("%s: %zu robots, N_t %d, %s %.6f s, model %d variables / %d constraints / %d "
                "complementarity pairs\n",
                p.id, scene.robots.size(), scene.steps, p.contact ? "reference" : "LB", t,
                size.variables, size.constraints, size.complementarity_pairs);
  }
}

TEST(PaperScenes, StraightPathsConflictInEveryMultiRobotScene) {
  for (const auto& p : paper_scenes()) {
    if (p.robots < 2) continue;
    SCOPED_TRACE(p.id);
    const Scene scene = load_paper(p.id);
    int conflicts = 0;
    for (const auto& pair : scene.pairs) {
      const Robot& a = scene.robots[pair.i];
      const Robot& b = scene.robots[pair.j];
      const double clear =
          a.radius + b.radius + (pair.mode == PairMode::kAvoid ? pair.safe_distance : 0.0);
      double s = 0;
      const double dmin = min_straight_distance(a, b, &s);
      if (dmin < clear) {
        ++conflicts;
        std::printf("%s: %s and %s meet on their straight paths at fraction %.3f (distance "
                    "%.3f < %.3f)\n",
                    p.id, a.name.c_str(), b.name.c_str(), s, dmin, clear);
      }
    }
    EXPECT_GT(conflicts, 0);
  }
  // The designs' intent: A3's four robots all pairwise (through the centre),
  // A4's nine up-right/up-left pairs, two pairs in B2 and in B3.
  auto count = [](const char* id) {
    const Scene scene = load_paper(id);
    int n = 0;
    for (const auto& pair : scene.pairs)
      if (min_straight_distance(scene.robots[pair.i], scene.robots[pair.j]) < 1.0) ++n;
    return n;
  };
  EXPECT_EQ(count("A3"), 6);
  EXPECT_EQ(count("A4"), 9);
  EXPECT_EQ(count("B1"), 1);
  EXPECT_EQ(count("B2"), 2);
  EXPECT_EQ(count("B3"), 2);
}

TEST(PaperScenes, B2AndB3ShareRobotsAndStartsAndDifferInTargets) {
  const Scene b2 = load_paper("B2");
  const Scene b3 = load_paper("B3");
  ASSERT_EQ(b2.robots.size(), b3.robots.size());
  EXPECT_EQ(b2.steps, b3.steps);
  EXPECT_EQ(b2.gravity, b3.gravity);
  bool targets_differ = false;
  for (size_t i = 0; i < b2.robots.size(); ++i) {
    const Robot& a = b2.robots[i];
    const Robot& b = b3.robots[i];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.radius, b.radius);
    EXPECT_EQ(a.mass, b.mass);
    EXPECT_EQ(a.inertia, b.inertia);
    EXPECT_EQ(a.mu, b.mu);
    EXPECT_EQ(a.damping, b.damping);
    EXPECT_EQ(a.force_max, b.force_max);
    EXPECT_EQ(a.force_dims, b.force_dims);
    EXPECT_EQ(a.friction_edges, b.friction_edges);
    EXPECT_EQ(a.start, b.start);
    if (a.target.lower != b.target.lower || a.target.upper != b.target.upper)
      targets_differ = true;
  }
  EXPECT_TRUE(targets_differ);
  ASSERT_EQ(b2.pairs.size(), b3.pairs.size());
  for (size_t k = 0; k < b2.pairs.size(); ++k) {
    EXPECT_EQ(b2.pairs[k].mode, b3.pairs[k].mode);
    EXPECT_EQ(b2.pairs[k].mu, b3.pairs[k].mu);
  }
}

TEST(PaperScenes, BenchmarkListsTheSevenScenes) {
  const SearchPlan plan = load_search_plan(
      {std::string(DISCO_SOURCE_DIR) + "/configs/benchmarks/paper.yaml"}, 0, 1, {});
  ASSERT_EQ(plan.scenes.size(), paper_scenes().size());
  for (size_t k = 0; k < plan.scenes.size(); ++k) {
    const SceneJob& job = plan.scenes[k];
    EXPECT_EQ(job.scene.name, std::string("paper_") + paper_scenes()[k].id);
    EXPECT_EQ(job.starts, 64);  // at most: the 60 s per scene stop the hand-out first
    EXPECT_EQ(job.time_limit, 60.0);
    EXPECT_EQ(job.start_time_limit, 60.0);
  }
  EXPECT_EQ(plan.total_starts(), 7 * 64);
}

// Smoke check, not optimality: the one-robot problems solve to their closed form.
void expect_solves_to_bound(const char* id) {
  const Scene scene = load_paper(id);
  const double lb = scene_lower_bound(scene).value();
  const SceneSolve run = solve_scene(scene, Settings::load(default_settings_path()));
  ASSERT_TRUE(run.solved()) << id << ": " << to_string(run.info.status);
  const double err = (run.T_f() - lb) / lb;
  std::printf("%s: T_f %.6f s, LB %.6f s, rel. gap %.2e\n", id, run.T_f(), lb, err);
  EXPECT_GE(run.T_f(), lb * (1 - 1e-3));
  EXPECT_LE(std::abs(err), 1e-3);
}

TEST(PaperScenes, A1SolvesToItsBound) { expect_solves_to_bound("A1"); }
TEST(PaperScenes, A2SolvesToItsBound) { expect_solves_to_bound("A2"); }

}  // namespace
}  // namespace disco
