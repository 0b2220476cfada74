#include "core/elastic/elastic_solver.h"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {
namespace {
// An elastic point is polished only when its complementarity is below this (run(), step 3);
// the relaxation homotopy goes on raising zeta above it (relaxation_homotopy).
constexpr double kPolishBelow = 1e-2;
}  // namespace

std::string to_string(MpccStatus s) {
  switch (s) {
    case MpccStatus::kSolved: return "solved";
    case MpccStatus::kElasticNotTight: return "elastic_not_tight";
    case MpccStatus::kInfeasible: return "infeasible";
    case MpccStatus::kFailed: return "failed";
  }
  return "failed";
}

std::string to_string(Stationarity s) {
  switch (s) {
    case Stationarity::kFeasible: return "feasible";
    case Stationarity::kStrong: return "strongly stationary";
    case Stationarity::kB: return "B-stationary";
  }
  return "feasible";
}

Certificate certify(const Mpcc& mpcc, const ConstVectorRef& z) {
  Certificate cert;
  Vector c(mpcc.num_constraints());
  if (!mpcc.constraints(z, c) || !z.allFinite()) {
    cert.max_violation = cert.max_complementarity = cert.complementarity_product = kInf;
    return cert;
  }
  auto excess = [](double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); };
  for (int k = 0; k < z.size(); ++k)
    cert.max_violation = std::max(
        cert.max_violation, excess(z[k], mpcc.variable_lower()[k], mpcc.variable_upper()[k]));
  for (int r = 0; r < c.size(); ++r)
    cert.max_violation = std::max(
        cert.max_violation, excess(c[r], mpcc.constraint_lower()[r], mpcc.constraint_upper()[r]));
  for (const auto& p : mpcc.complementarity_pairs()) {
    const double g = side_value(p.g, z, c), h = side_value(p.h, z, c);
    cert.max_complementarity = std::max(cert.max_complementarity, std::abs(std::min(g, h)));
    cert.complementarity_product += g * h;
  }
  return cert;
}

namespace {
// One Ipopt solve's limits under a request (a solve started past the deadline stops at its
// first iteration); fixed_branch: a polish or branch solve (NlpLimits::fixed_branch).
NlpLimits limits(const ElasticRequest& request, bool fixed_branch = false) {
  NlpLimits l{request.iteration_limit, request.deadline, std::nullopt, {}, std::nullopt};
  l.push_as_warm = request.cold_start;  // only its first solve starts without duals
  l.fixed_branch = fixed_branch;
  return l;
}
bool past(const ElasticRequest& request) {
  return request.deadline && Clock::now() >= *request.deadline;
}
// The solve log's note on a solve that kkt.polish_rescue started again with its solver.
const char* rescue_note(const NlpResult& r) {
  return r.kkt.polish_rescues > 0 ? "  rescued (kkt.polish_rescue)" : "";
}
// The status of a solve that did not converge.
MpccStatus unconverged_status(const NlpResult& r) {
  return r.outcome == NlpOutcome::kInfeasible ? MpccStatus::kInfeasible : MpccStatus::kFailed;
}
}  // namespace

MpccResult ElasticSolver::solve(const Mpcc& mpcc, const ConstVectorRef& z0,
                                const ElasticRequest& request) const {
  ElasticNlp shape(mpcc, settings_.formulation, settings_.zeta);
  NlpPoint start;
  start.z = shape.lift(z0);
  return run(mpcc, std::move(start), request.zeta > 0 ? request.zeta : settings_.zeta, request);
}

MpccResult ElasticSolver::solve(const Mpcc& mpcc, const MpccResult& warm,
                                const ElasticRequest& request) const {
  const double zeta = request.zeta > 0 ? request.zeta : warm_zeta(warm);
  if (request.cold_start) {  // the primal point alone: IpoptSolver then starts cold
    NlpPoint primal;
    primal.z = warm.elastic_point.z;
    return run(mpcc, std::move(primal), zeta, request);
  }
  return run(mpcc, warm.elastic_point, zeta, request);
}

