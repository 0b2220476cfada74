#include "search/solve_scene.h"

#include <chrono>

#include "core/config/solver_settings.h"

namespace disco {

SceneSolve solve_scene(const Scene& scene, const Settings& settings, const SolveCallback& on_solve) {
  const auto t0 = std::chrono::steady_clock::now();
  IpoptSolver ipopt(ipopt_options(settings));
  ElasticSolver solver(ipopt, elastic_settings(settings));
  const ReductionSettings reduction = reduction_settings(settings);

  SceneSolve out;
  out.problem = std::make_unique<RobotProblem>(scene);
  out.result = reduce_objective(*out.problem, solver, reduction, {}, on_solve);
  out.info.status = to_string(out.result.status);
  out.info.nlp_solves = out.result.nlp_solves;
  out.info.iterations = out.result.iterations;
  if (out.result.found) {
    out.z = out.result.best.z;
    out.info.certificate = certify(out.problem->program(), out.z);
  } else if (!out.result.solves.empty()) {
    out.info.detail = out.result.feasibility_detail;
    out.info.certificate = out.result.solves.back().certificate;
  }
  out.info.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace disco
