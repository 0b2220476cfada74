// disco — solving an Nlp with Ipopt (exact Jacobian, exact Hessian).
//
// IpoptSolver owns one Ipopt application configured from option entries
// (normally the `ipopt:` section of configs/disco.yaml plus `--set ipopt.*`), and the `kkt:`
// section's treatment of Ipopt's factorisations (core/ipopt/kkt_solver.h).
// Each entry is checked against Ipopt's registry when the solver is made: an
// unknown name or a bad value is an InputError naming where it was given.
//
// solve() runs one Ipopt solve from a start point, optionally warm-started
// with the multipliers of an earlier solve of an NLP of the same shape, within
// the limits of an NlpLimits (a request: the solver keeps nothing of it), and
// says how it ended as an NlpOutcome (Ipopt's own status is kept for messages). MUMPS
// (Ipopt's linear solver here) is not thread-safe: call solve() from one
// thread of a process at a time.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/linalg/sparse_ldlt.h"
#include "core/nlp/nlp.h"
#include "core/util/clock.h"

namespace disco {

struct IpoptOption {
  std::string name, value;
  std::string where;  // "FILE:LINE" or "--set", for error messages
};

// What an IpoptSolver is made from: Ipopt's options, and how disco treats Ipopt's KKT
// factorisations (the `kkt:` section of configs/disco.yaml).
// Which solver factorises Ipopt's KKT matrices (kkt.solver).
enum class KktSolverKind {
  kMumps,  // Ipopt's MUMPS interface
  kLdlt,   // disco's LDLᵀ (core/linalg/sparse_ldlt.h), MUMPS for what it cannot solve
  kPivoted,  // disco's pivoting LDLᵀ (core/linalg/pivoted_ldlt.h), MUMPS for what it cannot
             // solve
};

// kkt.dump: every `every`-th factorised KKT matrix to `dir` (0: none; core/ipopt/kkt_solver.h).
struct KktDump {
  int every = 0;
  std::string dir;
};

struct IpoptSettings {
  std::vector<IpoptOption> options;
  // Start every iteration's factorisation from a Hessian perturbation (Ipopt's
  // degenerate-Hessian mode) instead of first trying none: core/ipopt/kkt_solver.h.
  bool perturbed_first = false;
  KktSolverKind kkt_solver = KktSolverKind::kMumps;
  // kkt.polish_rescue: a solve with a branch fixed (NlpLimits::fixed_branch) that has not
  // converged within `polish_rescue_after` iterations by kkt_solver starts again, from the same
  // point, with `polish_rescue_solver` (0: with it from the first iteration). Its 'same' is
  // resolved to kkt_solver when the settings are read: then there is no rescue.
  KktSolverKind polish_rescue_solver = KktSolverKind::kMumps;
  int polish_rescue_after = 0;
  LdltSettings ldlt;  // used with KktSolverKind::kLdlt and kPivoted
  KktDump dump;
};

// Primal and dual values of an NLP solve (Ipopt's sign conventions).
struct NlpPoint {
  Vector z;       // primal
  Vector lambda;  // constraint multipliers
  Vector z_lo;    // lower-bound multipliers (>= 0)
  Vector z_hi;    // upper-bound multipliers (>= 0)
  // Duals exist when the bound multipliers do (an NLP may have no rows).
  bool has_duals() const { return z_lo.size() > 0; }
};

// One stage of a barrier path: Ipopt's barrier parameter mu starts at mu_init and falls
// monotonically (mu_strategy monotone) to mu_target, where the solve ends once the barrier
// problem's optimality error is below max(tol, the configured tol). Used by a homotopy that
// moves its relaxation with the barrier (core/elastic/elastic_solver.h, formulation relaxed).
struct BarrierStage {
  double mu_init = 0.0;  // 0: the configured mu_init
  double mu_target = 0.0;
  double tol = 0.0;
};

// What one solve may spend, and where it stops.
struct NlpLimits {
  int iterations = 0;               // stop after this many iterations (0: Ipopt's max_iter only)
  std::optional<Deadline> deadline;  // stop at the first iteration past it on disco's clock
                                     // (core/util/clock.h; none: no limit);
                                     // an interrupt (core/util/interrupt.h) stops it too
  std::optional<BarrierStage> barrier;  // none: the configured mu strategy, to Ipopt's tol
  // Not a limit: a model that follows the barrier parameter inside the solve (elastic
  // formulation barrier, core/elastic/elastic_solver.h). Called at every iteration of Ipopt's
  // regular mode (not in its restoration phase) with Ipopt's current mu, after Ipopt has
  // evaluated the iterate and before it tests convergence; returns whether it changed the NLP's
  // functions. If so, the solver makes Ipopt evaluate the current iterate again: it replaces
  // Ipopt's current iterate by a copy (the same values under new tags, so none of Ipopt's
  // cached values of the old functions is used again), and records a BarrierRefresh.
  std::function<bool(double mu)> follow_barrier;
  // Not a limit on its own: called at every iteration of Ipopt's regular mode with what
  // Ipopt reports of the iterate (its intermediate callback's values) and the current value
  // of the NLP's variable `watch.index` (read from Ipopt's iterate; index < 0: none);
  // returning true stops the solve there (NlpOutcome::kStagnated).
  struct Iterate {
    int iteration = 0;
    double value = 0.0;           // the watched variable (NaN without one)
    double objective = 0.0;       // the NLP's objective (Ipopt's unscaled f)
    double infeasibility = 0.0;   // Ipopt's primal infeasibility (its log's inf_pr)
    double mu = 0.0;              // Ipopt's barrier parameter
  };
  struct Watch {
    int index = -1;
    std::function<bool(const Iterate&)> stop;
  };
  std::optional<Watch> watch;
  // Not a limit: a start without duals (Ipopt then starts cold: its own initial multipliers and
  // mu) is pushed inside its bounds as a warm start is (the configured warm_start_bound_push,
  // warm_start_bound_frac, warm_start_slack_bound_push and warm_start_slack_bound_frac) instead
  // of by bound_push, bound_frac, slack_bound_push and slack_bound_frac. For a cold start from a
  // converged point (ElasticRequest::cold_start), which stays that near its corner.
  bool push_as_warm = false;
  // Not a limit: the NLP has a branch fixed (elastic polish, branch descent): one side of every
  // complementarity pair held at zero, so its Jacobian is often rank-deficient, which disco's
  // regularised LDLᵀ hides from Ipopt. Such a solve may be rescued (kkt.polish_rescue,
  // IpoptSettings::polish_rescue_solver): started again with another KKT solver.
  bool fixed_branch = false;
};

// One change of the NLP by NlpLimits::follow_barrier, as Ipopt saw it: its iteration, its
// barrier parameter, and the largest change of its own inequality-constraint values d(x) at
// the (unchanged) current iterate, read from Ipopt's calculated quantities before and after.
struct BarrierRefresh {
  int iteration = 0;
  double mu = 0.0;
  double d_change = 0.0;  // max_i |d_i(x) after − d_i(x) before|, in Ipopt's scaling of d
};

// How an NLP solve ended, in disco's terms.
enum class NlpOutcome {
  kConverged,      // Ipopt's Solve_Succeeded or Solved_To_Acceptable_Level
  kInfeasible,     // Infeasible_Problem_Detected: locally infeasible
  kIterationCap,   // stopped at NlpLimits::iterations
  kTimeLimit,      // stopped at NlpLimits::deadline, or by an interrupt
  kMaxIterations,  // Ipopt's own max_iter
  kInvalidNumber,  // an evaluation failed: NaN, Inf or an error in a callback
  kStagnated,      // stopped by NlpLimits::watch
  kFailed,         // any other Ipopt status (ipopt_status says which)
};
// "converged", "infeasible", "iteration cap", "time limit", "max_iter", "invalid number",
// "stagnated", "failed".
std::string to_string(NlpOutcome outcome);

// What the KKT linear solver did in one solve (core/ipopt/kkt_solver.h).
struct KktCounts {
  int factorisations = 0;  // factorisations run by either solver (the LDLᵀ's refusals of a
                           // matrix with an empty row included)
  int answered = 0;        // answered "singular" without factorising (kkt.perturbed_first)
  // kkt.solver ldlt or pivoted: the matrices MUMPS factorised because disco's LDLᵀ could not solve them
  // to kkt.ldlt.residual_tolerance (or met a NaN or Inf), could not certify a wrong inertia,
  // or because Ipopt asked for more quality; counted in factorisations too.
  int fallbacks = 0;
  // kkt.solver pivoted: Ipopt's requests for more quality answered by raising the pivot
  // threshold (and factorising again, counted in factorisations).
  int threshold_raises = 0;
  // kkt.solver ldlt with kkt.ldlt.fallback pivoted: the matrices the LDLᵀ passed to the
  // pivoting LDLᵀ instead of MUMPS (counted in factorisations too).
  int to_pivoted = 0;
  // Analyses of a structure by disco's LDLᵀ solvers (once per solve and solver) whose ordering
  // is METIS's nested dissection rather than AMD (kkt.ldlt.ordering;
  // core/linalg/permuted_symmetric.h).
  int nested_dissection = 0;
  // Solves with a branch fixed that kkt.polish_rescue started again with its solver (their KKT
  // work before and after is counted in the other fields).
  int polish_rescues = 0;
  // Fill-reducing orderings computed: structures the IpoptSolver met for the first time (its
  // analyses of a structure met before reuse that ordering; permuted_symmetric.h, OrderingCache).
  int orderings = 0;
  // The matrices Ipopt handed over for factorisation: every factorisation but a matrix's second
  // or later (a fallback, a pass to the pivoting LDLᵀ, a factorisation with a raised threshold).
  int matrices() const { return factorisations - fallbacks - to_pivoted - threshold_raises; }
  KktCounts& operator+=(const KktCounts& o) {
    factorisations += o.factorisations;
    answered += o.answered;
    fallbacks += o.fallbacks;
    threshold_raises += o.threshold_raises;
    to_pivoted += o.to_pivoted;
    nested_dissection += o.nested_dissection;
    polish_rescues += o.polish_rescues;
    orderings += o.orderings;
    return *this;
  }
};

struct NlpResult {
  NlpPoint point;
  double objective = 0.0;
  NlpOutcome outcome = NlpOutcome::kFailed;
  int ipopt_status = 0;  // Ipopt::ApplicationReturnStatus, for messages
  int iterations = 0;
  double seconds = 0.0;
  KktCounts kkt;
  std::vector<BarrierRefresh> refreshes;  // with NlpLimits::follow_barrier
  bool converged() const { return outcome == NlpOutcome::kConverged; }
};

// Ipopt's name for a return status, e.g. "Solve_Succeeded".
std::string ipopt_status_name(int status);
// How a solve ended, for messages: "iteration cap" or "time limit" when a limit of disco's
// stopped it, else Ipopt's status, e.g. "Ipopt: Invalid_Number_Detected".
std::string describe(NlpOutcome outcome, int ipopt_status);

class IpoptSolver {
 public:
  explicit IpoptSolver(const IpoptSettings& settings);
  // Ipopt exactly as these options configure it (no disco treatment of its factorisations).
  explicit IpoptSolver(const std::vector<IpoptOption>& options);
  ~IpoptSolver();
  IpoptSolver(const IpoptSolver&) = delete;
  IpoptSolver& operator=(const IpoptSolver&) = delete;

