// PolynomialProgram: values equal a hand evaluation, derivatives equal finite
// differences with nothing outside the patterns, evaluation is bitwise
// independent of the OpenMP thread count; and the Nlp public wrapper turns
// non-finite values and exceptions into `false`.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>

#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/numbers.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using test_support::expect_exact_derivatives;
using test_support::make_random_program;
using test_support::random_vector;
using test_support::RandomProgramShape;

const Affine X0 = Affine::variable(0), X1 = Affine::variable(1), X2 = Affine::variable(2),
             X3 = Affine::variable(3);

// Rows of the hand-checked program (see hand_program()).
double hand_row(int r, const Vector& z) {
  const double x0 = z[0], x1 = z[1], x2 = z[2], x3 = z[3];
  switch (r) {
    case 0: return 2.0 * (x0 + 3.0) * (x1 - 2.0 * x2 + 1.0) * (x0 - 0.5);
    case 1: return x0 * x0 - 0.5 * x1 * x1 * x1 + 3.0 * x0 * x0 * x1 + 5.0;
    case 2: return 2.5 * x2 * x2 * x3 + x0 * x0 - x1 * x1 + 2.0 * x3;
    case 3: return 0.0;
    default: return (x0 - x3) * (x0 - x3) + x1 * x2 + 7.0;  // objective
  }
}

PolynomialProgram hand_program() {
  PolynomialProgram p;
  for (int k = 0; k < 4; ++k) p.add_variable(-10, 10, 0.1 * k);
  const int r0 = p.add_row(-1, 1), r1 = p.add_row(-1, 1), r2 = p.add_row(-1, 1),
            r3 = p.add_row(-1, 1);
  // Row 0: a product of affine factors with constants, expanded on add.
  p.add(r0, 2.0, X0 + Affine(3.0), X1 - 2.0 * X2 + Affine(1.0), X0 - Affine(0.5));
  // Row 1: x0^2, x1^3, x0^2 x1 (factors given unsorted), a constant.
  p.add(r1, 1.0, X0, X0);
  p.add(r1, -0.5, X1, X1, X1);
  p.add(r1, 3.0, X0, X1, X0);
  p.add(r1, 2.0, Affine(2.5));
  // Row 2: monomials that cancel (x0 x1 - x1 x0, and inside (x0+x1)(x0-x1))
  // and merge (2 x2^2 x3 + 0.5 x2 x3 x2), a variable repeated in one Affine.
  p.add(r2, 1.0, X0, X1);
  p.add(r2, -1.0, X1, X0);
  p.add(r2, 2.0, X2, X3, X2);
  p.add(r2, 0.5, X2, X2, X3);
  p.add(r2, 1.0, X0 + X1, X0 - X1);
  p.add(r2, 1.0, X3 + X3);
  // Row 3: everything cancels, constants included.
  p.add(r3, 1.0, X0, X1);
  p.add(r3, -1.0, X0, X1);
  p.add(r3, 1.0, Affine(3.0));
  p.add(r3, -1.0, Affine(3.0));
  // Objective: (x0 - x3)^2 + x1 x2 + 7.
  p.add(PolynomialProgram::kObjective, 1.0, X0 - X3, X0 - X3);
  p.add(PolynomialProgram::kObjective, 1.0, X1, X2);
  p.add(PolynomialProgram::kObjective, 7.0, Affine(1.0));
  p.finalize();
  return p;
}

TEST(PolynomialProgram, ValuesEqualHandEvaluation) {
  const auto p = hand_program();
  ASSERT_EQ(p.num_variables(), 4);
  ASSERT_EQ(p.num_constraints(), 4);
  EXPECT_DOUBLE_EQ(p.initial_point()[3], 0.3);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Vector z = random_vector(rng, 4, -3.0, 3.0);
    Vector c(4);
    double f = 0.0;
    ASSERT_TRUE(p.constraints(z, c));
    ASSERT_TRUE(p.objective(z, f));
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(c[r], hand_row(r, z), 1e-12 * (1.0 + std::abs(hand_row(r, z)))) << "row " << r;
    EXPECT_NEAR(f, hand_row(-1, z), 1e-12 * (1.0 + std::abs(f)));
  }
  // Row 3 cancels exactly: value 0 and no Jacobian entries at all.
  const auto& jp = p.jacobian_pattern();
  for (int e = 0; e < jp.size(); ++e) EXPECT_NE(jp.rows[e], 3) << "cancelled row has an entry";
}

