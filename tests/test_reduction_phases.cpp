// The objective reduction's phases (search/reduction_phases.h): every transition of
// next_phase, without a solve.
#include <gtest/gtest.h>

#include "search/reduction_phases.h"

namespace disco {
namespace {

// With reduction.probe_after_minimize: the transitions below a local optimum
// (AConvergedMinimisationEndsTheLoopWithoutProbing has the default's).
ReductionSettings schedule() {
  return {.rate = 0.05, .grow = 2.0, .shrink = 0.5, .min_rate = 0.01, .max_solves = 10,
          .step_iterations = 60, .probe_after_minimize = true};
}

ReductionState in(Phase phase, double rate = 0.05) {
  ReductionState s;
  s.phase = phase;
  s.rate = rate;
  s.attempt = 1;
  return s;
}

// A phase's outcome at T_best = 10 s, with no step bound below 1 s.
PhaseOutcome outcome() {
  PhaseOutcome o;
  o.best_value = 10.0;
  o.smallest = 1.0;
  return o;
}
PhaseOutcome improved(bool inside_bound = false) {
  PhaseOutcome o = outcome();
  o.solved = o.improved = true;
  o.inside_bound = inside_bound;
  return o;
}
PhaseOutcome no_gain() { return outcome(); }  // e.g. infeasible or not tight
PhaseOutcome failed() {
  PhaseOutcome o = outcome();
  o.failed = true;
  return o;
}

TEST(ReductionPhases, TheReductionBeginsWithFeasibilityAtTheConfiguredRate) {
  const ReductionState s = begin_reduction(schedule());
  EXPECT_EQ(s.phase, Phase::kFeasibility);
  EXPECT_EQ(s.attempt, 0);
  EXPECT_EQ(s.rate, 0.05);
  EXPECT_EQ(s.steps, 0);
  EXPECT_FALSE(s.minimized);
}

TEST(ReductionPhases, AFeasiblePointLeadsToAMinimizingStep) {
  const ReductionState s = next_phase(begin_reduction(schedule()), improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  EXPECT_EQ(s.attempt, 1);
}

TEST(ReductionPhases, AFeasiblePointLeadsToThePerturbationWhenOneIsAsked) {
  PhaseOutcome o = improved();
  o.perturb = true;
  EXPECT_EQ(next_phase(begin_reduction(schedule()), o, schedule()).phase, Phase::kPerturbed);
  o.out_of_time = true;  // no time for it: the loop ends
  EXPECT_EQ(next_phase(begin_reduction(schedule()), o, schedule()).phase, Phase::kDone);
}

// feasibility.guess_minimize: a start from a trajectory (its own first horizon) minimises
// right after its feasible point; the early minimisation then counts as the loop's
// minimisation, so a converged one is probed below and a failed probe ends the loop.
TEST(ReductionPhases, AStartFromATrajectoryMinimisesFirstWhenAsked) {
  ReductionSettings given = schedule();
  given.horizon = 12.0;  // a start from a trajectory
  given.guess_minimize = true;
  ReductionState s = next_phase(begin_reduction(given), improved(), given);
  EXPECT_EQ(s.phase, Phase::kEarlyMinimize);
  EXPECT_TRUE(s.minimized);
  EXPECT_EQ(s.rate, 0.05);
  s = next_phase(s, improved(true), given);
  EXPECT_EQ(s.phase, Phase::kProbe);
  s = next_phase(s, no_gain(), given);
  EXPECT_EQ(s.phase, Phase::kDone);  // minimised already: no final minimisation
  EXPECT_EQ(s.stop, StopReason::kLocalOptimum);

  // A minimisation that does not converge hands over to the fixed steps, as the early one does.
  s = next_phase(next_phase(begin_reduction(given), improved(), given), failed(), given);
  EXPECT_EQ(s.phase, Phase::kFixedStep);

  // After step 1b too.
  PhaseOutcome perturb = improved();
  perturb.perturb = true;
  s = next_phase(begin_reduction(given), perturb, given);
  EXPECT_EQ(s.phase, Phase::kPerturbed);
  EXPECT_EQ(next_phase(s, no_gain(), given).phase, Phase::kEarlyMinimize);

  // Not for a start from its own guess, nor without the setting, nor when T_f is fixed.
  ReductionSettings own = given;
  own.horizon = 0.0;
  EXPECT_EQ(next_phase(begin_reduction(own), improved(), own).phase, Phase::kMinimizingStep);
  ReductionSettings off = given;
  off.guess_minimize = false;
  EXPECT_EQ(next_phase(begin_reduction(off), improved(), off).phase, Phase::kMinimizingStep);
  PhaseOutcome fixed = improved();
  fixed.horizon_fixed = true;
  EXPECT_EQ(next_phase(begin_reduction(given), fixed, given).phase, Phase::kMinimizingStep);
}

TEST(ReductionPhases, TheFeasibilityPhaseTriesThreeHorizons) {
  ReductionState s = begin_reduction(schedule());
  s = next_phase(s, failed(), schedule());
  EXPECT_EQ(s.phase, Phase::kFeasibility);
  EXPECT_EQ(s.attempt, 1);
  s = next_phase(s, no_gain(), schedule());
  EXPECT_EQ(s.phase, Phase::kFeasibility);
  EXPECT_EQ(s.stop, StopReason::kNone);
  s = next_phase(s, failed(), schedule());
  EXPECT_EQ(s.phase, Phase::kDone);
  EXPECT_EQ(s.attempt, 3);
  EXPECT_EQ(s.stop, StopReason::kNoFeasiblePoint);
}

// Objective energy: T_f is the scene's, so there is no other horizon to try.
TEST(ReductionPhases, AFixedHorizonGivesOneFeasibilityAttempt) {
  PhaseOutcome o = failed();
  o.horizon_fixed = true;
  const ReductionState s = next_phase(begin_reduction(schedule()), o, schedule());
  EXPECT_EQ(s.phase, Phase::kDone);
  EXPECT_EQ(s.attempt, 1);
  EXPECT_EQ(s.stop, StopReason::kNoFeasiblePointAtHorizon);
  EXPECT_EQ(stop_line(s.stop, schedule()),
            "stopped: no feasible point at the scene's fixed horizon (objective.horizon)");
}

// Objectives other than time: minimising steps that all fail (the feasible point was within a
// step's rate of the optimum) still end with a minimisation of J; one that converged inside
// its bound needs none.
TEST(ReductionPhases, MinimizeLastEndsAnyLoopWithAMinimisation) {
  PhaseOutcome o = no_gain();
  o.minimize_last = true;
  const ReductionState s = next_phase(in(Phase::kMinimizingStep, 0.015), o, schedule());
  EXPECT_EQ(s.phase, Phase::kFinalMinimize);
  EXPECT_EQ(s.stop, StopReason::kMinRate);
  ReductionState minimized = in(Phase::kMinimizingStep, 0.015);
  minimized.minimized = true;
  EXPECT_EQ(next_phase(minimized, o, schedule()).phase, Phase::kDone);
  o.out_of_time = true;
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep, 0.015), o, schedule()).phase, Phase::kDone);
}

