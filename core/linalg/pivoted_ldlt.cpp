// disco — multifrontal LDLᵀ with threshold pivoting (core/linalg/pivoted_ldlt.h says what and
// why).
#include "core/linalg/pivoted_ldlt.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/util/check.h"

namespace disco {
namespace {

// `count` more entries at the end of the first `used` of v, which grows (geometrically, zeroing
// only what it adds) when it is too short: no allocation once it has been long enough.
// Fronts with fewer pivots update their rows below by columns, more by a GEMM (Eigen's).
constexpr int kGemmPivots = 16;

double* grow(std::vector<double>& v, size_t& used, size_t count) {
  if (v.size() < used + count) v.resize(std::max(used + count, 2 * v.size()));
  double* out = v.data() + used;
  used += count;
  return out;
}

// v with at least `count` entries, grown only when too short (the contents are then scratch).
template <class T>
T* at_least(std::vector<T>& v, size_t count) {
  if (v.size() < count) v.resize(std::max(count, 2 * v.size()));
  return v.data();
}

using Matrix = Eigen::Map<Eigen::MatrixXd>;
using ConstVector = Eigen::Map<const Eigen::VectorXd>;

// max_i |x_i| over `count` entries (0 when there are none), in Eigen's packets.
double largest_abs(const double* x, int count) {
  return count > 0 ? ConstVector(x, count).cwiseAbs().maxCoeff() : 0.0;
}
using ConstMatrix = Eigen::Map<const Eigen::MatrixXd>;
using Vector = Eigen::Map<Eigen::VectorXd>;

// A postorder of the forest `parent` (children in increasing order): post[k] is the k-th node.
std::vector<int> postorder(const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> head(n, -1), next(n, -1), post, stack;
  post.reserve(n);
  for (int j = n - 1; j >= 0; --j) {
    if (parent[j] == -1) continue;
    next[j] = head[parent[j]];
    head[parent[j]] = j;
  }
  for (int root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int j = stack.back();
      if (head[j] != -1) {  // descend into the next child first
        const int child = head[j];
        head[j] = next[child];
        stack.push_back(child);
      } else {
        post.push_back(j);
        stack.pop_back();
      }
    }
  }
  return post;
}

}  // namespace

std::vector<int> PivotedLdlt::postponed_order(int n, int nnz, const int* rows, const int* cols,
                                              int base, int dual_from,
                                              const FillReducingOrder& chosen) {
  DISCO_CHECK(static_cast<int>(chosen.order.size()) == n, "an ordering of the structure");
  const std::vector<int>& fill = chosen.order;
  ordering_ = {{}, chosen.ordering, chosen.amd_flops, chosen.nested_dissection_flops};
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[fill[k]] = k;
  std::vector<int> earliest(n, n);  // a constraint row's earliest primal neighbour in `fill`
  for (int t = 0; t < nnz; ++t) {
    const int i = rows[t] - base, j = cols[t] - base;
    if (i >= dual_from && j < dual_from) earliest[i] = std::min(earliest[i], position[j]);
    if (j >= dual_from && i < dual_from) earliest[j] = std::min(earliest[j], position[i]);
  }
  // Sorted by (where it goes, after the variable there or not, where it was).
  struct Key {
    int at, after, was;
    bool operator<(const Key& o) const {
      return at != o.at ? at < o.at : after != o.after ? after < o.after : was < o.was;
    }
  };
  std::vector<Key> key(n);
  postponed_ = 0;
  for (int k = 0; k < n; ++k) {
    const int i = fill[k];
    const bool postpone = i >= dual_from && earliest[i] < n && earliest[i] > k;
    key[k] = postpone ? Key{earliest[i], 1, k} : Key{k, 0, k};
    postponed_ += postpone;
  }
  std::sort(key.begin(), key.end());
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = fill[key[k].was];
  return order;
}