MpccResult ElasticSolver::solve_branch(const Mpcc& mpcc, const MpccResult& from,
                                       int max_flip_rounds, const ElasticRequest& request) const {
  const auto t0 = Clock::now();
  const int n = mpcc.num_variables();
  const int pairs = mpcc.num_complementarity_pairs();
  ElasticNlp nlp(mpcc, settings_.formulation, settings_.zeta);
  const Vector lo0 = nlp.variable_lower(), hi0 = nlp.variable_upper();
  // The branch: fixed[i] is the elastic index of pair i's side held at 0.
  NlpPoint point = from.elastic_point;
  point.z.head(n) = from.z;  // the certified point (polished), with the elastic duals
  {
    const Vector lifted = nlp.lift(from.z);
    point.z.tail(point.z.size() - n) = lifted.tail(lifted.size() - n);
  }
  std::vector<int> fixed(pairs);
  for (int i = 0; i < pairs; ++i)
    fixed[i] = point.z[nlp.u(i)] <= point.z[nlp.w(i)] ? nlp.u(i) : nlp.w(i);

  MpccResult out = from;
  out.nlp_solves = out.iterations = 0;
  out.kkt = {};
  out.branch_solves = out.flips = 0;
  out.b_stationary = false;
  const double tol = settings_.complementarity_tol;
  Vector grad(nlp.num_variables()), jac(nlp.jacobian_pattern().size()), nu(nlp.num_variables());
  for (int round = 0; round <= max_flip_rounds; ++round) {
    for (int k = 0; k < nlp.num_variables(); ++k) nlp.set_variable_bounds(k, lo0[k], hi0[k]);
    for (int v : fixed) nlp.set_variable_bounds(v, 0.0, 0.0);
    for (int k = 0; k < nlp.num_variables(); ++k)
      point.z[k] = std::clamp(point.z[k], nlp.variable_lower()[k], nlp.variable_upper()[k]);
    if (past(request)) break;
    const NlpResult r = ipopt_.solve(nlp, point, limits(request, true));
    out.nlp_solves += 1;
    out.iterations += r.iterations;
    out.kkt += r.kkt;
    out.branch_solves += 1;
    out.outcome = r.outcome;
    out.ipopt_status = r.ipopt_status;
    const Vector z = r.point.z.head(n);
    const Certificate cert = certify(mpcc, z);
    spdlog::debug("      ipopt branch  round {:<3} {:<26} {:>5} it {:>8.3f} s  compl {:.1e}  viol {:.1e}"
                  "  kkt {}/{}{}",
                  round, ipopt_status_name(r.ipopt_status), r.iterations, r.seconds,
                  cert.max_complementarity, cert.max_violation, r.kkt.fallbacks,
                  r.kkt.factorisations, rescue_note(r));
    if (!r.converged() || !cert.within(settings_.violation_tol, tol)) {
      // The first branch solve failing is the result's status; a later one keeps the last
      // certified branch point.
      if (out.branch_solves == 1)
        out.status = r.outcome == NlpOutcome::kInfeasible ? MpccStatus::kInfeasible
                                                          : MpccStatus::kFailed;
      break;
    }
    double f = kInf;
    if (!mpcc.objective(z, f)) break;
    out.status = MpccStatus::kSolved;
    out.z = z;
    out.objective = f;
    out.certificate = cert;
    out.polished = true;
    point = r.point;
    // Warm starts continue from this branch point (fixed sides at 0, with the branch's duals).
    out.elastic_point = point;
    // Multipliers of the fixed sides: dL/dx = grad f + J^T lambda (Ipopt's signs: at a lower
    // bound the bound multiplier is this value, >= 0 at a stationary point).
    if (!nlp.gradient(point.z, grad) || !nlp.jacobian(point.z, jac)) break;
    nu = grad;
    const auto& pat = nlp.jacobian_pattern();
    for (int e = 0; e < pat.size(); ++e) nu[pat.cols[e]] += jac[e] * point.lambda[pat.rows[e]];
    const double scale = std::max(1.0, grad.lpNorm<Eigen::Infinity>());
    int flips = 0;
    for (int i = 0; i < pairs; ++i) {
      const int a = fixed[i], b = a == nlp.u(i) ? nlp.w(i) : nlp.u(i);
      // b is at its bound 0 when it is below the tolerance or, at an interior-point solution
      // (b * z_b = mu), when its bound multiplier exceeds it (b ~ sqrt(mu), e.g. 2e-5).
      const bool biactive = point.z[b] <= tol || point.z_lo[b] >= point.z[b];
      if (!biactive || nu[a] >= -1e-6 * scale) continue;
      fixed[i] = b;  // biactive, and releasing a descends: hold b at 0 instead
      ++flips;
    }
    out.flips += flips;
    spdlog::debug("      branch round {}: T objective {:.6f}, {} flips", round, f, flips);
    if (flips == 0) {
      out.b_stationary = true;
      break;
    }
  }
  out.seconds = seconds_since(t0);
  return out;
}

