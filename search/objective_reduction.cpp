#include "search/objective_reduction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include <spdlog/fmt/fmt.h>

#include "core/config/solver_settings.h"
#include "core/util/check.h"
#include "core/util/errors.h"
#include "core/util/numbers.h"

namespace disco {
namespace {
// A minimising step's T_f this far (relative) below its bound left the bound inactive.
constexpr double kInsideBound = 1e-6;
// A new best must be this much (relative) below the old one.
constexpr double kBetter = 1e-7;

// A minimisation by Minimizer::kBranch (see objective_reduction.h). `solve`, `budget`, `record`,
// `take_best` and `out_of_time` are reduce_objective's: one elastic solve under the time
// limit, the wall limit for the next solve, the solve log, "this certified result is the new
// best", and whether the time limit has passed.
template <class Solve, class Budget, class Record, class TakeBest, class OutOfTime>
void branch_descent(RobotProblem& problem, ElasticSolver& solver, const ReductionSettings& cfg,
                    ReductionResult& out, Solve&& solve, Budget&& budget, Record&& record,
                    TakeBest&& take_best, OutOfTime&& out_of_time) {
  // A branch descent from `from` (certified or not) under T_f <= T_best; true if it improved.
  auto branch = [&](const MpccResult& from) {
    problem.limit_horizon(out.T_best);
    budget();
    solver.set_iteration_limit(0);
    MpccResult r = solver.solve_branch(problem.program(), from, cfg.flip_rounds);
    const double T_f = problem.horizon(r.z);
    const bool improved = r.solved() && T_f < out.T_best * (1.0 - kBetter);
    record("branch", out.T_best, r, improved);
    if (improved) take_best(std::move(r));
    return improved;
  };
  // One segment of the elastic minimisation: at most step_iterations Ipopt iterations from
  // `from` under T_f <= bound.
  auto segment = [&](const MpccResult& from, double bound) {
    problem.limit_horizon(bound);
    solver.set_iteration_limit(cfg.step_iterations);
    MpccResult r = solve(from);
    solver.set_iteration_limit(0);
    const bool improved = r.solved() && problem.horizon(r.z) < out.T_best * (1.0 - kBetter);
    record("minimize", bound, r, improved);
    if (improved) take_best(MpccResult(r));
    return std::make_pair(std::move(r), improved);
  };
  // From the best point to a local optimum.
  // a. One segment from the best point. Converged, it is a local optimum (one-robot scenes
  // end here); else a branch descent from its point. (A branch descent straight from the
  // feasible point commits to the branch of a slow motion: on paper A1 the elastic
  // minimisation from there ended 2 % above the optimum it reaches from the feasible point.)
  {
    auto [r, improved] = segment(out.best, out.T_best);
    if (!out_of_time()) branch(r);
    if (r.solved()) return;
  }
  // b. More segments, the first from the best branch point, each continuing the last (its
  // primal-dual point and barrier parameter) and bounded by the T_f it starts from (the
  // bound never forces it); after each one that ends below the best, a branch descent from
  // its point (the smaller side of every pair fixed: even at complementarity 3e-2 that was
  // the branch of a new best, on three_robots_contact).
  MpccResult from = out.best;
  double T_from = out.T_best;
  int idle = 0;  // segments in a row that gave no new best
  solver.set_resume_barrier(true);
  for (int k = 0; k < cfg.max_solves && !out_of_time(); ++k) {
    auto [r, better] = segment(from, T_from);
    T_from = problem.horizon(r.z);
    if (!out_of_time() && T_from < out.T_best) better = branch(r) || better;
    // A segment that converged (certified) is a local optimum of the elastic program.
    if (r.solved() || r.status == MpccStatus::kInfeasible) break;
    // Not tight: raising zeta no longer moves it, and the next segment starts where it ended.
    if (r.status == MpccStatus::kElasticNotTight && !better) break;
    idle = better ? 0 : idle + 1;
    if (idle >= 2) break;
    from = std::move(r);
  }
  solver.set_resume_barrier(false);
}
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
  r.minimize_iterations = s.integer("reduction.minimize_iterations");
  if (r.minimize_iterations < 0)
    throw InputError(s.where("reduction.minimize_iterations") +
                     ": key 'reduction.minimize_iterations': must be >= 0");
  r.minimizer = choice<Minimizer>(s, "reduction.minimize",
                                  {{"elastic", Minimizer::kElastic}, {"branch", Minimizer::kBranch}});
  r.flip_rounds = s.integer("reduction.flip_rounds");
  if (r.flip_rounds < 0)
    throw InputError(s.where("reduction.flip_rounds") + ": key 'reduction.flip_rounds': must be >= 0");
  r.time_limit = s.number("reduction.time_limit");
  if (r.time_limit < 0)
    throw InputError(s.where("reduction.time_limit") + ": key 'reduction.time_limit': must be >= 0");
  return r;
}

double feasibility_horizon(const RobotProblem& problem, const ReductionSettings& cfg) {
  const auto scale = problem.reference_time();
  return scale ? std::max(cfg.horizon_min, cfg.horizon_factor * *scale) : cfg.horizon_min;
}

std::string solve_log_header() {
  return fmt::format("{:>3} {:<11} {:>10} {:>10} {:<17} {:>9} {:>9} {:>4} {:>5} {:>7}", "#",
                     "phase", "bound[s]", "T_f[s]", "status", "compl", "viol", "nlp", "iter",
                     "sec");
}

std::string solve_log_line(int number, const SolveRecord& r) {
  return fmt::format(
      "{:>3} {:<11} {:>10.5f} {:>10.5f} {:<17} {:>9.1e} {:>9.1e} {:>4} {:>5} {:>7.3f}{}", number,
      r.phase, r.bound, r.T_f, to_string(r.status), r.certificate.max_complementarity,
      r.certificate.max_violation, r.nlp_solves, r.iterations, r.seconds,
      r.improved                          ? std::string("  *")
      : r.status == MpccStatus::kFailed ? "  (Ipopt: " + ipopt_status_name(r.ipopt_status) + ")"
                                          : std::string());
}

ReductionResult reduce_objective(RobotProblem& problem, ElasticSolver& solver,
                                 const ReductionSettings& cfg, const GuessFunction& guess,
                                 const SolveCallback& on_solve, const PerturbFunction& perturb) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  ReductionResult out;
  // Every elastic solve gets at most the time left (and its own limit, if smaller).
  const double own_wall_limit = solver.settings().wall_limit_s;
  auto budget = [&] {  // the next solve's wall limit
    if (cfg.time_limit > 0) {
      const double left = std::max(cfg.time_limit - elapsed(), 1e-3);
      solver.set_wall_limit(own_wall_limit > 0 ? std::min(own_wall_limit, left) : left);
    }
  };
  auto solve = [&](const auto& start) {
    budget();
    return solver.solve(problem.program(), start);
  };
  auto record = [&](const std::string& phase, double bound, const MpccResult& r, bool improved) {
    SolveRecord rec{phase, bound, problem.horizon(r.z), r.status, r.ipopt_status, r.certificate,
                    r.nlp_solves, r.iterations, r.seconds, improved};
    out.solves.push_back(rec);
    out.nlp_solves += r.nlp_solves;
    out.iterations += r.iterations;
    if (on_solve) on_solve(rec);
  };
  // `r` (certified, T_f below the best so far) becomes the best point.
  auto take_best = [&](MpccResult&& r) {
    out.best = std::move(r);
    out.T_best = problem.horizon(out.best.z);
    out.time_to_best = elapsed();
    out.history.push_back({out.time_to_best, out.T_best});
  };

