#include "core/ipopt/ipopt_solver.h"
#include "core/ipopt/kkt_solver.h"

#include <IpIpoptApplication.hpp>
#include <IpIpoptCalculatedQuantities.hpp>
#include <IpIpoptData.hpp>
#include <IpDenseVector.hpp>
#include <IpIteratesVector.hpp>
#include <IpTNLP.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>

#include "core/util/clock.h"
#include "core/util/interrupt.h"
#include "core/util/check.h"
#include "core/util/errors.h"

namespace disco {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// The TNLP adapter (shape of Ipopt's hs071 example): forwards every callback
// to the Nlp's checked public evaluation, which already turns exceptions and
// non-finite values into `false`. Nothing crosses into Ipopt: a failed internal
// check (or any other exception) is caught in the callback, which returns false,
// and the next intermediate callback stops the solve; IpoptSolver::solve rethrows it.
class TnlpAdapter : public Ipopt::TNLP {
 public:
  TnlpAdapter(const Nlp& nlp, const NlpPoint& start, NlpResult& out, const NlpLimits& limits)
      : nlp_(nlp), start_(start), out_(out), limits_(limits) {}

  // Why the adapter stopped the solve (kFailed: it did not).
  NlpOutcome stopped() const { return stopped_; }
  // The exception a callback caught, if any.
  std::exception_ptr error() const { return error_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h,
                    IndexStyleEnum& style) override {
    return caught([&] { return nlp_info(n, m, nnz_jac, nnz_h, style); });
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    return caught([&] { return bounds_info(n, x_l, x_u, m, g_l, g_u); });
  }
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L, Number* z_U,
                          Index m, bool init_lambda, Number* lambda) override {
    return caught([&] { return starting_point(n, init_x, x, init_z, z_L, z_U, m, init_lambda, lambda); });
  }
  bool eval_f(Index n, const Number* x, bool, Number& f) override {
    return caught([&] { return nlp_.objective(Eigen::Map<const Vector>(x, n), f); });
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* g) override {
    return caught([&] {
      Eigen::Map<Vector> out(g, n);
      return nlp_.gradient(Eigen::Map<const Vector>(x, n), out);
    });
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return caught([&] {
      Eigen::Map<Vector> out(g, m);
      return nlp_.constraints(Eigen::Map<const Vector>(x, n), out);
    });
  }
  bool eval_jac_g(Index n, const Number* x, bool, Index, Index nele, Index* irow, Index* jcol,
                  Number* values) override {
    return caught([&] { return jacobian(n, x, nele, irow, jcol, values); });
  }
  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index m, const Number* lambda,
              bool, Index nele, Index* irow, Index* jcol, Number* values) override {
    return caught([&] { return hessian(n, x, obj_factor, m, lambda, nele, irow, jcol, values); });
  }

  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iter, Number obj_value,
                             Number inf_pr, Number, Number mu, Number, Number, Number, Number,
                             Index,
                             const Ipopt::IpoptData* data,
                             Ipopt::IpoptCalculatedQuantities* quantities) override {
    out_.iterations = iter;
    clock_iteration();  // the simulated clock advances before the deadline is read
    if (error_) return false;  // a callback failed on a bug: stop here
    if (limits_.follow_barrier && mode == Ipopt::RegularMode && data != nullptr &&
        quantities != nullptr && !caught([&] { return follow(iter, data, quantities); }))
      return false;
    if (limits_.watch && mode == Ipopt::RegularMode && data != nullptr) {
      bool stop = false;
      if (!caught([&] {
            stop = watched_stop({static_cast<int>(iter), std::nan(""), obj_value, inf_pr, mu}, *data);
            return true;
          }))
        return false;
      if (stop) {
        stopped_ = NlpOutcome::kStagnated;
        return false;
      }
    }
    if (limits_.iterations > 0 && iter >= limits_.iterations) {
      stopped_ = NlpOutcome::kIterationCap;
      return false;
    }
    if ((limits_.deadline && Clock::now() > *limits_.deadline) || interrupt_requested()) {
      stopped_ = NlpOutcome::kTimeLimit;
      return false;
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number* z_L,
                         const Number* z_U, Index m, const Number*, const Number* lambda,
                         Number obj_value, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    caught([&] {
      out_.point.z = Eigen::Map<const Vector>(x, n);
      out_.point.z_lo = Eigen::Map<const Vector>(z_L, n);
      out_.point.z_hi = Eigen::Map<const Vector>(z_U, n);
      out_.point.lambda = Eigen::Map<const Vector>(lambda, m);
      out_.objective = obj_value;
      return true;
    });
  }

 private:
  // NlpLimits::watch: the watched variable's value in Ipopt's current iterate. Ipopt's x
  // leaves out the variables whose bounds are equal (fixed_variable_treatment make_parameter)
  // unless it fell back to relaxing them, so the position is found from its dimension.
  bool watched_stop(NlpLimits::Iterate it, const Ipopt::IpoptData& data) {
    if (limits_.watch->index < 0) return limits_.watch->stop(it);
    const auto* x = dynamic_cast<const Ipopt::DenseVector*>(Ipopt::GetRawPtr(data.curr()->x()));
    DISCO_CHECK(x != nullptr, "Ipopt's x is a dense vector");
    if (watch_position_ < 0) {  // once per solve
      const int n = nlp_.num_variables(), k = limits_.watch->index;
      DISCO_CHECK(k >= 0 && k < n && nlp_.variable_lower()[k] != nlp_.variable_upper()[k],
                  "a watched variable is a free variable of the NLP");
      int fixed = 0, fixed_before = 0;
      for (int j = 0; j < n; ++j) {
        const bool is_fixed = nlp_.variable_lower()[j] == nlp_.variable_upper()[j];
        fixed += is_fixed;
        fixed_before += is_fixed && j < k;
      }
      DISCO_CHECK(x->Dim() == n - fixed || x->Dim() == n,
                  "Ipopt's x is the NLP's, with or without its fixed variables");
      watch_position_ = x->Dim() == n ? k : k - fixed_before;
    }
    it.value = x->IsHomogeneous() ? x->Scalar() : x->Values()[watch_position_];
    return limits_.watch->stop(it);
  }

  // NlpLimits::follow_barrier: the NLP changed at Ipopt's current mu, Ipopt's current iterate
  // is replaced by a copy under new tags (IpoptData keeps everything else: W, mu, tau), so
  // that Ipopt evaluates the new functions there.
  bool follow(Index iter, const Ipopt::IpoptData* data, Ipopt::IpoptCalculatedQuantities* q) {
    const double mu = data->curr_mu();
    const Ipopt::SmartPtr<const Ipopt::Vector> before = q->curr_d();
    if (!limits_.follow_barrier(mu)) return true;
    auto* ip_data = const_cast<Ipopt::IpoptData*>(data);  // (the callback's data is Ipopt's own)
    Ipopt::SmartPtr<Ipopt::IteratesVector> copy = ip_data->curr()->MakeNewIteratesVectorCopy();
    ip_data->set_trial(copy);
    ip_data->AcceptTrialPoint();
    Ipopt::SmartPtr<Ipopt::Vector> change = q->curr_d()->MakeNewCopy();
    change->Axpy(-1.0, *before);
    out_.refreshes.push_back({static_cast<int>(iter), mu, change->Amax()});
    return true;
  }

  // Runs a callback's body; an exception is kept (the first one) and becomes `false`.
  template <class Body>
  bool caught(Body&& body) {
    try {
      return body();
    } catch (...) {
      if (!error_) error_ = std::current_exception();
      return false;
    }
  }

  bool nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h, IndexStyleEnum& style) {
    n = nlp_.num_variables();
    m = nlp_.num_constraints();
    nnz_jac = nlp_.jacobian_pattern().size();
    nnz_h = nlp_.hessian_pattern().size();
    style = C_STYLE;
    return true;
  }

  bool bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) {
    Eigen::Map<Vector>(x_l, n) = nlp_.variable_lower();
    Eigen::Map<Vector>(x_u, n) = nlp_.variable_upper();
    Eigen::Map<Vector>(g_l, m) = nlp_.constraint_lower();
    Eigen::Map<Vector>(g_u, m) = nlp_.constraint_upper();
    return true;
  }

  bool starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L, Number* z_U,
                      Index m, bool init_lambda, Number* lambda) {
    if (init_x) Eigen::Map<Vector>(x, n) = start_.z;
    if (init_z || init_lambda) {
      if (!start_.has_duals()) return false;
      if (init_z) {
        Eigen::Map<Vector>(z_L, n) = start_.z_lo;
        Eigen::Map<Vector>(z_U, n) = start_.z_hi;
      }
      if (init_lambda) Eigen::Map<Vector>(lambda, m) = start_.lambda;
    }
    return true;
  }

  bool jacobian(Index n, const Number* x, Index nele, Index* irow, Index* jcol, Number* values) {
    if (values == nullptr) {
      const auto& p = nlp_.jacobian_pattern();
      std::copy(p.rows.begin(), p.rows.end(), irow);
      std::copy(p.cols.begin(), p.cols.end(), jcol);
      return true;
    }
    Eigen::Map<Vector> out(values, nele);
    return nlp_.jacobian(Eigen::Map<const Vector>(x, n), out);
  }
  bool hessian(Index n, const Number* x, Number obj_factor, Index m, const Number* lambda,
               Index nele, Index* irow, Index* jcol, Number* values) {
    if (values == nullptr) {
      const auto& p = nlp_.hessian_pattern();
      std::copy(p.rows.begin(), p.rows.end(), irow);
      std::copy(p.cols.begin(), p.cols.end(), jcol);
      return true;
    }
    Eigen::Map<Vector> out(values, nele);
    return nlp_.hessian(Eigen::Map<const Vector>(x, n), obj_factor,
                        Eigen::Map<const Vector>(lambda, m), out);
  }

  const Nlp& nlp_;
  const NlpPoint& start_;
  NlpResult& out_;
  const NlpLimits& limits_;
  NlpOutcome stopped_ = NlpOutcome::kFailed;
  int watch_position_ = -1;  // of NlpLimits::watch's variable in Ipopt's x, once known
  std::exception_ptr error_;
};

