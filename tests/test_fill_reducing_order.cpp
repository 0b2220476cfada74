// The fill-reducing orderings of disco's LDLᵀ solvers (core/linalg/permuted_symmetric.h):
// the symbolic counts they are judged by, the choice between AMD and METIS's nested dissection
// (kkt.ldlt.ordering), both solvers on a structure where nested dissection is kept, and the
// OrderingCache that keeps one ordering per structure.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "core/linalg/permuted_symmetric.h"
#include "core/linalg/pivoted_ldlt.h"
#include "core/linalg/sparse_ldlt.h"
#include "test_support_kkt.h"

namespace disco {
namespace {

using namespace testing_kkt;

// A pattern as triplets numbered from 0 (lower triangle, diagonal included).
struct Pattern {
  int n = 0;
  std::vector<int> rows, cols;
  void add(int i, int j) {
    rows.push_back(std::max(i, j));
    cols.push_back(std::min(i, j));
  }
  int nnz() const { return static_cast<int>(rows.size()); }
};

// The 7-point stencil of a g × g × g grid: nested dissection's textbook case (its separators are
// planes; minimum degree's fill grows faster there).
Pattern grid3(int g) {
  Pattern p;
  p.n = g * g * g;
  auto id = [g](int x, int y, int z) { return (x * g + y) * g + z; };
  for (int x = 0; x < g; ++x)
    for (int y = 0; y < g; ++y)
      for (int z = 0; z < g; ++z) {
        p.add(id(x, y, z), id(x, y, z));
        if (x + 1 < g) p.add(id(x + 1, y, z), id(x, y, z));
        if (y + 1 < g) p.add(id(x, y + 1, z), id(x, y, z));
        if (z + 1 < g) p.add(id(x, y, z + 1), id(x, y, z));
      }
  return p;
}

// The 5-point stencil of a g × g grid (a path-like band where minimum degree does well).
Pattern grid2(int g) {
  Pattern p;
  p.n = g * g;
  for (int x = 0; x < g; ++x)
    for (int y = 0; y < g; ++y) {
      const int i = x * g + y;
      p.add(i, i);
      if (x + 1 < g) p.add(i + g, i);
      if (y + 1 < g) p.add(i + 1, i);
    }
  return p;
}

// A random sparse pattern with repeated and mirrored entries.
Pattern random_pattern(int n, int per_row, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  Pattern p;
  p.n = n;
  for (int i = 0; i < n; ++i) {
    p.add(i, i);
    for (int e = 0; e < per_row; ++e) {
      const int j = pick(rng);
      p.rows.push_back(i);  // either triangle, as Ipopt's triplets may come
      p.cols.push_back(j);
    }
  }
  return p;
}

// The column counts of L by brute force: the pattern as a dense boolean matrix, eliminated in
// `order` (each pivot joins all its later neighbours into a clique).
std::vector<int> dense_symbolic_counts(const Pattern& p, const std::vector<int>& order) {
  const int n = p.n;
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  std::vector<std::vector<char>> a(n, std::vector<char>(n, 0));
  for (int t = 0; t < p.nnz(); ++t) {
    const int i = position[p.rows[t]], j = position[p.cols[t]];
    a[i][j] = a[j][i] = 1;
  }
  std::vector<int> count(n, 0);
  for (int k = 0; k < n; ++k) {
    std::vector<int> later;
    for (int i = k + 1; i < n; ++i)
      if (a[i][k]) later.push_back(i);
    count[k] = static_cast<int>(later.size());
    for (const int i : later)
      for (const int j : later) a[i][j] = 1;
  }
  return count;
}

double flops_of(const std::vector<int>& count) {
  double sum = 0.0;
  for (const int c : count) sum += static_cast<double>(c) * (c + 1) / 2.0;
  return sum;
}

constexpr double kNever = std::numeric_limits<double>::infinity();

TEST(FillReducingOrder, SymbolicCountsAreThoseOfADenseElimination) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Pattern p = random_pattern(70, 2, seed);
    std::vector<int> natural(p.n);
    std::iota(natural.begin(), natural.end(), 0);
    const std::vector<int> amd = amd_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0);
    const std::vector<int> nd =
        nested_dissection_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0);
    ASSERT_EQ(static_cast<int>(nd.size()), p.n);
    for (const std::vector<int>* order : std::vector<const std::vector<int>*>{&natural, &amd, &nd}) {
      EXPECT_EQ(elimination_flops(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0, *order),
                flops_of(dense_symbolic_counts(p, *order)))
          << "seed " << seed;
    }
    // The tree's counts themselves, on a structure laid out in AMD's order.
    PermutedSymmetric a;
    a.assign(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0, amd);
    EXPECT_EQ(elimination_tree(p.n, a.ap(), a.ai()).count, dense_symbolic_counts(p, amd));
  }
}

