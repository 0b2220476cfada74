#include "search/solve_scene.h"

#include <algorithm>
#include <chrono>

#include "core/config/solver_settings.h"

namespace disco {

SceneSolve solve_scene(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s, const SolveCallback& on_solve) {
  const auto t0 = std::chrono::steady_clock::now();
  IpoptSolver ipopt(ipopt_options(settings));
  // The budget caps the reduction, which gives every elastic solve only the time left.
  ReductionSettings schedule = start.schedule;
  if (time_budget_s > 0) {
    schedule.time_limit =
        schedule.time_limit > 0 ? std::min(schedule.time_limit, time_budget_s) : time_budget_s;
  }
  ElasticSolver solver(ipopt, start.elastic);

  SceneSolve out;
  out.problem = std::make_unique<RobotProblem>(scene);
  RobotProblem& problem = *out.problem;
  out.result = reduce_objective(
      problem, solver, schedule, [&](double T) { return make_guess(problem, start, T); },
      on_solve, make_perturbation(problem, start));
  out.info.status = to_string(out.result.status);
  out.info.nlp_solves = out.result.nlp_solves;
  out.info.iterations = out.result.iterations;
  if (out.result.found) {
    out.z = out.result.best.z;
    out.info.certificate = certify(problem.program(), out.z);
  } else if (!out.result.solves.empty()) {
    out.info.detail = out.result.feasibility_detail;
    out.info.certificate = out.result.solves.back().certificate;
  }
  out.info.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

SceneSolve solve_scene(const Scene& scene, const Settings& settings, const SolveCallback& on_solve) {
  const StartSpec start =
      make_start(scene, 0, 0, reduction_settings(settings), elastic_settings(settings));
  return solve_scene(scene, settings, start, 0.0, on_solve);
}

}  // namespace disco