TEST(PolynomialProgram, RepeatedVariablesHaveExactDerivatives) {
  // Row 1 = x0^2 - 0.5 x1^3 + 3 x0^2 x1 + 5, checked against hand derivatives
  // (diagonal second derivatives of x^2, x^3 and x^2 y are where a factor of
  // 2 or 3 is easy to lose).
  const auto p = hand_program();
  Vector z(4);
  z << 0.7, -1.3, 2.1, 0.4;
  const double x0 = z[0], x1 = z[1];
  Vector jv(p.jacobian_pattern().size());
  ASSERT_TRUE(p.jacobian(z, jv));
  std::map<std::pair<int, int>, double> J;
  for (int e = 0; e < jv.size(); ++e)
    J[{p.jacobian_pattern().rows[e], p.jacobian_pattern().cols[e]}] = jv[e];
  EXPECT_NEAR((J[{1, 0}]), 2 * x0 + 6 * x0 * x1, 1e-14);
  EXPECT_NEAR((J[{1, 1}]), -1.5 * x1 * x1 + 3 * x0 * x0, 1e-14);
  EXPECT_EQ(J.count({1, 2}), 0u);

  Vector lambda = Vector::Zero(4);
  lambda[1] = 1.0;
  Vector hv(p.hessian_pattern().size());
  ASSERT_TRUE(p.hessian(z, 0.0, lambda, hv));
  std::map<std::pair<int, int>, double> H;
  for (int e = 0; e < hv.size(); ++e)
    H[{p.hessian_pattern().rows[e], p.hessian_pattern().cols[e]}] = hv[e];
  EXPECT_NEAR((H[{0, 0}]), 2 + 6 * x1, 1e-14);
  EXPECT_NEAR((H[{1, 0}]), 6 * x0, 1e-14);
  EXPECT_NEAR((H[{1, 1}]), -3 * x1, 1e-14);

  // Objective alone (sigma = 2): 2 * Hessian of (x0 - x3)^2 + x1 x2.
  Vector none = Vector::Zero(4);
  ASSERT_TRUE(p.hessian(z, 2.0, none, hv));
  H.clear();
  for (int e = 0; e < hv.size(); ++e)
    H[{p.hessian_pattern().rows[e], p.hessian_pattern().cols[e]}] = hv[e];
  EXPECT_EQ((H[{0, 0}]), 4.0);
  EXPECT_EQ((H[{3, 3}]), 4.0);
  EXPECT_EQ((H[{3, 0}]), -4.0);
  EXPECT_EQ((H[{2, 1}]), 2.0);
  Vector g(4);
  ASSERT_TRUE(p.gradient(z, g));
  EXPECT_NEAR(g[0], 2 * (z[0] - z[3]), 1e-14);
  EXPECT_NEAR(g[1], z[2], 1e-14);
  EXPECT_NEAR(g[2], z[1], 1e-14);
  EXPECT_NEAR(g[3], -2 * (z[0] - z[3]), 1e-14);
}

// sin(a x), for function terms.
class Sine : public UnivariateFunction {
 public:
  std::array<double, 3> eval(double x) const override { return {std::sin(x), std::cos(x), -std::sin(x)}; }
};

