// disco — the paper's inexact objective reduction (Section IV-B, last
// paragraph), from one start.
//
//   1. Feasibility: fix T_f = max(horizon_min, horizon_factor * reference
//      time: the slowest robot's straight move alone), or the start's own horizon
//      (ReductionSettings::horizon, a start from a trajectory), and solve
//      the elastic MPCC from the guess (the objective is then constant). If it
//      is not solved, double T_f and try again (three times at most). An attempt whose eps
//      stagnates far from tight ends there, not tight (ElasticRequest::feasibility,
//      elastic.stagnation.feasibility_after; core/elastic/elastic_solver.h). This
//      horizon is the largest any later step asks for, so each attempt first
//      sets the model's T_max to it (RobotProblem::set_horizon_max: the
//      adaptive model builds what the scene needs up to that horizon).
//   1b. Optional perturbation (a PerturbFunction, below): called once with the
//      certified feasible point, it returns another guess and a fixed horizon;
//      the elastic MPCC is solved there once more, from that guess (a cold
//      start), and recorded as phase "perturbed feasibility". If that solve is
//      certified, its point becomes the best and the reduction continues from
//      it; otherwise the reduction continues from the feasible point of step 1
//      exactly as without a perturbation. Skipped past the time limit.
//   2. Reduction: with r = rate, require T_f <= (1 - r) T_best, warm-started
//      from the best point. A certified solution with a smaller T_f becomes
//      the best and r *= grow (at most 0.5); anything else r *= shrink. A step
//      whose bound lies below a valid lower bound (RobotProblem::lower_bound)
//      or below the model's smallest horizon (its lower bound on T_f, which
//      keeps h > 0) cannot succeed and is not tried: r shrinks instead. (A
//      fixed step below the smallest horizon once "succeeded" on a robot whose
//      target is its start, T_f -> 1e-20 s, and left a best point that
//      violates the model's bound by 1e-3 reported as solved.) Stop when
//      r < min_rate, after max_solves reduction solves or at the time limit.
//      Steps first minimise T_f under the bound with at most step_iterations
//      Ipopt iterations. The first time such a step does not converge, the
//      loop switches for good to fixed steps that solve at exactly
//      T_f = (1 - r) T_best, a homotopy in the horizon. Measured on
//      three_robots_contact: minimising inside the step stalled for 3000
//      iterations, fixed steps took 35-74 each.
//   3. Minimise T_f <= T_best from the best point, to land on the local
//      optimum rather than on a step of the homotopy: right after the first
//      fixed step that fails (the homotopy has passed the optimum's horizon),
//      else once the loop ends. minimize_iterations > 0 caps the early one:
//      cut short, it changes nothing, the fixed steps go on and the loop
//      minimises again, uncapped, at its end. Measured (start 0): with 400,
//      three_robots_contact took 1471 iterations / 48 s to 2.307668 s instead
//      of 2909 / 105 s to 2.301855 s; paper B2 went the slower way. Default 0.
//   A local optimum found inside the loop (an early minimisation that
//   converged, or a minimising step strictly inside its bound) is probed
//   below with a fixed step, as the paper's reduction steps down until a
//   step fails, and the loop stops when that fails; a probe that succeeds
//   continues the homotopy from there. Below a minimisation's optimum only
//   with reduction.probe_after_minimize (off by default: no such probe
//   succeeded on 234 starts, and they cost 5-7 % of the iterations;
//   search/README.md, "Why the defaults"): without it the loop ends there.
//   Measured on paper A3 (start 0): 935 iterations with the minimisation only
//   at the end, 436 with it after the first failure, the same optimum; B2:
//   2263 and 1177.
//   Minimising (step 3 below and its early call) is one of two methods (reduction.minimize;
//   configs/disco.yaml says which is the default and why): kElastic, one elastic-mode
//   minimisation to convergence (as described above), or kBranch, a descent by branches
//   instead of one long elastic solve:
//   a) one segment of the elastic minimisation (T_f <= T_best, at most segment_iterations
//   Ipopt iterations) from the best point; b) a branch descent from the segment's point
//   (ElasticSolver::solve_branch: the smooth program with the smaller side of every pair
//   fixed at 0, minimised under T_f <= T_best, and biactive pairs whose fixed side has a
//   negative multiplier flipped, at most flip_rounds times: a B-stationary point when no
//   flip is left; 3-30 iterations mostly without inertia corrections); if the segment
//   converged, stop; c) more segments, the first from the best branch point, each
//   continuing the last (its primal-dual point) under the T_f
//   it starts from, each followed by a branch descent when its T_f is below the best; stop
//   when a segment converges or is infeasible, when one ends elastic_not_tight without a
//   new best, after two segments in a row without a new best, after max_solves segments
//   or at the time limit. The descent counts as a local optimum for the loop.
//   Measured (start 0, paper A3): the long minimisation after the fixed steps is replaced
//   by a 60-iteration segment and a 16-iteration branch descent that lands on the same
//   optimum 9.832592.
// Another objective (core/model/objective.h: energy, time + energy): read J for T_f in every
// bound, step and best above (RobotProblem::bound_objective); the feasibility phase still
// fixes T_f itself (energy: at the scene's horizon, in one attempt, since T_f is not free)
// and sets T_max to RobotProblem::horizon_reach (time + energy: a better point may be slower),
// step 1b runs for time and time + energy only, and no step is asked below
// RobotProblem::objective_floor().
// Salvage (reduction.salvage_iterations > 0, under a time limit). A step or minimisation that
//   the limit cuts short ends at a point that is not certified: without more, its progress is
//   lost (on paper B1 the minimisation after the fixed steps runs 70 s; a 60 s search kept the
//   last fixed step's T_f). So every solve after the feasibility phase ends that much earlier
//   than the limit: salvage_iterations Ipopt iterations at the start's own pace so far (its
//   seconds per iteration), at most half the time left. A solve cut there is salvaged: from
//   its point, the branch NLP (the smaller side of every pair fixed at 0, as polish does,
//   without flips) minimises T_f <= T_best in at most salvage_iterations iterations, by the
//   limit itself; certified and below the best, its point becomes the best (not stationary:
//   "feasible"). The loop then ends, out of time. An interrupt is not salvaged.
//   A minimisation that stalls, ending at Ipopt's max_iter (ipopt.max_iter), is salvaged the
//   same way, with or without a time limit, and the loop goes on from its best point (the
//   minimisation did not converge: an early one hands over to fixed steps). Its point is often
//   within reach of a branch: on a refine of paper B3 (start 9 from its screen) three
//   minimisations each ended at max_iter with complementarity 2e-8-1e-6, and the start took
//   15,284 iterations to 10.092682 without the salvage.
// The stall rule (elastic.stall, off by default; core/elastic/elastic_solver.h, Stall). A
//   minimisation (step 3 and its early call, never a step or a segment) that creeps at a
//   settled iterate ends there and is judged as if converged; certified, it counts as a local
//   optimum for the loop (the end, or probed below with reduction.probe_after_minimize) but its
//   point is not shown stationary
//   (SolveRecord::stalled); not certified, it is salvaged as at max_iter.
// Minimisations (reduction.minimize_duals, kElastic; step 3 and its early call, never a step,
//   segment or salvage). A minimisation starts from the best point, the optimum of a fixed step
//   (or of the feasibility phase), and travels far: paper B2 start 1 from T_f 13.87 to 10.14.
//   Warm-started from that point's multipliers its barrier begins near zero, and Ipopt
//   creeps along the boundary (core/README.md, "The iterations of one start"). `cold`: it
//   starts from the best point's primal values only, with Ipopt's own initial multipliers,
//   bound push and mu (ElasticRequest::cold_start); its zeta rule's raises and polish are
//   warm-started as always. `warm`: from the multipliers too.
//   reduction.minimize_zeta > 0 and below the best point's zeta: the minimisation first runs
//   with that weak penalty on eps (ElasticRequest::zeta), its raises limited to the best
//   point's zeta times elastic.zeta_factor (ElasticRequest::zeta_limit). A weak penalty lets
//   the minimisation cross the complementarity corners with eps > 0 instead of creeping along
//   them, and the raises then make it tight: paper B3 start 0's minimisation took 576, 331 and
//   182 iterations at zeta 1, 10 and 100 to 10.107932, against 2,677 and 326 at 10 and 100 to
//   10.138635. If that attempt is not certified, it is recorded and the minimisation runs
//   again from the best point as it would without the setting (not when a limit ended it: the
//   time limit or an interrupt, then salvaged as always, or the early minimisation's cap)
//   (push_coin start 1: not tight at any zeta from 1 to 1e5, measured without the limit).
//   reduction.minimize_weak homotopy: that weak attempt runs the relaxation homotopy of
//   formulation relaxed on the lumped row (ElasticRequest::relaxation: sigma from elastic.sigma
//   down, each stage ended on the barrier path, its zeta raised while the relaxation has never
//   held or where it stops holding too far from the corner for polish, then polish) instead of
//   the penalty loop's raises to tight; its fallback runs
//   as always. Paper B1 start 1's minimisation: 337 iterations to 9.786586 against 1,449 to
//   9.771682 (search/README.md, "Why the defaults").
// Fixed steps and zeta. A fixed step (and a probe) fixes J, so J is constant on its feasible
//   set and the elastic NLP minimises eps alone, whatever zeta: a fixed step that converges
//   with complementarity not tight ends there (ElasticRequest::objective_fixed), without the
//   zeta rule's raises, which only rescale the objective (polish is still tried below 1e-2).
//   One that ends tight below elastic.polish_fixed_above is not polished
//   (ElasticSettings::polish_fixed_above): certified as it stands, at its fixed J.
//   One whose eps has stagnated far from tight ends there, as not tight (elastic.stagnation,
//   core/elastic/elastic_solver.h): a fixed step that fails leaves nothing behind, so a cut
//   that only shortens a failure changes nothing else in the loop.
//   The path does not change: a failed step leaves nothing behind (the next starts from the
//   best point). Measured on the 18-start set (starts 0-2 of paper A3, A4, B1, B2, B3 and
//   three_robots_contact): the same answers bit for bit, 0.953 of the Ipopt iterations. With
//   raises, 2 of 123 fixed steps that ended not tight at the first zeta became tight (176
//   starts, 0-3 of every scene in configs/scenarios and configs/stress, and paper A1, A2),
//   both from a residual within twice the tolerance, where polish certifies them (without the
//   raises those two starts ended lower, the other 174 the same). The
//   feasibility phases keep the zeta rule: they start from a guess, where Ipopt can stop at a
//   stationary point of eps that is not its minimum and the warm-started re-solve leaves it
//   (tests/test_solution_file.cpp's push_box scene: 0.19, then 7e-9 after one raise).
// Polish. A point the loop keeps only to start later solves from, at a J that polish cannot
//   change, is not polished when its elastic solve already ends tight, complementarity at most
//   elastic.polish_fixed_above (ElasticSettings::polish_fixed_above): fixed steps and probes
//   (objective_fixed), and the feasibility phases of objective time (objective_constant: J is
//   their fixed horizon; they keep the zeta rule), unless step 1b perturbs the feasible point
//   next, which starts from the certified point itself. Later solves start from the elastic
//   point either way (core/elastic/elastic_solver.h, solve()), so the path is the same.
//   Minimisations are polished: polish can lower their J, and gives the reported optimum exact
//   complementarity.
// The control flow above is search/reduction_phases.h: named phases and one transition
// function; reduce_objective runs each phase's solve, passing the elastic solver its limits
// (iteration cap, the time limit's deadline) as an ElasticRequest.
// Only certified (kSolved) points ever become the best. If no horizon gives
// one, the scene is reported kInfeasible: Ipopt found the elastic NLP locally
// infeasible, or complementarity could not be made tight (the elastic mode
// needs eps > 0) at any horizon tried; `feasibility_detail` says which.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"  // ReductionSettings, Minimizer, reduction_settings
#include "core/elastic/elastic_solver.h"
#include "core/model/robot_problem.h"
#include "core/util/numbers.h"

