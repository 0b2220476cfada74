// ElasticNlp: structure (variables, slacks, eps, bounds), values, lift() and
// exact derivatives of both formulations on a small MPCC whose pairs mix
// variable sides and row sides, with one variable and one row each used in
// two pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "core/elastic/elastic_nlp.h"
#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/numbers.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using test_support::expect_exact_derivatives;
using test_support::random_vector;

// Variables: x0 in [-3, 4], x1 in [0.5, 10], x2 in [-5, 5], x3 free, x4 in [-1, 1].
// Rows:      r0 = x0 x2 + x4^2                    in [-1, 1]   (no side)
//            r1 = x2^2 - x1 x4 + 0.3 x0 x2 x3     free         (side of p1 and p3)
//            r2 = x3 x4 + x2 - 1                  in [-1, 5]   (side of p2)
//            r3 = x1^2 x3 - x0                    in [0.5, inf](side of p3)
// Pairs:     p0: x0 _|_ x1,  p1: x0 _|_ r1,  p2: r2 _|_ x3,  p3: r1 _|_ r3.
// Objective: x0^2 x1 + x2 x3 - x4^3 + 2.
constexpr int kN = 5, kM = 4;

struct SmallMpcc {
  PolynomialProgram p;
  SmallMpcc() {
    const Affine x0 = Affine::variable(0), x1 = Affine::variable(1), x2 = Affine::variable(2),
                 x3 = Affine::variable(3), x4 = Affine::variable(4);
    p.add_variable(-3, 4);
    p.add_variable(0.5, 10);
    p.add_variable(-5, 5);
    p.add_variable(-kInf, kInf);
    p.add_variable(-1, 1);
    const int r0 = p.add_row(-1, 1), r1 = p.add_row(-kInf, kInf), r2 = p.add_row(-1, 5),
              r3 = p.add_row(0.5, kInf);
    p.add(r0, 1.0, x0, x2);
    p.add(r0, 1.0, x4, x4);
    p.add(r1, 1.0, x2, x2);
    p.add(r1, -1.0, x1, x4);
    p.add(r1, 0.3, x0, x2, x3);
    p.add(r2, 1.0, x3, x4);
    p.add(r2, 1.0, x2 - Affine(1.0));
    p.add(r3, 1.0, x1, x1, x3);
    p.add(r3, -1.0, x0);
    p.add(PolynomialProgram::kObjective, 1.0, x0, x0, x1);
    p.add(PolynomialProgram::kObjective, 1.0, x2, x3);
    p.add(PolynomialProgram::kObjective, -1.0, x4, x4, x4);
    p.add(PolynomialProgram::kObjective, 1.0, Affine(2.0));
    using S = ComplementaritySide;
    p.add_pair(S::variable(0), S::variable(1));
    p.add_pair(S::variable(0), S::row(r1));
    p.add_pair(S::row(r2), S::variable(3));
    p.add_pair(S::row(r1), S::row(r3));
    p.finalize();
  }
};

class ElasticNlpTest : public ::testing::TestWithParam<ElasticFormulation> {
 protected:
  // kLumped and kRelaxed have the lumped row and eps (kRelaxed: the same NLP at sigma = 0).
  bool lumped() const { return GetParam() != ElasticFormulation::kPerPair; }
  SmallMpcc mpcc_;
};

TEST_P(ElasticNlpTest, VariablesSlacksAndEps) {
  const ElasticNlp e(mpcc_.p, GetParam(), 10.0);
  EXPECT_EQ(e.num_variables(), kN + 3 + (lumped() ? 1 : 0));  // r1 gets ONE slack
  EXPECT_EQ(e.num_constraints(), kM + (lumped() ? 1 : 0));
  EXPECT_EQ(e.eps_index(), lumped() ? kN + 3 : -1);
  // Variable sides are the variables themselves.
  EXPECT_EQ(e.u(0), 0);
  EXPECT_EQ(e.w(0), 1);
  EXPECT_EQ(e.u(1), 0);
  EXPECT_EQ(e.w(2), 3);
  // Row sides are slacks: distinct per row, shared by the two uses of r1.
  const int s1 = e.w(1), s2 = e.u(2), s3 = e.w(3);
  EXPECT_EQ(e.u(3), s1);
  std::set<int> slacks{s1, s2, s3};
  EXPECT_EQ(slacks.size(), 3u);
  for (int s : slacks) {
    EXPECT_GE(s, kN);
    EXPECT_LT(s, kN + 3);
  }
}

