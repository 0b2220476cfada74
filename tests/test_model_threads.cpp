// Bitwise thread invariance of the robot model (core/nlp/polynomial_program.h
// promises: "each output is summed by one thread in a fixed order, so results
// are bitwise identical for any thread count").
//
// 1. Evaluations: with the parallel threshold lowered so that every OpenMP
//    loop forks (PolynomialProgram::set_parallel_threshold), constraints,
//    Jacobian and Hessian values at a random point must be the same bits with
//    1, 2 and 3 threads.
// 2. A whole elastic solve (configs/scenarios/one_robot_axis.yaml, 20 steps,
//    solvers made from configs/disco.yaml) must end at the same bits with 1
//    and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>
#include <string>

#include "search/guess.h"
#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"

namespace disco {
namespace {

// Loops over at least this many outputs fork; set on every program here.
constexpr int kParallelMin = 2;

std::string scenario(const std::string& file) {
  return std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + file;
}

bool same_bits(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// Sets the OpenMP thread count (no dynamic adjustment) and restores the
// previous settings when it goes out of scope.
class ThreadCount {
 public:
  ThreadCount() : threads_(omp_get_max_threads()), dynamic_(omp_get_dynamic()) {
    omp_set_dynamic(0);
  }
  ~ThreadCount() {
    omp_set_num_threads(threads_);
    omp_set_dynamic(dynamic_);
  }
  void set(int n) {
    omp_set_num_threads(n);
    int team = 0;
#pragma omp parallel
    {
#pragma omp single
      team = omp_get_num_threads();
    }
    ASSERT_EQ(team, n) << "OpenMP would not give " << n << " threads";
  }

 private:
  int threads_, dynamic_;
};

struct Evaluation {
  Vector c, jac, hess;
};

Evaluation evaluate(const PolynomialProgram& P, const Vector& z, double sigma,
                    const Vector& lambda) {
  Evaluation e{Vector(P.num_constraints()), Vector(P.jacobian_pattern().size()),
               Vector(P.hessian_pattern().size())};
  EXPECT_TRUE(P.constraints(z, e.c));
  EXPECT_TRUE(P.jacobian(z, e.jac));
  EXPECT_TRUE(P.hessian(z, sigma, lambda, e.hess));
  return e;
}

TEST(ModelThreads, EvaluationsAreBitwiseIdenticalForAnyThreadCount) {
  RobotProblem rp(load_scene(scenario("three_robots_contact.yaml"), {"steps=100"}));
  rp.program().set_parallel_threshold(kParallelMin);
  const PolynomialProgram& P = rp.program();
  // Every loop of the evaluator must actually run in parallel.
  ASSERT_GE(P.num_constraints(), kParallelMin);
  ASSERT_GE(P.jacobian_pattern().size(), kParallelMin);
  ASSERT_GE(P.hessian_pattern().size(), kParallelMin);

  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Vector z(P.num_variables()), lambda(P.num_constraints());
  for (int k = 0; k < z.size(); ++k) z[k] = u(rng);
  for (int r = 0; r < lambda.size(); ++r) lambda[r] = u(rng);
  const double sigma = 0.75;

  ThreadCount threads;
  threads.set(1);
  const Evaluation one = evaluate(P, z, sigma, lambda);
  for (int n : {2, 3}) {
    SCOPED_TRACE(std::to_string(n) + " threads");
    threads.set(n);
    const Evaluation many = evaluate(P, z, sigma, lambda);
    EXPECT_TRUE(same_bits(one.c, many.c));
    EXPECT_TRUE(same_bits(one.jac, many.jac));
    EXPECT_TRUE(same_bits(one.hess, many.hess));
  }
  // Not a vacuous comparison: the values are not all zero.
  EXPECT_GT(one.c.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(one.jac.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(one.hess.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ModelThreads, ElasticSolveIsBitwiseIdenticalWithOneAndTwoThreads) {
  const Scene scene = load_scene(scenario("one_robot_axis.yaml"), {"steps=20"});
  const Settings settings = Settings::load(default_settings_path());

  auto solve = [&](int n) {
    ThreadCount threads;
    threads.set(n);
    RobotProblem rp(scene);
    rp.program().set_parallel_threshold(kParallelMin);
    // At least the Jacobian loop forks with two threads.
    EXPECT_GE(rp.program().jacobian_pattern().size(), kParallelMin);
    IpoptSolver ipopt(ipopt_settings(settings));
    ElasticSolver solver(ipopt, elastic_settings(settings));
    // The feasibility phase (fixed, generous horizon), then a free horizon
    // below it, warm-started: both phases of the objective reduction.
    const double T = 2.0 * rp.lower_bound().value();
    rp.fix_horizon(T);
    const MpccResult feasible = solver.solve(rp.program(), smoothstep_guess(rp, T));
    rp.limit_horizon(0.95 * T);
    MpccResult faster = solver.solve(rp.program(), feasible);
    return std::make_pair(feasible, faster);
  };
  const auto [feasible1, faster1] = solve(1);
  const auto [feasible2, faster2] = solve(2);

  EXPECT_TRUE(feasible1.solved()) << to_string(feasible1.status);
  EXPECT_TRUE(faster1.solved()) << to_string(faster1.status);
  EXPECT_GT(feasible1.iterations, 0);
  EXPECT_EQ(feasible1.iterations, feasible2.iterations);
  EXPECT_EQ(faster1.iterations, faster2.iterations);
  EXPECT_EQ(feasible1.status, feasible2.status);
  EXPECT_EQ(faster1.status, faster2.status);
  EXPECT_TRUE(same_bits(feasible1.z, feasible2.z));
  EXPECT_TRUE(same_bits(faster1.z, faster2.z));
  EXPECT_TRUE(same_bits(faster1.elastic_point.lambda, faster2.elastic_point.lambda));
}

}  // namespace
}  // namespace disco