namespace disco {

// What an elastic-mode solve of the reduction is (the solve log's "phase" column):
// step 1, step 1b, a minimising step of step 2, a fixed step (or the probe below a local
// optimum), a minimisation (step 3, or a segment of the kBranch minimiser), a branch descent.
// A salvage: the branch solve from the point of a step or minimisation that the time limit cut
// short (below, "Salvage").
enum class SolveKind {
  kFeasibility, kPerturbedFeasibility, kReduction, kFixedStep, kMinimize, kBranch, kSalvage
};
// "feasibility", "perturbed feasibility", "reduction", "fixed step", "minimize", "branch",
// "salvage".
std::string to_string(SolveKind kind);

// One elastic-mode solve (possibly several Ipopt solves inside), as the solve log shows it.
struct SolveRecord {
  SolveKind kind = SolveKind::kFeasibility;
  double bound = 0.0;  // the fixed T_f [s] (feasibility phases), or J's bound or fixed value
  double T_f = 0.0;    // s: at the solve's end
  double value = 0.0;  // J at the solve's end (SI; T_f for objective time)
  MpccStatus status = MpccStatus::kFailed;
  NlpOutcome outcome = NlpOutcome::kFailed;  // of its last NLP solve
  int ipopt_status = 0;                       // ... Ipopt's, for messages
  Certificate certificate;
  int nlp_solves = 0, iterations = 0;
  double seconds = 0.0;
  bool improved = false;  // became the new best
  // A minimisation that the stall rule ended (elastic.stall, ElasticSettings::Stall): even
  // certified, its point is not shown stationary.
  bool stalled = false;
  // A solve of the coarse stage of a coarse-to-fine start (search/solve_scene.h): of the
  // scene at fewer steps, so never a best of the start (improved stays false).
  bool coarse = false;
};

// The solve log of `disco solve` (and of every start under `disco search
// --verbose`): a header, then one line per elastic-mode solve, numbered from 1:
// phase ("coarse " before it in a coarse stage), T_f bound and reached (for another
// objective: J's bound, J and T_f), how it ended in
// words (solve_outcome_words; ", stalled" after them for a minimisation the stall rule ended),
// certificate, Ipopt solves, iterations and seconds, and "*" for a new best (for a real failure, Ipopt's status in parentheses). The loop's last line, stop_line() (search/reduction_phases.h),
// says why it stopped.
std::string solve_log_header(ObjectiveKind kind = ObjectiveKind::kTime);
std::string solve_log_line(int number, const SolveRecord& r, ObjectiveKind kind = ObjectiveKind::kTime);
// "solved", "not tight", "infeasible", "cap reached" (its iteration cap), "time limit",
// "invalid number" (an evaluation gave NaN or Inf), "max_iter" (Ipopt's own), or "failed".
std::string solve_outcome_words(MpccStatus status, NlpOutcome outcome);

enum class StopReason;  // search/reduction_phases.h

struct ReductionResult {
  bool found = false;        // a certified solution exists
  StopReason stop{};         // why the loop ended (stop_line() says it in words)
  MpccStatus status = MpccStatus::kFailed;  // kSolved if found; else kInfeasible or kFailed
  std::string feasibility_detail;           // the last feasibility solve's own status; when
                                            // kFailed with Ipopt's, "failed (Ipopt: NAME)"
  Vector last_attempt;  // when none is found: the point the last feasibility solve ended at
  double best_value = 0.0;   // J of best (SI: T_f in s for objective time)
  MpccResult best;           // the certified solve that gave best_value
  Stationarity stationarity = Stationarity::kFeasible;  // of best
  std::vector<SolveRecord> solves;
  int nlp_solves = 0, iterations = 0;
  KktCounts kkt;  // of all its NLP solves
  double seconds = 0.0;
  double time_to_first_feasible = -1.0;  // s, -1 if none
  double time_to_best = -1.0;
  // Every new best, in order: the time since the start of the run (the clock of
  // time_to_best) and its J. The first is the feasible point; the last is best_value.
  struct Improvement {
    double seconds = 0.0;
    double value = 0.0;
  };
  std::vector<Improvement> history;
  double incumbent = kInf;  // J: the scene's incumbent when the loop ended (+inf: none)
};

// The first feasibility horizon (step 1) for `problem`, in seconds.
double feasibility_horizon(const RobotProblem& problem, const ReductionSettings& settings);

using SolveCallback = std::function<void(const SolveRecord&)>;
// The initial guess for a feasibility horizon of `seconds` (model-unit z).
using GuessFunction = std::function<Vector(double seconds)>;

// Step 1b: a guess and the fixed horizon (seconds) to solve it at.
struct Perturbation {
  Vector guess;          // model-unit z, the size of the program's variables
  double seconds = 0.0;  // > 0
};
// Called once with the certified feasible point of step 1 (model-unit z); the
// horizon must not exceed the feasible point's.
using PerturbFunction = std::function<Perturbation(const Vector& feasible)>;

// The best certified J (T_f in s for objective time) that other starts of a search found for the scene so far, +inf
// if none: the shared incumbent (search/reduction_phases.h). Called between solves only.
using IncumbentFunction = std::function<double()>;

// `guess` defaults to smoothstep_guess (search/guess.h); without `perturb`,
// step 1b is skipped; without `incumbent` there is none (+inf).
ReductionResult reduce_objective(RobotProblem& problem, const ElasticSolver& solver,
                                 const ReductionSettings& settings, const GuessFunction& guess = {},
                                 const SolveCallback& on_solve = {},
                                 const PerturbFunction& perturb = {},
                                 const IncumbentFunction& incumbent = {});

}  // namespace disco
