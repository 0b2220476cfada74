#include "search/objective_reduction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "core/util/check.h"
#include "core/util/errors.h"
#include "core/util/numbers.h"

namespace disco {
namespace {
// A minimising step's T_f this far (relative) below its bound left the bound inactive.
constexpr double kInsideBound = 1e-6;
}  // namespace

ReductionSettings reduction_settings(const Settings& s) {
  ReductionSettings r;
  auto positive = [&](const std::string& key) {
    const double v = s.number(key);
    if (!(v > 0)) throw InputError(s.where(key) + ": key '" + key + "': must be positive");
    return v;
  };
  r.horizon_factor = positive("feasibility.horizon_factor");
  r.horizon_min = positive("feasibility.horizon_min");
  r.rate = positive("reduction.rate");
  if (r.rate >= 1) throw InputError(s.where("reduction.rate") + ": key 'reduction.rate': must be < 1");
  r.grow = positive("reduction.grow");
  r.shrink = positive("reduction.shrink");
  if (r.shrink >= 1)
    throw InputError(s.where("reduction.shrink") + ": key 'reduction.shrink': must be < 1");
  r.min_rate = positive("reduction.min_rate");
  r.max_solves = s.integer("reduction.max_solves");
  if (r.max_solves < 0)
    throw InputError(s.where("reduction.max_solves") + ": key 'reduction.max_solves': must be >= 0");
  r.step_iterations = s.integer("reduction.step_iterations");
  if (r.step_iterations < 1)
    throw InputError(s.where("reduction.step_iterations") +
                     ": key 'reduction.step_iterations': must be >= 1");
  r.time_limit = s.number("reduction.time_limit");
  if (r.time_limit < 0)
    throw InputError(s.where("reduction.time_limit") + ": key 'reduction.time_limit': must be >= 0");
  return r;
}

ReductionResult reduce_objective(RobotProblem& problem, ElasticSolver& solver,
                                 const ReductionSettings& cfg, const GuessFunction& guess,
                                 const SolveCallback& on_solve, const PerturbFunction& perturb) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  ReductionResult out;
  auto record = [&](const std::string& phase, double bound, const MpccResult& r, bool improved) {
    SolveRecord rec{phase, bound, problem.horizon(r.z), r.status, r.ipopt_status, r.certificate,
                    r.nlp_solves, r.iterations, r.seconds, improved};
    out.solves.push_back(rec);
    out.nlp_solves += r.nlp_solves;
    out.iterations += r.iterations;
    if (on_solve) on_solve(rec);
  };

  // 1. Feasibility at a fixed, generous horizon.
  const auto scale = problem.reference_time();
  double T = cfg.horizon_min;
  if (scale) T = std::max(T, cfg.horizon_factor * *scale);
  for (int attempt = 0; attempt < 3 && !out.found; ++attempt, T *= 2.0) {
    problem.fix_horizon(T);
    const Vector z0 = guess ? guess(T) : problem.straight_line_guess(T);
    MpccResult r = solver.solve(problem.program(), z0);
    out.feasibility_detail = to_string(r.status);
    out.status = r.status == MpccStatus::kElasticNotTight ? MpccStatus::kInfeasible : r.status;
    const bool ok = r.solved();
    record("feasibility", T, r, ok);
    if (ok) {
      out.found = true;
      out.best = std::move(r);
      out.T_best = problem.horizon(out.best.z);
      out.time_to_first_feasible = out.time_to_best = elapsed();
    }
    if (cfg.time_limit > 0 && elapsed() > cfg.time_limit) break;
  }
  if (!out.found) {
    out.seconds = elapsed();
    return out;
  }

  // 1b. Once more from a perturbation of the feasible point, if asked.
  if (perturb && !(cfg.time_limit > 0 && elapsed() > cfg.time_limit)) {
    const Perturbation p = perturb(out.best.z);
    DISCO_CHECK(p.seconds > 0.0, "a perturbation's horizon is positive");
    DISCO_CHECK(p.guess.size() == out.best.z.size(), "a perturbation's guess is a model point");
    problem.fix_horizon(p.seconds);
    MpccResult r = solver.solve(problem.program(), p.guess);
    const bool ok = r.solved();
    record("perturbed feasibility", p.seconds, r, ok);
    if (ok) {
      out.best = std::move(r);
      out.T_best = problem.horizon(out.best.z);
      out.time_to_best = elapsed();
    }
  }

  // 2. Inexact objective reduction.
  // Minimise T_f <= T_best from the best point (steps 2 and 3 below); true if
  // the solve converged (certified), i.e. the best point is now a local optimum.
  auto minimize = [&] {
    problem.limit_horizon(out.T_best);
    MpccResult r = solver.solve(problem.program(), out.best);
    const double T_f = problem.horizon(r.z);
    const bool improved = r.solved() && T_f < out.T_best;
    record("minimize", out.T_best, r, improved);
    if (improved) {
      out.best = std::move(r);
      out.T_best = T_f;
      out.time_to_best = elapsed();
      return true;
    }
    return r.solved();
  };
  double rate = cfg.rate;
  bool fixed_steps = false;
  bool at_local_optimum = false, minimized = false;
  const std::optional<double> lower_bound = problem.lower_bound();
  for (int k = 0; k < cfg.max_solves; ++k) {
    if (cfg.time_limit > 0 && elapsed() > cfg.time_limit) break;
    // Never ask for less than a valid lower bound: such a step cannot succeed.
    while (lower_bound && rate >= cfg.min_rate && (1.0 - rate) * out.T_best < *lower_bound)
      rate *= cfg.shrink;
    if (rate < cfg.min_rate) break;
    const double bound = (1.0 - rate) * out.T_best;
    if (fixed_steps) {
      problem.fix_horizon(bound);
    } else {
      problem.limit_horizon(bound);
      solver.set_iteration_limit(cfg.step_iterations);
    }
    MpccResult r = solver.solve(problem.program(), out.best);
    solver.set_iteration_limit(0);
    const double T_f = problem.horizon(r.z);
    const bool improved = r.solved() && T_f < out.T_best;
    record(fixed_steps ? "fixed step" : "reduction", bound, r, improved);
    if (!fixed_steps && r.status == MpccStatus::kFailed) {
      fixed_steps = true;  // minimising stalled: retry this bound as a fixed step
      continue;
    }
    if (improved) {
      out.best = std::move(r);
      out.T_best = T_f;
      out.time_to_best = elapsed();
      // A minimising step that converged strictly inside its bound is at a
      // local optimum: further steps only probe the homotopy and fail.
      if (!fixed_steps && T_f < bound * (1.0 - kInsideBound)) {
        at_local_optimum = true;
        break;
      }
      rate *= cfg.grow;
      rate = std::min(rate, 0.5);
      continue;
    }
    rate *= cfg.shrink;
    // The first fixed step that fails: the homotopy has passed the local
    // optimum's horizon, so minimise from the best point now (step 3 early).
    if (fixed_steps && !minimized && !(cfg.time_limit > 0 && elapsed() > cfg.time_limit)) {
      minimized = true;
      if (minimize()) {
        at_local_optimum = true;
        break;
      }
    }
  }
  // 3. From the last homotopy step to the local optimum.
  if (fixed_steps && !at_local_optimum && !(cfg.time_limit > 0 && elapsed() > cfg.time_limit))
    minimize();
  // Free the horizon again: the problem is the model itself for later users.
  problem.limit_horizon(kInf);
  out.status = MpccStatus::kSolved;
  out.seconds = elapsed();
  return out;
}

}  // namespace disco