bool ElasticSettings::Stagnation::Rule::stagnated(int iteration,
                                                  const std::vector<double>& eps) const {
  const int n = static_cast<int>(eps.size());
  if (after <= 0 || iteration < after || n < 2 * window) return false;
  const double last = *std::min_element(eps.end() - window, eps.end());
  const double before = *std::min_element(eps.end() - 2 * window, eps.end() - window);
  return last > level && last > (1.0 - decrease) * before;
}

bool ElasticSettings::Stagnation::stagnated(int iteration, const std::vector<double>& eps) const {
  return first.stagnated(iteration, eps) || late.stagnated(iteration, eps);
}

bool ElasticSettings::Stall::stalled(int iteration,
                                     const std::vector<std::pair<int, double>>& settled) const {
  if (after <= 0 || iteration < after || settled.empty() || settled.back().first != iteration)
    return false;
  double before = kInf, recent = kInf;
  for (const auto& [k, objective] : settled) {
    double& least = k > iteration - window ? recent : before;
    least = std::min(least, objective);
  }
  return before < kInf && before - recent < decrease * std::abs(before);
}

bool ElasticSolver::raise_zeta(const ElasticRequest& request, double residual,
                               double& previous_residual, double& zeta) const {
  const bool stalled = previous_residual >= 0 && std::abs(residual - previous_residual) <=
                                                     settings_.stall_change * previous_residual;
  previous_residual = residual;
  const double limit = request.zeta_limit > 0 ? std::min(request.zeta_limit, settings_.zeta_max)
                                              : settings_.zeta_max;
  if (stalled || zeta * settings_.zeta_factor > limit) return false;
  zeta *= settings_.zeta_factor;
  return true;
}

bool ElasticSolver::penalty_loop(ElasticNlp& nlp, NlpPoint start, double zeta,
                                 const ElasticRequest& request, MpccResult& out,
                                 const Record& record) const {
  double previous_residual = -1.0;
  NlpLimits solve_limits = limits(request);
  const bool follow = nlp.formulation() == ElasticFormulation::kBarrier;
  // The stagnation rule of this request: a fixed step's, or a feasibility phase's, which
  // watches from feasibility_after on (ElasticSettings::Stagnation; after 0: not watched).
  ElasticSettings::Stagnation stagnation = settings_.stagnation;
  if (!request.objective_fixed) {
    stagnation.first.after = request.feasibility ? stagnation.feasibility_after : 0;
    stagnation.late.after = 0;  // the late rule watches fixed steps alone
  }
  if ((stagnation.first.after > 0 || stagnation.late.after > 0) && nlp.eps_index() >= 0) {
    // eps of each regular Ipopt iteration of the current solve.
    solve_limits.watch = NlpLimits::Watch{
        nlp.eps_index(), [stagnation, eps = std::vector<double>()](
                             const NlpLimits::Iterate& it) mutable {
          if (it.iteration == 0) eps.clear();
          eps.push_back(it.value);
          return stagnation.stagnated(it.iteration, eps);
        }};
  } else if (request.stall && settings_.stall.after > 0) {
    // The objective at each settled iterate of the current solve (ElasticSettings::Stall).
    solve_limits.watch = NlpLimits::Watch{
        -1, [this, settled = std::vector<std::pair<int, double>>()](
                const NlpLimits::Iterate& it) mutable {
          if (it.iteration == 0) settled.clear();
          if (!settings_.stall.settled(it)) return false;
          settled.emplace_back(it.iteration, it.objective);
          return settings_.stall.stalled(it.iteration, settled);
        }};
  }
  if (follow) {
    // elastic.barrier_mu monotone: sigma follows a Fiacco-McCormick mu (header).
    if (settings_.barrier_monotone_mu) solve_limits.barrier = BarrierStage{};
    solve_limits.follow_barrier = [&nlp, this](double mu) {
      const double sigma =
          settings_.barrier_sigma_factor * std::pow(mu, settings_.barrier_sigma_exponent);
      if (sigma == nlp.live_relaxation()) return false;
      nlp.set_live_relaxation(sigma);
      return true;
    };
  }
  while (true) {
    nlp.set_zeta(zeta);
    const NlpResult r = ipopt_.solve(nlp, start, solve_limits);
    if (follow) nlp.set_live_relaxation(0.0);  // polish and the certificate see the MPCC
    record(r, follow ? "barrier" : "elastic", zeta);
    if (r.outcome == NlpOutcome::kStagnated && (request.objective_fixed || request.feasibility)) {
      out.status = MpccStatus::kElasticNotTight;  // not tight, as it would have converged
      return true;
    }
    if (r.outcome == NlpOutcome::kStagnated) {
      out.stalled = true;  // a minimisation creeping at the corner: judged as if converged
    } else if (!r.converged()) {
      out.status = unconverged_status(r);
      return false;
    }
    if (out.certificate.max_complementarity <= settings_.complementarity_tol) {
      // Tight; a violation above tolerance (Ipopt's scaled tolerance met,
      // ours not) is an honest failure unless polishing repairs it.
      out.status = out.certificate.within(settings_.violation_tol, settings_.complementarity_tol)
                       ? MpccStatus::kSolved
                       : MpccStatus::kFailed;
      return true;
    }
    if (request.objective_fixed ||
        !raise_zeta(request, out.certificate.max_complementarity, previous_residual, zeta)) {
      out.status = MpccStatus::kElasticNotTight;
      return true;
    }
    start = r.point;
  }
}