double parse_number(const IpoptOption& o, bool integer) {
  char* end = nullptr;
  const double v = std::strtod(o.value.c_str(), &end);
  const bool integral = std::isfinite(v) && std::abs(v) <= 2147483647.0 && v == std::floor(v);
  if (end == o.value.c_str() || *end != '\0' || !std::isfinite(v) || (integer && !integral))
    throw InputError(o.where + ": key 'ipopt." + o.name + "': expected " +
                     (integer ? "an integer" : "a number") + ", got '" + o.value + "'");
  return v;
}

NlpOutcome outcome_of(int ipopt_status, NlpOutcome stopped) {
  switch (ipopt_status) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level: return NlpOutcome::kConverged;
    case Ipopt::Infeasible_Problem_Detected: return NlpOutcome::kInfeasible;
    case Ipopt::User_Requested_Stop: return stopped;
    case Ipopt::Maximum_Iterations_Exceeded: return NlpOutcome::kMaxIterations;
    case Ipopt::Invalid_Number_Detected: return NlpOutcome::kInvalidNumber;
    default: return NlpOutcome::kFailed;
  }
}

}  // namespace

std::string to_string(NlpOutcome outcome) {
  switch (outcome) {
    case NlpOutcome::kConverged: return "converged";
    case NlpOutcome::kInfeasible: return "infeasible";
    case NlpOutcome::kIterationCap: return "iteration cap";
    case NlpOutcome::kTimeLimit: return "time limit";
    case NlpOutcome::kMaxIterations: return "max_iter";
    case NlpOutcome::kInvalidNumber: return "invalid number";
    case NlpOutcome::kStagnated: return "stagnated";
    case NlpOutcome::kFailed: return "failed";
  }
  return "failed";
}

