#include "search/objective_reduction.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <spdlog/fmt/fmt.h>

#include "core/model/objective.h"
#include "core/util/clock.h"
#include "core/util/interrupt.h"
#include "core/config/solver_settings.h"
#include "core/util/check.h"
#include "core/util/errors.h"
#include "search/guess.h"
#include "core/util/numbers.h"
#include "search/reduction_phases.h"

namespace disco {
namespace {
// A minimising step's T_f this far (relative) below its bound left the bound inactive.
constexpr double kInsideBound = 1e-6;
// A new best must be this much (relative) below the old one.
constexpr double kBetter = 1e-7;

// What a step fixes or bounds.
enum class Bound {
  kHorizon,  // T_f = value (seconds; the feasibility phases), J free
  kFixed,    // J = value (for objective time: T_f = value)
  kUpper,    // J <= value
};
// One elastic-mode solve of the reduction, as data.
struct StepRequest {
  Bound bound = Bound::kUpper;
  double value = 0.0;
  int iteration_limit = 0;  // per Ipopt solve; 0 = none
  bool minimize = false;    // a minimisation (step 3): ElasticSettings::Stall applies
  double zeta = 0.0;        // > 0: ElasticRequest::zeta
  double zeta_limit = 0.0;  // > 0: ElasticRequest::zeta_limit
  bool relaxation = false;  // ElasticRequest::relaxation (a weak minimisation's homotopy)
  // A feasibility phase whose certified point is perturbed next (step 1b): polished as always,
  // since the perturbation starts from it (objective_reduction.h, "Polish").
  bool perturbed_next = false;
};

// One run of reduce_objective: its solves, its solve log and its best point. The control flow
// is reduce_objective's (the phases of search/reduction_phases.h) and the kBranch minimiser's.
struct Reduction {
  RobotProblem& problem;
  const ElasticSolver& solver;
  const ReductionSettings& cfg;
  ReductionResult& out;
  const SolveCallback& on_solve;
  Clock::time_point t0;