bool ElasticSolver::relaxation_homotopy(ElasticNlp& nlp, NlpPoint start, double zeta,
                                        const ElasticRequest& request, MpccResult& out,
                                        const Record& record) const {
  const int eps = nlp.eps_index();
  DISCO_CHECK(eps >= 0 && settings_.polish, "the relaxation homotopy needs the lumped row and polish");
  double sigma = settings_.sigma;
  bool first = true, held = false;
  double previous_residual = -1.0;
  auto finish = [&](bool converged) {
    nlp.set_relaxation(0.0);  // the certificate is on the MPCC; the NLP is left unrelaxed
    if (!converged) return false;
    const bool within =
        out.certificate.within(settings_.violation_tol, settings_.complementarity_tol);
    out.status = within ? MpccStatus::kSolved : MpccStatus::kElasticNotTight;
    return true;
  };
  while (true) {
    nlp.set_zeta(zeta);
    nlp.set_relaxation(sigma);
    NlpLimits stage = limits(request);
    // The first stage starts at the configured mu_init (its start may be far from the
    // relaxed problem's solution); each later one where the last ended.
    stage.barrier = BarrierStage{first ? 0.0 : settings_.barrier_ratio * sigma / settings_.sigma_factor,
                                 settings_.barrier_ratio * sigma, sigma};
    const NlpResult r = ipopt_.solve(nlp, start, stage);
    record(r, "relaxed", zeta);
    spdlog::debug("        sigma {:.1e}, eps {:.1e}", sigma, r.point.z[eps]);
    first = false;
    if (!r.converged()) {
      out.status = unconverged_status(r);
      return finish(false);
    }
    start = r.point;
    if (out.certificate.max_complementarity <= settings_.complementarity_tol) return finish(true);
    if (r.point.z[eps] > sigma) {
      // The relaxation does not hold (the penalty prefers eps > 0). Once it has held, the
      // homotopy ends here if polish can take over (complementarity below kPolishBelow): its
      // multiplier grows like 1/sqrt(sigma) (raising zeta at every sigma was measured: paper
      // B2 start 0 took 4,417 iterations instead of 1,672). If it never held, zeta is too
      // weak for any relaxation, and if it stopped holding too far from complementarity for
      // polish, the homotopy would end unpolished, not tight: raise zeta as the penalty loop
      // does (same stall rule, same limit) and solve this sigma again.
      // With the objective fixed, eps's minimiser does not depend on zeta: no raise either.
      const bool polishable = out.certificate.max_complementarity < kPolishBelow;
      if ((held && polishable) || request.objective_fixed ||
          !raise_zeta(request, out.certificate.max_complementarity, previous_residual, zeta))
        return finish(true);
      continue;
    }
    held = true;
    sigma *= settings_.sigma_factor;
    if (sigma < settings_.sigma_min) return finish(true);
  }
}