TEST(ReductionPhases, NoFurtherFeasibilityAttemptPastTheTimeLimit) {
  PhaseOutcome o = failed();
  o.out_of_time = true;
  EXPECT_EQ(next_phase(begin_reduction(schedule()), o, schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(begin_reduction(schedule()), o, schedule()).stop, StopReason::kOutOfTime);
}

TEST(ReductionPhases, ThePerturbedFeasibilityLeadsToAMinimizingStepWhateverItGave) {
  for (const PhaseOutcome& o : {improved(), no_gain(), failed()})
    EXPECT_EQ(next_phase(in(Phase::kPerturbed), o, schedule()).phase, Phase::kMinimizingStep);
}

TEST(ReductionPhases, AnImprovingMinimizingStepOnItsBoundGrowsTheRateAndGoesOn) {
  const ReductionState s = next_phase(in(Phase::kMinimizingStep), improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.1);
  EXPECT_EQ(s.steps, 1);
  EXPECT_FALSE(s.minimized);
}

TEST(ReductionPhases, TheRateGrowsToOneHalfAtMost) {
  const ReductionState s = next_phase(in(Phase::kMinimizingStep, 0.4), improved(), schedule());
  EXPECT_DOUBLE_EQ(s.rate, 0.5);
}

TEST(ReductionPhases, AMinimizingStepInsideItsBoundIsALocalOptimumProbedBelow) {
  const ReductionState s =
      next_phase(in(Phase::kMinimizingStep), improved(/*inside_bound=*/true), schedule());
  EXPECT_EQ(s.phase, Phase::kProbe);
  EXPECT_TRUE(s.minimized);
  EXPECT_DOUBLE_EQ(s.rate, 0.1);
}

TEST(ReductionPhases, AStalledMinimizingStepIsRetriedAsAFixedStepAtTheSameRate) {
  const ReductionState s = next_phase(in(Phase::kMinimizingStep), failed(), schedule());
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.05);
  EXPECT_EQ(s.steps, 1);
}

