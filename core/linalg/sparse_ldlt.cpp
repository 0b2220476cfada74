// disco — sparse symmetric indefinite LDLᵀ (core/linalg/sparse_ldlt.h says what and why).
#include "core/linalg/sparse_ldlt.h"

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/util/check.h"

namespace disco {
namespace {

// A pivot below this share of δ after the elimination is replaced by ±δ (counted).
constexpr double kPivotFloor = 1e-6;

}  // namespace

void SparseLdlt::analyse(int n, int nnz, const int* rows, const int* cols, int base,
                         int dual_from) {
  DISCO_CHECK(n >= 0 && nnz >= 0 && dual_from >= 0 && dual_from <= n, "a matrix shape");
  n_ = n;
  dual_from_ = dual_from;

  // The ordering: AMD on the symmetric pattern.
  std::vector<Eigen::Triplet<double, int>> pattern;
  pattern.reserve(2 * static_cast<size_t>(nnz) + n);
  for (int t = 0; t < nnz; ++t) {
    const int i = rows[t] - base, j = cols[t] - base;
    DISCO_CHECK(i >= 0 && i < n && j >= 0 && j < n, "a triplet inside the matrix");
    pattern.emplace_back(i, j, 1.0);
    pattern.emplace_back(j, i, 1.0);
  }
  for (int i = 0; i < n; ++i) pattern.emplace_back(i, i, 1.0);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> full(n, n);
  full.setFromTriplets(pattern.begin(), pattern.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(full, amd);
  order_.assign(amd.indices().data(), amd.indices().data() + n);
  position_.assign(n, 0);
  for (int k = 0; k < n; ++k) position_[order_[k]] = k;
  dual_.assign(n, 0);
  for (int k = 0; k < n; ++k) dual_[k] = order_[k] >= dual_from ? 1 : 0;

  // A's upper triangle, permuted, by columns: one slot per distinct entry plus every diagonal.
  std::vector<std::pair<int, int>> entries;  // (column, row), row <= column
  entries.reserve(static_cast<size_t>(nnz) + n);
  for (int t = 0; t < nnz; ++t) {
    const int a = position_[rows[t] - base], b = position_[cols[t] - base];
    entries.emplace_back(std::max(a, b), std::min(a, b));
  }
  for (int k = 0; k < n; ++k) entries.emplace_back(k, k);
  std::vector<int> by_entry(entries.size());
  std::iota(by_entry.begin(), by_entry.end(), 0);
  std::stable_sort(by_entry.begin(), by_entry.end(),
                   [&](int x, int y) { return entries[x] < entries[y]; });
  ap_.assign(n + 1, 0);
  ai_.clear();
  slot_.assign(nnz, 0);
  diagonal_.assign(n, 0);
  for (size_t q = 0; q < by_entry.size(); ++q) {
    const int e = by_entry[q];
    if (q == 0 || entries[e] != entries[by_entry[q - 1]]) {
      ai_.push_back(entries[e].second);
      ++ap_[entries[e].first + 1];
    }
    const int s = static_cast<int>(ai_.size()) - 1;
    if (e < nnz) slot_[e] = s;
    if (entries[e].first == entries[e].second) diagonal_[entries[e].first] = s;
  }
  for (int k = 0; k < n; ++k) ap_[k + 1] += ap_[k];
  ax_.assign(ai_.size(), 0.0);

  // Elimination tree and column counts of L (the up-looking elimination's reach of each row).
  std::vector<int> parent(n, -1), count(n, 0), flag(n, -1);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      for (int i = ai_[p]; flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++count[i];
        flag[i] = k;
      }
    }
  }
  lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp_[k + 1] = lp_[k] + count[k];
  const int entries_l = lp_[n];
  li_.assign(entries_l, 0);
  lx_.assign(entries_l, 0.0);
  flops_ = 0.0;
  for (int k = 0; k < n; ++k) flops_ += static_cast<double>(count[k]) * (count[k] + 1) / 2.0;

  // Every row's pattern of L in the order its elimination visits it (reverse of the reach's
  // discovery, path by path: a topological order of the tree), and where each entry lies.
  rp_.assign(n + 1, 0);
  ri_.assign(entries_l, 0);
  rslot_.assign(entries_l, 0);
  std::vector<int> stack(n), path(n), filled(n, 0);
  std::fill(flag.begin(), flag.end(), -1);
  int out = 0;
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    int top = n;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      int length = 0;
      for (int i = ai_[p]; flag[i] != k; i = parent[i]) {
        path[length++] = i;
        flag[i] = k;
      }
      while (length > 0) stack[--top] = path[--length];
    }
    for (int t = top; t < n; ++t) {
      const int i = stack[t];
      const int slot = lp_[i] + filled[i]++;
      li_[slot] = k;
      ri_[out] = i;
      rslot_[out] = slot;
      ++out;
    }
    rp_[k + 1] = out;
  }
  DISCO_CHECK(out == entries_l, "the row patterns cover L");

  s_.assign(n, 1.0);
  row_norm_.assign(n, 0.0);
  d_.assign(n, 0.0);
  column_max_.assign(n, 1.0);
  dinv_.assign(n, 0.0);
  y_.assign(n, 0.0);
  w1_.assign(n, 0.0);
  w2_.assign(n, 0.0);
  w3_.assign(n, 0.0);
  negative_ = perturbed_ = regularised_ = 0;
}