std::string describe(NlpOutcome outcome, int ipopt_status) {
  if (outcome == NlpOutcome::kIterationCap || outcome == NlpOutcome::kTimeLimit ||
      outcome == NlpOutcome::kStagnated)
    return to_string(outcome);
  return "Ipopt: " + ipopt_status_name(ipopt_status);
}

std::string ipopt_status_name(int status) {
  switch (status) {
    case 0: return "Solve_Succeeded";
    case 1: return "Solved_To_Acceptable_Level";
    case 2: return "Infeasible_Problem_Detected";
    case 3: return "Search_Direction_Becomes_Too_Small";
    case 4: return "Diverging_Iterates";
    case 5: return "User_Requested_Stop";
    case 6: return "Feasible_Point_Found";
    case -1: return "Maximum_Iterations_Exceeded";
    case -2: return "Restoration_Failed";
    case -3: return "Error_In_Step_Computation";
    case -4: return "Maximum_CpuTime_Exceeded";
    case -10: return "Not_Enough_Degrees_Of_Freedom";
    case -11: return "Invalid_Problem_Definition";
    case -12: return "Invalid_Option";
    case -13: return "Invalid_Number_Detected";
    case -100: return "Unrecoverable_Exception";
    case -101: return "NonIpopt_Exception_Thrown";
    case -102: return "Insufficient_Memory";
    default: return "Internal_Error";
  }
}