TEST(ReductionPhases, AMinimizingStepWithoutGainShrinksTheRateAndGoesOn) {
  const ReductionState s = next_phase(in(Phase::kMinimizingStep), no_gain(), schedule());
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.025);
}

TEST(ReductionPhases, AnImprovingFixedStepContinuesTheHomotopy) {
  ReductionState from = in(Phase::kFixedStep);
  from.minimized = true;
  const ReductionState s = next_phase(from, improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.1);
  EXPECT_FALSE(s.minimized);  // the new best has not been minimised
}

TEST(ReductionPhases, TheFirstFailedFixedStepMinimizesEarly) {
  const ReductionState s = next_phase(in(Phase::kFixedStep), failed(), schedule());
  EXPECT_EQ(s.phase, Phase::kEarlyMinimize);
  EXPECT_TRUE(s.minimized);
  EXPECT_DOUBLE_EQ(s.rate, 0.025);
}

TEST(ReductionPhases, AFailedFixedStepAfterAMinimisationGoesOnWithFixedSteps) {
  ReductionState from = in(Phase::kFixedStep);
  from.minimized = true;
  const ReductionState s = next_phase(from, no_gain(), schedule());
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.025);
}

TEST(ReductionPhases, AnEarlyMinimisationCutShortIsNotRepeated) {
  ReductionState from = in(Phase::kFixedStep);
  from.cut_short = true;
  EXPECT_EQ(next_phase(from, no_gain(), schedule()).phase, Phase::kFixedStep);
}

TEST(ReductionPhases, NoEarlyMinimisationPastTheTimeLimit) {
  PhaseOutcome o = no_gain();
  o.out_of_time = true;
  EXPECT_EQ(next_phase(in(Phase::kFixedStep), o, schedule()).phase, Phase::kDone);
}

TEST(ReductionPhases, AConvergedEarlyMinimisationIsProbedBelow) {
  ReductionState from = in(Phase::kEarlyMinimize);
  from.minimized = true;
  const ReductionState s = next_phase(from, improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kProbe);
  EXPECT_TRUE(s.minimized);
}

TEST(ReductionPhases, AnUnconvergedEarlyMinimisationGoesOnWithFixedSteps) {
  ReductionState from = in(Phase::kEarlyMinimize);
  from.minimized = true;
  // Uncapped: it ran to its end, the loop does not minimise again.
  ReductionState s = next_phase(from, no_gain(), schedule());
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_TRUE(s.minimized);
  EXPECT_FALSE(s.cut_short);
  // Capped at minimize_iterations: cut short, the loop minimises again at its end.
  ReductionSettings capped = schedule();
  capped.minimize_iterations = 400;
  s = next_phase(from, no_gain(), capped);
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_FALSE(s.minimized);
  EXPECT_TRUE(s.cut_short);
}

// reduction.probe_after_minimize false (the default): a minimisation that converged ends the
// loop, with no final minimisation (it was just minimised); a minimising step that converged
// inside its bound is still probed below, and everything else is as with the setting.
TEST(ReductionPhases, AConvergedMinimisationEndsTheLoopWithoutProbing) {
  ReductionSettings off = schedule();
  off.probe_after_minimize = false;
  ReductionState s = next_phase(in(Phase::kEarlyMinimize), improved(true), off);
  EXPECT_EQ(s.phase, Phase::kDone);
  EXPECT_EQ(s.stop, StopReason::kMinimized);
  EXPECT_EQ(next_phase(in(Phase::kEarlyMinimize), improved(true), schedule()).phase,
            Phase::kProbe);
  // A start from a trajectory: its first minimisation converged, and that is its answer.
  ReductionSettings given = off;
  given.horizon = 12.0;
  given.guess_minimize = true;
  s = next_phase(next_phase(begin_reduction(given), improved(), given), improved(true), given);
  EXPECT_EQ(s.phase, Phase::kDone);
  EXPECT_EQ(s.stop, StopReason::kMinimized);
  // A minimising step that converged inside its bound: probed below, as with the setting.
  s = next_phase(in(Phase::kMinimizingStep), improved(true), off);
  EXPECT_EQ(s.phase, Phase::kProbe);
  EXPECT_TRUE(s.minimized);
  // The rest as with the setting.
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep), improved(false), off).phase,
            Phase::kMinimizingStep);
  EXPECT_EQ(next_phase(in(Phase::kEarlyMinimize), failed(), off).phase, Phase::kFixedStep);
  const ReductionState fixed = in(Phase::kFixedStep);
  EXPECT_EQ(next_phase(fixed, no_gain(), off).phase, Phase::kEarlyMinimize);
  EXPECT_EQ(next_phase(fixed, improved(), off).phase, Phase::kFixedStep);
  EXPECT_EQ(stop_line(StopReason::kMinimized, off),
            "stopped: a local optimum (a minimisation converged; not probed below: "
            "reduction.probe_after_minimize is false)");
}