// Function terms coef * g(a z_k) (g = sin here): values and derivatives by hand, merged with
// monomials on the same entries, in a row, the objective, and a row with nothing else; then
// every derivative against finite differences.
TEST(PolynomialProgram, FunctionTermsHaveExactDerivatives) {
  const auto g = std::make_shared<const Sine>();
  PolynomialProgram p;
  for (int k = 0; k < 3; ++k) p.add_variable(-10, 10);
  const int r0 = p.add_row(-1, 1), r1 = p.add_row(-1, 1);
  p.add(r0, 1.0, X0, X1);              // x0 x1
  p.add_function(r0, 2.0, g, 0, 0.5);  // + 2 sin(x0 / 2)
  p.add_function(r0, -1.0, g, 1);      // - sin(x1)
  p.add_function(r1, 3.0, g, 2, -2.0);  // 3 sin(-2 x2)
  p.add(PolynomialProgram::kObjective, 1.0, X2, X2);  // x2^2
  p.add_function(PolynomialProgram::kObjective, 1.0, g, 2);  // + sin(x2)
  p.finalize();
  EXPECT_EQ(p.num_function_terms(), 4);
  Vector z(3);
  z << 0.7, -1.3, 0.4;
  const double x0 = z[0], x1 = z[1], x2 = z[2];
  Vector c(2);
  ASSERT_TRUE(p.constraints(z, c));
  EXPECT_NEAR(c[0], x0 * x1 + 2 * std::sin(x0 / 2) - std::sin(x1), 1e-15);
  EXPECT_NEAR(c[1], 3 * std::sin(-2 * x2), 1e-15);
  double f = 0;
  ASSERT_TRUE(p.objective(z, f));
  EXPECT_NEAR(f, x2 * x2 + std::sin(x2), 1e-15);
  Vector gr(3);
  ASSERT_TRUE(p.gradient(z, gr));
  EXPECT_NEAR(gr[2], 2 * x2 + std::cos(x2), 1e-15);
  Vector jv(p.jacobian_pattern().size());
  ASSERT_TRUE(p.jacobian(z, jv));
  std::map<std::pair<int, int>, double> J;
  for (int e = 0; e < jv.size(); ++e) J[{p.jacobian_pattern().rows[e], p.jacobian_pattern().cols[e]}] = jv[e];
  EXPECT_EQ(J.size(), 3u) << "one entry per (row, variable), monomials and functions merged";
  EXPECT_NEAR((J[{0, 0}]), x1 + std::cos(x0 / 2), 1e-15);
  EXPECT_NEAR((J[{0, 1}]), x0 - std::cos(x1), 1e-15);
  EXPECT_NEAR((J[{1, 2}]), -6 * std::cos(-2 * x2), 1e-15);
  Vector lambda(2);
  lambda << 0.5, -2.0;
  Vector hv(p.hessian_pattern().size());
  ASSERT_TRUE(p.hessian(z, 1.5, lambda, hv));
  std::map<std::pair<int, int>, double> H;
  for (int e = 0; e < hv.size(); ++e) H[{p.hessian_pattern().rows[e], p.hessian_pattern().cols[e]}] = hv[e];
  EXPECT_NEAR((H[{0, 0}]), 0.5 * (-0.5 * std::sin(x0 / 2)), 1e-15);
  EXPECT_NEAR((H[{1, 0}]), 0.5, 1e-15);
  EXPECT_NEAR((H[{1, 1}]), 0.5 * std::sin(x1), 1e-15);
  EXPECT_NEAR((H[{2, 2}]), -2.0 * (-12 * std::sin(-2 * x2)) + 1.5 * (2 - std::sin(x2)), 1e-14);
  test_support::expect_exact_derivatives(check_derivatives(p, z, 1.5, lambda), 1e-6);
}

TEST(PolynomialProgram, CancelledMonomialsLeaveNoStructure) {
  // x0 x1 - x1 x0 + (x0 + x1)(x0 - x1) = x0^2 - x1^2: two monomials, no
  // Hessian entry (1, 0).
  PolynomialProgram p;
  p.add_variable(-1, 1);
  p.add_variable(-1, 1);
  const int r = p.add_row(0, 0);
  p.add(r, 1.0, X0, X1);
  p.add(r, -1.0, X1, X0);
  p.add(r, 1.0, X0 + X1, X0 - X1);
  p.finalize();
  EXPECT_EQ(p.num_monomials(), 2);
  std::set<std::pair<int, int>> hs;
  for (int e = 0; e < p.hessian_pattern().size(); ++e)
    hs.insert({p.hessian_pattern().rows[e], p.hessian_pattern().cols[e]});
  EXPECT_EQ(hs, (std::set<std::pair<int, int>>{{0, 0}, {1, 1}}));
  Vector z(2), lambda(1), hv(p.hessian_pattern().size());
  z << 0.3, -0.8;
  lambda << 1.0;
  ASSERT_TRUE(p.hessian(z, 1.0, lambda, hv));
  for (int e = 0; e < hv.size(); ++e)
    EXPECT_EQ(hv[e], p.hessian_pattern().rows[e] == 0 ? 2.0 : -2.0);
}

void expect_valid_patterns(const Nlp& nlp) {
  std::set<std::pair<int, int>> seen;
  const auto& jp = nlp.jacobian_pattern();
  for (int e = 0; e < jp.size(); ++e) {
    EXPECT_TRUE(jp.rows[e] >= 0 && jp.rows[e] < nlp.num_constraints());
    EXPECT_TRUE(jp.cols[e] >= 0 && jp.cols[e] < nlp.num_variables());
    EXPECT_TRUE(seen.insert({jp.rows[e], jp.cols[e]}).second) << "repeated Jacobian entry";
  }
  seen.clear();
  const auto& hp = nlp.hessian_pattern();
  for (int e = 0; e < hp.size(); ++e) {
    EXPECT_GE(hp.rows[e], hp.cols[e]) << "Hessian entry above the diagonal";
    EXPECT_TRUE(hp.cols[e] >= 0 && hp.rows[e] < nlp.num_variables());
    EXPECT_TRUE(seen.insert({hp.rows[e], hp.cols[e]}).second) << "repeated Hessian entry";
  }
}