void SparseLdlt::scale() {
  std::fill(s_.begin(), s_.end(), 1.0);
  std::vector<double>& largest = w1_;
  for (int sweep = 0; sweep < settings_.scaling_sweeps; ++sweep) {
    for (int k = 0; k < n_; ++k) {
      // Column k holds rows i <= k, so no earlier column reached largest[k]: its own maximum is
      // kept in a register and stored once, before any later column reads it (a max is exact:
      // the same bits as updating largest[k] entry by entry; no clearing between sweeps).
      const double sk = s_[k];
      double column = 0.0;
      for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
        const int i = ai_[p];
        const double v = std::abs(ax_[p]) * s_[i] * sk;
        if (i != k) largest[i] = std::max(largest[i], v);
        column = std::max(column, v);
      }
      largest[k] = column;
    }
    // s_k ← s_k / √largest_k where largest_k > 0 (a row whose entries underflowed keeps s_k:
    // / √1), in Eigen's packets: IEEE square roots and divisions, the same bits as one at a time.
    for (double& l : largest)
      if (!(l > 0.0)) l = 1.0;
    Eigen::Map<Eigen::ArrayXd>(s_.data(), n_) /=
        Eigen::Map<const Eigen::ArrayXd>(largest.data(), n_).sqrt();
  }
}

SparseLdlt::Factorised SparseLdlt::factor(const double* values, const LdltSettings& settings) {
  settings_ = settings;
  std::fill(ax_.begin(), ax_.end(), 0.0);
  const int nnz = static_cast<int>(slot_.size());
  for (int t = 0; t < nnz; ++t) ax_[slot_[t]] += values[t];
  std::fill(row_norm_.begin(), row_norm_.end(), 0.0);
  for (int k = 0; k < n_; ++k) {
    // As in scale(): row k's sum over column k in a register, added in the same order.
    double column = 0.0;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      const double a = std::abs(ax_[p]);
      if (!std::isfinite(a)) return Factorised::kNotFinite;
      if (ai_[p] != k) row_norm_[ai_[p]] += a;
      column += a;
    }
    row_norm_[k] = column;
  }
  norm_ = n_ > 0 ? *std::max_element(row_norm_.begin(), row_norm_.end()) : 0.0;
  empty_rows_ = static_cast<int>(std::count(row_norm_.begin(), row_norm_.end(), 0.0));
  if (empty_rows_ > 0) return Factorised::kEmptyRow;
  scale();

  const double delta = settings.regularisation;
  negative_ = perturbed_ = regularised_ = 0;
  regularisation_norm_ = 0.0;
  std::fill(column_max_.begin(), column_max_.end(), 1.0);
  for (int k = 0; k < n_; ++k) {
    const double sk = s_[k];
    // Column k of S A S (rows <= k) into y_.
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) y_[ai_[p]] += ax_[p] * s_[ai_[p]] * sk;
    double d = y_[k];
    y_[k] = 0.0;
    const double sign = dual_[k] ? -1.0 : 1.0;
    double change = 0.0;  // R(k, k): what the regularisation adds to (S A S)(k, k)
    if (std::abs(d) < delta) {
      change = sign * delta - d;
      d = sign * delta;
      ++regularised_;
    }
    // Row k of L: L(0:k−1, 0:k−1) D l = column k, over the row's pattern in topological order.
    for (int q = rp_[k]; q < rp_[k + 1]; ++q) {
      const int i = ri_[q];
      const double yi = y_[i];
      y_[i] = 0.0;
      const int end = rslot_[q];
      for (int p = lp_[i]; p < end; ++p) y_[li_[p]] -= lx_[p] * yi;
      const double l = yi * dinv_[i];
      d -= l * yi;
      lx_[end] = l;
      column_max_[i] = std::max(column_max_[i], std::abs(l));
    }
    if (!std::isfinite(d)) {
      for (int q = rp_[k]; q < rp_[k + 1]; ++q) y_[ri_[q]] = 0.0;
      return Factorised::kNotFinite;
    }
    if (std::abs(d) < kPivotFloor * delta) {
      change += sign * delta - d;
      d = sign * delta;
      ++perturbed_;
    }
    regularisation_norm_ = std::max(regularisation_norm_, std::abs(change));
    d_[k] = d;
    dinv_[k] = 1.0 / d;
    if (d < 0.0) ++negative_;
  }
  growth_ = 0.0;
  for (int k = 0; k < n_; ++k)
    growth_ = std::max(growth_, std::abs(d_[k]) * column_max_[k] * column_max_[k]);
  return growth_ > settings.growth_limit ? Factorised::kUnstable : Factorised::kDone;
}

