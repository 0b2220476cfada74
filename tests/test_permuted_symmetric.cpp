// PermutedSymmetric (core/linalg/permuted_symmetric.h), what both LDLᵀ solvers load their values
// through: the symmetric Ruiz scaling, against the same sweeps on the dense matrix.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "core/linalg/permuted_symmetric.h"
#include "test_support_kkt.h"

namespace disco {
namespace {

using namespace testing_kkt;

// `sweeps` sweeps of s_i ← s_i / √(max_j |s_i a_ij s_j|) (s_i kept where the maximum is 0) on
// the dense matrix b, each product formed as the solvers form it: an entry (i, j) with i ≤ j
// (their column j holds rows i ≤ j) as (|b_ij| · s_i) · s_j.
Eigen::VectorXd dense_ruiz(const Eigen::MatrixXd& b, int sweeps) {
  const int n = static_cast<int>(b.rows());
  Eigen::VectorXd s = Eigen::VectorXd::Ones(n);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    Eigen::VectorXd largest = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int lo = std::min(i, j), hi = std::max(i, j);
        largest[i] = std::max(largest[i], std::abs(b(i, j)) * s[lo] * s[hi]);
      }
    for (int i = 0; i < n; ++i) s[i] /= std::sqrt(largest[i] > 0.0 ? largest[i] : 1.0);
  }
  return s;
}

// The scaling of every sweep count, bit for bit, on KKT-shaped matrices with repeated and
// mirrored triplets (summed as the dense matrix sums them), in AMD's order; and a second load of
// other values on the same structure is scaled as if it were the first.
TEST(PermutedSymmetric, TheRuizScalingIsTheDenseSweepsBitForBit) {
  for (unsigned seed : {3u, 17u}) {
    const Triplets first = kkt(24, 9, 0.0, false, seed);
    Triplets second = first;
    for (size_t t = 0; t < second.values.size(); ++t) second.values[t] *= 1.0 + 0.37 * (t % 5);
    const int nnz = static_cast<int>(first.values.size());
    const std::vector<int> order =
        amd_order(first.n, nnz, first.rows.data(), first.cols.data(), 1);
    PermutedSymmetric a;
    a.assign(first.n, nnz, first.rows.data(), first.cols.data(), 1, order);
    for (const Triplets* t : {&first, static_cast<const Triplets*>(&second)}) {
      // The dense matrix in the elimination order: b(k, l) = A(order[k], order[l]).
      const Eigen::MatrixXd dense = t->dense();
      Eigen::MatrixXd b(t->n, t->n);
      for (int k = 0; k < t->n; ++k)
        for (int l = 0; l < t->n; ++l) b(k, l) = dense(order[k], order[l]);
      for (int sweeps : {0, 1, 2, 5}) {
        SCOPED_TRACE(testing::Message() << "seed " << seed << ", sweeps " << sweeps);
        ASSERT_EQ(a.load_scaled(t->values.data(), sweeps), PermutedSymmetric::Loaded::kDone);
        const Eigen::VectorXd expected = dense_ruiz(b, sweeps);
        ASSERT_EQ(static_cast<int>(a.s().size()), t->n);
        for (int k = 0; k < t->n; ++k) EXPECT_EQ(a.s()[k], expected[k]) << "row " << k;
        EXPECT_DOUBLE_EQ(a.norm(), b.cwiseAbs().rowwise().sum().maxCoeff());
      }
    }
  }
}

}  // namespace
}  // namespace disco