TEST_P(ElasticNlpTest, Bounds) {
  const ElasticNlp e(mpcc_.p, GetParam(), 10.0);
  const Vector &lo = e.variable_lower(), &hi = e.variable_upper();
  // Variable sides: lower bound max(lo, 0), upper bound kept.
  EXPECT_EQ(lo[0], 0.0);  // was -3
  EXPECT_EQ(hi[0], 4.0);
  EXPECT_EQ(lo[1], 0.5);  // already positive
  EXPECT_EQ(hi[1], 10.0);
  EXPECT_EQ(lo[3], 0.0);  // was -inf
  EXPECT_EQ(hi[3], kInf);
  // Other variables untouched.
  EXPECT_EQ(lo[2], -5.0);
  EXPECT_EQ(hi[2], 5.0);
  EXPECT_EQ(lo[4], -1.0);
  EXPECT_EQ(hi[4], 1.0);
  // Row-side slacks take the row's bounds (lower at least 0) ...
  const int s1 = e.w(1), s2 = e.u(2), s3 = e.w(3);
  EXPECT_EQ(lo[s1], 0.0);
  EXPECT_EQ(hi[s1], kInf);
  EXPECT_EQ(lo[s2], 0.0);  // row lower -1
  EXPECT_EQ(hi[s2], 5.0);
  EXPECT_EQ(lo[s3], 0.5);
  EXPECT_EQ(hi[s3], kInf);
  // ... and those rows become equalities c_r - s_r = 0.
  const Vector &clo = e.constraint_lower(), &chi = e.constraint_upper();
  for (int r : {1, 2, 3}) {
    EXPECT_EQ(clo[r], 0.0) << r;
    EXPECT_EQ(chi[r], 0.0) << r;
  }
  EXPECT_EQ(clo[0], -1.0);
  EXPECT_EQ(chi[0], 1.0);
  if (lumped()) {
    EXPECT_EQ(lo[e.eps_index()], 0.0);
    EXPECT_EQ(hi[e.eps_index()], kInf);
    EXPECT_EQ(clo[kM], -kInf);
    EXPECT_EQ(chi[kM], 0.0);
  }
  // The MPCC itself is untouched.
  EXPECT_EQ(mpcc_.p.variable_lower()[0], -3.0);
  EXPECT_EQ(mpcc_.p.constraint_lower()[2], -1.0);
  EXPECT_EQ(mpcc_.p.constraint_upper()[2], 5.0);
}

TEST_P(ElasticNlpTest, LiftGivesSlacksEqualToRowsAndEpsEqualToProducts) {
  const ElasticNlp e(mpcc_.p, GetParam(), 10.0);
  Vector z(kN);
  z << 0.6, 1.5, 1.2, 0.8, 0.4;  // every side positive here
  Vector c(kM);
  ASSERT_TRUE(mpcc_.p.constraints(z, c));
  ASSERT_GT(c[1], 0.0);
  ASSERT_GT(c[2], 0.0);
  ASSERT_GT(c[3], 0.0);
  const Vector x = e.lift(z);
  ASSERT_EQ(x.size(), e.num_variables());
  EXPECT_EQ(x.head(kN), z);
  EXPECT_EQ(x[e.w(1)], c[1]);
  EXPECT_EQ(x[e.u(2)], c[2]);
  EXPECT_EQ(x[e.w(3)], c[3]);
  const double products = z[0] * z[1] + z[0] * c[1] + c[2] * z[3] + c[1] * c[3];
  if (lumped()) {
    EXPECT_NEAR(x[e.eps_index()], products, 1e-14 * products);
  }
  // At the lifted point every lifted row is exactly satisfied.
  Vector ce(e.num_constraints());
  ASSERT_TRUE(e.constraints(x, ce));
  EXPECT_EQ(ce[0], c[0]);
  for (int r : {1, 2, 3}) EXPECT_EQ(ce[r], 0.0) << r;
  if (lumped()) {
    EXPECT_NEAR(ce[kM], 0.0, 1e-14 * products);
  }

  // A point where the products sum to a negative number: eps stays in its
  // bounds (>= 0).
  Vector zneg(kN);
  zneg << -2.0, 1.5, 1.2, 0.8, -0.4;
  const Vector xneg = e.lift(zneg);
  if (lumped()) {
    EXPECT_GE(xneg[e.eps_index()], 0.0);
  }
}