// Ipopt's options that push a cold start inside its bounds; "warm_start_" + each is its
// warm-start counterpart.
constexpr const char* kColdPushes[] = {"bound_push", "bound_frac", "slack_bound_push",
                                       "slack_bound_frac"};

struct IpoptSolver::Application {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication();
};

IpoptSolver::IpoptSolver(const IpoptSettings& settings) : IpoptSolver(settings.options) {
  perturbed_first_ = settings.perturbed_first;
  kkt_solver_ = settings.kkt_solver;
  polish_rescue_solver_ = settings.polish_rescue_solver;
  polish_rescue_after_ = settings.polish_rescue_after;
  ldlt_ = settings.ldlt;
  dump_ = settings.dump;
}

IpoptSolver::IpoptSolver(const std::vector<IpoptOption>& options)
    : app_(std::make_unique<Application>()) {
  auto& app = app_->app;
  // Never read an "ipopt.opt" lying in the working directory: options come
  // only from disco's settings.
  if (app->Initialize("") != Ipopt::Solve_Succeeded)
    throw std::runtime_error("Ipopt failed to initialize");
  auto registry = app->RegOptions();
  auto list = app->Options();
  for (const auto& o : options) {
    auto reg = registry->GetOption(o.name);
    if (!Ipopt::IsValid(reg))
      throw InputError(o.where + ": key 'ipopt." + o.name + "': Ipopt has no such option");
    // Ipopt's CPU-time limit would stop solves on a clock of its own, outside disco's
    // (core/util/clock.h), where no limit of disco's and no simulated clock could see it.
    if (o.name == "max_cpu_time")
      throw InputError(o.where + ": key 'ipopt.max_cpu_time': disco's time limits are on its own "
                       "clock: set reduction.time_limit or --time-limit (clock: in the settings)");
    bool ok = false;
    switch (reg->Type()) {
      case Ipopt::OT_Number: ok = list->SetNumericValue(o.name, parse_number(o, false)); break;
      case Ipopt::OT_Integer:
        ok = list->SetIntegerValue(o.name, static_cast<Index>(parse_number(o, true)));
        break;
      default: ok = list->SetStringValue(o.name, o.value); break;
    }
    if (!ok)
      throw InputError(o.where + ": key 'ipopt." + o.name + "': Ipopt rejects the value '" +
                       o.value + "'");
  }
  // Every solve factorises through disco's KKT linear solver (core/ipopt/kkt_solver.h), which
  // wraps Ipopt's MUMPS interface.
  std::string linear_solver;
  list->GetStringValue("linear_solver", linear_solver, "");
  if (linear_solver != "mumps") {
    const auto given = std::find_if(options.rbegin(), options.rend(),
                                    [](const IpoptOption& o) { return o.name == "linear_solver"; });
    throw InputError((given == options.rend() ? std::string("Ipopt's default") : given->where) +
                     ": key 'ipopt.linear_solver': disco factorises through "
                     "Ipopt's MUMPS interface (core/ipopt/kkt_solver.h): it must be 'mumps', got '" +
                     linear_solver + "'");
  }
  list->SetStringValue("linear_solver", kCustomLinearSolver);
  std::string warm;
  list->GetStringValue("warm_start_init_point", warm, "");
  warm_start_ = warm == "yes";
  list->GetStringValue("mu_strategy", mu_strategy_, "");
  list->GetNumericValue("mu_init", mu_init_, "");
  list->GetNumericValue("mu_target", mu_target_, "");
  list->GetNumericValue("tol", tol_, "");
  std::string scaling;
  list->GetStringValue("nlp_scaling_method", scaling, "");
  if (scaling == "gradient-based")
    list->GetNumericValue("nlp_scaling_max_gradient", scaling_max_gradient_, "");
  for (int k = 0; k < kPushes; ++k) {
    list->GetNumericValue(kColdPushes[k], cold_push_[k], "");
    list->GetNumericValue(std::string("warm_start_") + kColdPushes[k], warm_push_[k], "");
  }
}

