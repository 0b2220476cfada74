// disco — solving an MPCC through its elastic mode, with a certificate.
//
// solve() runs, from a start point (or a warm start):
//   1. the elastic NLP (core/elastic/elastic_nlp.h) with penalty zeta;
//   2. if Ipopt converged but complementarity is not yet tight
//      (max_i |min(G_i, H_i)| > complementarity_tol), zeta *= zeta_factor and
//      the elastic NLP is solved again, warm-started, while zeta <= zeta_max;
//      past the limit, or when a raise changes the residual by less than
//      stall_change (relative), the result is kElasticNotTight, never
//      "solved". The exact penalty works as a threshold (the residual stays
//      put, then drops to zero once zeta passes the MPCC's multipliers), so
//      only a residual that does not move at all signals that raising cannot
//      help: that is what an active bound T_f <= B below the MPCC's optimum
//      gives, since eps is then already minimal over {T_f <= B}. When the
//      objective is fixed (ElasticRequest::objective_fixed: T_f = B), eps is
//      minimal after the first solve whatever zeta, and zeta is never raised;
//      such a solve whose eps has stopped falling far from tight is ended there, not tight,
//      as it would end at convergence (ElasticSettings::Stagnation);
//   With formulation kRelaxed (or kLumped and ElasticRequest::relaxation), steps 1-2 are
//   instead a homotopy that follows Ipopt's barrier
//   (after Leyffer, Lopez-Calva & Nocedal's relaxation; nosnoc's homotopy): the relaxed NLP
//   (elastic_nlp.h) at sigma = sigma_0, sigma_0 * sigma_factor, ... down to sigma_min, each
//   solve warm-started from the last and ended at Ipopt's barrier level
//   mu = barrier_ratio * sigma (a BarrierStage; to tolerance max(tol, sigma)), so that every
//   solve is a short, regular one and none crawls at the complementarity corner. The
//   homotopy ends when complementarity is tight, or where the relaxation stops holding
//   (eps > sigma: the penalty prefers to violate it, as below the MPCC's optimal horizon).
//   zeta is raised (as in step 2: same stall rule, same limit) while the relaxation has not yet
//   held, and where it stops holding at a point too far from complementarity for polish
//   (1e-2; the same sigma is then solved again). Polish (step 3) then fixes the branch; the
//   certificate decides.
//   With formulation kBarrier (a relaxation row per pair), steps 1-2 are the penalty loop of
//   steps 1-2 with the relaxation inside each Ipopt run (after Raghunathan & Biegler's IPOPT-C and Leyffer, Lopez-Calva &
//   Nocedal, where the relaxation moves with the barrier parameter): at every iteration
//   sigma = barrier_sigma_factor * mu^barrier_sigma_exponent, with mu Ipopt's own
//   (NlpLimits::follow_barrier; Ipopt then evaluates the current iterate again). With
//   elastic.barrier_mu monotone mu falls monotonically (Fiacco-McCormick, a BarrierStage from
//   the configured mu_init), as in those papers: Ipopt's adaptive mu may drop by orders of
//   magnitude in one iteration, and sigma with it, which fixes a branch before the iterate
//   has chosen one (ExpSqrt in tests/test_mpcc_textbook.cpp). One Ipopt run goes from a relaxed
//   problem with an interior to the MPCC's corner, as mu goes to 0. Polish is required (as
//   for kRelaxed): at a corner where both sides vanish the relaxation leaves both near
//   sqrt(sigma).
//   3. polish (optional: elastic.polish): the branch NLP in which, for every
//      pair, the smaller side at the elastic solution is fixed to zero, solved
//      warm-started. Complementarity then holds exactly up to the constraint
//      tolerance. If the branch NLP fails, the elastic answer stands. Not for a
//      fixed or constant objective's point that is already tight below polish_fixed_above.
//      With a side of every pair fixed every product is zero, so eps's optimum is 0 whatever
//      its weight: polish weighs it with min(zeta, IpoptSolver::scaling_max_gradient()), since
//      a zeta above that would only make Ipopt scale the objective down (gradient-based
//      scaling at the start, by nlp_scaling_max_gradient / zeta) and loosen the polished
//      point's optimality as much. Its solve, like solve_branch's, has a branch fixed
//      (NlpLimits::fixed_branch): one that has not converged within kkt.polish_rescue.after
//      iterations starts again with the pivoting LDLᵀ (IpoptSolver::solve).
// Every answer is certified on the MPCC itself (certify()); a result is
// kSolved only when Ipopt converged AND the certificate meets both
// tolerances.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/elastic/elastic_nlp.h"
#include "core/ipopt/ipopt_solver.h"

