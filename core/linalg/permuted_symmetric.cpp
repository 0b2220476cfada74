// disco — a symmetric matrix in a fixed elimination order (core/linalg/permuted_symmetric.h).
#include "core/linalg/permuted_symmetric.h"

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <metis.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

#include "core/util/check.h"

namespace disco {

namespace {

using PatternMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The symmetric pattern of the triplets (both triangles) with every diagonal entry.
PatternMatrix symmetric_pattern(int n, int nnz, const int* rows, const int* cols, int base) {
  DISCO_CHECK(n >= 0 && nnz >= 0, "a matrix shape");
  std::vector<Eigen::Triplet<double, int>> pattern;
  pattern.reserve(2 * static_cast<size_t>(nnz) + n);
  for (int t = 0; t < nnz; ++t) {
    const int i = rows[t] - base, j = cols[t] - base;
    DISCO_CHECK(i >= 0 && i < n && j >= 0 && j < n, "a triplet inside the matrix");
    pattern.emplace_back(i, j, 1.0);
    pattern.emplace_back(j, i, 1.0);
  }
  for (int i = 0; i < n; ++i) pattern.emplace_back(i, i, 1.0);
  PatternMatrix full(n, n);
  full.setFromTriplets(pattern.begin(), pattern.end());
  return full;
}

// METIS's seed: fixed, so that an ordering depends on the pattern alone.
constexpr idx_t kMetisSeed = 1;

}  // namespace

std::vector<int> amd_order(int n, int nnz, const int* rows, const int* cols, int base) {
  const PatternMatrix full = symmetric_pattern(n, nnz, rows, cols, base);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(full, amd);
  return std::vector<int>(amd.indices().data(), amd.indices().data() + n);
}

std::vector<int> nested_dissection_order(int n, int nnz, const int* rows, const int* cols,
                                         int base) {
  const PatternMatrix full = symmetric_pattern(n, nnz, rows, cols, base);
  // METIS's graph: each vertex's neighbours, without the vertex itself.
  std::vector<idx_t> start(n + 1, 0), neighbours;
  neighbours.reserve(full.nonZeros());
  for (int j = 0; j < n; ++j) {
    for (PatternMatrix::InnerIterator it(full, j); it; ++it)
      if (it.row() != j) neighbours.push_back(it.row());
    start[j + 1] = static_cast<idx_t>(neighbours.size());
  }
  if (n == 0) return {};
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = kMetisSeed;
  idx_t vertices = n;
  std::vector<idx_t> perm(n), iperm(n);
  // perm[k]: the vertex that is k-th in the new order (METIS's manual).
  if (METIS_NodeND(&vertices, start.data(), neighbours.data(), nullptr, options, perm.data(),
                   iperm.data()) != METIS_OK)
    return {};
  return std::vector<int>(perm.begin(), perm.end());
}

double EliminationTree::flops() const {
  double sum = 0.0;
  for (const int c : count) sum += static_cast<double>(c) * (c + 1) / 2.0;
  return sum;
}

EliminationTree elimination_tree(int n, const std::vector<int>& ap, const std::vector<int>& ai) {
  EliminationTree tree;
  tree.parent.assign(n, -1);
  tree.count.assign(n, 0);
  std::vector<int> flag(n, -1);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap[k]; p < ap[k + 1]; ++p) {
      for (int i = ai[p]; flag[i] != k; i = tree.parent[i]) {
        if (tree.parent[i] == -1) tree.parent[i] = k;
        ++tree.count[i];
        flag[i] = k;
      }
    }
  }
  return tree;
}