void PivotedLdlt::analyse(int n, int nnz, const int* rows, const int* cols, int base,
                          int dual_from, const OrderingSettings& ordering) {
  DISCO_CHECK(n >= 0 && nnz >= 0, "a matrix shape");
  analyse(n, nnz, rows, cols, base, dual_from,
          fill_reducing_order(n, nnz, rows, cols, base, ordering));
}

void PivotedLdlt::analyse(int n, int nnz, const int* rows, const int* cols, int base,
                          int dual_from, const FillReducingOrder& chosen) {
  DISCO_CHECK(n >= 0 && nnz >= 0 && dual_from >= 0 && dual_from <= n, "a matrix shape");
  n_ = n;
  // The fill-reducing ordering with constraint rows postponed behind a primal neighbour, then a
  // postorder of its elimination tree (the same fill; fronts become contiguous and children's
  // update matrices lie on a stack in the order their parent needs them).
  const std::vector<int> postponed = postponed_order(n, nnz, rows, cols, base, dual_from, chosen);
  a_.assign(n, nnz, rows, cols, base, postponed);
  const std::vector<int> post = postorder(elimination_tree(n, a_.ap(), a_.ai()).parent);
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = postponed[post[k]];
  a_.assign(n, nnz, rows, cols, base, order);
  const std::vector<int>& ap = a_.ap();
  const std::vector<int>& ai = a_.ai();
  // The tree and the column counts of L below the diagonal (row k's reach in the tree).
  const EliminationTree tree = elimination_tree(n, ap, ai);
  const std::vector<int>& parent = tree.parent;
  const std::vector<int>& count = tree.count;
  std::vector<int> flag(n, -1), children(n, 0);
  for (int k = 0; k < n; ++k)
    if (parent[k] != -1) ++children[parent[k]];
  // Fundamental supernodes: column k joins k−1's when k−1's only parent is k, k has no other
  // child, and the patterns nest (count[k−1] = count[k] + 1).
  first_.clear();
  std::vector<int> node_of(n, 0);
  for (int k = 0; k < n; ++k) {
    const bool joins =
        k > 0 && parent[k - 1] == k && children[k] == 1 && count[k - 1] == count[k] + 1;
    if (!joins) first_.push_back(k);
    node_of[k] = static_cast<int>(first_.size()) - 1;
  }
  first_.push_back(n);
  relax(count, parent, node_of);
  const int nodes = static_cast<int>(first_.size()) - 1;

  // Each supernode's rows: its own columns, then the pattern of its last column below them.
  rows_ptr_.assign(nodes + 1, 0);
  for (int s = 0; s < nodes; ++s) {
    const int last = first_[s + 1] - 1;
    rows_ptr_[s + 1] = rows_ptr_[s] + (first_[s + 1] - first_[s]) + count[last];
  }
  rows_.assign(rows_ptr_[nodes], 0);
  std::vector<int> filled(nodes, 0);
  for (int s = 0; s < nodes; ++s)
    for (int k = first_[s]; k < first_[s + 1]; ++k) rows_[rows_ptr_[s] + filled[s]++] = k;
  std::fill(flag.begin(), flag.end(), -1);
  for (int k = 0; k < n; ++k) {  // k below a supernode's last column, in increasing k
    flag[k] = k;
    for (int p = ap[k]; p < ap[k + 1]; ++p)
      for (int i = ai[p]; flag[i] != k; i = parent[i]) {
        flag[i] = k;
        const int s = node_of[i];
        if (i == first_[s + 1] - 1) rows_[rows_ptr_[s] + filled[s]++] = k;
      }
  }
  for (int s = 0; s < nodes; ++s)
    DISCO_CHECK(filled[s] == rows_ptr_[s + 1] - rows_ptr_[s], "a supernode's rows");

  // The supernodal tree, and where a child's rows below land in its parent's structure.
  parent_.assign(nodes, -1);
  children_.assign(nodes, 0);
  for (int s = 0; s < nodes; ++s) {
    const int up = parent[first_[s + 1] - 1];
    if (up != -1) {
      parent_[s] = node_of[up];
      ++children_[parent_[s]];
    }
  }
  std::vector<int> local(n, -1);
  child_map_ptr_.assign(nodes + 1, 0);
  for (int s = 0; s < nodes; ++s)
    child_map_ptr_[s + 1] =
        child_map_ptr_[s] +
        (parent_[s] == -1 ? 0 : rows_ptr_[s + 1] - rows_ptr_[s] - (first_[s + 1] - first_[s]));
  child_map_.assign(child_map_ptr_[nodes], 0);
  for (int s = 0; s < nodes; ++s) {
    if (parent_[s] == -1) continue;
    const int up = parent_[s];
    for (int q = rows_ptr_[up]; q < rows_ptr_[up + 1]; ++q) local[rows_[q]] = q - rows_ptr_[up];
    const int own = first_[s + 1] - first_[s];
    for (int q = rows_ptr_[s] + own, t = child_map_ptr_[s]; q < rows_ptr_[s + 1]; ++q, ++t) {
      DISCO_CHECK(local[rows_[q]] >= 0, "a child's row in its parent's front");
      child_map_[t] = local[rows_[q]];
    }
    for (int q = rows_ptr_[up]; q < rows_ptr_[up + 1]; ++q) local[rows_[q]] = -1;
  }

  // A's entries by supernode: entry (row k, column i ≤ k) of the lower triangle (slot p of
  // column k's upper triangle) lies in the front of i's supernode.
  assembly_ptr_.assign(nodes + 1, 0);
  for (int k = 0; k < n; ++k)
    for (int p = ap[k]; p < ap[k + 1]; ++p) ++assembly_ptr_[node_of[ai[p]] + 1];
  for (int s = 0; s < nodes; ++s) assembly_ptr_[s + 1] += assembly_ptr_[s];
  const int entries = assembly_ptr_[nodes];
  assembly_slot_.assign(entries, 0);
  assembly_row_.assign(entries, 0);
  assembly_col_.assign(entries, 0);
  std::vector<int> next(assembly_ptr_.begin(), assembly_ptr_.end() - 1);
  for (int k = 0; k < n; ++k) {
    for (int p = ap[k]; p < ap[k + 1]; ++p) {
      const int i = ai[p], s = node_of[i];
      const int e = next[s]++;
      assembly_slot_[e] = p;
      assembly_col_[e] = i - first_[s];
      assembly_row_[e] = k;  // made local below
    }
  }
  for (int s = 0; s < nodes; ++s) {
    for (int q = rows_ptr_[s]; q < rows_ptr_[s + 1]; ++q) local[rows_[q]] = q - rows_ptr_[s];
    for (int e = assembly_ptr_[s]; e < assembly_ptr_[s + 1]; ++e) {
      const int r = local[assembly_row_[e]];
      DISCO_CHECK(r >= 0, "an entry of A in its front");
      assembly_row_[e] = r;
    }
    for (int q = rows_ptr_[s]; q < rows_ptr_[s + 1]; ++q) local[rows_[q]] = -1;
  }

  flops_ = tree.flops();
  m_.assign(nodes, 0);
  npiv_.assign(nodes, 0);
  index_ptr_.assign(nodes + 1, 0);
  pivot_ptr_.assign(nodes + 1, 0);
  lx_ptr_.assign(nodes + 1, 0);
  d_.assign(n, 0.0);
  e_.assign(n, 0.0);
  second_.assign(n, 0);
  index_.assign(rows_.size(), 0);

  negative_ = delayed_ = two_by_two_ = forced_ = 0;
}