namespace disco {

enum class MpccStatus {
  kSolved,           // converged, certificate within tolerances
  kElasticNotTight,  // converged, but complementarity not tight at zeta_max
  kInfeasible,       // Ipopt found the (elastic) problem locally infeasible
  kFailed,           // Ipopt stopped otherwise; see ipopt_status
};
std::string to_string(MpccStatus s);

// What a certified point is known to be for the MPCC's objective (solution.json
// "stationarity"; search/objective_reduction.h says which solves give which).
enum class Stationarity {
  kFeasible,  // certified feasible: a step of the homotopy, no stationarity shown
  kStrong,    // a converged elastic-mode minimisation with complementarity tight and the bound
              // on T_f inactive: a KKT point of the elastic NLP at eps = 0, strongly stationary
              // for the MPCC (paper Section IV)
  kB,         // a branch descent that ended without a flip, the bound on T_f inactive: no
              // biactive pair's fixed side has a negative multiplier, B-stationary
};
std::string to_string(Stationarity s);  // "feasible", "strongly stationary", "B-stationary"

// The elastic mode's parameters: the `elastic:` section of configs/disco.yaml
// (core/config/solver_settings.h, elastic_settings), which holds their values; none are kept
// here.
struct ElasticSettings {
  ElasticFormulation formulation = ElasticFormulation::kLumped;
  double zeta = 0.0;           // initial penalty on eps
  double zeta_factor = 0.0;    // > 1: raise zeta by this factor
  double zeta_max = 0.0;       // give up beyond this
  double stall_change = 0.0;   // stop raising when the residual moves less; < 0: never stop early
  double complementarity_tol = 0.0;
  double violation_tol = 0.0;
  bool polish = false;
  // > 0: a solve whose objective is fixed or constant (ElasticRequest::objective_fixed: a fixed
  // step or a probe; ElasticRequest::objective_constant: a feasibility phase) that ends solved
  // with complementarity at most this is not polished: its elastic point is certified as it
  // stands, and warm starts continue from that point whether it is polished or not (solve()).
  // 0: polished as every other solve.
  double polish_fixed_above = 0.0;
  // kRelaxed only: the relaxation homotopy.
  double sigma = 0.0;          // first relaxation
  double sigma_factor = 0.0;   // next = sigma * factor
  double sigma_min = 0.0;      // the last relaxation solved
  double barrier_ratio = 0.0;  // each relaxed solve ends at mu = ratio * sigma
  // kBarrier only: sigma = factor * mu^exponent at every Ipopt iteration.
  double barrier_sigma_factor = 0.0;
  double barrier_sigma_exponent = 0.0;
  // kBarrier only: Ipopt's mu falls monotonically in its solves (true) or as configured
  // (ipopt.mu_strategy; false).
  bool barrier_monotone_mu = false;
  // A solve with the objective fixed (ElasticRequest::objective_fixed) minimises eps alone;
  // one whose eps has stopped falling far from tight would end not tight, and only after
  // many more iterations. It ends there (NlpOutcome::kStagnated, kElasticNotTight as at
  // convergence; polish is tried as then) by the rule `first`: from Ipopt iteration
  // first.after on (0: never), when the least eps of the last first.window iterations is
  // above first.level and less than the fraction first.decrease below the least eps of the
  // first.window iterations before those. Lumped and barrier formulations (penalty loop); eps
  // in the model's scaled units.
  // A feasibility phase (ElasticRequest::feasibility) minimises eps alone too, from a guess:
  // the same rule watches it from Ipopt iteration `feasibility_after` on (0: never), and a
  // stagnant eps ends it the same way, not tight, without the zeta rule's raises (from a
  // stagnant, unconverged point they stagnate again). Later than first.after: from a guess eps
  // can sit on a plateau above first.level for a while and then fall to 0.
  // A fixed step is also watched by a second, late rule of the same form (`late`: from
  // iteration late.after on, windows of late.window, eps above late.level, fallen by less
  // than late.decrease): a step whose eps settles just above 0, below first.level, can take a
  // thousand iterations to converge not tight (core/README.md, "The elastic mode").
  struct Stagnation {
    // One rule: from iteration `after` on (0: never), the least eps of the last `window`
    // iterations above `level` and less than the fraction `decrease` below the least of the
    // `window` iterations before those.
    struct Rule {
      int after = 0;
      int window = 0;
      double level = 0.0;
      double decrease = 0.0;
      bool stagnated(int iteration, const std::vector<double>& eps) const;
    };
    Rule first;  // fixed steps; feasibility phases with `after` = feasibility_after
    int feasibility_after = 0;
    Rule late;  // fixed steps only (ElasticRequest::objective_fixed)
    // Whether eps, given the values of consecutive Ipopt iterations (the last at `iteration`),
    // has stagnated by `first` or by `late`.
    bool stagnated(int iteration, const std::vector<double>& eps) const;
  };
  Stagnation stagnation;
  // A minimisation (ElasticRequest::stall) that creeps at the corner: Ipopt settled (mu at
  // most `mu`, primal infeasibility at most `infeasibility`: a settled iterate) while the
  // objective has moved by less than the fraction `decrease` over the last `window`
  // iterations. From iteration `after` on (0: never), at a settled iterate, when the least
  // objective of the settled iterates of the last `window` iterations lies less than
  // `decrease` times its size below the least of the settled iterates before those, the
  // solve ends there (NlpOutcome::kStagnated) and is judged as if it had converged: tight,
  // polish; not tight, the zeta rule. Its point is not shown stationary (MpccResult::stalled).
  struct Stall {
    int after = 0;
    int window = 0;
    double decrease = 0.0;
    double mu = 0.0;
    double infeasibility = 0.0;
    bool settled(const NlpLimits::Iterate& it) const {
      return it.mu <= mu && it.infeasibility <= infeasibility;
    }
    // Whether the solve has stalled at `iteration`, given the (iteration, objective) of its
    // settled iterates so far, the current one last.
    bool stalled(int iteration, const std::vector<std::pair<int, double>>& settled) const;
  };
  Stall stall;
};

// One call's own limits, as data: the solver keeps no per-call state.
struct ElasticRequest {
  int iteration_limit = 0;           // per Ipopt solve; 0 = Ipopt's max_iter only
  std::optional<Deadline> deadline;  // for the whole call; none = no limit
  // The MPCC's objective is constant on its feasible set: a bound fixes it (T_f for objective
  // time, or J's row). Then the elastic NLP minimises eps alone whatever zeta (zeta only scales
  // the objective, and Ipopt's gradient scaling undoes even that), so a solve that converges
  // with complementarity not tight is final: no zeta raise (kElasticNotTight at once; polish
  // is still tried). Without it, the zeta rule of step 2.
  bool objective_fixed = false;
  // The MPCC's objective is constant on its feasible set, but zeta's rule applies (the
  // reduction's feasibility phases: objective time at a fixed horizon, started from a guess),
  // and the caller has no use for a polished point: a solve that ends solved with
  // complementarity at most ElasticSettings::polish_fixed_above is certified as it stands, not
  // polished, as with objective_fixed. Polish could not change its objective either.
  bool objective_constant = false;
  // A feasibility phase of objective time (the reduction's steps 1 and 1b, whether or not a
  // perturbation follows): the objective is constant on the feasible set (the fixed horizon),
  // the solve starts from a guess and the zeta rule applies; ElasticSettings::Stagnation
  // watches eps from `feasibility_after` on, and a stagnant eps ends the call, not tight.
  bool feasibility = false;
  // A minimisation: ElasticSettings::Stall ends a solve that creeps at the corner.
  bool stall = false;
  // From a warm result (solve(mpcc, warm, ...)): start from its primal point only, with
  // Ipopt's own initial multipliers and barrier parameter (a cold start; the point pushed
  // inside its bounds as a warm start is, NlpLimits::push_as_warm), for a solve that travels
  // far from that point (the reduction's minimisations, reduction.minimize_duals). Its zeta
  // is still reused, and the solves after the first (zeta raises, polish) are warm-started as
  // always.
  bool cold_start = false;
  // > 0: the first solve's zeta, instead of the warm result's (or ElasticSettings::zeta from a
  // point); the reduction's minimisations start weak (reduction.minimize_zeta).
  double zeta = 0.0;
  // > 0: the zeta rule raises zeta at most to this (and never past ElasticSettings::zeta_max).
  double zeta_limit = 0.0;
  // Steps 1-2 by the relaxation homotopy of formulation kRelaxed (elastic.sigma, sigma_factor,
  // sigma_min, barrier_ratio) whatever elastic.formulation, which must then be kLumped or
  // kRelaxed (the same NLP) and polish on: the reduction's weak minimisations with
  // reduction.minimize_weak homotopy (search/objective_reduction.h, "Minimisations").
  bool relaxation = false;
};

// How well z satisfies the MPCC, in the MPCC's own units.
struct Certificate {
  double max_violation = 0.0;        // bounds and constraint rows, max over all
  double max_complementarity = 0.0;  // max_i |min(G_i, H_i)|
  double complementarity_product = 0.0;  // sum_i G_i H_i
  bool within(double violation_tol, double complementarity_tol) const {
    return max_violation <= violation_tol && max_complementarity <= complementarity_tol;
  }
};
Certificate certify(const Mpcc& mpcc, const ConstVectorRef& z);

struct MpccResult {
  MpccStatus status = MpccStatus::kFailed;
  NlpOutcome outcome = NlpOutcome::kFailed;  // of the last NLP solve
  int ipopt_status = 0;    // of the last NLP solve (Ipopt's, for messages)
  Vector z;                // MPCC variables
  double objective = 0.0;  // f(z), without the elastic penalty
  Certificate certificate;
  int nlp_solves = 0;
  int iterations = 0;
  KktCounts kkt;  // of all its NLP solves
  double seconds = 0.0;
  double zeta = 0.0;       // penalty at the end
  bool polished = false;
  // An elastic solve was ended by ElasticSettings::Stall: even certified, the point is not
  // shown to be stationary.
  bool stalled = false;
  NlpPoint elastic_point;  // elastic primal-dual point (before polish), for warm starts
  // solve_branch only: branch solves run, pairs flipped, and whether the end point passed the
  // sign test of every biactive pair (strongly stationary on its branch, hence B-stationary).
  int branch_solves = 0, flips = 0;
  bool b_stationary = false;
  bool solved() const { return status == MpccStatus::kSolved; }
};

class ElasticSolver {
 public:
  ElasticSolver(IpoptSolver& ipopt, ElasticSettings settings)
      : ipopt_(ipopt), settings_(settings) {}
  const ElasticSettings& settings() const { return settings_; }