  // Solves `nlp` from start.z; when start has duals (from a solve of an NLP
  // of the same shape) they warm-start Ipopt, if the configured warm_start_init_point is
  // "yes" (configs/disco.yaml; "no": every solve starts its duals cold).
  // A solve with limits.fixed_branch may be two Ipopt solves from `start` (kkt.polish_rescue):
  // the result is the second's, with both solves' iterations, seconds and KKT counts.
  NlpResult solve(const Nlp& nlp, const NlpPoint& start, const NlpLimits& limits = {});

  // The largest gradient entry at a solve's start that Ipopt leaves unscaled (its
  // nlp_scaling_max_gradient with gradient-based scaling; infinity with none): a larger one
  // scales the objective down by this over it, and Ipopt's tolerances with it.
  double scaling_max_gradient() const { return scaling_max_gradient_; }

 private:
  // One Ipopt solve, its KKT matrices factorised by `kkt_solver`.
  NlpResult solve_once(const Nlp& nlp, const NlpPoint& start, const NlpLimits& limits,
                       KktSolverKind kkt_solver);

  struct Application;  // holds Ipopt's reference-counted application
  std::unique_ptr<Application> app_;
  bool perturbed_first_ = false;  // IpoptSettings::perturbed_first
  KktSolverKind kkt_solver_ = KktSolverKind::kMumps;
  KktSolverKind polish_rescue_solver_ = KktSolverKind::kMumps;  // IpoptSettings::polish_rescue_*
  int polish_rescue_after_ = 0;
  LdltSettings ldlt_;
  KktDump dump_;
  int dumped_ = 0;  // KKT matrices factorised so far, for kkt.dump.every
  // The fill-reducing orderings of the KKT structures met so far (the solves of one
  // IpoptSolver, a start, meet a few structures again and again; permuted_symmetric.h).
  OrderingCache orderings_;
  bool warm_start_ = false;  // the configured warm_start_init_point (Ipopt's default: no)
  // The configured barrier options, restored after a solve with a BarrierStage.
  std::string mu_strategy_;
  double mu_init_ = 0.0, mu_target_ = 0.0, tol_ = 0.0;
  double scaling_max_gradient_ = std::numeric_limits<double>::infinity();
  // Ipopt's cold-start pushes (bound_push, bound_frac, slack_bound_push, slack_bound_frac) and
  // their warm-start counterparts, as configured (NlpLimits::push_as_warm).
  static constexpr int kPushes = 4;
  double cold_push_[kPushes] = {}, warm_push_[kPushes] = {};
};

}  // namespace disco