TEST(FillReducingOrder, NestedDissectionIsAPermutationAndDeterministic) {
  const Pattern p = random_pattern(300, 3, 7);
  const std::vector<int> first =
      nested_dissection_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0);
  std::vector<int> sorted = first;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(p.n);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(sorted, identity);
  for (int run = 0; run < 3; ++run)
    EXPECT_EQ(nested_dissection_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0), first);
}

TEST(FillReducingOrder, BelowTheThresholdAmdAloneIsComputed) {
  const Pattern p = grid3(8);
  const FillReducingOrder o = fill_reducing_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0,
                                                  OrderingSettings{kNever});
  EXPECT_EQ(o.ordering, Ordering::kAmd);
  EXPECT_EQ(o.order, amd_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0));
  EXPECT_EQ(o.nested_dissection_flops, -1.0);  // not computed
  // A threshold just below AMD's count: nested dissection is judged.
  const FillReducingOrder judged = fill_reducing_order(
      p.n, p.nnz(), p.rows.data(), p.cols.data(), 0, OrderingSettings{o.amd_flops * 0.999});
  EXPECT_GT(judged.nested_dissection_flops, 0.0);
  const FillReducingOrder equal = fill_reducing_order(p.n, p.nnz(), p.rows.data(), p.cols.data(),
                                                      0, OrderingSettings{o.amd_flops});
  EXPECT_EQ(equal.nested_dissection_flops, -1.0);  // "more than the threshold" only
}

TEST(FillReducingOrder, KeepsTheOrderingWithFewerMultiplyAdds) {
  // Nested dissection's textbook win (a 3-D grid) and minimum degree's (a 2-D grid of this
  // size), and random patterns: whichever is kept, it is the cheaper of the two.
  const Pattern cube = grid3(10), square = grid2(20);
  const Pattern patterns[] = {cube, square, random_pattern(400, 2, 11), random_pattern(400, 4, 12)};
  for (const Pattern& p : patterns) {
    const FillReducingOrder o = fill_reducing_order(p.n, p.nnz(), p.rows.data(), p.cols.data(),
                                                    0, OrderingSettings{0.0});
    const std::vector<int> amd = amd_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0);
    const std::vector<int> nd =
        nested_dissection_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0);
    const double amd_flops = elimination_flops(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0, amd);
    const double nd_flops = elimination_flops(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0, nd);
    EXPECT_EQ(o.amd_flops, amd_flops);
    EXPECT_EQ(o.nested_dissection_flops, nd_flops);
    EXPECT_EQ(o.ordering, nd_flops < amd_flops ? Ordering::kNestedDissection : Ordering::kAmd);
    EXPECT_EQ(o.order, nd_flops < amd_flops ? nd : amd);
  }
  // On the cube, by a wide margin (a third fewer multiply-adds with the METIS of Debian 12).
  const FillReducingOrder o = fill_reducing_order(cube.n, cube.nnz(), cube.rows.data(),
                                                  cube.cols.data(), 0, OrderingSettings{0.0});
  EXPECT_EQ(o.ordering, Ordering::kNestedDissection);
  EXPECT_LT(o.nested_dissection_flops, 0.8 * o.amd_flops);
}