void SparseLdlt::apply_inverse(const double* b, double* x) {
  for (int k = 0; k < n_; ++k) x[k] = s_[k] * b[k];
  apply_factors_inverse(x);
  for (int k = 0; k < n_; ++k) x[k] *= s_[k];
}

void SparseLdlt::apply_factors_inverse(double* x) const {
  for (int k = 0; k < n_; ++k) {
    const double xk = x[k];
    if (xk == 0.0) continue;
    for (int p = lp_[k]; p < lp_[k + 1]; ++p) x[li_[p]] -= lx_[p] * xk;
  }
  for (int k = 0; k < n_; ++k) x[k] *= dinv_[k];
  for (int k = n_ - 1; k >= 0; --k) {
    double xk = x[k];
    for (int p = lp_[k]; p < lp_[k + 1]; ++p) xk -= lx_[p] * x[li_[p]];
    x[k] = xk;
  }
}

bool SparseLdlt::inertia_certified() {
  if (settings_.certificate_iterations == 0 || regularisation_norm_ == 0.0) return true;
  return smallest_eigenvalue(settings_.certificate_iterations) >
         settings_.certificate_margin * regularisation_norm_;
}

double SparseLdlt::smallest_eigenvalue(int iterations) {
  DISCO_CHECK(iterations >= 1, "at least one inverse iteration");
  if (n_ == 0) return std::numeric_limits<double>::infinity();
  // A fixed start with every component nonzero and no structure (splitmix64 of the index), so
  // the estimate is deterministic yet has a component along every eigenvector.
  double* x = w1_.data();
  for (int k = 0; k < n_; ++k) {
    uint64_t z = static_cast<uint64_t>(k) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    x[k] = static_cast<double>(z >> 11) * 0x1.0p-53 - 0.5;
  }
  auto norm2 = [&](const double* v) {
    double sum = 0.0;
    for (int k = 0; k < n_; ++k) sum += v[k] * v[k];
    return std::sqrt(sum);
  };
  double largest = 0.0;  // the largest ‖M⁻¹ x‖ / ‖x‖ seen: at most ‖M⁻¹‖₂
  for (int it = 0; it < iterations; ++it) {
    const double before = norm2(x);
    if (!(before > 0.0) || !std::isfinite(before)) break;
    for (int k = 0; k < n_; ++k) x[k] /= before;
    apply_factors_inverse(x);
    const double after = norm2(x);
    if (!std::isfinite(after)) return 0.0;
    largest = std::max(largest, after);
  }
  return largest > 0.0 ? 1.0 / largest : std::numeric_limits<double>::infinity();
}

void SparseLdlt::residual(const double* b, const double* x, double* r) const {
  std::copy(b, b + n_, r);
  for (int k = 0; k < n_; ++k) {
    double rk = 0.0;
    const double xk = x[k];
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      const int i = ai_[p];
      r[i] -= ax_[p] * xk;
      if (i != k) rk -= ax_[p] * x[i];
    }
    r[k] += rk;
  }
}

double SparseLdlt::solve(double* b) {
  double* rhs = w1_.data();  // b, permuted
  double* x = w2_.data();
  double* r = w3_.data();
  for (int k = 0; k < n_; ++k) rhs[k] = b[order_[k]];
  double norm_b = 0.0;
  for (int k = 0; k < n_; ++k) norm_b = std::max(norm_b, std::abs(rhs[k]));
  auto backward_error = [&]() {
    residual(rhs, x, r);
    double norm_r = 0.0, norm_x = 0.0;
    bool finite = true;  // (std::max would pass over a NaN)
    for (int k = 0; k < n_; ++k) {
      finite = finite && std::isfinite(r[k]) && std::isfinite(x[k]);
      norm_r = std::max(norm_r, std::abs(r[k]));
      norm_x = std::max(norm_x, std::abs(x[k]));
    }
    const double scale = norm_ * norm_x + norm_b;
    if (!finite || !std::isfinite(scale)) return std::numeric_limits<double>::infinity();
    return scale > 0.0 ? norm_r / scale : 0.0;
  };
  apply_inverse(rhs, x);
  double error = backward_error();
  refinement_steps_used_ = 0;
  while (error > settings_.residual_tolerance &&
         refinement_steps_used_ < settings_.refinement_steps) {
    apply_inverse(r, y_.data());
    for (int k = 0; k < n_; ++k) x[k] += y_[k];
    std::fill(y_.begin(), y_.end(), 0.0);
    ++refinement_steps_used_;
    const double before = error;
    error = backward_error();
    if (!(error < 0.5 * before)) break;  // stalled: more steps would not reach it
  }
  for (int k = 0; k < n_; ++k) b[order_[k]] = x[k];
  return error;
}

}  // namespace disco