void PivotedLdlt::relax(const std::vector<int>& count, const std::vector<int>& parent,
                        std::vector<int>& node_of) {
  // Relaxed amalgamation (after CHOLMOD's): a supernode takes in its last child (the one whose
  // columns end just before its own) while the merged front has at most 4 columns, or its
  // explicit zeros are less than 30 % of its entries with at most 16 columns, 10 % with at most
  // 48, 5 % beyond. Fewer, larger fronts: less overhead per front, and a zero diagonal meets a
  // partner for a 2×2 pivot in its own front more often. (CHOLMOD's 80 % for 16 columns: 1.11
  // times the factorisation time on bench_kkt matrices of paper A1, A3, B2, doorway and
  // three_robots_contact; 20 % or 10 %: 1.06, 1.08. No merging beyond fundamental supernodes:
  // 1.3–1.5 times, measured with the earlier, slower small fronts.)
  const int fundamental = static_cast<int>(first_.size()) - 1;
  std::vector<int> start(fundamental), columns(fundamental), rep(fundamental), up(fundamental);
  std::vector<double> zeros(fundamental, 0.0);
  auto find = [&](int x) {
    while (rep[x] != x) x = rep[x];
    return x;
  };
  for (int s = 0; s < fundamental; ++s) {
    const int last = first_[s + 1] - 1;
    up[s] = parent[last] == -1 ? -1 : node_of[parent[last]];
    start[s] = first_[s];
    columns[s] = first_[s + 1] - first_[s];
    rep[s] = s;
    const double below = count[last];
    while (start[s] > 0) {
      const int c = find(node_of[start[s] - 1]);
      if (up[c] == -1 || find(up[c]) != s) break;
      const double added =
          static_cast<double>(columns[c]) * (columns[s] + below - count[first_[c + 1] - 1]);
      const double z = zeros[c] + zeros[s] + added;
      const int merged = columns[c] + columns[s];
      const double entries = merged * (merged + 1.0) / 2.0 + merged * below;
      const bool take = merged <= 4 || (merged <= 16 && z < 0.3 * entries) ||
                        (merged <= 48 && z < 0.1 * entries) || z < 0.05 * entries;
      if (!take) break;
      rep[c] = s;
      start[s] = start[c];
      columns[s] = merged;
      zeros[s] = z;
    }
  }
  std::vector<int> first;
  for (int s = 0; s < fundamental; ++s)
    if (rep[s] == s) first.push_back(start[s]);
  first.push_back(n_);
  first_ = first;
  for (int s = 0; s + 1 < static_cast<int>(first_.size()); ++s)
    for (int k = first_[s]; k < first_[s + 1]; ++k) node_of[k] = s;
}

