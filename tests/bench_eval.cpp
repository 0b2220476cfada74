// Evaluation speed of the robot model with 1 and 2 OpenMP threads (a benchmark,
// not a test: scripts/bench_search runs it and prints the ratio).
//
//   bench_eval SCENE.yaml [REPEATS]
// Times REPEATS evaluations of constraints + Jacobian + Hessian at a fixed
// point, with the default parallel threshold and with every loop forked.
#include <omp.h>

#include <cstdio>
#include <random>
#include <string>

#include "core/elastic/elastic_nlp.h"
#include "core/util/clock.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"

using namespace disco;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_eval SCENE.yaml [REPEATS]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 2000;
  RobotProblem rp(load_scene(argv[1]));
  const ElasticNlp nlp(rp.program(), ElasticFormulation::kLumped, 10.0);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector z(nlp.num_variables()), lambda(nlp.num_constraints());
  for (auto& v : z) v = u(rng);
  for (auto& v : lambda) v = u(rng);
  Vector c(nlp.num_constraints()), jac(nlp.jacobian_pattern().size()),
      hess(nlp.hessian_pattern().size());
  std::printf("scene %s: %d variables, %d rows, %d Jacobian and %d Hessian nonzeros (elastic NLP)\n",
              argv[1], nlp.num_variables(), nlp.num_constraints(), static_cast<int>(jac.size()),
              static_cast<int>(hess.size()));
  auto time_it = [&](int threads) {
    omp_set_num_threads(threads);
    const Stopwatch stopwatch;
    for (int k = 0; k < repeats; ++k) {
      nlp.constraints(z, c);
      nlp.jacobian(z, jac);
      nlp.hessian(z, 1.0, lambda, hess);
    }
    return stopwatch.seconds() / repeats;
  };
  for (int threshold : {PolynomialProgram::kDefaultParallelMin, 1}) {
    rp.program().set_parallel_threshold(threshold);
    time_it(1);  // warm up
    const double one = time_it(1), two = time_it(2);
    std::printf("parallel threshold %6d: 1 thread %.1f us, 2 threads %.1f us, speed-up %.2f\n",
                threshold, 1e6 * one, 1e6 * two, one / two);
  }
  return 0;
}