  // 1. Feasibility at a fixed, generous horizon.
  double T = feasibility_horizon(problem, cfg);
  for (int attempt = 0; attempt < 3 && !out.found; ++attempt, T *= 2.0) {
    problem.set_horizon_max(T);
    problem.fix_horizon(T);
    const Vector z0 = guess ? guess(T) : problem.straight_line_guess(T);
    MpccResult r = solve(z0);
    // A failure says why: Ipopt's own status (Invalid_Number_Detected: an evaluation gave
    // NaN or Inf, which the Nlp wrapper turns into a failed callback).
    out.feasibility_detail = to_string(r.status);
    if (r.status == MpccStatus::kFailed)
      out.feasibility_detail += " (Ipopt: " + ipopt_status_name(r.ipopt_status) + ")";
    out.status = r.status == MpccStatus::kElasticNotTight ? MpccStatus::kInfeasible : r.status;
    const bool ok = r.solved();
    record("feasibility", T, r, ok);
    if (ok) {
      out.found = true;
      take_best(std::move(r));
      out.time_to_first_feasible = out.time_to_best;
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
    DISCO_CHECK(p.seconds > 0.0 && p.seconds <= out.T_best,
                "a perturbation's horizon is positive and at most the feasible one");
    DISCO_CHECK(p.guess.size() == out.best.z.size(), "a perturbation's guess is a model point");
    problem.fix_horizon(p.seconds);
    MpccResult r = solve(p.guess);
    const bool ok = r.solved();
    record("perturbed feasibility", p.seconds, r, ok);
    if (ok) take_best(std::move(r));
  }

  // 2. Inexact objective reduction.
  // Minimise T_f <= T_best from the best point (steps 2 and 3 below); true if
  // the solve converged (certified), i.e. the best point is now a local optimum.
  auto out_of_time = [&] { return cfg.time_limit > 0 && elapsed() > cfg.time_limit; };
  auto minimize = [&](int iteration_limit) {
    if (cfg.minimizer == Minimizer::kBranch) {
      branch_descent(problem, solver, cfg, out, solve, budget, record, take_best, out_of_time);
      return true;  // a local optimum: a descent stops at one, or at the time limit
    }
    problem.limit_horizon(out.T_best);
    solver.set_iteration_limit(iteration_limit);
    MpccResult r = solve(out.best);
    solver.set_iteration_limit(0);
    const double T_f = problem.horizon(r.z);
    const bool improved = r.solved() && T_f < out.T_best;
    record("minimize", out.T_best, r, improved);
    if (improved) {
      take_best(std::move(r));
      return true;
    }
    return r.solved();
  };
  double rate = cfg.rate;
  bool fixed_steps = false;
  bool at_local_optimum = false;  // the best point is a converged minimisation's
  bool minimized = false;         // minimised since the last improving fixed step
  bool cut_short = false;         // an early minimisation hit minimize_iterations
  // No step is asked below a valid lower bound, nor below the smallest horizon the
  // model allows (RobotProblem keeps h > 0): a fixed step there would leave T_best
  // outside the model's own bounds on T_f, so its point could not be certified on it.
  problem.limit_horizon(kInf);
  const double smallest = std::max(problem.lower_bound().value_or(0.0),
                                   problem.horizon(problem.program().variable_lower()));
  for (int k = 0; k < cfg.max_solves; ++k) {
    if (out_of_time()) break;
    // Never ask for less than that: such a step cannot succeed.
    while (rate >= cfg.min_rate && (1.0 - rate) * out.T_best < smallest) rate *= cfg.shrink;
    if (rate < cfg.min_rate) break;
    const double bound = (1.0 - rate) * out.T_best;
    if (fixed_steps) {
      problem.fix_horizon(bound);
    } else {
      problem.limit_horizon(bound);
      solver.set_iteration_limit(cfg.step_iterations);
    }
    MpccResult r = solve(out.best);
    solver.set_iteration_limit(0);
    const double T_f = problem.horizon(r.z);
    const bool improved = r.solved() && T_f < out.T_best;
    record(fixed_steps ? "fixed step" : "reduction", bound, r, improved);
    if (!fixed_steps && r.status == MpccStatus::kFailed) {
      fixed_steps = true;  // minimising stalled: retry this bound as a fixed step
      continue;
    }
    if (improved) {
      take_best(std::move(r));
      rate = std::min(rate * cfg.grow, 0.5);
      // A minimising step that converged strictly inside its bound is a local
      // optimum: probe below it with fixed steps (the next one that fails ends
      // the loop). An improving fixed step leaves the old optimum behind.
      at_local_optimum = !fixed_steps && T_f < bound * (1.0 - kInsideBound);
      if (at_local_optimum) fixed_steps = true;
      minimized = at_local_optimum;
      continue;
    }
    rate *= cfg.shrink;
    if (at_local_optimum) break;  // the probe below a local optimum failed
    // The first fixed step that fails: the homotopy has passed the local
    // optimum's horizon, so minimise from the best point now (step 3 early).
    // Capped at minimize_iterations: if it does not converge within them, the
    // fixed steps go on and the loop minimises again at its end.
    if (fixed_steps && !minimized && !cut_short && !out_of_time()) {
      minimized = true;
      at_local_optimum = minimize(cfg.minimize_iterations);
      if (!at_local_optimum && cfg.minimize_iterations > 0) minimized = false, cut_short = true;
    }
  }
  // 3. From the last homotopy step to the local optimum.
  if (fixed_steps && !minimized && !out_of_time()) minimize(0);
  solver.set_wall_limit(own_wall_limit);
  // Free the horizon again: the problem is the model itself for later users.
  problem.limit_horizon(kInf);
  out.status = MpccStatus::kSolved;
  out.seconds = elapsed();
  return out;
}

}  // namespace disco