TEST(PolynomialProgram, RandomProgramsMatchReferenceAndFiniteDifferences) {
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto rp = make_random_program(seed, RandomProgramShape{});
    const auto& p = rp.program;
    ASSERT_EQ(p.num_variables(), 30);
    ASSERT_EQ(p.num_constraints(), 20);
    expect_valid_patterns(p);
    std::mt19937 rng(100 + seed);
    for (int trial = 0; trial < 3; ++trial) {
      const Vector z = random_vector(rng, 30, -1.5, 1.5);
      const Vector lambda = random_vector(rng, 20, -2.0, 2.0);
      // Values against the independent record of the terms.
      Vector c(20);
      double f = 0.0;
      ASSERT_TRUE(p.constraints(z, c));
      ASSERT_TRUE(p.objective(z, f));
      for (int r = 0; r < 20; ++r) {
        const double ref = rp.reference_value(r, z);
        EXPECT_NEAR(c[r], ref, 1e-12 * (1.0 + std::abs(ref))) << "row " << r;
      }
      const double fref = rp.reference_value(PolynomialProgram::kObjective, z);
      EXPECT_NEAR(f, fref, 1e-12 * (1.0 + std::abs(fref)));
      // Derivatives against central differences.
      const auto rep = check_derivatives(p, z, 0.5 + trial, lambda);
      ASSERT_NO_FATAL_FAILURE(expect_exact_derivatives(rep));
    }
  }
}

// Restores the OpenMP thread count on scope exit, even after a failure.
class ThreadCountGuard {
 public:
  ThreadCountGuard() : saved_(omp_get_max_threads()) {}
  ~ThreadCountGuard() { omp_set_num_threads(saved_); }

 private:
  int saved_;
};

struct Evaluation {
  double f = 0.0;
  Vector grad, c, jac, hess;
};

Evaluation evaluate_all(const PolynomialProgram& p, const Vector& z, double sigma,
                        const Vector& lambda) {
  Evaluation e;
  e.grad.resize(p.num_variables());
  e.c.resize(p.num_constraints());
  e.jac.resize(p.jacobian_pattern().size());
  e.hess.resize(p.hessian_pattern().size());
  EXPECT_TRUE(p.objective(z, e.f));
  EXPECT_TRUE(p.gradient(z, e.grad));
  EXPECT_TRUE(p.constraints(z, e.c));
  EXPECT_TRUE(p.jacobian(z, e.jac));
  EXPECT_TRUE(p.hessian(z, sigma, lambda, e.hess));
  return e;
}