TEST(ReductionPhases, AProbeThatFailsEndsTheLoop) {
  ReductionState from = in(Phase::kProbe);
  from.minimized = true;
  EXPECT_EQ(next_phase(from, no_gain(), schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(from, failed(), schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(from, failed(), schedule()).stop, StopReason::kLocalOptimum);
  // Without a minimisation since its last new best, the loop minimises first; the reason stays.
  from.minimized = false;
  const ReductionState s = next_phase(from, no_gain(), schedule());
  EXPECT_EQ(s.phase, Phase::kFinalMinimize);
  EXPECT_EQ(s.stop, StopReason::kLocalOptimum);
  EXPECT_EQ(next_phase(s, improved(), schedule()).stop, StopReason::kLocalOptimum);
}

TEST(ReductionPhases, AProbeThatImprovesLeavesTheOptimumBehind) {
  ReductionState from = in(Phase::kProbe);
  from.minimized = true;
  const ReductionState s = next_phase(from, improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kFixedStep);
  EXPECT_FALSE(s.minimized);
}

// A fixed step's state with one step left before max_solves.
ReductionState last_fixed_step(bool minimized = false) {
  ReductionState s = in(Phase::kFixedStep);
  s.steps = schedule().max_solves - 1;
  s.minimized = minimized;
  return s;
}

TEST(ReductionPhases, AfterMaxSolvesStepsFixedStepsEndWithAFinalMinimisation) {
  const ReductionState s = next_phase(last_fixed_step(), improved(), schedule());
  EXPECT_EQ(s.phase, Phase::kFinalMinimize);
  EXPECT_EQ(s.steps, schedule().max_solves);
  EXPECT_EQ(s.stop, StopReason::kMaxSolves);
  const ReductionState done = next_phase(s, improved(), schedule());
  EXPECT_EQ(done.phase, Phase::kDone);
  EXPECT_EQ(done.stop, StopReason::kMaxSolves);
}

TEST(ReductionPhases, AfterMaxSolvesMinimizingStepsEndWithoutOne) {
  ReductionState from = in(Phase::kMinimizingStep);
  from.steps = schedule().max_solves - 1;
  EXPECT_EQ(next_phase(from, improved(), schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(from, improved(), schedule()).stop, StopReason::kMaxSolves);
}

TEST(ReductionPhases, NoFinalMinimisationOfAnAlreadyMinimisedBest) {
  EXPECT_EQ(next_phase(last_fixed_step(true), no_gain(), schedule()).phase, Phase::kDone);
}

TEST(ReductionPhases, NoFinalMinimisationPastTheTimeLimit) {
  PhaseOutcome o = improved();
  o.out_of_time = true;
  EXPECT_EQ(next_phase(last_fixed_step(), o, schedule()).phase, Phase::kDone);
}

TEST(ReductionPhases, TheRateShrinksUntilTheBoundClearsTheSmallestHorizon) {
  // T_best 10, smallest 9.5: rate 0.1 asks for 9, shrinks to 0.05 (9.5, allowed).
  PhaseOutcome o = improved();
  o.smallest = 9.5;
  const ReductionState s = next_phase(in(Phase::kMinimizingStep, 0.05), o, schedule());
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  EXPECT_DOUBLE_EQ(s.rate, 0.05);
  EXPECT_GE(step_bound(s, o.best_value), o.smallest);
}

TEST(ReductionPhases, ARateBelowMinRateEndsTheLoop) {
  // Fixed steps without a minimisation since: end with one.
  ReductionState from = in(Phase::kFixedStep, 0.015);
  from.cut_short = true;
  EXPECT_EQ(next_phase(from, no_gain(), schedule()).phase, Phase::kFinalMinimize);
  // Minimising steps: done.
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep, 0.015), no_gain(), schedule()).phase,
            Phase::kDone);
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep, 0.015), no_gain(), schedule()).stop,
            StopReason::kMinRate);
  EXPECT_EQ(next_phase(from, no_gain(), schedule()).stop, StopReason::kMinRate);
  // No rate keeps the bound above the smallest horizon.
  PhaseOutcome o = improved();
  o.smallest = 9.99;
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep), o, schedule()).phase, Phase::kDone);
}