double elimination_flops(int n, int nnz, const int* rows, const int* cols, int base,
                         const std::vector<int>& order) {
  DISCO_CHECK(n >= 0 && nnz >= 0 && static_cast<int>(order.size()) == n, "a matrix shape");
  std::vector<int> position(n, -1);
  for (int k = 0; k < n; ++k) {
    DISCO_CHECK(order[k] >= 0 && order[k] < n && position[order[k]] < 0, "a permutation");
    position[order[k]] = k;
  }
  // The upper triangle by columns in the new numbering (unsorted, repeats kept).
  std::vector<int> ap(n + 1, 0), ai(nnz);
  for (int t = 0; t < nnz; ++t) {
    const int i = rows[t] - base, j = cols[t] - base;
    DISCO_CHECK(i >= 0 && i < n && j >= 0 && j < n, "a triplet inside the matrix");
    ++ap[std::max(position[i], position[j]) + 1];
  }
  for (int k = 0; k < n; ++k) ap[k + 1] += ap[k];
  std::vector<int> next(ap.begin(), ap.end() - 1);
  for (int t = 0; t < nnz; ++t) {
    const int a = position[rows[t] - base], b = position[cols[t] - base];
    ai[next[std::max(a, b)]++] = std::min(a, b);
  }
  return elimination_tree(n, ap, ai).flops();
}

FillReducingOrder fill_reducing_order(int n, int nnz, const int* rows, const int* cols, int base,
                                      const OrderingSettings& settings) {
  FillReducingOrder chosen;
  chosen.order = amd_order(n, nnz, rows, cols, base);
  chosen.amd_flops = elimination_flops(n, nnz, rows, cols, base, chosen.order);
  if (!(chosen.amd_flops > settings.nested_dissection_above)) return chosen;
  std::vector<int> nd = nested_dissection_order(n, nnz, rows, cols, base);
  if (nd.empty()) return chosen;  // METIS failed: AMD's stands
  chosen.nested_dissection_flops = elimination_flops(n, nnz, rows, cols, base, nd);
  if (chosen.nested_dissection_flops < chosen.amd_flops) {
    chosen.order = std::move(nd);
    chosen.ordering = Ordering::kNestedDissection;
  }
  return chosen;
}

OrderingCache::OrderingCache(int capacity) : capacity_(capacity) {
  DISCO_CHECK(capacity >= 1, "an ordering cache holds at least one structure");
}

const FillReducingOrder& OrderingCache::order(int n, int nnz, const int* rows, const int* cols,
                                              int base, const OrderingSettings& settings) {
  ++uses_;
  for (Entry& e : entries_) {
    if (e.n == n && e.base == base && static_cast<int>(e.rows.size()) == nnz &&
        e.nested_dissection_above == settings.nested_dissection_above &&
        std::equal(rows, rows + nnz, e.rows.begin()) &&
        std::equal(cols, cols + nnz, e.cols.begin())) {
      e.last_use = uses_;
      ++reused_;
      return e.chosen;
    }
  }
  // The entry is made whole before it replaces one: an exception leaves the cache as it was.
  Entry made;
  made.n = n;
  made.base = base;
  made.nested_dissection_above = settings.nested_dissection_above;
  made.rows.assign(rows, rows + nnz);
  made.cols.assign(cols, cols + nnz);
  made.chosen = fill_reducing_order(n, nnz, rows, cols, base, settings);
  made.last_use = uses_;
  Entry* slot = nullptr;
  if (static_cast<int>(entries_.size()) < capacity_) {
    slot = &entries_.emplace_back();
  } else {
    slot = &*std::min_element(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
      return a.last_use < b.last_use;
    });
  }
  *slot = std::move(made);
  ++computed_;
  return slot->chosen;
}

