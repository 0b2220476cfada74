#include "search/reduction_phases.h"

#include <algorithm>

#include <spdlog/fmt/fmt.h>

#include "core/util/check.h"

namespace disco {
namespace {
// Feasibility attempts, each at twice the horizon of the last.
constexpr int kFeasibilityAttempts = 3;
// The rate never grows beyond this.
constexpr double kMaxRate = 0.5;

// The loop after it ends: a last minimisation if the best came from fixed steps not
// minimised since (or, with minimize_last, from any phase not minimised since), else done.
ReductionState finish(ReductionState s, const PhaseOutcome& o, StopReason why) {
  s.stop = why;
  const bool fixed = s.phase == Phase::kFixedStep || s.phase == Phase::kProbe;
  s.phase = (fixed || o.minimize_last) && !s.minimized && !o.out_of_time ? Phase::kFinalMinimize
                                                                          : Phase::kDone;
  return s;
}

// The start cannot get below the incumbent (another start's best): it stops, without the
// final minimisation (its local optimum would not win the scene either).
ReductionState dominated(ReductionState s) {
  s.stop = StopReason::kDominated;
  s.phase = Phase::kDone;
  return s;
}

// `s` asks for a step of kind s.phase next: run it, or end the loop. A step whose bound lies
// below `smallest` cannot succeed, so the rate shrinks until it does not.
ReductionState admit(ReductionState s, const PhaseOutcome& o, const ReductionSettings& cfg) {
  if (o.out_of_time) {
    s.phase = Phase::kDone;
    s.stop = StopReason::kOutOfTime;
    return s;
  }
  if (s.steps >= cfg.max_solves) return finish(s, o, StopReason::kMaxSolves);
  const double reference = step_reference(o, cfg);
  while (s.rate >= cfg.min_rate && step_bound(s, reference) < o.smallest) s.rate *= cfg.shrink;
  if (s.rate < cfg.min_rate) {
    // Aiming below the incumbent, no rate is left: it cannot get below it. Dominated.
    if (reference < o.best_value) return dominated(s);
    return finish(s, o, StopReason::kMinRate);
  }
  return s;
}

ReductionState with_phase(ReductionState s, Phase phase) {
  s.phase = phase;
  return s;
}

// The first step after the feasible point: a start from a trajectory with guess_minimize
// minimises at once (its point lies near a local optimum); every other start takes the
// reduction's minimising steps.
ReductionState after_feasible(ReductionState s, const PhaseOutcome& o,
                              const ReductionSettings& cfg) {
  if (cfg.guess_minimize && cfg.horizon > 0.0 && !o.horizon_fixed && !o.out_of_time) {
    s.minimized = true;
    return with_phase(s, Phase::kEarlyMinimize);
  }
  return admit(with_phase(s, Phase::kMinimizingStep), o, cfg);
}

// The phases whose solve is a step of the reduction (they count towards dominated_after).
bool is_step(Phase phase) {
  return phase == Phase::kMinimizingStep || phase == Phase::kFixedStep ||
         phase == Phase::kProbe || phase == Phase::kEarlyMinimize;
}
}  // namespace

double step_reference(const PhaseOutcome& o, const ReductionSettings& cfg) {
  return cfg.jump_to_incumbent ? std::min(o.best_value, o.incumbent) : o.best_value;
}

SolveKind solve_kind(Phase phase) {
  switch (phase) {
    case Phase::kFeasibility: return SolveKind::kFeasibility;
    case Phase::kPerturbed: return SolveKind::kPerturbedFeasibility;
    case Phase::kMinimizingStep: return SolveKind::kReduction;
    case Phase::kFixedStep:
    case Phase::kProbe: return SolveKind::kFixedStep;
    case Phase::kEarlyMinimize:
    case Phase::kFinalMinimize:
    case Phase::kDone: return SolveKind::kMinimize;  // kDone runs no solve
  }
  return SolveKind::kMinimize;
}

std::string stop_line(StopReason reason, const ReductionSettings& cfg) {
  switch (reason) {
    case StopReason::kNone: return "stopped: (still running)";
    case StopReason::kNoFeasiblePoint:
      return fmt::format("stopped: no feasible point after {} feasibility attempts (each at twice "
                         "the horizon of the last)", kFeasibilityAttempts);
    case StopReason::kNoFeasiblePointAtHorizon:
      return "stopped: no feasible point at the scene's fixed horizon (objective.horizon)";
    case StopReason::kOutOfTime: return "stopped: time limit reached";
    case StopReason::kInterrupted: return "stopped: interrupted (SIGINT or SIGTERM)";
    case StopReason::kMaxSolves:
      return fmt::format("stopped: reduction.max_solves = {} steps made", cfg.max_solves);
    case StopReason::kMinRate:
      return fmt::format("stopped: the reduction rate fell below reduction.min_rate = {:g}",
                         cfg.min_rate);
    case StopReason::kLocalOptimum:
      return "stopped: a local optimum (a fixed step below it found nothing better)";
    case StopReason::kMinimized:
      return "stopped: a local optimum (a minimisation converged; not probed below: "
             "reduction.probe_after_minimize is false)";
    case StopReason::kDominated:
      return fmt::format("stopped: dominated (its best stayed above the best another start found, "
                         "for reduction.dominated_after = {} steps or until no reduction.rate "
                         ">= reduction.min_rate = {:g} was left below it)",
                         cfg.dominated_after, cfg.min_rate);
  }
  return "stopped";
}

ReductionState begin_reduction(const ReductionSettings& cfg) {
  ReductionState s;
  s.rate = cfg.rate;
  return s;
}

ReductionState next_phase(const ReductionState& state, const PhaseOutcome& o,
                          const ReductionSettings& cfg) {
  ReductionState s = state;
  if (is_step(state.phase)) {
    // Dominated: after dominated_after steps in a row, its best is still above what another
    // start found. It cannot win the scene within that effort: stop (no final minimisation).
    s.above_incumbent = o.best_value > o.incumbent ? s.above_incumbent + 1 : 0;
    if (cfg.dominated_after > 0 && s.above_incumbent >= cfg.dominated_after) return dominated(s);
  }
  switch (state.phase) {
    case Phase::kFeasibility:
      s.attempt += 1;
      if (o.solved) {
        if (o.perturb && !o.out_of_time) return with_phase(s, Phase::kPerturbed);
        return after_feasible(s, o, cfg);
      }
      if (s.attempt < (o.horizon_fixed ? 1 : kFeasibilityAttempts) && !o.out_of_time)
        return with_phase(s, Phase::kFeasibility);
      s.stop = o.out_of_time     ? StopReason::kOutOfTime
               : o.horizon_fixed ? StopReason::kNoFeasiblePointAtHorizon
                                 : StopReason::kNoFeasiblePoint;
      return with_phase(s, Phase::kDone);
    case Phase::kPerturbed: return after_feasible(s, o, cfg);
    case Phase::kMinimizingStep:
      s.steps += 1;
      // It stalled: retry this bound as a fixed step, and take fixed steps from now on.
      if (o.failed) return admit(with_phase(s, Phase::kFixedStep), o, cfg);
      if (o.improved) {
        s.rate = std::min(s.rate * cfg.grow, kMaxRate);
        // Converged strictly inside its bound: a local optimum of a short step, probed with
        // fixed steps (always: a probe may leave it, e.g. stress/K_3 start 2).
        s.minimized = o.inside_bound;
        return admit(with_phase(s, o.inside_bound ? Phase::kProbe : Phase::kMinimizingStep), o,
                     cfg);
      }
      s.rate *= cfg.shrink;
      return admit(s, o, cfg);
    case Phase::kFixedStep:
    case Phase::kProbe:
      s.steps += 1;
      if (o.improved) {  // the homotopy goes on (from below the old optimum, after a probe)
        s.rate = std::min(s.rate * cfg.grow, kMaxRate);
        s.minimized = false;
        return admit(with_phase(s, Phase::kFixedStep), o, cfg);
      }
      s.rate *= cfg.shrink;
      if (state.phase == Phase::kProbe)  // nothing below the optimum
        return finish(s, o, StopReason::kLocalOptimum);
      // The first fixed step that fails: the homotopy has passed the local optimum's
      // horizon, so minimise from the best point now.
      if (!s.minimized && !s.cut_short && !o.out_of_time) {
        s.minimized = true;
        return with_phase(s, Phase::kEarlyMinimize);
      }
      return admit(s, o, cfg);
    case Phase::kEarlyMinimize:
      // Converged: a local optimum, probed below with reduction.probe_after_minimize, else
      // the end. Cut at minimize_iterations: it changed nothing, the fixed steps go on and
      // the loop minimises again at its end.
      if (o.solved && !cfg.probe_after_minimize) return finish(s, o, StopReason::kMinimized);
      if (o.solved) return admit(with_phase(s, Phase::kProbe), o, cfg);
      if (cfg.minimize_iterations > 0) s.minimized = false, s.cut_short = true;
      return admit(with_phase(s, Phase::kFixedStep), o, cfg);
    case Phase::kFinalMinimize:
    case Phase::kDone:
      DISCO_CHECK(s.stop != StopReason::kNone, "only finish() leads to the final minimisation");
      return with_phase(s, Phase::kDone);
  }
  DISCO_CHECK(false, "unknown reduction phase");
  return s;
}

}  // namespace disco
