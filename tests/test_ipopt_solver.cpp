// IpoptSolver: option checking (InputError naming where and what), a known
// NLP solved to its optimum, a non-finite start handled without a crash, and
// the wall-clock limit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/util/check.h"
#include "core/util/clock.h"
#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/errors.h"
#include "core/util/numbers.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using test_support::disco_yaml_ipopt_options;
using test_support::tight_warm_start_options;
using test_support::expect_exact_derivatives;

// Constructs a solver from the valid defaults plus one extra option and
// returns the InputError message ("" if nothing was thrown).
std::string construction_error(const IpoptOption& extra) {
  auto options = disco_yaml_ipopt_options();
  options.push_back(extra);
  try {
    IpoptSolver solver(options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(IpoptSolverOptions, UnknownNameIsAnInputErrorNamingWhereAndWhat) {
  const std::string msg = construction_error({"no_such_option", "1", "settings.yaml:17"});
  EXPECT_NE(msg.find("settings.yaml:17"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no_such_option"), std::string::npos) << msg;
}

TEST(IpoptSolverOptions, BadNumericValueIsAnInputError) {
  const std::string msg = construction_error({"tol", "abc", "--set"});
  EXPECT_NE(msg.find("--set"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tol"), std::string::npos) << msg;
  EXPECT_NE(msg.find("abc"), std::string::npos) << msg;
  // Trailing garbage and an empty value are not numbers either.
  EXPECT_NE(construction_error({"tol", "1e-8x", "w"}), "");
  EXPECT_NE(construction_error({"tol", "", "w"}), "");
  // Out of Ipopt's range (tol > 0).
  EXPECT_NE(construction_error({"tol", "-1", "w"}), "");
}

TEST(IpoptSolverOptions, InvalidStringValueIsAnInputError) {
  const std::string msg = construction_error({"mu_strategy", "sometimes", "cfg:3"});
  EXPECT_NE(msg.find("cfg:3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mu_strategy"), std::string::npos) << msg;
  EXPECT_NE(construction_error({"hessian_approximation", "exactly", "w"}), "");
}

TEST(IpoptSolverOptions, NonIntegerForAnIntegerOptionIsAnInputError) {
  const std::string msg = construction_error({"max_iter", "2.5", "cfg:9"});
  EXPECT_NE(msg.find("cfg:9"), std::string::npos) << msg;
  EXPECT_NE(msg.find("max_iter"), std::string::npos) << msg;
  EXPECT_NE(construction_error({"max_iter", "ten", "w"}), "");
  EXPECT_NE(construction_error({"print_level", "-3", "w"}), "");  // below Ipopt's range
}

// Every time limit is on disco's clock (core/util/clock.h): Ipopt's own CPU-time limit would
// cut solves outside it.
TEST(IpoptSolverOptions, IpoptsOwnTimeLimitIsRefusedForDiscosClock) {
  const std::string msg = construction_error({"max_cpu_time", "10", "--set"});
  EXPECT_EQ(msg, "--set: key 'ipopt.max_cpu_time': disco's time limits are on its own clock: set "
                 "reduction.time_limit or --time-limit (clock: in the settings)");
}

// Every solve factorises through disco's KKT linear solver, which wraps Ipopt's MUMPS interface
// (core/ipopt/kkt_solver.h): another linear solver is refused, naming the key.
TEST(IpoptSolverOptions, ALinearSolverOtherThanMumpsIsRefused) {
  EXPECT_EQ(construction_error({"linear_solver", "ma27", "cfg:4"}),
            "cfg:4: key 'ipopt.linear_solver': disco factorises through Ipopt's MUMPS interface "
            "(core/ipopt/kkt_solver.h): it must be 'mumps', got 'ma27'");
  EXPECT_EQ(construction_error({"linear_solver", "mumps", "w"}), "");
}

TEST(IpoptSolverOptions, ValidListIsAccepted) {
  EXPECT_NO_THROW(IpoptSolver solver(disco_yaml_ipopt_options()));
  EXPECT_EQ(construction_error({"max_iter", "50", "w"}), "");
  EXPECT_EQ(construction_error({"max_iter", "1e2", "w"}), "");  // an integral number
  EXPECT_EQ(construction_error({"tol", "1e-7", "w"}), "");
  EXPECT_EQ(construction_error({"mu_strategy", "monotone", "w"}), "");
  EXPECT_NO_THROW(IpoptSolver solver(std::vector<IpoptOption>{}));
}

// The objective scaling limit ElasticSolver's polish reads: Ipopt's nlp_scaling_max_gradient
// (default 100) with gradient-based scaling, none without scaling.
TEST(IpoptSolverOptions, TheScalingLimitIsIpoptsMaxGradientOrNoneWithoutScaling) {
  auto with = [](std::vector<IpoptOption> extra) {
    std::vector<IpoptOption> options = disco_yaml_ipopt_options();
    options.insert(options.end(), extra.begin(), extra.end());
    return IpoptSolver(options).scaling_max_gradient();
  };
  EXPECT_EQ(with({}), 100.0);
  EXPECT_EQ(with({{"nlp_scaling_max_gradient", "250", "w"}}), 250.0);
  EXPECT_EQ(with({{"nlp_scaling_method", "none", "w"}}),
            std::numeric_limits<double>::infinity());
}

// Finding (see the report): "nan" parses as a number and passes Ipopt's range
// check (every comparison with NaN is false), so tol = nan is accepted.
TEST(IpoptSolverOptions, NanIsNotANumericValue) {
  EXPECT_NE(construction_error({"tol", "nan", "w"}), "");
  EXPECT_NE(construction_error({"constr_viol_tol", "NaN", "w"}), "");
}

// An integral value beyond int's range must not reach Ipopt as some other
// number. (It is rejected today only because the unchecked double -> int cast
// in parse_number's caller yields INT_MIN on x86, which Ipopt refuses.)
TEST(IpoptSolverOptions, IntegerOutOfRangeIsAnInputError) {
  EXPECT_NE(construction_error({"max_iter", "1e10", "w"}), "");
  EXPECT_NE(construction_error({"max_iter", "1e30", "w"}), "");
}

// ------------------------------------------------------------ hs071 ---

// Hock & Schittkowski problem 71 (Ipopt's own example):
//   min x1 x4 (x1 + x2 + x3) + x3
//   s.t. x1 x2 x3 x4 >= 25, x1^2 + x2^2 + x3^2 + x4^2 = 40, 1 <= x <= 5,
// start (1, 5, 5, 1); f* = 17.0140173 at (1, 4.7429996, 3.8211499, 1.3794083).
class Hs071 : public Nlp {
 public:
  Hs071() {
    z_lo_ = Vector::Constant(4, 1.0);
    z_hi_ = Vector::Constant(4, 5.0);
    c_lo_ = (Vector(2) << 25.0, 40.0).finished();
    c_hi_ = (Vector(2) << kInf, 40.0).finished();
    for (int r = 0; r < 2; ++r)
      for (int k = 0; k < 4; ++k) jac_.add(r, k);
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k <= r; ++k) hess_.add(r, k);
  }

 private:
  bool do_objective(const ConstVectorRef& x, double& f) const override {
    f = x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2];
    return true;
  }
  bool do_gradient(const ConstVectorRef& x, VectorRef g) const override {
    g[0] = x[0] * x[3] + x[3] * (x[0] + x[1] + x[2]);
    g[1] = x[0] * x[3];
    g[2] = x[0] * x[3] + 1;
    g[3] = x[0] * (x[0] + x[1] + x[2]);
    return true;
  }
  bool do_constraints(const ConstVectorRef& x, VectorRef c) const override {
    c[0] = x[0] * x[1] * x[2] * x[3];
    c[1] = x.squaredNorm();
    return true;
  }
  bool do_jacobian(const ConstVectorRef& x, VectorRef v) const override {
    v[0] = x[1] * x[2] * x[3];
    v[1] = x[0] * x[2] * x[3];
    v[2] = x[0] * x[1] * x[3];
    v[3] = x[0] * x[1] * x[2];
    for (int k = 0; k < 4; ++k) v[4 + k] = 2 * x[k];
    return true;
  }
  bool do_hessian(const ConstVectorRef& x, double s, const ConstVectorRef& l,
                  VectorRef v) const override {
    // Lower triangle, row by row: (0,0) (1,0) (1,1) (2,0) (2,1) (2,2) (3,0) ... (3,3).
    v[0] = s * 2 * x[3] + l[1] * 2;
    v[1] = s * x[3] + l[0] * x[2] * x[3];
    v[2] = l[1] * 2;
    v[3] = s * x[3] + l[0] * x[1] * x[3];
    v[4] = l[0] * x[0] * x[3];
    v[5] = l[1] * 2;
    v[6] = s * (2 * x[0] + x[1] + x[2]) + l[0] * x[1] * x[2];
    v[7] = s * x[0] + l[0] * x[0] * x[2];
    v[8] = s * x[0] + l[0] * x[0] * x[1];
    v[9] = l[1] * 2;
    return true;
  }
};

TEST(IpoptSolverSolve, Hs071HasExactDerivatives) {
  const Hs071 nlp;
  Vector x(4), l(2);
  x << 1.3, 4.1, 3.7, 1.9;
  l << -0.7, 0.4;
  const auto rep = check_derivatives(nlp, x, 1.1, l);
  expect_exact_derivatives(rep);
}

TEST(IpoptSolverSolve, Hs071ReachesItsKnownOptimum) {
  const Hs071 nlp;
  IpoptSolver solver(tight_warm_start_options());  // its last check restarts warm
  NlpPoint start;
  start.z = (Vector(4) << 1.0, 5.0, 5.0, 1.0).finished();
  const NlpResult r = solver.solve(nlp, start);
  ASSERT_TRUE(r.converged()) << ipopt_status_name(r.ipopt_status);
  EXPECT_EQ(r.ipopt_status, 0);
  EXPECT_NEAR(r.objective, 17.0140173, 1e-6);
  EXPECT_NEAR(r.point.z[0], 1.0, 1e-6);
  EXPECT_NEAR(r.point.z[1], 4.7429996, 1e-6);
  EXPECT_NEAR(r.point.z[2], 3.8211499, 1e-6);
  EXPECT_NEAR(r.point.z[3], 1.3794083, 1e-6);
  EXPECT_GT(r.iterations, 0);
  // Each iteration factorised through disco's KKT linear solver at least once; nothing was
  // answered without kkt.perturbed_first (core/ipopt/kkt_solver.h).
  EXPECT_GE(r.kkt.factorisations, r.iterations);
  EXPECT_EQ(r.kkt.answered, 0);
  // The duals come back with the right shapes (they warm-start later solves)
  // and Ipopt's sign convention: x1 sits at its lower bound with a positive
  // multiplier; the active inequality c0 >= 25 has a negative multiplier.
  ASSERT_EQ(r.point.lambda.size(), 2);
  ASSERT_EQ(r.point.z_lo.size(), 4);
  ASSERT_EQ(r.point.z_hi.size(), 4);
  EXPECT_GT(r.point.z_lo[0], 1e-3);
  EXPECT_LT(r.point.lambda[0], 0.0);

  // A warm start from the solution converges at once.
  const NlpResult again = solver.solve(nlp, r.point);
  ASSERT_TRUE(again.converged());
  EXPECT_NEAR(again.objective, 17.0140173, 1e-6);
  EXPECT_LE(again.iterations, 2);
}

// The same known optimum through disco's LDLᵀ solvers (kkt.solver ldlt and pivoted,
// core/ipopt/kkt_solver.h), every KKT matrix solved by them alone.
TEST(IpoptSolverSolve, Hs071ReachesItsKnownOptimumThroughDiscosLdlt) {
  for (const char* solver_name : {"ldlt", "pivoted"}) {
    SCOPED_TRACE(solver_name);
    const Hs071 nlp;
    Settings settings = Settings::load(default_settings_path());
    settings.apply_override(std::string("kkt.solver=") + solver_name);
    IpoptSolver solver(ipopt_settings(settings));
    NlpPoint start;
    start.z = (Vector(4) << 1.0, 5.0, 5.0, 1.0).finished();
    const NlpResult r = solver.solve(nlp, start);
    ASSERT_TRUE(r.converged()) << ipopt_status_name(r.ipopt_status);
    EXPECT_NEAR(r.objective, 17.0140173, 1e-6);
    EXPECT_NEAR(r.point.z[1], 4.7429996, 1e-6);
    EXPECT_NEAR(r.point.z[2], 3.8211499, 1e-6);
    EXPECT_NEAR(r.point.z[3], 1.3794083, 1e-6);
    EXPECT_GE(r.kkt.factorisations, r.iterations);
    EXPECT_EQ(r.kkt.fallbacks, 0);
  }
}

// Hs071 whose objective fails an internal check (a bug) from its `fail_at`-th evaluation on.
class Hs071WithABug : public Hs071 {
 public:
  explicit Hs071WithABug(int fail_at) : fail_at_(fail_at) {}

 private:
  bool do_objective(const ConstVectorRef& x, double& f) const override {
    DISCO_CHECK(++calls_ < fail_at_, "a bug met in the middle of a solve");
    f = x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2];
    return true;
  }
  int fail_at_;
  mutable int calls_ = 0;
};

TEST(IpoptSolverSolve, AFailedInternalCheckInACallbackIsRethrownAfterTheSolveNotHidden) {
  // Not turned into a failed evaluation (which Ipopt would step around): the solve stops
  // and the check's message reaches the caller, at the first evaluation and later on.
  for (int fail_at : {1, 5}) {
    const Hs071WithABug nlp(fail_at);
    IpoptSolver solver(disco_yaml_ipopt_options());
    NlpPoint start;
    start.z = (Vector(4) << 1.0, 5.0, 5.0, 1.0).finished();
    try {
      solver.solve(nlp, start);
      ADD_FAILURE() << "the solve returned; fail_at " << fail_at;
    } catch (const InternalError& e) {
      EXPECT_NE(std::string(e.what()).find("internal check failed at"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("a bug met in the middle of a solve"), std::string::npos);
    }
  }
}

// f = sqrt(x - 1) + x: NaN at the start x = 0.
class NanAtStart : public Nlp {
 public:
  NanAtStart() {
    z_lo_ = Vector::Constant(1, -1.0);
    z_hi_ = Vector::Constant(1, 10.0);
    hess_.add(0, 0);
  }

 private:
  bool do_objective(const ConstVectorRef& x, double& f) const override {
    f = std::sqrt(x[0] - 1) + x[0];
    return true;
  }
  bool do_gradient(const ConstVectorRef& x, VectorRef g) const override {
    g[0] = 0.5 / std::sqrt(x[0] - 1) + 1;
    return true;
  }
  bool do_constraints(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_jacobian(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_hessian(const ConstVectorRef& x, double s, const ConstVectorRef&,
                  VectorRef v) const override {
    v[0] = -s * 0.25 * std::pow(x[0] - 1, -1.5);
    return true;
  }
};

TEST(IpoptSolverSolve, NanAtTheStartIsANonConvergedStatusNotACrash) {
  const NanAtStart nlp;
  double f = 0.0;
  ASSERT_FALSE(nlp.objective(Vector::Zero(1), f));  // the wrapper already says no
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = Vector::Zero(1);
  const NlpResult r = solver.solve(nlp, start);
  EXPECT_FALSE(r.converged()) << ipopt_status_name(r.ipopt_status);
  EXPECT_NE(r.ipopt_status, 5);
  // A result of the right shape is still returned.
  EXPECT_EQ(r.point.z.size(), 1);
  EXPECT_EQ(r.point.lambda.size(), 0);
  EXPECT_EQ(r.point.z_lo.size(), 1);
}

// f = sqrt(1 + (x - 1)^2), minimum at x = 1, but NaN for x > 5 (say, outside the domain
// of a model). From x = -3 the Newton step (exact Hessian 1/s^3) lands at x = 65; every
// callback at such a point returns NaN, which the wrapper turns into `false`.
class NanPastFive : public Nlp {
 public:
  NanPastFive() {
    z_lo_ = Vector::Constant(1, -kInf);
    z_hi_ = Vector::Constant(1, kInf);
    hess_.add(0, 0);
  }
  mutable int nan_evaluations = 0;

 private:
  double nan_past_five(double x, double v) const {
    if (x <= 5.0) return v;
    ++nan_evaluations;
    return std::numeric_limits<double>::quiet_NaN();
  }
  bool do_objective(const ConstVectorRef& x, double& f) const override {
    f = nan_past_five(x[0], std::sqrt(1 + (x[0] - 1) * (x[0] - 1)));
    return true;
  }
  bool do_gradient(const ConstVectorRef& x, VectorRef g) const override {
    g[0] = nan_past_five(x[0], (x[0] - 1) / std::sqrt(1 + (x[0] - 1) * (x[0] - 1)));
    return true;
  }
  bool do_constraints(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_jacobian(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_hessian(const ConstVectorRef& x, double s, const ConstVectorRef&,
                  VectorRef v) const override {
    v[0] = nan_past_five(x[0], s * std::pow(1 + (x[0] - 1) * (x[0] - 1), -1.5));
    return true;
  }
};

TEST(IpoptSolverSolve, NanInsideTheSolveIsCaughtAndTheSolveGoesOn) {
  const NanPastFive nlp;
  double f = 0.0;
  ASSERT_FALSE(nlp.objective(Vector::Constant(1, 65.0), f));  // the callback says no
  ASSERT_TRUE(nlp.objective(Vector::Constant(1, -3.0), f));
  nlp.nan_evaluations = 0;
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = Vector::Constant(1, -3.0);
  const NlpResult r = solver.solve(nlp, start);
  // Ipopt met NaN (a failed callback) and cut its step back instead of stopping.
  EXPECT_GT(nlp.nan_evaluations, 0);
  ASSERT_TRUE(r.converged()) << ipopt_status_name(r.ipopt_status);
  EXPECT_NEAR(r.point.z[0], 1.0, 1e-6);
  EXPECT_NEAR(r.objective, 1.0, 1e-12);
}

// The Rosenbrock function (unconstrained).
class Rosenbrock : public Nlp {
 public:
  Rosenbrock() {
    z_lo_ = Vector::Constant(2, -kInf);
    z_hi_ = Vector::Constant(2, kInf);
    hess_.add(0, 0);
    hess_.add(1, 0);
    hess_.add(1, 1);
  }

 private:
  bool do_objective(const ConstVectorRef& x, double& f) const override {
    f = 100 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1 - x[0], 2);
    return true;
  }
  bool do_gradient(const ConstVectorRef& x, VectorRef g) const override {
    g[0] = -400 * x[0] * (x[1] - x[0] * x[0]) - 2 * (1 - x[0]);
    g[1] = 200 * (x[1] - x[0] * x[0]);
    return true;
  }
  bool do_constraints(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_jacobian(const ConstVectorRef&, VectorRef) const override { return true; }
  bool do_hessian(const ConstVectorRef& x, double s, const ConstVectorRef&,
                  VectorRef v) const override {
    v[0] = s * (1200 * x[0] * x[0] - 400 * x[1] + 2);
    v[1] = s * (-400 * x[0]);
    v[2] = s * 200;
    return true;
  }
};

// A deadline on disco's clock (core/util/clock.h) stops a solve at the first iteration report
// past it. On a simulated clock of 10 ms per report (iteration 0 is the first), a deadline
// 55 ms after the solve's start is passed at the sixth report, iteration 5, on any machine.
TEST(IpoptSolverSolve, ADeadlineStopsTheSolveAtTheFirstIterationPastIt) {
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = (Vector(2) << -1.2, 1.0).finished();
  IterationTime time(0.01);
  const ScopedTimeSource clock(time);
  // Unlimited: converges to (1, 1) after a good number of iterations, one report each.
  const NlpResult full = solver.solve(Rosenbrock(), start);
  ASSERT_TRUE(full.converged()) << ipopt_status_name(full.ipopt_status);
  EXPECT_NEAR(full.point.z[0], 1.0, 1e-6);
  ASSERT_GE(full.iterations, 15);
  EXPECT_EQ(time.iterations(), full.iterations + 1) << "iteration 0 and one report per iteration";
  EXPECT_NEAR(full.seconds, 0.01 * (full.iterations + 1), 1e-9) << "a solve's seconds are the clock's";

  NlpLimits limits;
  limits.deadline = after(Clock::now(), 0.055);
  const NlpResult cut = solver.solve(Rosenbrock(), start, limits);
  EXPECT_EQ(cut.outcome, NlpOutcome::kTimeLimit) << ipopt_status_name(cut.ipopt_status);
  EXPECT_EQ(ipopt_status_name(cut.ipopt_status), "User_Requested_Stop");
  EXPECT_EQ(describe(cut.outcome, cut.ipopt_status), "time limit");
  EXPECT_FALSE(cut.converged());
  EXPECT_EQ(cut.iterations, 5);
  EXPECT_NEAR(cut.seconds, 0.06, 1e-9);
  EXPECT_EQ(cut.point.z.size(), 2);
  // A deadline exactly on a report is not yet past: the solve goes on to the next one.
  limits.deadline = after(Clock::now(), 0.05);
  EXPECT_EQ(solver.solve(Rosenbrock(), start, limits).iterations, 5);
  // A solve started past its deadline stops at iteration 0.
  limits.deadline = after(Clock::now(), -1.0);
  const NlpResult late = solver.solve(Rosenbrock(), start, limits);
  EXPECT_EQ(late.outcome, NlpOutcome::kTimeLimit);
  EXPECT_EQ(late.iterations, 0);
  // The limit is per call: the same solver solves fully afterwards, along the same path.
  const NlpResult again = solver.solve(Rosenbrock(), start);
  EXPECT_TRUE(again.converged());
  EXPECT_EQ(again.iterations, full.iterations);
}

// Finding (see the report): NlpPoint::has_duals() is lambda.size() > 0, so
// the bound multipliers of an NLP without constraint rows (e.g. the kPerPair
// elastic NLP of an MPCC whose sides are all variables) never warm-start
// Ipopt. From its own solution, such an NLP should converge at once, as it
// does when a free dummy row is added (1 iteration instead of 3).
TEST(IpoptSolverSolve, WarmStartUsesBoundMultipliersWithoutRows) {
  // min (x + 1)^2 + (y - 2)^2, x >= 0: x* = 0 with bound multiplier 2.
  auto make = [](bool dummy_row) {
    PolynomialProgram p;
    const Affine x = Affine::variable(0), y = Affine::variable(1);
    p.add_variable(0.0, kInf, 1.0);
    p.add_variable(-kInf, kInf, 0.0);
    if (dummy_row) p.add(p.add_row(-kInf, kInf), 1.0, y);
    p.add(PolynomialProgram::kObjective, 1.0, x + Affine(1.0), x + Affine(1.0));
    p.add(PolynomialProgram::kObjective, 1.0, y - Affine(2.0), y - Affine(2.0));
    p.finalize();
    return p;
  };
  IpoptSolver solver(tight_warm_start_options());
  for (bool dummy_row : {true, false}) {
    SCOPED_TRACE(dummy_row ? "with a dummy row" : "without rows");
    const auto p = make(dummy_row);
    NlpPoint start;
    start.z = p.initial_point();
    const NlpResult cold = solver.solve(p, start);
    ASSERT_TRUE(cold.converged());
    EXPECT_NEAR(cold.point.z_lo[0], 2.0, 1e-6);
    const NlpResult warm = solver.solve(p, cold.point);
    ASSERT_TRUE(warm.converged());
    EXPECT_LE(warm.iterations, 1);
  }
}

// warm_start_init_point is a setting: "no" starts every solve's duals cold, so a solve from
// the solution of the same NLP (with its multipliers) takes the cold start's way back.
TEST(IpoptSolverSolve, WarmStartInitPointNoStartsTheDualsCold) {
  // min (x + 1)^2 + (y - 2)^2, x >= 0, with a free row y: x* = 0, bound multiplier 2.
  PolynomialProgram p;
  const Affine x = Affine::variable(0), y = Affine::variable(1);
  p.add_variable(0.0, kInf, 1.0);
  p.add_variable(-kInf, kInf, 0.0);
  p.add(p.add_row(-kInf, kInf), 1.0, y);
  p.add(PolynomialProgram::kObjective, 1.0, x + Affine(1.0), x + Affine(1.0));
  p.add(PolynomialProgram::kObjective, 1.0, y - Affine(2.0), y - Affine(2.0));
  p.finalize();
  auto iterations_from_the_solution = [&](const std::string& warm_start) {
    auto options = tight_warm_start_options();
    for (auto& o : options)
      if (o.name == "warm_start_init_point") o.value = warm_start;
    IpoptSolver solver(options);
    NlpPoint start;
    start.z = p.initial_point();
    const NlpResult cold = solver.solve(p, start);
    EXPECT_TRUE(cold.converged());
    const NlpResult again = solver.solve(p, cold.point);
    EXPECT_TRUE(again.converged());
    EXPECT_NEAR(again.point.z[0], 0.0, 1e-6);
    return again.iterations;
  };
  const int warm = iterations_from_the_solution("yes");
  const int cold = iterations_from_the_solution("no");
  EXPECT_LE(warm, 1);
  EXPECT_GT(cold, warm);
}

// A solve stopped at its iteration cap says so, and is not a failure of Ipopt's.
TEST(IpoptSolverSolve, AnIterationCapIsItsOwnOutcome) {
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = (Vector(2) << -1.2, 1.0).finished();
  NlpLimits limits;
  limits.iterations = 3;
  const NlpResult cut = solver.solve(Rosenbrock(), start, limits);
  EXPECT_EQ(cut.outcome, NlpOutcome::kIterationCap) << ipopt_status_name(cut.ipopt_status);
  EXPECT_EQ(cut.iterations, 3);
  EXPECT_FALSE(cut.converged());
  EXPECT_EQ(describe(cut.outcome, cut.ipopt_status), "iteration cap");
  const NlpResult full = solver.solve(Rosenbrock(), start);
  EXPECT_EQ(full.outcome, NlpOutcome::kConverged);
  EXPECT_GT(full.iterations, 3);
}

// HS071 with x0 fixed at its optimal value 1 (equal bounds): Ipopt leaves x0 out of its own x
// (fixed_variable_treatment make_parameter), so a watched variable's place there moves.
class Hs071FirstFixed : public Hs071 {
 public:
  Hs071FirstFixed() { z_hi_[0] = 1.0; }
};

// NlpLimits::watch sees the watched variable of every iterate (the last is the answer), and
// stops the solve where it says (NlpOutcome::kStagnated), at that iterate.
TEST(IpoptSolverSolve, AWatchSeesTheVariableOfEachIterateAndCanStopTheSolve) {
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = (Vector(4) << 1.0, 5.0, 5.0, 1.0).finished();
  for (const int index : {1, 2, 3}) {
    SCOPED_TRACE("watched x" + std::to_string(index));
    std::vector<std::pair<int, double>> seen;
    NlpLimits limits;
    limits.watch = NlpLimits::Watch{index, [&seen](const NlpLimits::Iterate& it) {
                                      seen.emplace_back(it.iteration, it.value);
                                      return false;
                                    }};
    const NlpResult full = solver.solve(Hs071FirstFixed(), start, limits);
    ASSERT_TRUE(full.converged()) << ipopt_status_name(full.ipopt_status);
    EXPECT_NEAR(full.objective, 17.0140173, 1e-6);
    ASSERT_EQ(static_cast<int>(seen.size()), full.iterations + 1) << "iteration 0 and one per iteration";
    EXPECT_EQ(seen.front().first, 0);
    EXPECT_NEAR(seen.front().second, start.z[index], 0.05) << "the start, pushed inside its bounds";
    EXPECT_EQ(seen.back().first, full.iterations);
    EXPECT_EQ(seen.back().second, full.point.z[index]);

    // Stopped at iteration 3: the answer is the iterate the watch saw there.
    seen.clear();
    limits.watch->stop = [&seen](const NlpLimits::Iterate& it) {
      seen.emplace_back(it.iteration, it.value);
      return it.iteration == 3;
    };
    const NlpResult cut = solver.solve(Hs071FirstFixed(), start, limits);
    EXPECT_EQ(cut.outcome, NlpOutcome::kStagnated) << ipopt_status_name(cut.ipopt_status);
    EXPECT_EQ(describe(cut.outcome, cut.ipopt_status), "stagnated");
    EXPECT_EQ(cut.iterations, 3);
    ASSERT_EQ(seen.size(), 4u);
    EXPECT_EQ(seen.back().second, cut.point.z[index]);
    EXPECT_NE(cut.point.z[index], full.point.z[index]);
  }
}

// A BarrierStage ends the solve on the barrier path at mu_target, and the next solve without
// one runs the configured strategy to Ipopt's tol again. For min (x + 1)^2 / 2, x >= 0, the
// barrier problem min (x + 1)^2 / 2 - mu ln x has its minimum where x + 1 = mu / x:
// x = (sqrt(1 + 4 mu) - 1) / 2 (up to Ipopt's damping, below).
// min (x + 1)^2 / 2 over x >= 0, from x = x0: its minimum is on the bound, x = 0.
PolynomialProgram shifted_square(double x0) {
  PolynomialProgram p;
  p.add_variable(0.0, kInf, x0);
  const Affine x1 = Affine::variable(0) + Affine(1.0);
  p.add(PolynomialProgram::kObjective, 0.5, x1, x1);
  p.finalize();
  return p;
}

TEST(IpoptSolverSolve, ABarrierStageStopsOnTheBarrierPathAtItsTarget) {
  const PolynomialProgram p = shifted_square(1.0);
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = p.initial_point();
  for (double target : {1e-1, 1e-2, 1e-4}) {
    NlpLimits limits;
    // Ipopt damps a one-sided bound (kappa_d = 1e-5): its dual infeasibility at the barrier
    // point is kappa_d * mu, below this tolerance.
    limits.barrier = BarrierStage{10 * target, target, 1e-3 * target};
    const NlpResult staged = solver.solve(p, start, limits);
    ASSERT_TRUE(staged.converged()) << ipopt_status_name(staged.ipopt_status);
    const double x_mu = (std::sqrt(1 + 4 * target) - 1) / 2;
    EXPECT_NEAR(staged.point.z[0], x_mu, 1e-2 * x_mu) << "mu_target " << target;
  }
  const NlpResult full = solver.solve(p, start);
  ASSERT_TRUE(full.converged());
  EXPECT_LT(full.point.z[0], 1e-8);
}

// NlpLimits::push_as_warm: a start without duals on its bound is pushed inside by the
// warm-start push (configs/disco.yaml: ipopt.warm_start_bound_push 1e-3), not by Ipopt's
// cold bound_push (its default, 1e-2), as Ipopt's first iterate shows; a start with duals is
// warm anyway, and the next solve without the flag is pushed as configured again.
TEST(IpoptSolverSolve, PushAsWarmPushesAColdStartOnlyAsFarAsAWarmStart) {
  const PolynomialProgram p = shifted_square(0.0);
  IpoptSolver solver(disco_yaml_ipopt_options());
  NlpPoint start;
  start.z = p.initial_point();
  ASSERT_EQ(start.z[0], 0.0);
  auto first_iterate = [&](bool push_as_warm) {
    double x0 = -1.0;
    NlpLimits limits;
    limits.push_as_warm = push_as_warm;
    limits.watch = NlpLimits::Watch{0, [&x0](const NlpLimits::Iterate& it) {
                                      if (it.iteration == 0) x0 = it.value;
                                      return false;
                                    }};
    const NlpResult r = solver.solve(p, start, limits);
    EXPECT_TRUE(r.converged()) << ipopt_status_name(r.ipopt_status);
    EXPECT_LT(r.point.z[0], 1e-8);
    return x0;
  };
  EXPECT_DOUBLE_EQ(first_iterate(false), 1e-2) << "Ipopt's bound_push";
  EXPECT_DOUBLE_EQ(first_iterate(true), 1e-3) << "ipopt.warm_start_bound_push";
  EXPECT_DOUBLE_EQ(first_iterate(false), 1e-2) << "the configured push again";
}

}  // namespace
}  // namespace disco
