// disco — the control flow of the objective reduction (search/objective_reduction.h says
// what each step does), as data: named phases and one transition function. Nothing here
// solves anything, so each transition is tested alone (tests/test_reduction_phases.cpp);
// reduce_objective runs the solve of the current phase and asks next_phase where to go.
//
//   kFeasibility --solved--> kPerturbed (if asked) --> kMinimizingStep
//                                                  (--> kEarlyMinimize instead: a start from a
//                                                   trajectory with feasibility.guess_minimize)
//        |  not solved: again at twice the horizon, three attempts, then kDone
//   kMinimizingStep --failed (did not converge)--> kFixedStep (same rate)
//                   --new best inside its bound--> kProbe (a local optimum)
//   kFixedStep --failed, first time--> kEarlyMinimize --converged--> kProbe
//                                                     --not converged--> kFixedStep
//   kProbe --new best--> kFixedStep;  --no new best--> kDone
//   Without reduction.probe_after_minimize (the default) an early minimisation that
//   converged ends the loop: its arrow into kProbe goes to kDone (stop reason kMinimized).
//   any step, before it runs: past the time limit -> kDone; max_solves steps made, or no rate
//   >= min_rate keeps the bound above the smallest horizon -> kFinalMinimize (fixed steps
//   that have not been minimised since their last new best; any phase with minimize_last)
//   or kDone; the start's best above
//   the scene's incumbent for reduction.dominated_after steps in a row, or no rate >=
//   min_rate left for a step aimed below the incumbent -> kDone (dominated).
//
// The incumbent (search/README.md, "The shared incumbent") is the best certified T_f of the
// scene found by other starts, +inf when none is known or the search is deterministic. With
// reduction.jump_to_incumbent a step asks for (1 - r) min(T_best, incumbent): a start whose
// best is above the incumbent aims straight below it. With an infinite incumbent every rule
// here is the one without it, step for step.
//
// With another objective than time (core/model/objective.h) read J for T_f in every step,
// bound and best; a scene that fixes T_f (energy) has one feasibility attempt.
#pragma once

#include <string>

#include "core/util/numbers.h"
#include "search/objective_reduction.h"

namespace disco {

enum class Phase {
  kFeasibility,     // step 1: the elastic MPCC at a fixed, generous horizon
  kPerturbed,       // step 1b: once more from a perturbation of the feasible point
  kMinimizingStep,  // step 2: minimise T_f <= (1 - rate) T_best, at most step_iterations
  kFixedStep,       // step 2: solve at T_f = (1 - rate) T_best (the homotopy in the horizon)
  kProbe,           // a fixed step below a local optimum: the loop ends if it fails
  kEarlyMinimize,   // step 3 right after the first fixed step that fails
  kFinalMinimize,   // step 3 once the loop ends
  kDone,
};
SolveKind solve_kind(Phase phase);  // what the phase's solve is, for the solve log

// Why the loop ended, decided by the transition that ends it (a final minimisation may run
// after the decision; it does not change the reason).
enum class StopReason {
  kNone,             // still running
  kNoFeasiblePoint,  // every feasibility attempt failed
  kNoFeasiblePointAtHorizon,  // the one feasibility attempt at the scene's fixed T_f failed
  kOutOfTime,        // the time limit passed
  kInterrupted,      // an interrupt (core/util/interrupt.h); set by reduce_objective
  kMaxSolves,        // reduction.max_solves steps made
  kMinRate,          // the rate fell below reduction.min_rate (or no rate >= it keeps the
                     // bound above the smallest horizon)
  kLocalOptimum,     // a fixed step below a local optimum (a probe) gave nothing better
  kMinimized,        // a minimisation converged (not probed below without
                     // reduction.probe_after_minimize)
  kDominated,        // its best stayed above the scene's incumbent (another start's best) for
                     // reduction.dominated_after steps in a row, or no rate was left to aim
                     // below it
};
// The solve log's last line: "stopped: ..." in words, with the settings it names.
std::string stop_line(StopReason reason, const ReductionSettings& settings);

struct ReductionState {
  Phase phase = Phase::kFeasibility;
  int attempt = 0;          // feasibility attempts made
  double rate = 0.0;        // r: the next step asks for T_f <= (1 - r) T_best
  int steps = 0;            // steps made (minimising, fixed and probes)
  bool minimized = false;   // minimised since the last fixed step that gave a new best
  bool cut_short = false;   // an early minimisation stopped at minimize_iterations
  int above_incumbent = 0;  // steps in a row after which the best was above the incumbent
  StopReason stop = StopReason::kNone;  // set by the transition that ends the loop
};

// What the current phase's solve gave, and the run's facts the next choice depends on.
struct PhaseOutcome {
  bool solved = false;        // certified; for a minimisation: it converged (a local optimum)
  bool improved = false;      // it gave a new best
  bool failed = false;        // MpccStatus::kFailed
  bool inside_bound = false;  // its T_f lies strictly inside its bound (a minimising step's)
  double best_value = 0.0;    // J (s for time), the best after the phase
  double smallest = 0.0;      // J, no step is asked below this (RobotProblem::objective_floor)
  bool perturb = false;       // step 1b is asked for
  bool out_of_time = false;   // the time limit has passed
  double incumbent = kInf;    // J, the scene's best from other starts (+inf: none known)
  bool horizon_fixed = false; // the scene fixes T_f (objective energy): one feasibility attempt
  // The loop ends with a minimisation of J from the best point unless one converged since its
  // last new best, whatever the last phase (objectives other than time: a feasible point at a
  // fixed T_f can lie within a step's rate of the optimum, where every step fails).
  bool minimize_last = false;
};

ReductionState begin_reduction(const ReductionSettings& settings);
ReductionState next_phase(const ReductionState& state, const PhaseOutcome& outcome,
                          const ReductionSettings& settings);
// The T_f a step's rate applies to, in seconds: the start's best, or the incumbent when it is
// lower and reduction.jump_to_incumbent is set.
double step_reference(const PhaseOutcome& outcome, const ReductionSettings& settings);
// The T_f a step asks for (its bound, or its fixed horizon), in seconds, from its reference.
inline double step_bound(const ReductionState& state, double reference) {
  return (1.0 - state.rate) * reference;
}

}  // namespace disco