  double elapsed() const { return seconds_since(t0); }
  bool out_of_time() const {
    return time_up || interrupt_requested() || (cfg.time_limit > 0 && elapsed() > cfg.time_limit);
  }
  // An interrupt (core/util/interrupt.h) ends the loop as the time limit does; so does a solve
  // cut at its deadline (salvaged or not), whose deadline kept back only the salvage's time,
  // and the loop's stop reason is then the time limit.
  bool time_up = false;
  // Seconds kept back from the time limit for a salvage: salvage_iterations at the start's
  // pace so far, at most half the time left; 0 before the first iteration or without salvage.
  double salvage_reserve() const {
    if (cfg.salvage_iterations <= 0 || cfg.time_limit <= 0 || out.iterations <= 0) return 0.0;
    const double pace = elapsed() / out.iterations;
    return std::min(cfg.salvage_iterations * pace, 0.5 * std::max(0.0, cfg.time_limit - elapsed()));
  }
  // Every solve ends by the time limit, less `reserve` seconds.
  ElasticRequest request(int iteration_limit, double reserve = 0.0) const {
    ElasticRequest r{iteration_limit, std::nullopt};
    if (cfg.time_limit > 0) r.deadline = after(t0, cfg.time_limit - reserve);
    return r;
  }
  // The elastic MPCC under the request's bound, from a point or a result (warm). Past the
  // feasibility phase it ends early enough for a salvage (salvage_reserve).
  template <class From>
  MpccResult step(const StepRequest& q, const From& from) {
    const double reserve = q.bound == Bound::kHorizon ? 0.0 : salvage_reserve();
    if (q.bound == Bound::kHorizon) {
      problem.free_objective();
      problem.fix_horizon(q.value);
    } else {
      problem.bound_objective(q.value, q.bound == Bound::kFixed);
    }
    ElasticRequest req = request(q.iteration_limit, reserve);
    // A fixed step fixes J: no zeta raise (objective_reduction.h, "Fixed steps and zeta").
    req.objective_fixed = q.bound == Bound::kFixed;
    // A feasibility phase of objective time: J is its fixed horizon, eps alone is minimised,
    // from a guess; its tight point is certified as it stands unless a perturbation of it
    // follows (objective_reduction.h, "Polish").
    req.feasibility =
        q.bound == Bound::kHorizon && problem.objective_kind() == ObjectiveKind::kTime;
    req.objective_constant = req.feasibility && !q.perturbed_next;
    req.stall = q.minimize;
    req.cold_start = q.minimize && cfg.cold_minimize;  // (objective_reduction.h, "Minimisations")
    req.zeta = q.zeta;
    req.zeta_limit = q.zeta_limit;
    req.relaxation = q.relaxation;
    MpccResult r = solver.solve(problem.program(), from, req);
    note_deadline(req, r);
    return r;
  }
  // A solve whose deadline passed ends the loop on the clock: Ipopt cut at it, or the elastic
  // solver past it skipped a polish or a zeta raise (so the point is not what the same solve
  // without a deadline gives, and the start's path is no longer its own).
  void note_deadline(const ElasticRequest& req, const MpccResult& r) {
    if (r.outcome == NlpOutcome::kTimeLimit ||
        (req.deadline && Clock::now() >= *req.deadline))
      time_up = true;
  }
  // Salvage (objective_reduction.h): after `cut` (a step or minimisation the time limit cut
  // short, recorded), its branch minimised under T_f <= T_best, by the limit itself.
  // A minimisation that ended at Ipopt's max_iter (`stalled`) is salvaged the same way, and the
  // loop goes on from what that gave.
  void salvage(const MpccResult& cut, bool stalled = false) {
    if (!(time_up || stalled) || cut.solved() || cfg.salvage_iterations <= 0 ||
        interrupt_requested() || cut.elastic_point.z.size() == 0)
      return;
    branch(cut, SolveKind::kSalvage, 0, cfg.salvage_iterations);
  }
  void record(SolveKind kind, double bound, const MpccResult& r, bool improved) {
    SolveRecord rec{kind,     bound,        problem.horizon(r.z), problem.objective(r.z),
                    r.status, r.outcome,    r.ipopt_status,       r.certificate,
                    r.nlp_solves, r.iterations, r.seconds,        improved};
    rec.stalled = r.stalled;
    out.solves.push_back(rec);
    out.nlp_solves += r.nlp_solves;
    out.iterations += r.iterations;
    out.kkt += r.kkt;
    if (on_solve) on_solve(rec);
  }
  void record(Phase phase, double bound, const MpccResult& r, bool improved) {
    record(solve_kind(phase), bound, r, improved);
  }
  // `r` (certified, T_f below the best so far) becomes the best point. `minimum`: r is a
  // converged minimisation under T_f <= bound (elastic, or a branch descent that ended
  // B-stationary); with its T_f strictly inside the bound, r is stationary for min T_f.
  void take_best(MpccResult&& r, bool minimum = false, double bound = 0.0) {
    const bool stationary = minimum && problem.objective(r.z) < bound * (1.0 - kInsideBound);
    out.stationarity = !stationary     ? Stationarity::kFeasible
                       : r.b_stationary ? Stationarity::kB
                                        : Stationarity::kStrong;
    out.best = std::move(r);
    out.best_value = problem.objective(out.best.z);
    out.time_to_best = elapsed();
    out.history.push_back({out.time_to_best, out.best_value});
  }

  // Minimise T_f <= T_best from the best point (step 3 and its early call), by
  // cfg.minimizer; true if the best point is now a local optimum.
  bool minimize(int iteration_limit) {
    if (cfg.minimizer == Minimizer::kBranch) {
      branch_descent();
      return true;  // a descent stops at a local optimum, or at the time limit
    }
    const double bound = out.best_value;
    const double zeta = solver.warm_zeta(out.best);  // what the minimisation would start at
    std::optional<MpccResult> weak;
    if (cfg.minimize_zeta > 0 && cfg.minimize_zeta < zeta) {
      // Weak first (objective_reduction.h, "Minimisations"); not certified, as before, unless
      // a limit ended it (the clock, an interrupt, the early minimisation's cap).
      weak = step({Bound::kUpper, bound, iteration_limit, true, cfg.minimize_zeta,
                   zeta * solver.settings().zeta_factor, cfg.weak_homotopy},
                  out.best);
      const bool limited =
          time_up || interrupt_requested() || weak->outcome == NlpOutcome::kIterationCap;
      if (!weak->solved() && !limited) {
        record(SolveKind::kMinimize, bound, *weak, false);
        weak.reset();
      }
    }
    MpccResult r =
        weak ? std::move(*weak) : step({Bound::kUpper, bound, iteration_limit, true}, out.best);
    const bool improved = r.solved() && problem.objective(r.z) < bound;
    record(SolveKind::kMinimize, bound, r, improved);
    // A minimisation ended by the stall rule (elastic.stall) counts as converged for the loop
    // (a local optimum, probed below), but its point is not shown stationary.
    const bool converged = r.solved(), stationary = converged && !r.stalled;
    if (improved) take_best(std::move(r), stationary, bound);
    else salvage(r, r.outcome == NlpOutcome::kMaxIterations || r.stalled);
    return converged;
  }

