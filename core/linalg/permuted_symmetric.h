// disco — a symmetric matrix held in a fixed elimination order: what disco's two LDLᵀ solvers
// (sparse_ldlt.h without pivoting, pivoted_ldlt.h with) share.
//
//   - the fill-reducing ordering of a pattern given as triplets (fill_reducing_order): AMD
//     (amd_order), or METIS's nested dissection (nested_dissection_order) where AMD's
//     elimination is expensive and nested dissection's is cheaper, judged by the symbolic count
//     of multiply-adds (elimination_flops; kkt.ldlt.ordering in configs/disco.yaml);
//   - the elimination tree and the column counts of L (elimination_tree);
//   - A's upper triangle in the permuted numbering, by columns, one slot per distinct entry and
//     every diagonal present, with the slot each triplet adds into (assign; repeats and mirrored
//     entries are summed by load);
//   - ‖A‖∞ and the rows without a nonzero (load);
//   - the symmetric Ruiz scaling S = diag(s): `sweeps` sweeps of s_i ← s_i / √(max_j |s_i a_ij
//     s_j|), which brings every row's largest entry near 1 (scale);
//   - r = b − A x (residual) and the refined solve: x = S F⁻¹ S b with the solver's factors F of
//     S A S (+ its regularisation), then refinement against A itself until the normwise backward
//     error ‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞) is at most a tolerance, a step limit is reached or a
//     step fails to halve the error (refined_solve).
//
// Deterministic: the same structure and values give the same bits. Not thread-safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace disco {

// The approximate minimum degree ordering (Eigen's AMD) of the symmetric pattern of an n × n
// matrix given as nnz triplets numbered from `base` (either triangle): order[k] is the row
// eliminated k-th.
std::vector<int> amd_order(int n, int nnz, const int* rows, const int* cols, int base);

// METIS's nested dissection (METIS_NodeND with its default options and a fixed seed, so the same
// pattern gives the same order) of the same pattern, as amd_order; empty if METIS fails (it
// reports only running out of memory or an invalid graph).
std::vector<int> nested_dissection_order(int n, int nnz, const int* rows, const int* cols,
                                         int base);

// The elimination tree of a symmetric pattern given by its upper triangle by columns (column k
// holds rows ap[k]..ap[k+1]−1 of ai, each at most k, in any order, repeats allowed) and the
// column counts of its Cholesky-like factor L (entries below the diagonal, without
// cancellation), from each row's reach in the tree (the up-looking elimination's pattern).
struct EliminationTree {
  std::vector<int> parent;  // parent[j]: the column j's update goes to first (−1: a root)
  std::vector<int> count;   // count[j]: entries of L's column j below the diagonal
  // Multiply-adds of one LDLᵀ elimination with this pattern: Σ_j count[j]·(count[j] + 1)/2.
  double flops() const;
};
EliminationTree elimination_tree(int n, const std::vector<int>& ap, const std::vector<int>& ai);

// The multiply-adds of an LDLᵀ elimination without pivoting of the pattern (as amd_order) in
// `order` (EliminationTree::flops of the permuted pattern).
double elimination_flops(int n, int nnz, const int* rows, const int* cols, int base,
                         const std::vector<int>& order);

// Which fill-reducing ordering an analysis chose.
enum class Ordering { kAmd, kNestedDissection };

// kkt.ldlt.ordering: the ordering of each new structure is AMD's, unless AMD's elimination
// needs more than `nested_dissection_above` multiply-adds; then METIS's nested dissection is
// computed too and kept when its elimination needs fewer.
struct OrderingSettings {
  double nested_dissection_above = 0.0;
};

struct FillReducingOrder {
  std::vector<int> order;  // order[k]: the row eliminated k-th
  Ordering ordering = Ordering::kAmd;
  double amd_flops = 0.0;                // elimination_flops of AMD's order
  double nested_dissection_flops = -1.0;  // of nested dissection's (−1: not computed)
};
FillReducingOrder fill_reducing_order(int n, int nnz, const int* rows, const int* cols, int base,
                                      const OrderingSettings& settings);

// The fill_reducing_order of the last few structures, so that a structure met again is not
// ordered again: by the other LDLᵀ solver (the pivoting one, when the LDLᵀ passes it a matrix)
// or by a later solve (an IpoptSolver keeps one for all the solves of a start). An ordering is
// a function of the pattern and the settings (AMD; METIS with a fixed seed), so a kept one is
// exactly the one fill_reducing_order would compute again: the same bits. A structure is the
// same when n, base, the settings and every triplet (rows[t], cols[t]) are. The least recently
// used of `capacity` is dropped for a new one. Not thread-safe.
class OrderingCache {
 public:
  explicit OrderingCache(int capacity = 4);
  // The ordering of the structure; valid until the next call.
  const FillReducingOrder& order(int n, int nnz, const int* rows, const int* cols, int base,
                                 const OrderingSettings& settings);
  int computed() const { return computed_; }  // orderings computed (structures met anew)
  int reused() const { return reused_; }      // calls answered with a kept ordering