void PivotedLdlt::swap(double* f, int m, int nf, int* g, int a, int b, int p) {
  if (a == b) return;
  // Rows a and b in every column of the panel (the L columns before p too), then columns a and
  // b from row p down: the symmetric exchange of two fully summed variables.
  for (int c = 0; c < nf; ++c)
    std::swap(f[a + static_cast<size_t>(c) * m], f[b + static_cast<size_t>(c) * m]);
  double* ca = f + static_cast<size_t>(a) * m;
  double* cb = f + static_cast<size_t>(b) * m;
  for (int i = p; i < m; ++i) std::swap(ca[i], cb[i]);
  std::swap(g[a], g[b]);
}

int PivotedLdlt::eliminate(double* f, int m, int nf, int* g, bool root, double threshold) {
  Matrix front(f, m, m);
  auto at = [&](int i, int j) -> double& { return f[i + static_cast<size_t>(j) * m]; };
  const double tiny = zero_pivot_;
  double u = threshold;
  int p = 0, c = 0, failed = 0;
  while (p < nf) {
    if (failed >= nf - p) {  // a whole pass over the remaining variables without a pivot
      if (!root) break;
      if (u == 0.0) return -1;  // every remaining pivot below zero_pivot: singular
      u = u > 1e-12 ? u * 1e-2 : 0.0;
      failed = 0;
    }
    if (c < p || c >= nf) c = p;
    // Column c: the largest |entry| among its fully summed rows other than c (few) and the row
    // r where it is, and among the rows below (most; vectorised).
    const double* col = f + static_cast<size_t>(c) * m;
    double largest_summed = 0.0;
    int r = -1;
    for (int i = p; i < nf; ++i) {
      const double v = std::abs(col[i]);
      if (i != c && v > largest_summed) {
        largest_summed = v;
        r = i;
      }
    }
    const double largest_below = largest_abs(col + nf, m - nf);
    const double gamma = std::max(largest_summed, largest_below);
    const double acc = at(c, c);
    int pivot = 0;  // 1: 1×1 on c; 2: 2×2 on (c, r); 3: 1×1 on r
    if (std::abs(acc) > tiny && std::abs(acc) >= u * gamma) {
      pivot = 1;
    } else if (r >= 0) {
      const double* colr = f + static_cast<size_t>(r) * m;
      // The largest |a_ic| and |a_ir| over i ≠ c, r.
      double gc = largest_below, gr = largest_abs(colr + nf, m - nf), gr_all = 0.0;
      for (int i = p; i < nf; ++i) {
        if (i == c || i == r) continue;
        gc = std::max(gc, std::abs(col[i]));
        gr = std::max(gr, std::abs(colr[i]));
      }
      const double arr = at(r, r), arc = at(r, c);
      gr_all = std::max(gr, std::abs(arc));
      const double det = acc * arr - arc * arc;
      const double big = std::max({std::abs(acc), std::abs(arr), std::abs(arc)});
      if (std::abs(det) > tiny * big &&
          u * (std::abs(arr) * gc + std::abs(arc) * gr) <= std::abs(det) &&
          u * (std::abs(arc) * gc + std::abs(acc) * gr) <= std::abs(det)) {
        pivot = 2;
      } else if (std::abs(arr) > tiny && std::abs(arr) >= u * gr_all) {
        pivot = 3;
      }
    }
    if (pivot == 0) {
      ++failed;
      ++c;
      continue;
    }
    if (u < threshold) ++forced_;
    const int q = static_cast<int>(pivot_count_);
    if (pivot == 1 || pivot == 3) {
      swap(f, m, nf, g, pivot == 1 ? c : r, p, p);
      const double d = at(p, p);
      const int below = m - p - 1, fully = nf - p - 1;
      if (below > 0) {
        auto w = front.col(p).segment(p + 1, below);
        if (fully > 0) {
          Vector t(at_least(work_, static_cast<size_t>(fully)), fully);
          t = w.head(fully) / d;
          front.block(p + 1, p + 1, below, fully).noalias() -= w * t.transpose();
        }
        w /= d;
      }
      d_[q] = d;
      e_[q] = 0.0;
      second_[q] = 0;
      if (d < 0.0) ++negative_;
      pivot_count_ += 1;
      p += 1;
    } else {
      swap(f, m, nf, g, c, p, p);
      const int r2 = r == p ? c : r;  // where r went if the exchange moved it
      swap(f, m, nf, g, r2, p + 1, p);
      const double a = at(p, p), b = at(p + 1, p), e = at(p + 1, p + 1);
      const double det = a * e - b * b;
      const int below = m - p - 2, fully = nf - p - 2;
      if (below > 0) {
        auto w = front.block(p + 2, p, below, 2);
        // L = W D⁻¹, D⁻¹ = [e, −b; −b, a] / det; the update −L Wᵀ over the fully summed columns.
        Matrix l(at_least(work_, static_cast<size_t>(below) * 2), below, 2);
        l.col(0) = (w.col(0) * e - w.col(1) * b) / det;
        l.col(1) = (w.col(1) * a - w.col(0) * b) / det;
        // Column by column (a GEMM's packing costs more than two columns' update).
        for (int j = 0; j < fully; ++j) {
          const double w0 = w(j, 0), w1 = w(j, 1);
          double* column = f + (p + 2) + static_cast<size_t>(p + 2 + j) * m;
          const double* l0 = l.col(0).data();
          const double* l1 = l.col(1).data();
          for (int i = 0; i < below; ++i) column[i] -= l0[i] * w0 + l1[i] * w1;
        }
        w = l;
      }
      at(p + 1, p) = 0.0;  // L's (p+1, p): the 2×2 block is in D
      d_[q] = a;
      e_[q] = b;
      second_[q] = 0;
      d_[q + 1] = e;
      e_[q + 1] = 0.0;
      second_[q + 1] = 1;
      // The block's eigenvalues: one of each sign when det < 0, else both of a's sign.
      negative_ += det < 0.0 ? 1 : (a < 0.0 ? 2 : 0);
      ++two_by_two_;
      pivot_count_ += 2;
      p += 2;
    }
    failed = 0;
    if (!std::isfinite(d_[q]) || !std::isfinite(d_[pivot_count_ - 1])) return -2;
  }
  return p;
}

