#include "search/solve_scene.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <spdlog/fmt/fmt.h>

#include "core/config/solver_settings.h"
#include "core/model/model_size.h"
#include "core/util/clock.h"
#include "search/guess.h"
#include "search/trajectory.h"

namespace disco {

namespace {

// The certificate of the best point z: on the model solved and, for the
// adaptive model, on the full model too (core/model/model_plan.h), the worse of
// the two. False if the full model does not certify it.
bool certify_best(const Scene& scene, const RobotProblem& problem, const ElasticSettings& tol,
                  const Vector& z, Certificate& out) {
  out = certify(problem.program(), z);
  if (!problem.options().adaptive) return true;
  const RobotProblem full(scene, ModelOptions{false, problem.options().horizon_max});
  const Certificate c = certify(full.program(), problem.transfer(z, full));
  out.max_violation = std::max(out.max_violation, c.max_violation);
  out.max_complementarity = std::max(out.max_complementarity, c.max_complementarity);
  out.complementarity_product = std::max(out.complementarity_product, c.complementarity_product);
  return c.within(tol.violation_tol, tol.complementarity_tol);
}

// One stage of a start: its objective reduction on `problem`. A start from a trajectory
// first solves at (1 + guess_slack) times the trajectory's T_f.
ReductionResult reduce(RobotProblem& problem, const ElasticSolver& solver, const StartSpec& start,
                       ReductionSettings schedule, const SolveCallback& on_solve,
                       const IncumbentFunction& incumbent) {
  if (start.guess == GuessKind::kGiven)
    schedule.horizon = (1.0 + schedule.guess_slack) * start.given.seconds;
  return reduce_objective(
      problem, solver, schedule, [&](double T) { return make_guess(problem, start, T); },
      on_solve, make_perturbation(problem, start), incumbent);
}

// The coarse stage's counts and clock in front of the fine stage's.
void prepend(const ReductionResult& coarse, ReductionResult& fine) {
  const double dt = coarse.seconds;
  fine.nlp_solves += coarse.nlp_solves;
  fine.iterations += coarse.iterations;
  fine.kkt += coarse.kkt;
  fine.seconds += dt;
  if (fine.time_to_first_feasible >= 0) fine.time_to_first_feasible += dt;
  if (fine.time_to_best >= 0) fine.time_to_best += dt;
  for (auto& h : fine.history) h.seconds += dt;
  std::vector<SolveRecord> solves = coarse.solves;
  for (SolveRecord& r : solves) {
    r.coarse = true;
    r.improved = false;
  }
  solves.insert(solves.end(), fine.solves.begin(), fine.solves.end());
  fine.solves = std::move(solves);
}

}  // namespace

int coarse_steps(const Scene& scene, const ReductionSettings& schedule) {
  if (!(schedule.coarse_fraction > 0.0)) return 0;
  const int n = std::max(2, static_cast<int>(std::lround(schedule.coarse_fraction * scene.steps)));
  return n < scene.steps ? n : 0;
}

SceneSolve solve_scene(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s, const SolveCallback& on_solve,
                       const IncumbentFunction& incumbent) {
  const auto t0 = Clock::now();
  check_model_size(scene, model_options(settings).adaptive, memory_limit(settings));
  IpoptSolver ipopt(ipopt_settings(settings));
  // The budget caps the reduction, which gives every elastic solve only the time left.
  ReductionSettings schedule = start.schedule;
  if (time_budget_s > 0) {
    schedule.time_limit =
        schedule.time_limit > 0 ? std::min(schedule.time_limit, time_budget_s) : time_budget_s;
  }
  ElasticSolver solver(ipopt, start.elastic);

  // Coarse to fine: the start on the scene at fewer steps, then the full scene from its
  // answer (or, without one, from the start's own guess).
  StartSpec fine = start;
  std::optional<ReductionResult> coarse;
  if (const int n = start.guess == GuessKind::kGiven ? 0 : coarse_steps(scene, schedule); n > 0) {
    Scene small = scene;
    small.steps = n;
    RobotProblem problem(small, model_options(settings));
    SolveCallback on_coarse;
    if (on_solve) {
      on_coarse = [&](const SolveRecord& r) {
        SolveRecord c = r;
        c.coarse = true;
        c.improved = false;
        on_solve(c);
      };
    }
    coarse = reduce(problem, solver, start, schedule, on_coarse, {});
    if (coarse->found)
      fine = with_guess(start, {resample(paths_of(problem, coarse->best.z), scene.steps),
                                problem.horizon(coarse->best.z), fmt::format("coarse N_t = {}", n)});
    if (schedule.time_limit > 0)  // the fine stage has what is left (at once past its end)
      schedule.time_limit = std::max(1e-3, schedule.time_limit - coarse->seconds);
  }

  SceneSolve out;
  out.problem = std::make_unique<RobotProblem>(scene, model_options(settings));
  RobotProblem& problem = *out.problem;
  out.result = reduce(problem, solver, fine, schedule, on_solve, incumbent);
  if (coarse) prepend(*coarse, out.result);
  if (out.result.found &&
      !certify_best(scene, problem, start.elastic, out.result.best.z, out.info.certificate)) {
    out.result.found = false;  // never expected: the plan is a proof
    out.result.status = MpccStatus::kFailed;
    out.result.feasibility_detail = "not certified on the full model";
  }
  out.info.status = out.result.status;
  out.info.nlp_solves = out.result.nlp_solves;
  out.info.iterations = out.result.iterations;
  out.info.kkt_factorisations = out.result.kkt.factorisations;
  out.info.kkt_fallbacks = out.result.kkt.fallbacks;
  out.info.kkt_threshold_raises = out.result.kkt.threshold_raises;
  out.info.kkt_to_pivoted = out.result.kkt.to_pivoted;
  out.info.kkt_nested_dissection = out.result.kkt.nested_dissection;
  out.info.kkt_polish_rescues = out.result.kkt.polish_rescues;
  if (out.result.found) {
    out.z = out.result.best.z;
    out.info.stationarity = out.result.stationarity;
  } else if (!out.result.solves.empty()) {
    out.info.detail = out.result.feasibility_detail;
    out.info.certificate = out.result.solves.back().certificate;
    out.info.violations = problem.violations(out.result.last_attempt, start.elastic.violation_tol);
  }
  out.info.wall_s = seconds_since(t0);
  return out;
}

SceneSolve solve_scene(const Scene& scene, const Settings& settings, const SolveCallback& on_solve) {
  const StartSpec start =
      make_start(scene, 0, 0, reduction_settings(settings), elastic_settings(settings));
  return solve_scene(scene, settings, start, 0.0, on_solve);
}

}  // namespace disco