bool same_bits(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

TEST(PolynomialProgram, EvaluationIsBitwiseIndependentOfThreadCount) {
  // Every parallel loop in polynomial_program.cpp runs forked (threshold
  // lowered to 2 outputs), with many terms per output so that any change of
  // summation order would show in the last bits.
  RandomProgramShape shape;
  shape.variables = 400;
  shape.rows = 3000;
  shape.min_terms = 4;
  shape.max_terms = 10;
  auto rp = make_random_program(42, shape);
  rp.program.set_parallel_threshold(2);
  const auto& p = rp.program;

  std::mt19937 rng(9);
  const Vector z = random_vector(rng, p.num_variables(), -1.7, 1.7);
  const Vector lambda = random_vector(rng, p.num_constraints(), -3.0, 3.0);
  const double sigma = 0.37;

  ThreadCountGuard guard;
  omp_set_num_threads(1);
  ASSERT_EQ(omp_get_max_threads(), 1);
  const Evaluation one = evaluate_all(p, z, sigma, lambda);
  for (int threads : {2, 3}) {
    omp_set_num_threads(threads);
    ASSERT_EQ(omp_get_max_threads(), threads);
    const Evaluation many = evaluate_all(p, z, sigma, lambda);
    SCOPED_TRACE(std::to_string(threads) + " threads");
    EXPECT_TRUE(std::memcmp(&one.f, &many.f, sizeof(double)) == 0);
    EXPECT_TRUE(same_bits(one.grad, many.grad));
    EXPECT_TRUE(same_bits(one.c, many.c)) << "constraints differ";
    EXPECT_TRUE(same_bits(one.jac, many.jac)) << "Jacobian differs";
    EXPECT_TRUE(same_bits(one.hess, many.hess)) << "Hessian differs";
  }
  // And the values are right, not merely reproducible.
  for (int r = 0; r < p.num_constraints(); r += 97) {
    const double ref = rp.reference_value(r, z);
    EXPECT_NEAR(one.c[r], ref, 1e-11 * (1.0 + std::abs(ref)));
  }
}

TEST(PolynomialProgram, ThreadCountGuardRestores) {
  const int before = omp_get_max_threads();
  {
    ThreadCountGuard guard;
    omp_set_num_threads(before + 1);
  }
  EXPECT_EQ(omp_get_max_threads(), before);
}

// ------------------------------------------------- Nlp's public wrapper ---

// One variable, one row, 1x1 Jacobian and Hessian; each evaluation can be
// made to misbehave in one way.
class Faulty : public Nlp {
 public:
  enum Mode { kGood, kNaN, kInfinite, kThrowStd, kThrowOther, kReturnFalse };
  explicit Faulty(Mode mode) : mode_(mode) {
    z_lo_ = z_hi_ = c_lo_ = c_hi_ = Vector::Zero(1);
    jac_.add(0, 0);
    hess_.add(0, 0);
  }

 private:
  double value(double good) const {
    switch (mode_) {
      case kNaN: return std::numeric_limits<double>::quiet_NaN();
      case kInfinite: return -std::numeric_limits<double>::infinity();
      case kThrowStd: throw std::runtime_error("evaluation failed");
      case kThrowOther: throw 42;
      default: return good;
    }
  }
  bool do_objective(const ConstVectorRef& z, double& f) const override {
    f = value(z[0] * z[0]);
    return mode_ != kReturnFalse;
  }
  bool do_gradient(const ConstVectorRef& z, VectorRef g) const override {
    g[0] = value(2 * z[0]);
    return mode_ != kReturnFalse;
  }
  bool do_constraints(const ConstVectorRef& z, VectorRef c) const override {
    c[0] = value(z[0]);
    return mode_ != kReturnFalse;
  }
  bool do_jacobian(const ConstVectorRef&, VectorRef v) const override {
    v[0] = value(1.0);
    return mode_ != kReturnFalse;
  }
  bool do_hessian(const ConstVectorRef&, double sigma, const ConstVectorRef&,
                  VectorRef v) const override {
    v[0] = value(2.0 * sigma);
    return mode_ != kReturnFalse;
  }
  Mode mode_;
};

TEST(PolynomialProgramNlpWrapper, NonFiniteValuesAndExceptionsBecomeFalse) {
  Vector z(1), out(1), lambda(1);
  z << 0.5;
  lambda << 1.0;
  double f = 0.0;
  {
    const Faulty good(Faulty::kGood);  // control: the same calls succeed
    EXPECT_TRUE(good.objective(z, f));
    EXPECT_EQ(f, 0.25);
    EXPECT_TRUE(good.gradient(z, out));
    EXPECT_TRUE(good.constraints(z, out));
    EXPECT_TRUE(good.jacobian(z, out));
    EXPECT_TRUE(good.hessian(z, 1.0, lambda, out));
  }
  for (auto mode : {Faulty::kNaN, Faulty::kInfinite, Faulty::kThrowStd, Faulty::kThrowOther,
                    Faulty::kReturnFalse}) {
    SCOPED_TRACE("mode " + std::to_string(static_cast<int>(mode)));
    const Faulty bad(mode);
    EXPECT_FALSE(bad.objective(z, f));
    EXPECT_FALSE(bad.gradient(z, out));
    EXPECT_FALSE(bad.constraints(z, out));
    EXPECT_FALSE(bad.jacobian(z, out));
    EXPECT_FALSE(bad.hessian(z, 1.0, lambda, out));
  }
}

// A real program whose evaluation goes non-finite at a finite point (an
// overflowing cube): the wrapper still reports `false`.
TEST(PolynomialProgramNlpWrapper, OverflowInAProgramBecomesFalse) {
  PolynomialProgram p;
  p.add_variable(-kInf, kInf);
  const int r = p.add_row(-1, 1);
  p.add(r, 1.0, X0, X0, X0);
  p.add(PolynomialProgram::kObjective, 1.0, X0, X0, X0);
  p.finalize();
  Vector z(1), c(1), jv(p.jacobian_pattern().size());
  double f = 0.0;
  z << 1e200;
  EXPECT_FALSE(p.constraints(z, c));
  EXPECT_FALSE(p.objective(z, f));
  EXPECT_FALSE(p.jacobian(z, jv));
  z << 2.0;
  EXPECT_TRUE(p.constraints(z, c));
  EXPECT_EQ(c[0], 8.0);
}

}  // namespace
}  // namespace disco