PivotedLdlt::Factorised PivotedLdlt::factor(const double* values, const LdltSettings& settings,
                                            double threshold) {
  DISCO_CHECK(threshold > 0.0 && threshold <= 0.5, "a pivot threshold in (0, 0.5]");
  settings_ = settings;
  zero_pivot_ = settings.zero_pivot;
  const PermutedSymmetric::Loaded loaded = a_.load_scaled(values, settings.scaling_sweeps);
  if (loaded == PermutedSymmetric::Loaded::kNotFinite) return Factorised::kNotFinite;
  if (loaded == PermutedSymmetric::Loaded::kEmptyRow) return Factorised::kEmptyRow;
  const std::vector<double>& ax = a_.ax();
  const std::vector<double>& s = a_.s();
  const int nodes = supernodes();
  negative_ = delayed_ = two_by_two_ = forced_ = 0;
  pivot_count_ = 0;
  factor_entries_ = 0;
  index_used_ = 0;
  lx_used_ = 0;
  stack_used_ = 0;
  stack_delayed_.clear();
  updates_.clear();
  for (int sn = 0; sn < nodes; ++sn) {
    const int own = first_[sn + 1] - first_[sn];
    const int structure = rows_ptr_[sn + 1] - rows_ptr_[sn];
    // The children's update matrices: the top children_[sn] of the stack, the first child
    // deepest.
    const int kids = children_[sn];
    const size_t top = updates_.size() - kids;
    int nd = 0;
    for (size_t u = top; u < updates_.size(); ++u) nd += updates_[u].delayed;
    const int m = nd + structure, nf = nd + own;
    // The front's variables: the delayed ones (in the children's order), then the structure.
    const size_t gofs = index_used_;
    index_used_ += m;
    int* g = at_least(index_, index_used_) + gofs;
    {
      int t = 0;
      for (size_t u = top; u < updates_.size(); ++u)
        for (int j = 0; j < updates_[u].delayed; ++j)
          g[t++] = stack_delayed_[updates_[u].delayed_offset + j];
      for (int q = rows_ptr_[sn]; q < rows_ptr_[sn + 1]; ++q) g[t++] = rows_[q];
    }
    if (front_.size() < static_cast<size_t>(m) * m) front_.resize(static_cast<size_t>(m) * m);
    double* f = front_.data();
    // Assembled into the lower triangle (zeroed first); the fully summed block is then mirrored
    // into the upper one, which the pivot search reads as the rest of each column.
    std::fill(f, f + static_cast<size_t>(m) * m, 0.0);  // one call: faster than by columns
    auto add = [&](int i, int j, double v) {
      f[std::max(i, j) + static_cast<size_t>(std::min(i, j)) * m] += v;
    };
    // A's entries (row ≥ column in the structure's order).
    const int* rows = rows_.data() + rows_ptr_[sn];
    for (int e = assembly_ptr_[sn]; e < assembly_ptr_[sn + 1]; ++e) {
      const int slot = assembly_slot_[e];
      const int r = assembly_row_[e], c = assembly_col_[e];
      f[(nd + r) + static_cast<size_t>(nd + c) * m] += ax[slot] * s[first_[sn] + c] * s[rows[r]];
    }
    // The children's update matrices (extend-add), then off the stack.
    {
      int delayed_at = 0;
      std::vector<int>& map = map_;
      for (size_t u = top; u < updates_.size(); ++u) {
        const Update& up = updates_[u];
        at_least(map, static_cast<size_t>(up.size));
        for (int t = 0; t < up.delayed; ++t) map[t] = delayed_at + t;
        const int* cmap = child_map_.data() + child_map_ptr_[up.node];
        for (int t = up.delayed; t < up.size; ++t) map[t] = nd + cmap[t - up.delayed];
        delayed_at += up.delayed;
        const double* cb = stack_.data() + up.offset;
        for (int j = 0; j < up.delayed; ++j) {  // delayed columns: their rows map anywhere
          for (int i = j; i < up.size; ++i)
            add(map[i], map[j], cb[i + static_cast<size_t>(j) * up.size]);
        }
        for (int j = up.delayed; j < up.size; ++j) {  // the structure's: rows map in order
          double* column = f + static_cast<size_t>(map[j]) * m;
          const double* from = cb + static_cast<size_t>(j) * up.size;
          for (int i = j; i < up.size; ++i) column[map[i]] += from[i];
        }
      }
      if (kids > 0) {
        stack_used_ = updates_[top].offset;
        stack_delayed_.resize(updates_[top].delayed_offset);
        updates_.resize(top);
      }
    }
    for (int j = 1; j < nf; ++j)
      for (int i = 0; i < j; ++i)
        f[i + static_cast<size_t>(j) * m] = f[j + static_cast<size_t>(i) * m];
    // Eliminate.
    const int q0 = pivot_count_;
    const int npiv = eliminate(f, m, nf, g, parent_[sn] == -1, threshold);
    if (npiv == -2) return Factorised::kNotFinite;
    if (npiv < 0) return Factorised::kSingular;
    m_[sn] = m;
    npiv_[sn] = npiv;
    index_ptr_[sn] = static_cast<int>(gofs);
    pivot_ptr_[sn] = q0;
    delayed_ += nf - npiv;
    // L's block, then the update matrix of the rows not eliminated (delayed first).
    lx_ptr_[sn] = lx_used_;
    std::copy(f, f + static_cast<size_t>(m) * npiv,
              grow(lx_, lx_used_, static_cast<size_t>(m) * npiv));
    factor_entries_ +=
        static_cast<int64_t>(npiv) * (m - npiv) + static_cast<int64_t>(npiv) * (npiv - 1) / 2;
    if (parent_[sn] == -1) continue;  // a root eliminates everything (eliminate() saw to it)
    // The update matrix, on the stack: the delayed variables' columns as eliminate() left them,
    // then the rows below with S − L_b D L_bᵀ (lower triangle).
    Matrix front(f, m, m);
    const int below = m - nf, nd2 = nf - npiv, size = m - npiv;
    const bool small = npiv < kGemmPivots;
    Matrix w(at_least(work_, static_cast<size_t>(below) * npiv), below, npiv);
    auto lb = front.block(nf, 0, below, npiv);
    if (npiv > 0 && below > 0) {
      for (int c = 0; c < npiv; ++c) {  // W = L_b D
        const int q = q0 + c;
        if (second_[q]) continue;
        if (c + 1 < npiv && second_[q + 1]) {
          w.col(c) = lb.col(c) * d_[q] + lb.col(c + 1) * e_[q];
          w.col(c + 1) = lb.col(c) * e_[q] + lb.col(c + 1) * d_[q + 1];
        } else {
          w.col(c) = lb.col(c) * d_[q];
        }
      }
      if (!small)
        front.block(nf, nf, below, below).triangularView<Eigen::Lower>() -= lb * w.transpose();
    }
    Update up{stack_used_, size, nd2, stack_delayed_.size(), sn};
    double* cb = grow(stack_, stack_used_, static_cast<size_t>(size) * size);
    for (int j = 0; j < size; ++j) {
      const double* from = f + npiv + static_cast<size_t>(npiv + j) * m;
      double* to = cb + static_cast<size_t>(j) * size;
      for (int i = j; i < size; ++i) to[i] = from[i];
      if (j < nd2 || !small) continue;
      // A small front's update column by column, in place on the stack: a GEMM's packing
      // costs more than it saves.
      const int jb = j - nd2;
      for (int c = 0; c < npiv; ++c) {
        const double coef = w(jb, c);
        if (coef == 0.0) continue;
        const double* l = f + nf + static_cast<size_t>(c) * m;
        double* t = to + nd2;
        for (int i = jb; i < below; ++i) t[i] -= l[i] * coef;
      }
    }
    for (int t = npiv; t < nf; ++t) stack_delayed_.push_back(g[t]);
    updates_.push_back(up);
  }
  DISCO_CHECK(updates_.empty(), "every update matrix assembled");
  DISCO_CHECK(pivot_count_ == n_, "every variable eliminated");
  return Factorised::kDone;
}