MpccResult ElasticSolver::run(const Mpcc& mpcc, NlpPoint start, double zeta,
                              const ElasticRequest& request) const {
  const auto t0 = Clock::now();
  const int n = mpcc.num_variables();
  ElasticNlp nlp(mpcc, settings_.formulation, zeta);
  DISCO_CHECK(start.z.size() == nlp.num_variables(), "warm start of another shape");

  MpccResult out;
  // `what` names the Ipopt solve for the --verbose log (debug level).
  const Record record = [&](const NlpResult& r, const char* what, double zeta_used) {
    out.outcome = r.outcome;
    out.ipopt_status = r.ipopt_status;
    out.nlp_solves += 1;
    out.iterations += r.iterations;
    out.kkt += r.kkt;
    out.elastic_point = r.point;
    out.zeta = zeta_used;
    out.z = r.point.z.head(n);
    out.certificate = certify(mpcc, out.z);
    if (!mpcc.objective(out.z, out.objective)) out.objective = kInf;
    spdlog::debug("      ipopt {:<7} zeta {:<8.3g} {:<26} {:>5} it {:>8.3f} s  compl {:.1e}  viol {:.1e}"
                  "  kkt {}/{}{}",
                  what, zeta_used, ipopt_status_name(r.ipopt_status), r.iterations, r.seconds,
                  out.certificate.max_complementarity, out.certificate.max_violation,
                  r.kkt.fallbacks, r.kkt.factorisations, rescue_note(r));
  };

  // 1-2. Elastic solves until complementarity is tight (or cannot be made so).
  const bool homotopy = settings_.formulation == ElasticFormulation::kRelaxed ||
                        (request.relaxation && settings_.formulation == ElasticFormulation::kLumped);
  DISCO_CHECK(homotopy || !request.relaxation,
              "a relaxation request needs elastic.formulation lumped or relaxed");
  const bool converged =
      homotopy
          ? relaxation_homotopy(nlp, std::move(start), zeta, request, out, record)
          : penalty_loop(nlp, std::move(start), zeta, request, out, record);

  // 3. Polish: fix the smaller side of every pair to zero and re-solve.
  // Worth it when the elastic solve converged near complementarity, unless a fixed or constant
  // objective's point is already tight (ElasticSettings::polish_fixed_above): the polished point
  // would only make complementarity exact, at the same objective, and warm starts go on from
  // the elastic point either way.
  const bool certified_as_is = (request.objective_fixed || request.objective_constant) &&
                           out.status == MpccStatus::kSolved &&
                           out.certificate.max_complementarity <= settings_.polish_fixed_above;
  const bool worth_polishing =
      converged && out.certificate.max_complementarity < kPolishBelow && !certified_as_is;
  if (settings_.polish && worth_polishing && !past(request)) {
    const MpccResult before = out;
    const Vector& x = out.elastic_point.z;
    for (int i = 0; i < mpcc.num_complementarity_pairs(); ++i) {
      const int fix = x[nlp.u(i)] <= x[nlp.w(i)] ? nlp.u(i) : nlp.w(i);
      nlp.set_variable_bounds(fix, 0.0, 0.0);
    }
    NlpPoint polish_start = out.elastic_point;
    for (int k = 0; k < nlp.num_variables(); ++k)  // start inside the new bounds
      polish_start.z[k] = std::clamp(polish_start.z[k], nlp.variable_lower()[k],
                                     nlp.variable_upper()[k]);
    // Every product is now zero: eps's optimum is 0 whatever its weight, and a zeta above
    // Ipopt's scaling limit would only scale the objective down and loosen the polish's
    // optimality (header).
    nlp.set_zeta(std::min(out.zeta, ipopt_.scaling_max_gradient()));
    const NlpResult r = ipopt_.solve(nlp, polish_start, limits(request, true));
    record(r, "polish", out.zeta);
    if (r.converged() &&
        out.certificate.within(settings_.violation_tol, settings_.complementarity_tol)) {
      out.status = MpccStatus::kSolved;
      out.polished = true;
      // Warm starts continue from the elastic solve's primal-dual point: Ipopt
      // returns no multipliers for the sides polish fixed (make_parameter), so
      // the polished point starts later elastic solves no better than cold.
      out.elastic_point = before.elastic_point;
    } else {
      const int solves = out.nlp_solves, iters = out.iterations;
      const KktCounts kkt = out.kkt;
      out = before;  // the elastic answer stands
      out.nlp_solves = solves;
      out.iterations = iters;
      out.kkt = kkt;
    }
  }
  out.seconds = seconds_since(t0);
  return out;
}

}  // namespace disco