IpoptSolver::~IpoptSolver() = default;

NlpResult IpoptSolver::solve(const Nlp& nlp, const NlpPoint& start, const NlpLimits& limits) {
  if (!limits.fixed_branch || polish_rescue_solver_ == kkt_solver_)
    return solve_once(nlp, start, limits, kkt_solver_);
  if (polish_rescue_after_ == 0) return solve_once(nlp, start, limits, polish_rescue_solver_);
  // The rescue's cap, unless the request's own limit comes first.
  const bool capped = limits.iterations == 0 || limits.iterations > polish_rescue_after_;
  NlpLimits first = limits;
  if (capped) first.iterations = polish_rescue_after_;
  NlpResult tried = solve_once(nlp, start, first, kkt_solver_);
  if (!capped || tried.outcome != NlpOutcome::kIterationCap) return tried;
  NlpLimits rest = limits;
  if (rest.iterations > 0) rest.iterations -= tried.iterations;
  NlpResult out = solve_once(nlp, start, rest, polish_rescue_solver_);
  out.iterations += tried.iterations;
  out.seconds += tried.seconds;
  out.kkt += tried.kkt;
  out.kkt.polish_rescues += 1;
  return out;
}

NlpResult IpoptSolver::solve_once(const Nlp& nlp, const NlpPoint& start, const NlpLimits& limits,
                                  KktSolverKind kkt_solver) {
  DISCO_CHECK(start.z.size() == nlp.num_variables(), "start point has the wrong size");
  if (start.has_duals()) {
    DISCO_CHECK(start.lambda.size() == nlp.num_constraints(), "warm-start duals: wrong size");
    DISCO_CHECK(start.z_lo.size() == nlp.num_variables(), "warm-start bound duals: wrong size");
  }
  NlpResult out;
  const auto t0 = Clock::now();
  auto& app = app_->app;
  app->Options()->SetStringValue("warm_start_init_point",
                                 warm_start_ && start.has_duals() ? "yes" : "no");
  const BarrierStage configured{mu_init_, mu_target_, tol_};
  const BarrierStage& stage = limits.barrier ? *limits.barrier : configured;
  app->Options()->SetStringValue("mu_strategy", limits.barrier ? "monotone" : mu_strategy_);
  app->Options()->SetNumericValue("mu_init", stage.mu_init > 0 ? stage.mu_init : mu_init_);
  app->Options()->SetNumericValue("mu_target", stage.mu_target);
  app->Options()->SetNumericValue("tol", std::max(stage.tol, tol_));
  for (int k = 0; k < kPushes; ++k)
    app->Options()->SetNumericValue(
        kColdPushes[k], limits.push_as_warm && !start.has_duals() ? warm_push_[k] : cold_push_[k]);
  auto* adapter = new TnlpAdapter(nlp, start, out, limits);
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp = adapter;
  const KktOptions kkt{perturbed_first_, !(warm_start_ && start.has_duals()), kkt_solver, ldlt_,
                       dump_, &dumped_, &orderings_};
  out.ipopt_status = static_cast<int>(optimize(*app, tnlp, kkt, out.kkt));
  if (adapter->error()) std::rethrow_exception(adapter->error());  // a bug in a callback
  out.outcome = outcome_of(out.ipopt_status, adapter->stopped());
  out.seconds = seconds_since(t0);
  if (out.point.z.size() != nlp.num_variables()) {  // Ipopt gave up before finalize
    out.point = start;
    if (!out.point.has_duals()) {
      out.point.lambda = Vector::Zero(nlp.num_constraints());
      out.point.z_lo = Vector::Zero(nlp.num_variables());
      out.point.z_hi = Vector::Zero(nlp.num_variables());
    }
  }
  return out;
}

}  // namespace disco