void PivotedLdlt::factors_inverse(double* x) {
  const int nodes = supernodes();
  std::vector<double>& xl = xl_;
  // Forward: L y = x, front by front.
  // Front sn's entries of x into xl (its variables, eliminated first).
  auto gather = [&](int sn) {
    const int* g = index_.data() + index_ptr_[sn];
    at_least(xl, static_cast<size_t>(m_[sn]));
    for (int i = 0; i < m_[sn]; ++i) xl[i] = x[g[i]];
    return g;
  };
  for (int sn = 0; sn < nodes; ++sn) {
    const int m = m_[sn], npiv = npiv_[sn];
    if (npiv == 0) continue;
    const int* g = gather(sn);
    const double* l = lx_.data() + lx_ptr_[sn];
    double* v = xl.data();
    // By columns (the fronts are small: Eigen's triangular solve and GEMV cost more).
    for (int c = 0; c < npiv; ++c) {
      const double vc = v[c];
      if (vc == 0.0) continue;
      const double* column = l + static_cast<size_t>(c) * m;
      for (int i = c + 1; i < m; ++i) v[i] -= column[i] * vc;
    }
    for (int i = 0; i < m; ++i) x[g[i]] = v[i];
  }
  // D.
  for (int sn = 0; sn < nodes; ++sn) {
    const int* g = index_.data() + index_ptr_[sn];
    for (int c = 0; c < npiv_[sn]; ++c) {
      const int q = pivot_ptr_[sn] + c;
      if (second_[q]) continue;
      if (c + 1 < npiv_[sn] && second_[q + 1]) {
        const double a = d_[q], b = e_[q], e = d_[q + 1], det = a * e - b * b;
        const double x0 = x[g[c]], x1 = x[g[c + 1]];
        x[g[c]] = (e * x0 - b * x1) / det;
        x[g[c + 1]] = (a * x1 - b * x0) / det;
      } else {
        x[g[c]] /= d_[q];
      }
    }
  }
  // Backward: Lᵀ x = y, fronts in reverse.
  for (int sn = nodes - 1; sn >= 0; --sn) {
    const int m = m_[sn], npiv = npiv_[sn];
    if (npiv == 0) continue;
    const int* g = gather(sn);
    const double* l = lx_.data() + lx_ptr_[sn];
    double* v = xl.data();
    for (int c = npiv - 1; c >= 0; --c) {  // by columns, as forward
      const int below = m - c - 1;
      if (below > 0)
        v[c] -= ConstVector(l + static_cast<size_t>(c) * m + c + 1, below)
                    .dot(ConstVector(v + c + 1, below));
    }
    for (int i = 0; i < npiv; ++i) x[g[i]] = v[i];
  }
}

double PivotedLdlt::largest_multiplier() const {
  double largest = 0.0;
  for (int sn = 0; sn < supernodes(); ++sn) {
    ConstMatrix l(lx_.data() + lx_ptr_[sn], m_[sn], npiv_[sn]);
    for (int c = 0; c < npiv_[sn]; ++c)
      for (int i = c + 1; i < m_[sn]; ++i) largest = std::max(largest, std::abs(l(i, c)));
  }
  return largest;
}

double PivotedLdlt::solve(double* b) {
  return a_.refined_solve(
      b, [this](double* x) { factors_inverse(x); }, settings_.residual_tolerance,
      settings_.refinement_steps, &refinement_steps_used_);
}

}  // namespace disco