 private:
  struct Entry {
    int n = 0, base = 0;
    double nested_dissection_above = 0.0;
    std::vector<int> rows, cols;
    FillReducingOrder chosen;
    long last_use = 0;
  };
  int capacity_;
  std::vector<Entry> entries_;
  long uses_ = 0;
  int computed_ = 0, reused_ = 0;
};

class PermutedSymmetric {
 public:
  // Lays out the structure in the numbering of `order` (order[k]: the original row that is k-th).
  void assign(int n, int nnz, const int* rows, const int* cols, int base,
              const std::vector<int>& order);

  enum class Loaded { kDone, kNotFinite, kEmptyRow };
  // Sums values[t] into the slots (the assigned structure), computes ‖A‖∞ and the empty rows,
  // then, when the values are finite and no row is empty, the Ruiz scaling of `sweeps` sweeps
  // (0: s = 1).
  Loaded load_scaled(const double* values, int sweeps);

  // Solves A x = b (original numbering, b overwritten by x): x = S F⁻¹ S b with
  // factors_inverse(v) computing v ← F⁻¹ v in the permuted numbering, then refinement (above);
  // returns the backward error reached and sets *steps_used.
  template <class FactorsInverse>
  double refined_solve(double* b, FactorsInverse&& factors_inverse, double tolerance, int max_steps,
                       int* steps_used);

  int n() const { return n_; }
  const std::vector<int>& order() const { return order_; }
  const std::vector<int>& position() const { return position_; }  // inverse of order()
  // The upper triangle in the permuted numbering: column k holds rows ai[p] <= k, p in
  // ap[k]..ap[k+1]−1, values ax[p].
  const std::vector<int>& ap() const { return ap_; }
  const std::vector<int>& ai() const { return ai_; }
  const std::vector<double>& ax() const { return ax_; }
  const std::vector<double>& s() const { return s_; }  // the scaling, permuted numbering
  double norm() const { return norm_; }                // ‖A‖∞
  int empty_rows() const { return empty_rows_; }

 private:
  // load_scaled's two parts. load also takes every row's largest |a_ij|, which is the first
  // sweep's maximum (s = 1 before it: |a_ij|·1·1 is |a_ij| exactly), so scale starts from it
  // instead of a pass of its own: the same bits as `sweeps` full sweeps, one pass over the
  // matrix fewer.
  Loaded load(const double* values);
  void scale(int sweeps);
  void residual(const double* b, const double* x, double* r) const;  // r = b − A x
  double backward_error(const double* b, const double* x, double norm_b, double* r) const;

  int n_ = 0;
  std::vector<int> order_, position_;
  std::vector<int> ap_, ai_;
  std::vector<int> slot_;  // slot_[t]: where triplet t adds into ax_
  std::vector<double> ax_, s_, row_norm_;
  std::vector<double> row_max_;  // each row's largest |entry| of S A S in the sweep under way
  double norm_ = 0.0;
  int empty_rows_ = 0;
  std::vector<double> rhs_, x_, r_, y_;  // work vectors of refined_solve, length n
};

template <class FactorsInverse>
double PermutedSymmetric::refined_solve(double* b, FactorsInverse&& factors_inverse,
                                        double tolerance, int max_steps, int* steps_used) {
  double* rhs = rhs_.data();  // b, permuted
  double* x = x_.data();
  double* r = r_.data();
  double* y = y_.data();
  double norm_b = 0.0;
  for (int k = 0; k < n_; ++k) {
    rhs[k] = b[order_[k]];
    norm_b = std::max(norm_b, std::abs(rhs[k]));
  }
  auto apply_inverse = [&](const double* v, double* out) {  // out = S F⁻¹ S v
    for (int k = 0; k < n_; ++k) out[k] = s_[k] * v[k];
    factors_inverse(out);
    for (int k = 0; k < n_; ++k) out[k] *= s_[k];
  };
  apply_inverse(rhs, x);
  double error = backward_error(rhs, x, norm_b, r);
  int steps = 0;
  while (error > tolerance && steps < max_steps) {
    apply_inverse(r, y);
    for (int k = 0; k < n_; ++k) x[k] += y[k];
    ++steps;
    const double before = error;
    error = backward_error(rhs, x, norm_b, r);
    if (!(error < 0.5 * before)) break;  // stalled: more steps would not reach it
  }
  *steps_used = steps;
  for (int k = 0; k < n_; ++k) b[order_[k]] = x[k];
  return error;
}

}  // namespace disco