// A KKT matrix [H, Jᵀ; J, 0] whose Hessian has the pattern of the g × g × g grid (random
// values, indefinite), J a row per `every`-th variable: that variable, and with offset > 0 also
// the variable `offset` further on (modulo g³).
Triplets cube_kkt(int g, int every, int offset, unsigned seed) {
  const Pattern cube = grid3(g);
  const int nx = cube.n, m = nx / every;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Triplets t;
  t.n = nx + m;
  for (int e = 0; e < cube.nnz(); ++e) {
    const int i = cube.rows[e], j = cube.cols[e];
    t.add(i, j, i == j ? 4.0 * u(rng) : u(rng));
  }
  for (int r = 0; r < m; ++r) {
    t.add(nx + r, every * r, 1.0 + std::abs(u(rng)));
    if (offset > 0) t.add(nx + r, (every * r + offset) % nx, u(rng));
  }
  return t;
}

// The cube's KKT matrix with J a row per fourth variable (the variable and its neighbour along
// x): both solvers, ordered by nested dissection, give the inertia and the solution of a dense
// eigen/LU solve.
TEST(FillReducingOrder, BothSolversAreExactInNestedDissectionsOrder) {
  const Triplets t = cube_kkt(6, 4, 36, 5);
  const int nx = 6 * 6 * 6;
  const Eigen::MatrixXd a = t.dense();
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues();
  ASSERT_GT(eigenvalues.cwiseAbs().minCoeff(), 1e-6);  // nonsingular: the inertia is defined
  const int negative = static_cast<int>((eigenvalues.array() < 0).count());
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(t.n, -1.0, 2.0);
  const Eigen::VectorXd expected = a.partialPivLu().solve(b);

  SparseLdlt ldlt = analysed<SparseLdlt>(t, nx);
  EXPECT_EQ(ldlt.ordering().ordering, Ordering::kNestedDissection);
  EXPECT_LT(ldlt.ordering().nested_dissection_flops, ldlt.ordering().amd_flops);
  ASSERT_EQ(ldlt.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(ldlt.negative(), negative);
  Eigen::VectorXd x = b;
  EXPECT_LE(ldlt.solve(x.data()), 1e-12);
  EXPECT_LE((x - expected).norm(), 1e-8 * expected.norm());

  PivotedLdlt pivoted = analysed<PivotedLdlt>(t, nx);
  EXPECT_EQ(pivoted.ordering().ordering, Ordering::kNestedDissection);
  ASSERT_EQ(pivoted.factor(t.values.data(), settings()), PivotedLdlt::Factorised::kDone);
  EXPECT_EQ(pivoted.negative(), negative);
  x = b;
  EXPECT_LE(pivoted.solve(x.data()), 1e-12);
  EXPECT_LE((x - expected).norm(), 1e-8 * expected.norm());
}

// OrderingCache: a structure met again gets the ordering fill_reducing_order gives it, without
// computing it again; another structure (another triplet, the same n and nnz), other settings
// or another base are met anew; the least recently used structure is the one dropped.
TEST(OrderingCache, AnswersAsFillReducingOrderAndComputesEachStructureOnce) {
  const Pattern cube = grid3(6), square = grid2(14), spread = random_pattern(300, 3, 7);
  auto direct = [](const Pattern& p, double above) {
    return fill_reducing_order(p.n, p.nnz(), p.rows.data(), p.cols.data(), 0,
                               OrderingSettings{above});
  };
  auto same = [](const FillReducingOrder& a, const FillReducingOrder& b) {
    return a.order == b.order && a.ordering == b.ordering && a.amd_flops == b.amd_flops &&
           a.nested_dissection_flops == b.nested_dissection_flops;
  };
  OrderingCache cache(2);
  auto cached = [&](const Pattern& p, double above, int base = 0) {
    return cache.order(p.n, p.nnz(), p.rows.data(), p.cols.data(), base, OrderingSettings{above});
  };
  EXPECT_TRUE(same(cached(cube, 0.0), direct(cube, 0.0)));  // nested dissection kept
  EXPECT_EQ(cached(cube, 0.0).ordering, Ordering::kNestedDissection);
  EXPECT_TRUE(same(cached(square, 0.0), direct(square, 0.0)));
  EXPECT_EQ(cache.computed(), 2);
  EXPECT_EQ(cache.reused(), 1);
  EXPECT_TRUE(same(cached(cube, 0.0), direct(cube, 0.0)));
  EXPECT_EQ(cache.computed(), 2);
  EXPECT_EQ(cache.reused(), 2);

  // Other settings are another answer: AMD alone.
  EXPECT_TRUE(same(cached(cube, kNever), direct(cube, kNever)));
  EXPECT_EQ(cached(cube, kNever).ordering, Ordering::kAmd);
  EXPECT_EQ(cache.computed(), 3);  // dropped: square, the least recently used
  EXPECT_TRUE(same(cached(cube, 0.0), direct(cube, 0.0)));
  EXPECT_EQ(cache.computed(), 3);
  EXPECT_TRUE(same(cached(square, 0.0), direct(square, 0.0)));
  EXPECT_EQ(cache.computed(), 4);

  // One triplet moved (the same n and nnz): another structure.
  Pattern moved = spread;
  EXPECT_TRUE(same(cached(spread, 0.0), direct(spread, 0.0)));
  moved.cols[5] = (moved.cols[5] + 1) % moved.n;
  const int before = cache.computed();
  EXPECT_TRUE(same(cached(moved, 0.0), direct(moved, 0.0)));
  EXPECT_EQ(cache.computed(), before + 1);

  // Numbered from 1: the same pattern as numbered from 0, but a structure of its own.
  Pattern one = moved;
  for (int& r : one.rows) ++r;
  for (int& c : one.cols) ++c;
  EXPECT_EQ(cached(one, 0.0, 1).order, direct(moved, 0.0).order);
  EXPECT_EQ(cache.computed(), before + 2);
}

// Both solvers analysed with an ordering from the cache are the solvers analysed with the
// settings: the same factors, bit for bit.
TEST(OrderingCache, SolversGivenTheCachedOrderingFactoriseTheSameBits) {
  const Triplets t = cube_kkt(5, 5, 0, 9);
  const int nx = 5 * 5 * 5;
  OrderingCache cache;
  const OrderingSettings ordering{0.0};
  const int nnz = static_cast<int>(t.values.size());
  const int* rows = t.rows.data();  // numbered from 1
  const int* cols = t.cols.data();
  const FillReducingOrder& chosen = cache.order(t.n, nnz, rows, cols, 1, ordering);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(t.n, -1.0, 2.0);

  SparseLdlt given, own;
  given.analyse(t.n, nnz, rows, cols, 1, nx, chosen);
  own.analyse(t.n, nnz, rows, cols, 1, nx, ordering);
  ASSERT_EQ(given.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
  ASSERT_EQ(own.factor(t.values.data(), settings()), SparseLdlt::Factorised::kDone);
  EXPECT_EQ(given.ordering().ordering, own.ordering().ordering);
  EXPECT_EQ(given.negative(), own.negative());
  Eigen::VectorXd x = b, y = b;
  given.solve(x.data());
  own.solve(y.data());
  EXPECT_EQ(x, y);

  PivotedLdlt given_p, own_p;
  given_p.analyse(t.n, nnz, rows, cols, 1, nx, chosen);
  own_p.analyse(t.n, nnz, rows, cols, 1, nx, ordering);
  ASSERT_EQ(given_p.factor(t.values.data(), settings(), settings().pivot_threshold),
            PivotedLdlt::Factorised::kDone);
  ASSERT_EQ(own_p.factor(t.values.data(), settings(), settings().pivot_threshold),
            PivotedLdlt::Factorised::kDone);
  EXPECT_EQ(given_p.negative(), own_p.negative());
  x = b;
  y = b;
  given_p.solve(x.data());
  own_p.solve(y.data());
  EXPECT_EQ(x, y);
  EXPECT_EQ(cache.computed(), 1);
}

}  // namespace
}  // namespace disco