  // From an MPCC point z0.
  MpccResult solve(const Mpcc& mpcc, const ConstVectorRef& z0,
                   const ElasticRequest& request = {}) const;
  // From an earlier result on an MPCC of the same structure (bounds may
  // differ): primal, duals and zeta (warm_zeta) are reused.
  MpccResult solve(const Mpcc& mpcc, const MpccResult& warm,
                   const ElasticRequest& request = {}) const;
  // The zeta a solve warm-started from `warm` begins with when its request sets none: the
  // zeta `warm` ended at, or ElasticSettings::zeta if it has none (a result not yet solved).
  double warm_zeta(const MpccResult& warm) const {
    return warm.zeta > 0 ? warm.zeta : settings_.zeta;
  }
  // From a result, certified or not (its elastic point says which side of each pair is the
  // smaller): the branch NLP (for every pair that side fixed to 0, as polish does), solved;
  // then, while some biactive pair (the free side at its bound too) has a negative multiplier
  // on its fixed side (releasing that side descends), those pairs are flipped (the other side
  // fixed instead) and the branch solved again, at most max_flip_rounds times. Every branch
  // point is certified on the MPCC; the result is the last certified one (status kSolved,
  // warm starts continue from its primal-dual point), or, if the first branch solve fails,
  // `from`'s point with that solve's status (kInfeasible or kFailed).
  MpccResult solve_branch(const Mpcc& mpcc, const MpccResult& from, int max_flip_rounds,
                          const ElasticRequest& request = {}) const;

 private:
  MpccResult run(const Mpcc& mpcc, NlpPoint start, double zeta,
                 const ElasticRequest& request) const;
  // Steps 1-2 of run(): the penalty loop (kLumped, kPerPair) or the relaxation homotopy
  // (kRelaxed, or a request with `relaxation`). Both fill `out` (status, last solve's point and figures); `record` logs a
  // solve into it. They return whether the last NLP solve converged.
  using Record = std::function<void(const NlpResult&, const char*, double zeta)>;
  // The zeta rule of step 2: raises zeta by zeta_factor and returns true, unless the residual
  // stalled against previous_residual (updated; < 0: none yet) or zeta_max (or the request's
  // zeta_limit, if lower) would be passed.
  bool raise_zeta(const ElasticRequest& request, double residual, double& previous_residual,
                  double& zeta) const;
  bool penalty_loop(ElasticNlp& nlp, NlpPoint start, double zeta, const ElasticRequest& request,
                    MpccResult& out, const Record& record) const;
  bool relaxation_homotopy(ElasticNlp& nlp, NlpPoint start, double zeta,
                           const ElasticRequest& request, MpccResult& out,
                           const Record& record) const;
  IpoptSolver& ipopt_;
  ElasticSettings settings_;
};

}  // namespace disco
