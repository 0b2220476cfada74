// disco — sparse symmetric indefinite LDLᵀ (core/linalg/sparse_ldlt.h says what and why).
#include "core/linalg/sparse_ldlt.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/util/check.h"

namespace disco {
namespace {

// A pivot below this share of δ after the elimination is replaced by ±δ (counted).
constexpr double kPivotFloor = 1e-6;

}  // namespace

void SparseLdlt::analyse(int n, int nnz, const int* rows, const int* cols, int base,
                         int dual_from, const OrderingSettings& ordering) {
  DISCO_CHECK(n >= 0 && nnz >= 0, "a matrix shape");
  analyse(n, nnz, rows, cols, base, dual_from,
          fill_reducing_order(n, nnz, rows, cols, base, ordering));
}

void SparseLdlt::analyse(int n, int nnz, const int* rows, const int* cols, int base,
                         int dual_from, const FillReducingOrder& chosen) {
  DISCO_CHECK(n >= 0 && nnz >= 0 && dual_from >= 0 && dual_from <= n, "a matrix shape");
  DISCO_CHECK(static_cast<int>(chosen.order.size()) == n, "an ordering of the structure");
  n_ = n;
  a_.assign(n, nnz, rows, cols, base, chosen.order);
  ordering_ = {{}, chosen.ordering, chosen.amd_flops, chosen.nested_dissection_flops};
  dual_.assign(n, 0);
  for (int k = 0; k < n; ++k) dual_[k] = a_.order()[k] >= dual_from ? 1 : 0;
  const std::vector<int>& ap = a_.ap();
  const std::vector<int>& ai = a_.ai();

  // Elimination tree and column counts of L (the up-looking elimination's reach of each row).
  const EliminationTree tree = elimination_tree(n, ap, ai);
  const std::vector<int>& parent = tree.parent;
  const std::vector<int>& count = tree.count;
  std::vector<int> flag(n, -1);
  lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp_[k + 1] = lp_[k] + count[k];
  const int entries_l = lp_[n];
  li_.assign(entries_l, 0);
  lx_.assign(entries_l, 0.0);
  flops_ = tree.flops();

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
    for (int p = ap[k]; p < ap[k + 1]; ++p) {
      int length = 0;
      for (int i = ai[p]; flag[i] != k; i = parent[i]) {
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

  d_.assign(n, 0.0);
  column_max_.assign(n, 1.0);
  dinv_.assign(n, 0.0);
  y_.assign(n, 0.0);
  w1_.assign(n, 0.0);
  negative_ = perturbed_ = regularised_ = 0;
}

SparseLdlt::Factorised SparseLdlt::factor(const double* values, const LdltSettings& settings) {
  settings_ = settings;
  const PermutedSymmetric::Loaded loaded = a_.load_scaled(values, settings.scaling_sweeps);
  if (loaded == PermutedSymmetric::Loaded::kNotFinite) return Factorised::kNotFinite;
  if (loaded == PermutedSymmetric::Loaded::kEmptyRow) return Factorised::kEmptyRow;
  const std::vector<int>& ap = a_.ap();
  const std::vector<int>& ai = a_.ai();
  const std::vector<double>& ax = a_.ax();
  const std::vector<double>& s = a_.s();

  const double delta = settings.regularisation;
  negative_ = perturbed_ = regularised_ = 0;
  regularisation_norm_ = 0.0;
  std::fill(column_max_.begin(), column_max_.end(), 1.0);
  for (int k = 0; k < n_; ++k) {
    const double sk = s[k];
    // Column k of S A S (rows <= k) into y_.
    for (int p = ap[k]; p < ap[k + 1]; ++p) y_[ai[p]] += ax[p] * s[ai[p]] * sk;
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

double SparseLdlt::solve(double* b) {
  return a_.refined_solve(
      b, [this](double* x) { apply_factors_inverse(x); }, settings_.residual_tolerance,
      settings_.refinement_steps, &refinement_steps_used_);
}

}  // namespace disco