TEST(ReductionPhases, NoStepPastTheTimeLimit) {
  PhaseOutcome o = improved();
  o.out_of_time = true;
  for (Phase p : {Phase::kPerturbed, Phase::kMinimizingStep, Phase::kFixedStep, Phase::kProbe,
                  Phase::kEarlyMinimize}) {
    EXPECT_EQ(next_phase(in(p), o, schedule()).phase, Phase::kDone) << static_cast<int>(p);
    EXPECT_EQ(next_phase(in(p), o, schedule()).stop, StopReason::kOutOfTime) << static_cast<int>(p);
  }
}

TEST(ReductionPhases, AStepThatGoesOnHasNoStopReason) {
  EXPECT_EQ(next_phase(in(Phase::kMinimizingStep), improved(), schedule()).stop, StopReason::kNone);
  EXPECT_EQ(next_phase(in(Phase::kFixedStep), improved(), schedule()).stop, StopReason::kNone);
}

TEST(ReductionPhases, TheLastLineSaysWhyTheLoopStoppedNamingTheSetting) {
  EXPECT_EQ(stop_line(StopReason::kMaxSolves, schedule()), "stopped: reduction.max_solves = 10 steps made");
  EXPECT_EQ(stop_line(StopReason::kMinRate, schedule()),
            "stopped: the reduction rate fell below reduction.min_rate = 0.01");
  EXPECT_EQ(stop_line(StopReason::kLocalOptimum, schedule()),
            "stopped: a local optimum (a fixed step below it found nothing better)");
  EXPECT_EQ(stop_line(StopReason::kNoFeasiblePoint, schedule()),
            "stopped: no feasible point after 3 feasibility attempts (each at twice the horizon of the last)");
  EXPECT_EQ(stop_line(StopReason::kOutOfTime, schedule()), "stopped: time limit reached");
  EXPECT_EQ(stop_line(StopReason::kInterrupted, schedule()), "stopped: interrupted (SIGINT or SIGTERM)");
}