TEST_P(ElasticNlpTest, ValuesFollowTheFormulation) {
  ElasticNlp e(mpcc_.p, GetParam(), 3.5);
  std::mt19937 rng(11);
  const Vector x = random_vector(rng, e.num_variables(), -2.0, 2.0);
  const Vector z = x.head(kN);
  double f0 = 0.0, f = 0.0;
  ASSERT_TRUE(mpcc_.p.objective(z, f0));
  ASSERT_TRUE(e.objective(x, f));
  double products = 0.0;
  for (int i = 0; i < 4; ++i) products += x[e.u(i)] * x[e.w(i)];
  const double penalty = lumped() ? x[e.eps_index()] : products;
  EXPECT_NEAR(f, f0 + 3.5 * penalty, 1e-12);
  e.set_zeta(100.0);
  EXPECT_EQ(e.zeta(), 100.0);
  ASSERT_TRUE(e.objective(x, f));
  EXPECT_NEAR(f, f0 + 100.0 * penalty, 1e-11);

  Vector c(kM), ce(e.num_constraints());
  ASSERT_TRUE(mpcc_.p.constraints(z, c));
  ASSERT_TRUE(e.constraints(x, ce));
  EXPECT_EQ(ce[0], c[0]);
  EXPECT_EQ(ce[1], c[1] - x[e.w(1)]);
  EXPECT_EQ(ce[2], c[2] - x[e.u(2)]);
  EXPECT_EQ(ce[3], c[3] - x[e.w(3)]);
  if (lumped()) {
    EXPECT_NEAR(ce[kM], products - x[e.eps_index()], 1e-14);
  }
}

TEST_P(ElasticNlpTest, DerivativesMatchFiniteDifferences) {
  ElasticNlp e(mpcc_.p, GetParam(), 7.3);
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 8; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    e.set_zeta(trial == 0 ? 7.3 : std::uniform_real_distribution<double>(0.1, 50.0)(rng));
    const Vector x = random_vector(rng, e.num_variables(), -2.0, 2.0);
    const Vector lambda = random_vector(rng, e.num_constraints(), -3.0, 3.0);
    const double sigma = std::uniform_real_distribution<double>(0.1, 2.0)(rng);
    const auto rep = check_derivatives(e, x, sigma, lambda);
    ASSERT_NO_FATAL_FAILURE(expect_exact_derivatives(rep));
  }
}

TEST_P(ElasticNlpTest, PatternsKeepTheMpccEntriesFirstAndAreValid) {
  const ElasticNlp e(mpcc_.p, GetParam(), 1.0);
  const auto &mj = mpcc_.p.jacobian_pattern(), &ej = e.jacobian_pattern();
  const auto &mh = mpcc_.p.hessian_pattern(), &eh = e.hessian_pattern();
  ASSERT_GE(ej.size(), mj.size());
  ASSERT_GE(eh.size(), mh.size());
  for (int k = 0; k < mj.size(); ++k) {
    EXPECT_EQ(ej.rows[k], mj.rows[k]);
    EXPECT_EQ(ej.cols[k], mj.cols[k]);
  }
  for (int k = 0; k < mh.size(); ++k) {
    EXPECT_EQ(eh.rows[k], mh.rows[k]);
    EXPECT_EQ(eh.cols[k], mh.cols[k]);
  }
  std::set<std::pair<int, int>> seen;
  for (int k = 0; k < ej.size(); ++k)
    EXPECT_TRUE(seen.insert({ej.rows[k], ej.cols[k]}).second) << "repeated Jacobian entry";
  seen.clear();
  for (int k = 0; k < eh.size(); ++k) {
    EXPECT_GE(eh.rows[k], eh.cols[k]);
    EXPECT_TRUE(seen.insert({eh.rows[k], eh.cols[k]}).second) << "repeated Hessian entry";
  }
}

// set_relaxation moves only the lumped row's upper bound, sum u w - eps <= sigma; values and
// derivatives do not change (the relaxation is a bound).
TEST(ElasticNlpRelaxed, TheRelaxationIsTheLumpedRowsUpperBound) {
  const SmallMpcc mpcc;
  ElasticNlp e(mpcc.p, ElasticFormulation::kRelaxed, 10.0);
  const int row = e.num_constraints() - 1;
  const Vector lo = e.constraint_lower(), hi = e.constraint_upper();
  EXPECT_EQ(hi[row], 0.0);
  e.set_relaxation(0.25);
  for (int r = 0; r < e.num_constraints(); ++r) {
    EXPECT_EQ(e.constraint_lower()[r], lo[r]) << r;
    EXPECT_EQ(e.constraint_upper()[r], r == row ? 0.25 : hi[r]) << r;
  }
  e.set_relaxation(0.0);
  EXPECT_EQ(e.constraint_upper()[row], 0.0);
}

INSTANTIATE_TEST_SUITE_P(ElasticNlp, ElasticNlpTest,
                         ::testing::Values(ElasticFormulation::kLumped,
                                           ElasticFormulation::kPerPair,
                                           ElasticFormulation::kRelaxed),
                         [](const auto& info) {
                           return std::string(info.param == ElasticFormulation::kLumped ? "Lumped"
                                              : info.param == ElasticFormulation::kPerPair
                                                  ? "PerPair"
                                                  : "Relaxed");
                         });

}  // namespace
}  // namespace disco
