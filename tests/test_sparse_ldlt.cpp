// SparseLdlt (core/linalg/sparse_ldlt.h) against dense linear algebra on KKT-shaped matrices
// [H, Jᵀ; J, −C]: the inertia equals the signs of the eigenvalues, the solution that of a dense
// LU, the backward error the tolerance; repeated and mirrored triplets are summed; a singular
// matrix's answer is reported with its real backward error; a NaN is refused; the same values
// give the same bits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "core/linalg/sparse_ldlt.h"
#include "tests/test_support_kkt.h"

namespace disco {
namespace {

using namespace testing_kkt;
// analysed(t, dual_from): testing_kkt::analysed with the ordering of settings().
const auto analysed = [](const testing_kkt::Triplets& t, int dual_from) {
  return testing_kkt::analysed<SparseLdlt>(t, dual_from);
};

TEST(SparseLdlt, KktMatricesGetTheDenseInertiaAndSolution) {
  int checked = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    for (double c : {0.0, 1e-6}) {  // δc = 0 leaves the constraint diagonal empty
      const bool convex = seed % 2 == 0;
      const Triplets t = kkt(40, 15, c, convex, seed);
      const Eigen::MatrixXd a = t.dense();
      // Only matrices whose inertia a perturbation of 1e-6 cannot change say anything.
      if (smallest_singular_value(a) < 1e-6) continue;
      SparseLdlt f = analysed(t, 40);
      ASSERT_EQ(f.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
      EXPECT_EQ(f.negative(), negative_eigenvalues(a)) << "seed " << seed << " c " << c;
      if (convex) {
        EXPECT_EQ(f.negative(), 15);  // a quasi-definite KKT matrix: m negative
      }
      Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(t.n, -1.0, 2.0);
      const Eigen::VectorXd expected = a.partialPivLu().solve(b);
      const double error = f.solve(b.data());
      EXPECT_LE(error, 1e-12);
      EXPECT_LE((b - expected).norm(), 1e-8 * expected.norm()) << "seed " << seed;
      ++checked;
    }
  }
  EXPECT_GE(checked, 18);
}

TEST(SparseLdlt, RepeatedAndMirroredTripletsAreSummed) {
  const Triplets t = kkt(20, 6, 0.0, true, 7);
  Triplets split = t;  // every off-diagonal entry as two halves, one of them mirrored
  split.rows.clear();
  split.cols.clear();
  split.values.clear();
  for (size_t k = 0; k < t.values.size(); ++k) {
    const int i = t.rows[k], j = t.cols[k];
    split.rows.push_back(i);
    split.cols.push_back(j);
    split.values.push_back(0.5 * t.values[k]);
    split.rows.push_back(j);  // upper triangle this time
    split.cols.push_back(i);
    split.values.push_back(0.5 * t.values[k]);
  }
  SparseLdlt whole = analysed(t, 20), halves = analysed(split, 20);
  ASSERT_EQ(whole.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
  ASSERT_EQ(halves.factor(split.values.data(), settings()), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(whole.negative(), halves.negative());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(t.n), y = x;
  whole.solve(x.data());
  halves.solve(y.data());
  EXPECT_LE((x - y).norm(), 1e-10 * x.norm());
}

// The backward error solve() reports is that of the x it returns, measured densely; on a
// singular matrix too, where it is small only because x is huge (a matrix within that error of
// A is solved exactly: what backward stability promises, and all any solver can give there).
TEST(SparseLdlt, TheReportedBackwardErrorIsTheReturnedSolutions) {
  const Triplets t = kkt(12, 4, 0.0, true, 3);
  const int nx = 12;
  const Triplets s = with_a_repeated_constraint(t, nx);
  ASSERT_LT(smallest_singular_value(s.dense()), 1e-12);
  for (const Triplets* m : std::vector<const Triplets*>{&t, &s}) {
    const Eigen::MatrixXd a = m->dense();
    SparseLdlt f = analysed(*m, nx);
    ASSERT_EQ(f.factor(m->values.data(), settings()), SparseLdlt::Factorised::kDone);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m->n, 1.0, 2.0);  // b_r != b_n
    Eigen::VectorXd x = b;
    const double reported = f.solve(x.data());
    const double norm_a = a.cwiseAbs().rowwise().sum().maxCoeff();
    const double measured = (b - a * x).lpNorm<Eigen::Infinity>() /
                            (norm_a * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
    EXPECT_LE(reported, 10 * measured + 1e-15);
    EXPECT_LE(measured, 10 * reported + 1e-15);
    if (m == &s) {
      EXPECT_GT(x.norm(), 1e6);  // the singular one: no moderate solution exists
    }
  }
}

// A constraint row without a nonzero (its variables all fixed, δc = 0) makes A singular: it is
// refused and counted, so that the caller can say so (core/ipopt/kkt_solver.h answers
// "singular").
TEST(SparseLdlt, AnEmptyRowIsRefusedAndCounted) {
  Triplets t = kkt(10, 3, 0.0, true, 9);
  SparseLdlt f = analysed(t, 10);
  ASSERT_EQ(f.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(f.empty_rows(), 0);
  for (size_t k = 0; k < t.values.size(); ++k)  // constraint row 11 (1-based) emptied
    if (t.rows[k] == 11 || t.cols[k] == 11) t.values[k] = 0.0;
  EXPECT_EQ(f.factor(t.values.data(), settings()), SparseLdlt::Factorised::kEmptyRow);
  EXPECT_EQ(f.empty_rows(), 1);
}

// Without pivoting, a pivot that is tiny but kept makes L huge: whichever of the two rows is
// eliminated first, [η 1; 1 0] with η = 1e-12 (kept: δ = 1e-14) gives |D|·max|L|² ≥ 1/η = 1e12,
// and the factors are reported unstable (kkt_solver.h takes such a matrix to MUMPS). The limit only
// judges: above the growth, the same factors are done.
TEST(SparseLdlt, ATinyPivotThatMakesLHugeIsReportedUnstable) {
  Triplets t;
  t.n = 2;
  t.add(0, 0, 1e-12);
  t.add(1, 0, 1.0);
  t.add(1, 1, 0.0);
  SparseLdlt f = analysed(t, 2);
  LdltSettings s = settings();
  s.regularisation = 1e-14;
  EXPECT_EQ(f.factor(t.values.data(), s), SparseLdlt::Factorised::kUnstable);
  EXPECT_GE(f.growth(), 0.99e12);
  const double growth = f.growth();
  s.growth_limit = 2.0 * growth;
  EXPECT_EQ(f.factor(t.values.data(), s), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(f.growth(), growth);
}

// Without scaling, M = A + R with R = −δ on the empty constraint diagonal: the estimate of M's
// smallest |eigenvalue| is never below the dense one, and close to it once converged.
TEST(SparseLdlt, TheSmallestEigenvalueEstimateIsNeverBelowTheTrueOne) {
  LdltSettings s = settings();
  s.scaling_sweeps = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Triplets t = kkt(30, 10, 0.0, seed % 2 == 0, seed);
    SparseLdlt f = analysed(t, 30);
    ASSERT_EQ(f.factor(t.values.data(), s), SparseLdlt::Factorised::kDone);
    ASSERT_EQ(f.perturbed(), 0);
    EXPECT_EQ(f.regularisation_norm(), s.regularisation);
    Eigen::MatrixXd m = t.dense();
    for (int i = 30; i < 40; ++i) m(i, i) -= s.regularisation;
    const double truth = smallest_singular_value(m);
    for (int iterations : {1, 2, 5}) {
      EXPECT_GE(f.smallest_eigenvalue(iterations), truth * (1 - 1e-10))
          << "seed " << seed << ", " << iterations << " iterations";
    }
    EXPECT_LE(f.smallest_eigenvalue(200), 1.05 * truth) << "seed " << seed;
  }
}

// A = [1, 1; 1, 1 − 1e-15], both rows primal, has det(A) = −1e-15 < 0: one negative
// eigenvalue, of order 1e-15. Its second pivot falls below the floor and becomes +δ, so the
// factors' inertia (no negative eigenvalue) is not A's. The certificate refuses it; it vouches
// for a KKT matrix whose eigenvalues are far from zero.
TEST(SparseLdlt, AnInertiaTheRegularisationDecidesIsNotCertified) {
  Triplets flipped;
  flipped.n = 2;
  flipped.add(0, 0, 1.0);
  flipped.add(1, 0, 1.0);
  flipped.add(1, 1, 1.0 - 1e-15);
  SparseLdlt f = analysed(flipped, 2);
  LdltSettings s = settings();
  ASSERT_EQ(f.factor(flipped.values.data(), s), SparseLdlt::Factorised::kDone);
  ASSERT_EQ(f.perturbed(), 1);
  EXPECT_EQ(f.negative(), 0);
  EXPECT_FALSE(f.inertia_certified());
  s.certificate_iterations = 0;  // no certificate asked for: the factors' inertia stands
  ASSERT_EQ(f.factor(flipped.values.data(), s), SparseLdlt::Factorised::kDone);
  EXPECT_TRUE(f.inertia_certified());

  Triplets kkt_2x2;  // [1, 1; 1, 0]: eigenvalues (1 ± √5) / 2
  kkt_2x2.n = 2;
  kkt_2x2.add(0, 0, 1.0);
  kkt_2x2.add(1, 0, 1.0);
  kkt_2x2.add(1, 1, 0.0);
  SparseLdlt g = analysed(kkt_2x2, 1);
  ASSERT_EQ(g.factor(kkt_2x2.values.data(), settings()), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(g.regularised(), 1);
  EXPECT_EQ(g.negative(), 1);
  EXPECT_TRUE(g.inertia_certified());
}

TEST(SparseLdlt, ANanIsRefused) {
  Triplets t = kkt(10, 3, 0.0, true, 5);
  t.values[4] = std::nan("");
  SparseLdlt f = analysed(t, 10);
  EXPECT_EQ(f.factor(t.values.data(), settings()), SparseLdlt::Factorised::kNotFinite);
}

TEST(SparseLdlt, NewValuesOnTheSameStructureAndTheSameBitsTwice) {
  expect_new_values_then_the_same_bits<SparseLdlt>();
}

}  // namespace
}  // namespace disco