TEST(ReductionPhases, AFinalMinimisationEndsTheRun) {
  ReductionState from = in(Phase::kFinalMinimize);
  from.stop = StopReason::kMinRate;  // set by the transition that led to it
  EXPECT_EQ(next_phase(from, improved(), schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(from, failed(), schedule()).phase, Phase::kDone);
  EXPECT_EQ(next_phase(from, failed(), schedule()).stop, StopReason::kMinRate);
}

TEST(ReductionPhases, PhasesHaveTheSolveLogsNames) {
  EXPECT_EQ(solve_kind(Phase::kFeasibility), SolveKind::kFeasibility);
  EXPECT_EQ(solve_kind(Phase::kPerturbed), SolveKind::kPerturbedFeasibility);
  EXPECT_EQ(solve_kind(Phase::kMinimizingStep), SolveKind::kReduction);
  EXPECT_EQ(solve_kind(Phase::kFixedStep), SolveKind::kFixedStep);
  EXPECT_EQ(solve_kind(Phase::kProbe), SolveKind::kFixedStep);
  EXPECT_EQ(solve_kind(Phase::kEarlyMinimize), SolveKind::kMinimize);
  EXPECT_EQ(solve_kind(Phase::kFinalMinimize), SolveKind::kMinimize);
}

// The shared incumbent (search/reduction_phases.h): another start's best, 8 s, below this
// start's 10 s.
ReductionSettings sharing(int dominated_after = 3, bool jump = true) {
  ReductionSettings r = schedule();
  r.jump_to_incumbent = jump;
  r.dominated_after = dominated_after;
  return r;
}
PhaseOutcome under(PhaseOutcome o, double incumbent = 8.0) {
  o.incumbent = incumbent;
  return o;
}

TEST(ReductionPhasesIncumbent, AStepAimsBelowTheIncumbentWhenItIsLowerAndJumpsAreOn) {
  EXPECT_DOUBLE_EQ(step_reference(under(outcome()), sharing()), 8.0);
  EXPECT_DOUBLE_EQ(step_reference(under(outcome(), 12.0), sharing()), 10.0);  // own best lower
  EXPECT_DOUBLE_EQ(step_reference(under(outcome()), sharing(3, false)), 10.0);
  EXPECT_DOUBLE_EQ(step_reference(outcome(), sharing()), 10.0);  // none known (+inf)
}

TEST(ReductionPhasesIncumbent, ABestAboveTheIncumbentForDominatedAfterStepsInARowStops) {
  ReductionState s = in(Phase::kMinimizingStep);
  s = next_phase(s, under(improved()), sharing());  // 10 is still above 8: one
  EXPECT_EQ(s.above_incumbent, 1);
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  s = next_phase(s, under(no_gain()), sharing());  // two
  EXPECT_EQ(s.above_incumbent, 2);
  EXPECT_NE(s.phase, Phase::kDone);
  s = next_phase(s, under(no_gain()), sharing());  // three: dominated, no final minimisation
  EXPECT_EQ(s.phase, Phase::kDone);
  EXPECT_EQ(s.stop, StopReason::kDominated);
}

TEST(ReductionPhasesIncumbent, ABestBelowTheIncumbentResetsTheCount) {
  ReductionState s = in(Phase::kFixedStep);
  s.above_incumbent = 2;
  PhaseOutcome o = under(improved());
  o.best_value = 7.5;  // below another start's 8: this start leads
  s = next_phase(s, o, sharing());
  EXPECT_EQ(s.above_incumbent, 0);
  EXPECT_EQ(s.phase, Phase::kFixedStep);
}

TEST(ReductionPhasesIncumbent, FeasibilityAndThePerturbationAreNotStepsOfTheCount) {
  ReductionState s = next_phase(begin_reduction(sharing(1)), under(improved()), sharing(1));
  EXPECT_EQ(s.phase, Phase::kMinimizingStep);
  EXPECT_EQ(s.above_incumbent, 0);
}

TEST(ReductionPhasesIncumbent, DominatedAfterZeroNeverStopsAStepForTheCount) {
  ReductionState s = in(Phase::kFixedStep);
  s.above_incumbent = 50;
  s = next_phase(s, under(improved()), sharing(0));
  EXPECT_EQ(s.phase, Phase::kFixedStep);
}

TEST(ReductionPhasesIncumbent, NoRateLeftToAimBelowTheIncumbentIsDominatedNotMinRate) {
  // Aiming below 8 with the smallest horizon at 7.99: no rate >= 0.01 is allowed.
  PhaseOutcome o = under(no_gain());
  o.smallest = 7.99;
  const ReductionState s = next_phase(in(Phase::kFixedStep, 0.05), o, sharing(0));
  // (a failed first fixed step goes to the early minimisation, which does not admit)
  EXPECT_EQ(s.phase, Phase::kEarlyMinimize);
  const ReductionState t = next_phase(in(Phase::kMinimizingStep, 0.05), o, sharing(0));
  EXPECT_EQ(t.phase, Phase::kDone);
  EXPECT_EQ(t.stop, StopReason::kDominated);
  // The same without jumps aims below its own 10 s: a rate is left.
  const ReductionState u = next_phase(in(Phase::kMinimizingStep, 0.05), o, sharing(0, false));
  EXPECT_EQ(u.phase, Phase::kMinimizingStep);
  EXPECT_DOUBLE_EQ(step_bound(u, step_reference(o, sharing(0, false))), 10.0 * (1 - 0.025));
}

TEST(ReductionPhasesIncumbent, WithoutAnIncumbentEveryTransitionIsTheSame) {
  // An infinite incumbent (none known; --deterministic) changes no transition.
  for (Phase p : {Phase::kMinimizingStep, Phase::kFixedStep, Phase::kProbe, Phase::kEarlyMinimize})
    for (const PhaseOutcome& o : {improved(), improved(true), no_gain(), failed()}) {
      const ReductionState a = next_phase(in(p), o, schedule());
      const ReductionState b = next_phase(in(p), o, sharing(1));
      EXPECT_EQ(a.phase, b.phase);
      EXPECT_EQ(a.stop, b.stop);
      EXPECT_DOUBLE_EQ(a.rate, b.rate);
    }
}

TEST(ReductionPhasesIncumbent, TheStopLineNamesTheSettings) {
  const std::string line = stop_line(StopReason::kDominated, sharing());
  EXPECT_NE(line.find("dominated"), std::string::npos);
  EXPECT_NE(line.find("reduction.dominated_after = 3"), std::string::npos);
}

}  // namespace
}  // namespace disco
