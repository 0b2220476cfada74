// Small symmetric matrices in Ipopt's form for the tests of disco's LDLᵀ solvers
// (test_sparse_ldlt.cpp, test_pivoted_ldlt.cpp), and their dense truths.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include "core/linalg/sparse_ldlt.h"  // LdltSettings

namespace disco {
namespace testing_kkt {

// kkt.ldlt's settings as configs/disco.yaml holds them, with a tighter residual tolerance (the
// tests do not depend on the values beyond the tolerance they ask for) and every structure's
// ordering judged (nested dissection kept where it needs fewer multiply-adds than AMD).
inline LdltSettings settings() {
  LdltSettings s;
  s.scaling_sweeps = 5;
  s.regularisation = 1e-8;
  s.residual_tolerance = 1e-12;
  s.refinement_steps = 5;
  s.growth_limit = 1e11;
  s.certificate_iterations = 5;
  s.certificate_margin = 2.0;
  s.pivot_threshold = 0.01;
  s.pivot_threshold_max = 0.5;
  s.zero_pivot = 1e-14;
  s.ordering.nested_dissection_above = 0.0;
  return s;
}

// A symmetric matrix in Ipopt's form: lower-triangle triplets, 1-based.
struct Triplets {
  int n = 0;
  std::vector<int> rows, cols;
  std::vector<double> values;
  void add(int i, int j, double v) {  // 0-based, any triangle
    rows.push_back(std::max(i, j) + 1);
    cols.push_back(std::min(i, j) + 1);
    values.push_back(v);
  }
  Eigen::MatrixXd dense() const {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (size_t t = 0; t < values.size(); ++t) {
      const int i = rows[t] - 1, j = cols[t] - 1;
      a(i, j) += values[t];
      if (i != j) a(j, i) += values[t];
    }
    return a;
  }
};

// [H, Jᵀ; J, −c I] with H (nx × nx) sparse-ish and indefinite unless `convex`, J (m × nx) full
// row rank (an identity block plus random entries), both with some repeated entries.
// A solver (SparseLdlt, PivotedLdlt) analysed for t's structure; rows dual_from.. are its
// constraint block.
template <class Solver>
Solver analysed(const Triplets& t, int dual_from,
                const OrderingSettings& ordering = settings().ordering) {
  Solver f;
  f.analyse(t.n, static_cast<int>(t.values.size()), t.rows.data(), t.cols.data(), 1, dual_from,
            ordering);
  return f;
}

inline Triplets kkt(int nx, int m, double c, bool convex, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Triplets t;
  t.n = nx + m;
  for (int i = 0; i < nx; ++i) {
    t.add(i, i, convex ? 2.0 + std::abs(u(rng)) * 1e3 : 3.0 * u(rng));
    if (i + 1 < nx) t.add(i + 1, i, 0.5 * u(rng));
    if (i % 3 == 0) t.add(i, i, 0.25);  // a repeat: summed
  }
  for (int r = 0; r < m; ++r) {
    t.add(nx + r, r, 1.0 + std::abs(u(rng)));
    for (int k = 0; k < 3; ++k) t.add(nx + r, (r * 7 + k * 5 + 3) % nx, u(rng));
    if (c != 0.0) t.add(nx + r, nx + r, -c);
  }
  return t;
}

// t (a kkt() matrix with nx primal rows) with its first constraint row repeated as a last row:
// two equal rows of J, a singular KKT matrix.
inline Triplets with_a_repeated_constraint(const Triplets& t, int nx) {
  Triplets s = t;
  s.n = t.n + 1;
  for (size_t k = 0; k < t.values.size(); ++k)  // row nx copied as row n
    if (t.rows[k] == nx + 1 && t.cols[k] <= nx) s.add(t.n, t.cols[k] - 1, t.values[k]);
  return s;
}

inline int negative_eigenvalues(const Eigen::MatrixXd& a) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues();
  return static_cast<int>((ev.array() < 0).count());
}

inline double smallest_singular_value(const Eigen::MatrixXd& a) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().cwiseAbs().minCoeff();
}

// A solver factorises new values on the same structure (1.5 times the first: a solution 1.5
// times smaller), and the first values again to the same bits.
template <class Solver>
void expect_new_values_then_the_same_bits() {
  const Triplets first = kkt(30, 10, 0.0, false, 11);
  Triplets second = first;
  for (double& v : second.values) v *= 1.5;
  Solver f = analysed<Solver>(first, 30);
  Eigen::VectorXd runs[3];
  const Triplets* order[3] = {&first, &second, &first};
  for (int r = 0; r < 3; ++r) {
    ASSERT_EQ(f.factor(order[r]->values.data(), settings()), Solver::Factorised::kDone);
    runs[r] = Eigen::VectorXd::LinSpaced(first.n, 0.0, 1.0);
    EXPECT_LE(f.solve(runs[r].data()), 1e-12);
  }
  // The second matrix is 1.5 times the first: its solution is the first's over 1.5.
  EXPECT_LE((1.5 * runs[1] - runs[0]).norm(), 1e-9 * runs[0].norm());
  for (int k = 0; k < first.n; ++k) EXPECT_EQ(runs[0][k], runs[2][k]);  // bit for bit
}

}  // namespace testing_kkt
}  // namespace disco