  // A branch descent from `from` (certified or not) under T_f <= T_best, with at most
  // flip_rounds flips and iteration_limit Ipopt iterations per solve (0: none); true if it
  // improved. A salvage's point is not stationary for the loop (its solve was not asked to
  // be: it ends by the limit).
  bool branch(const MpccResult& from, SolveKind kind, int flip_rounds, int iteration_limit = 0) {
    const double bound = out.best_value;
    problem.bound_objective(bound, false);
    const ElasticRequest req = request(iteration_limit);
    MpccResult r = solver.solve_branch(problem.program(), from, flip_rounds, req);
    note_deadline(req, r);
    const bool improved = r.solved() && problem.objective(r.z) < bound * (1.0 - kBetter);
    record(kind, bound, r, improved);
    if (improved) take_best(std::move(r), kind == SolveKind::kBranch && r.b_stationary, bound);
    return improved;
  }
  bool branch(const MpccResult& from) { return branch(from, SolveKind::kBranch, cfg.flip_rounds); }
  // One segment of the elastic minimisation: at most segment_iterations Ipopt iterations from
  // `from` under T_f <= bound; the second member says whether it gave a new best.
  std::pair<MpccResult, bool> segment(const MpccResult& from, double bound) {
    MpccResult r = step({Bound::kUpper, bound, cfg.segment_iterations}, from);
    const bool improved = r.solved() && problem.objective(r.z) < out.best_value * (1.0 - kBetter);
    record(SolveKind::kMinimize, bound, r, improved);
    if (improved) take_best(MpccResult(r), true, bound);  // improved: converged
    return {std::move(r), improved};
  }
  // The kBranch minimiser (objective_reduction.h): from the best point to a local optimum.
  void branch_descent() {
    // a. One segment from the best point. Converged, it is a local optimum (one-robot scenes
    // end here); else a branch descent from its point. (A branch descent straight from the
    // feasible point commits to the branch of a slow motion: on paper A1 the elastic
    // minimisation from there ended 2 % above the optimum it reaches from the feasible point.)
    {
      auto [r, improved] = segment(out.best, out.best_value);
      if (!out_of_time()) branch(r);
      else salvage(r);
      if (r.solved()) return;
    }
    // b. More segments, the first from the best branch point, each continuing the last (its
    // primal-dual point) and bounded by the T_f it starts from (the bound never forces it);
    // after each one that ends below the best, a branch descent from
    // its point (the smaller side of every pair fixed: even at complementarity 3e-2 that was
    // the branch of a new best, on three_robots_contact).
    MpccResult from = out.best;
    double T_from = out.best_value;
    int idle = 0;  // segments in a row that gave no new best
    for (int k = 0; k < cfg.max_solves && !out_of_time(); ++k) {
      auto [r, better] = segment(from, T_from);
      T_from = problem.objective(r.z);
      if (!out_of_time() && T_from < out.best_value) better = branch(r) || better;
      else salvage(r);
      // A segment that converged (certified) is a local optimum of the elastic program.
      if (r.solved() || r.status == MpccStatus::kInfeasible) break;
      // Not tight: raising zeta no longer moves it, and the next segment starts where it ended.
      if (r.status == MpccStatus::kElasticNotTight && !better) break;
      idle = better ? 0 : idle + 1;
      if (idle >= 2) break;
      from = std::move(r);
    }
  }
};
}  // namespace


double feasibility_horizon(const RobotProblem& problem, const ReductionSettings& cfg) {
  if (problem.horizon_is_fixed()) return problem.scene().objective.horizon;
  if (cfg.horizon > 0.0) return cfg.horizon;  // a start from a trajectory
  auto scale = problem.reference_time();
  // A robot that takes a coin on its way to its own target (search/guess.h, pushers_way_time).
  if (const auto way = pushers_way_time(problem.scene())) scale = std::max(scale.value_or(0.0), *way);
  return scale ? std::max(cfg.horizon_min, cfg.horizon_factor * *scale) : cfg.horizon_min;
}

std::string to_string(SolveKind kind) {
  switch (kind) {
    case SolveKind::kFeasibility: return "feasibility";
    case SolveKind::kPerturbedFeasibility: return "perturbed feasibility";
    case SolveKind::kReduction: return "reduction";
    case SolveKind::kFixedStep: return "fixed step";
    case SolveKind::kMinimize: return "minimize";
    case SolveKind::kBranch: return "branch";
    case SolveKind::kSalvage: return "salvage";
  }
  return "?";
}

std::string solve_log_header(ObjectiveKind kind) {
  // Time: the bound and T_f; otherwise the bound on J, J and T_f.
  const std::string J = kind == ObjectiveKind::kEnergy ? "E" : "T+wE";
  const std::string unit = "[" + objective_unit(kind) + "]";
  const std::string head =
      kind == ObjectiveKind::kTime
          ? fmt::format("{:>10} {:>10}", "bound[s]", "T_f[s]")
          : fmt::format("{:>10} {:>10} {:>10}", "bound" + unit, J + unit, "T_f[s]");
  return fmt::format("{:>3} {:<18} {} {:<17} {:>9} {:>9} {:>4} {:>5} {:>7}", "#", "phase", head,
                     "ended", "compl", "viol", "nlp", "iter", "sec");
}

std::string solve_outcome_words(MpccStatus status, NlpOutcome outcome) {
  switch (status) {
    case MpccStatus::kSolved: return "solved";
    case MpccStatus::kElasticNotTight: return "not tight";
    case MpccStatus::kInfeasible: return "infeasible";
    case MpccStatus::kFailed: break;
  }
  switch (outcome) {
    case NlpOutcome::kIterationCap: return "cap reached";
    case NlpOutcome::kTimeLimit: return interrupt_requested() ? "interrupted" : "time limit";
    case NlpOutcome::kInvalidNumber: return "invalid number";
    case NlpOutcome::kMaxIterations: return "max_iter";
    default: return "failed";
  }
}

std::string solve_log_line(int number, const SolveRecord& r, ObjectiveKind kind) {
  const std::string words =
      solve_outcome_words(r.status, r.outcome) + (r.stalled ? ", stalled" : "");
  // A feasibility phase's bound is its fixed T_f, not a bound on J: "-" for another objective.
  const bool on_J = r.kind != SolveKind::kFeasibility && r.kind != SolveKind::kPerturbedFeasibility;
  const std::string values =
      kind == ObjectiveKind::kTime
          ? fmt::format("{:>10.5f} {:>10.5f}", r.bound, r.T_f)
          : fmt::format("{:>10} {:>10.5g} {:>10.5f}", on_J ? fmt::format("{:.5g}", r.bound) : "-",
                        r.value, r.T_f);
  return fmt::format(
      "{:>3} {:<18} {} {:<17} {:>9.1e} {:>9.1e} {:>4} {:>5} {:>7.3f}{}", number,
      (r.coarse ? "coarse " : "") + to_string(r.kind), values, words, r.certificate.max_complementarity,
      r.certificate.max_violation, r.nlp_solves, r.iterations, r.seconds,
      r.improved ? std::string("  *")
      : words == "failed" || words == "invalid number"
          ? "  (Ipopt: " + ipopt_status_name(r.ipopt_status) + ")"
          : std::string());
}

ReductionResult reduce_objective(RobotProblem& problem, const ElasticSolver& solver,
                                 const ReductionSettings& cfg, const GuessFunction& guess,
                                 const SolveCallback& on_solve, const PerturbFunction& perturb,
                                 const IncumbentFunction& incumbent) {
  ReductionResult out;
  Reduction run{problem, solver, cfg, out, on_solve, Clock::now()};

  // The phases (search/reduction_phases.h): each runs its solve, then asks where to go.
  PhaseOutcome o;  // facts carried from phase to phase (smallest, perturb)
  o.perturb = static_cast<bool>(perturb);
  o.horizon_fixed = problem.horizon_is_fixed();
  o.minimize_last = problem.objective_kind() != ObjectiveKind::kTime;
  ReductionState s = begin_reduction(cfg);
  for (; s.phase != Phase::kDone; s = next_phase(s, o, cfg)) {
    o.solved = o.improved = o.failed = o.inside_bound = false;
    switch (s.phase) {
      case Phase::kFeasibility: {  // 1. at a fixed, generous horizon (doubled per attempt)
        const double T = feasibility_horizon(problem, cfg) * std::pow(2.0, s.attempt);
        problem.set_horizon_max(problem.horizon_reach(T));
        const Vector z0 = guess ? guess(T) : smoothstep_guess(problem, T);
        StepRequest q{Bound::kHorizon, T, 0};
        q.perturbed_next = o.perturb;
        const MpccResult r = run.step(q, z0);
        // A failure says why: the outcome of the last NLP solve (invalid number: an
        // evaluation gave NaN or Inf, which the Nlp wrapper turns into a failed callback).
        out.feasibility_detail = to_string(r.status);
        if (r.status == MpccStatus::kFailed)
          out.feasibility_detail += " (" + describe(r.outcome, r.ipopt_status) + ")";
        out.status = r.status == MpccStatus::kElasticNotTight ? MpccStatus::kInfeasible : r.status;
        o.solved = r.solved();
        run.record(s.phase, T, r, o.solved);
        if (!o.solved) out.last_attempt = r.z;
        if (o.solved) {
          out.found = true;
          run.take_best(MpccResult(r));
          out.time_to_first_feasible = out.time_to_best;
          // No step is asked below a valid lower bound, nor below the smallest horizon the
          // model allows (RobotProblem keeps h > 0): a fixed step there would leave T_best
          // outside the model's own bounds on T_f, so its point could not be certified on it.
          problem.free_objective();
          o.smallest = problem.objective_floor();
        }
        break;
      }
      case Phase::kPerturbed: {  // 1b. once more from a perturbation of the feasible point
        const Perturbation p = perturb(out.best.z);
        DISCO_CHECK(!problem.horizon_is_fixed(), "no perturbed horizon when the scene fixes T_f");
        DISCO_CHECK(p.seconds > 0.0 && p.seconds <= problem.horizon(out.best.z),
                    "a perturbation's horizon is positive and at most the feasible one");
        DISCO_CHECK(p.guess.size() == out.best.z.size(), "a perturbation's guess is a model point");
        MpccResult r = run.step({Bound::kHorizon, p.seconds, 0}, p.guess);
        // For time + energy a faster point may cost more: it must not raise J. (For time, J is
        // its horizon, never above the feasible one.)
        o.solved = r.solved() && problem.objective(r.z) <= out.best_value;
        run.record(s.phase, p.seconds, r, o.solved);
        if (o.solved) run.take_best(std::move(r));
        problem.free_objective();
        break;
      }
      case Phase::kMinimizingStep:
      case Phase::kFixedStep:
      case Phase::kProbe: {  // 2. T_f <= (1 - r) T_best, minimised or fixed
        const double bound = step_bound(s, step_reference(o, cfg));
        const bool fixed = s.phase != Phase::kMinimizingStep;
        MpccResult r = run.step(
            {fixed ? Bound::kFixed : Bound::kUpper, bound, fixed ? 0 : cfg.step_iterations},
            out.best);
        const double T_f = problem.objective(r.z);  // J
        o.solved = r.solved();
        o.failed = r.status == MpccStatus::kFailed;
        o.improved = o.solved && T_f < out.best_value;
        o.inside_bound = T_f < bound * (1.0 - kInsideBound);
        run.record(s.phase, bound, r, o.improved);
        if (o.improved) run.take_best(std::move(r), s.phase == Phase::kMinimizingStep, bound);
        else run.salvage(r);
        break;
      }
      case Phase::kEarlyMinimize:  // 3. from the best point to its local optimum
      case Phase::kFinalMinimize:
        o.solved = run.minimize(s.phase == Phase::kEarlyMinimize ? cfg.minimize_iterations : 0);
        break;
      case Phase::kDone: break;
    }
    o.best_value = out.best_value;
    o.out_of_time = run.out_of_time();
    if (incumbent) o.incumbent = incumbent();
  }
  // Free the objective again: the problem is the model itself for later users.
  problem.free_objective();
  if (out.found) out.status = MpccStatus::kSolved;
  // A solve the time limit cut short ends the loop on the clock, also where it was the loop's
  // last (the final minimisation, cut and salvaged): the start did not reach its own end.
  const StopReason stop = run.time_up ? StopReason::kOutOfTime : s.stop;
  out.stop = stop == StopReason::kOutOfTime && interrupt_requested() ? StopReason::kInterrupted : stop;
  out.incumbent = o.incumbent;
  out.seconds = run.elapsed();
  return out;
}

}  // namespace disco