void PermutedSymmetric::assign(int n, int nnz, const int* rows, const int* cols, int base,
                               const std::vector<int>& order) {
  DISCO_CHECK(n >= 0 && nnz >= 0 && static_cast<int>(order.size()) == n, "a matrix shape");
  n_ = n;
  order_ = order;
  position_.assign(n, -1);
  for (int k = 0; k < n; ++k) {
    DISCO_CHECK(order[k] >= 0 && order[k] < n && position_[order[k]] < 0, "a permutation");
    position_[order[k]] = k;
  }
  // One slot per distinct (column, row ≤ column) plus every diagonal.
  std::vector<std::pair<int, int>> entries;
  entries.reserve(static_cast<size_t>(nnz) + n);
  for (int t = 0; t < nnz; ++t) {
    const int i = rows[t] - base, j = cols[t] - base;
    DISCO_CHECK(i >= 0 && i < n && j >= 0 && j < n, "a triplet inside the matrix");
    const int a = position_[i], b = position_[j];
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
  for (size_t q = 0; q < by_entry.size(); ++q) {
    const int e = by_entry[q];
    if (q == 0 || entries[e] != entries[by_entry[q - 1]]) {
      ai_.push_back(entries[e].second);
      ++ap_[entries[e].first + 1];
    }
    if (e < nnz) slot_[e] = static_cast<int>(ai_.size()) - 1;
  }
  for (int k = 0; k < n; ++k) ap_[k + 1] += ap_[k];
  ax_.assign(ai_.size(), 0.0);
  s_.assign(n, 1.0);
  row_norm_.assign(n, 0.0);
  row_max_.assign(n, 0.0);
  rhs_.assign(n, 0.0);
  x_.assign(n, 0.0);
  r_.assign(n, 0.0);
  y_.assign(n, 0.0);
  norm_ = 0.0;
  empty_rows_ = 0;
}

PermutedSymmetric::Loaded PermutedSymmetric::load_scaled(const double* values, int sweeps) {
  const Loaded loaded = load(values);
  if (loaded == Loaded::kDone) scale(sweeps);
  return loaded;
}

PermutedSymmetric::Loaded PermutedSymmetric::load(const double* values) {
  std::fill(ax_.begin(), ax_.end(), 0.0);
  const int nnz = static_cast<int>(slot_.size());
  for (int t = 0; t < nnz; ++t) ax_[slot_[t]] += values[t];
  std::fill(row_norm_.begin(), row_norm_.end(), 0.0);
  for (int k = 0; k < n_; ++k) {
    // Row k's sum and maximum over column k in registers (column k holds rows <= k: no earlier
    // column reached row k); the other rows' sums in the same order as entry by entry. A
    // maximum is exact in any order, so row_max_ needs no clearing: row k's is stored at
    // column k, before any later column reads it (as in scale).
    double column = 0.0, column_max = 0.0;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      const double a = std::abs(ax_[p]);
      if (!std::isfinite(a)) return Loaded::kNotFinite;
      const int i = ai_[p];
      if (i != k) {
        row_norm_[i] += a;
        row_max_[i] = std::max(row_max_[i], a);
      }
      column += a;
      column_max = std::max(column_max, a);
    }
    row_norm_[k] = column;
    row_max_[k] = column_max;
  }
  norm_ = n_ > 0 ? *std::max_element(row_norm_.begin(), row_norm_.end()) : 0.0;
  empty_rows_ = static_cast<int>(std::count(row_norm_.begin(), row_norm_.end(), 0.0));
  return empty_rows_ > 0 ? Loaded::kEmptyRow : Loaded::kDone;
}

void PermutedSymmetric::scale(int sweeps) {
  std::fill(s_.begin(), s_.end(), 1.0);
  std::vector<double>& largest = row_max_;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    // Every row's largest |s_i a_ij s_j|. The first sweep's (s = 1) are load's.
    if (sweep > 0) {
      for (int k = 0; k < n_; ++k) {
        // Column k holds rows i <= k, so no earlier column reached largest[k]: its own maximum
        // is kept in a register and stored once, before any later column reads it (a max is
        // exact: the same bits as updating largest[k] entry by entry; no clearing between
        // sweeps).
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
    }
    // s_k ← s_k / √largest_k where largest_k > 0 (a row whose entries underflowed keeps s_k:
    // / √1), in Eigen's packets: IEEE square roots and divisions, the same bits as one at a time.
    for (double& l : largest)
      if (!(l > 0.0)) l = 1.0;
    Eigen::Map<Eigen::ArrayXd>(s_.data(), n_) /=
        Eigen::Map<const Eigen::ArrayXd>(largest.data(), n_).sqrt();
  }
}

void PermutedSymmetric::residual(const double* b, const double* x, double* r) const {
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

double PermutedSymmetric::backward_error(const double* b, const double* x, double norm_b,
                                         double* r) const {
  residual(b, x, r);
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
}

}  // namespace disco
