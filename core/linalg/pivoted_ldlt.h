// disco — a multifrontal sparse symmetric indefinite LDLᵀ with threshold Bunch–Kaufman pivoting
// and delayed pivots, for Ipopt's KKT matrices (issue 33; kkt.solver pivoted).
//
// Factorises P (S A S) Pᵀ = L D Lᵀ, where
//   - A is the symmetric matrix as given (one triangle in triplets, repeats summed) and S its
//     symmetric Ruiz scaling (permuted_symmetric.h): every row's largest entry near 1;
//   - P is a fill-reducing ordering (AMD, or METIS's nested dissection where that needs fewer
//     multiply-adds: permuted_symmetric.h, fill_reducing_order) with each constraint row moved
//     behind a primal neighbour (postponed_order()), followed by a postorder of its elimination
//     tree, then changed during the factorisation by the pivoting (delayed pivots);
//   - D is block diagonal with 1×1 and 2×2 blocks, L unit lower triangular.
// No regularisation: a zero diagonal (the constraint block of a KKT matrix with δc = 0) gains a
// diagonal from the primal variable eliminated before it, or is eliminated with a primal
// variable as a 2×2 pivot. So D's inertia is that of S A S,
// which is A's (Sylvester's law), up to the roundoff of a stable elimination: every multiplier is
// bounded by 1/u (below), unlike sparse_ldlt.h's static pivots.
//
// Analysis (analyse(), once per structure): the ordering, the elimination tree, fundamental
// supernodes (consecutive columns with nested patterns: a front's fully summed variables) merged
// into larger fronts where few explicit zeros result (relax()), each
// front's row structure, where every entry of A and every row of a child's update matrix lands in
// its parent's front.
//
// Factorisation (factor()): the fronts in postorder. A front holds its own columns and the
// variables its children could not eliminate (delayed) as fully summed variables, and its rows
// below. It is assembled from A's entries and its children's update matrices (extend-add), then
// its fully summed variables are eliminated as far as the threshold test allows (Duff–Reid, as in
// MA57 and SPRAL's SSIDS): a 1×1 pivot a_cc when |a_cc| ≥ u·max_{i≠c} |a_ic|; else a 2×2 pivot on
// (c, r), r the fully summed row of c's largest entry, when
// |D⁻¹| (max_{i≠c,r} |a_ic|, max_{i≠c,r} |a_ir|)ᵀ ≤ (1/u, 1/u)ᵀ componentwise; else a 1×1 on r
// when r passes the test; else c waits. What cannot be eliminated is passed to the parent with
// the update matrix (S − L D Lᵀ on the rows below: by columns in a front with fewer than 16
// pivots, where a GEMM's packing would cost more than it saves, else by Eigen's GEMM). At a root every remaining variable is fully summed: when no pivot passes, u
// is lowered (pivots taken so are counted in forced()), and a remaining block whose pivots are
// all below `zero_pivot` makes the matrix kSingular (as MUMPS reports a null pivot). u is
// `pivot_threshold`, raised by the caller on Ipopt's IncreaseQuality.
//
// Solve (solve()): with the factors and iterative refinement against A, as sparse_ldlt.h does
// (the normwise backward error must reach residual_tolerance; the caller sends a matrix that does
// not to MUMPS).
//
// Storage: every array is sized by analyse() or grows to the largest front seen and is then kept:
// a factorisation allocates only when delays make a front larger than any before. Deterministic:
// the same structure and values give the same bits. Not thread-safe.
//
// Ideas from MA57 and SPRAL/SSIDS (threshold 1×1/2×2 pivoting in fronts, delayed pivots), Liu's
// multifrontal method and Davis's CSparse (elimination tree, postorder); no code copied.
#pragma once

#include <cstdint>
#include <vector>

#include "core/linalg/permuted_symmetric.h"
#include "core/linalg/sparse_ldlt.h"  // LdltSettings

namespace disco {

class PivotedLdlt {
 public:
  // Analyses an n × n symmetric structure given as nnz triplets numbered from `base` (either
  // triangle; an entry and its mirror are summed). Rows dual_from..n−1 are the constraint block
  // (zero diagonals expected; the ordering puts each behind a primal neighbour; n: none).
  // The fill-reducing ordering is chosen as `ordering` says (fill_reducing_order), or given:
  // `chosen`, fill_reducing_order's answer for this structure (e.g. from an OrderingCache).
  void analyse(int n, int nnz, const int* rows, const int* cols, int base, int dual_from,
               const OrderingSettings& ordering);
  void analyse(int n, int nnz, const int* rows, const int* cols, int base, int dual_from,
               const FillReducingOrder& chosen);

  enum class Factorised {
    kDone,       // L and D computed; negative() is the inertia of A
    kNotFinite,  // a value or a pivot was NaN or infinite: no factors
    kEmptyRow,   // a row without a nonzero: A is singular (empty_rows()); no factors
    kSingular,   // a remaining block with every pivot below zero_pivot: A is singular
  };
  // Factorises the matrix with values[t] at triplet t, with pivot threshold `threshold`
  // (0 < threshold ≤ 0.5: settings.pivot_threshold or more).
  Factorised factor(const double* values, const LdltSettings& settings, double threshold);
  // The same with settings.pivot_threshold.
  Factorised factor(const double* values, const LdltSettings& settings) {
    return factor(values, settings, settings.pivot_threshold);
  }

  // Solves A x = b in place, refining; returns the backward error reached.
  double solve(double* b);

  int dimension() const { return n_; }
  int negative() const { return negative_; }      // negative eigenvalues of D
  int delayed() const { return delayed_; }        // pivots passed from a front to its parent
  int two_by_two() const { return two_by_two_; }  // 2×2 pivots
  int forced() const { return forced_; }          // pivots taken below the threshold at a root
  int empty_rows() const { return a_.empty_rows(); }
  int64_t factor_entries() const { return factor_entries_; }  // nnz(L) with delays, no diagonal
  // max |L(i, j)|: at most 1/threshold unless forced() (the threshold test bounds every
  // multiplier of a 1×1 and a 2×2 pivot).
  double largest_multiplier() const;  // computed from the stored factors
  double flops() const { return flops_; }  // multiply-adds of the analysis (no delays)
  int postponed() const { return postponed_; }  // constraint rows moved behind a primal one
  // The fill-reducing ordering the analysis chose, before the postponement (order field empty).
  const FillReducingOrder& ordering() const { return ordering_; }
  int supernodes() const { return static_cast<int>(first_.size()) - 1; }
  int last_refinement_steps() const { return refinement_steps_used_; }

 private:
  // Eliminates the fully summed variables 0..nf−1 of the front f (m × m, column-major, its
  // columns 0..nf−1 whole, the rest lower) as far as the threshold allows; g: its variables.
  // Returns the pivots taken, or −1 when a root's remaining block is singular.
  int eliminate(double* f, int m, int nf, int* g, bool root, double threshold);
  // The ordering: sparse_ldlt.h's on A's graph (fill_reducing_order), with every constraint row
  // that comes before all of its primal neighbours moved to right after the first of them. A
  // constraint row's diagonal is zero (δc = 0), so eliminated first it could only wait for a
  // later front; after a primal neighbour it has a diagonal (−a²/h from that elimination).
  // Moving a row there changes the fill little: none of its neighbours lies between the two
  // places. (On the bench_kkt corpus's paper B2 matrices, 1.3e6 multiply-adds against 1.1e6
  // for AMD alone and 3.9e6 for AMD on the graph with each constraint row merged with a
  // primal neighbour, the ordering this one replaced.)
  std::vector<int> postponed_order(int n, int nnz, const int* rows, const int* cols, int base,
                                   int dual_from, const FillReducingOrder& chosen);
  // Merges supernodes (first_, node_of) into larger fronts (relaxed amalgamation).
  void relax(const std::vector<int>& count, const std::vector<int>& parent,
             std::vector<int>& node_of);
  void swap(double* f, int m, int nf, int* g, int a, int b, int p);
  void factors_inverse(double* x);  // x ← (L D Lᵀ)⁻¹ x, permuted numbering

  int n_ = 0;
  PermutedSymmetric a_;
  // Supernodes s: columns first_[s]..first_[s+1]−1; row structure rows_[rows_ptr_[s]..] (its
  // own columns, then the rows below, ascending); parent_[s] (−1: a root); children_[s]: how
  // many; for a child, where its rows below lie in its parent's structure: child_map_[...]
  // from child_map_ptr_[s]. A's entries: assembly_ptr_[s].. with the slot in a_.ax() and the
  // local (row, column) in s's structure.
  std::vector<int> first_, rows_ptr_, rows_, parent_, children_, child_map_ptr_, child_map_;
  std::vector<int> assembly_ptr_, assembly_slot_, assembly_row_, assembly_col_;
  double flops_ = 0.0;
  // Factors, per supernode: m_[s] front rows (its variables, eliminated first: index_[...] from
  // index_ptr_[s]), npiv_[s] pivots, L's m × npiv block at lx_[lx_ptr_[s]..] (column-major, unit
  // lower in its top npiv rows), D at d_/e_ from pivot_ptr_[s]: d_ the diagonal, e_[q] the
  // entry below it in a 2×2 block starting at q (0 for a 1×1; second_[q] marks a block's second).
  std::vector<int> m_, npiv_, index_ptr_, index_, pivot_ptr_;
  std::vector<size_t> lx_ptr_;
  std::vector<double> lx_, d_, e_;
  size_t lx_used_ = 0;     // entries of lx_ this factorisation wrote
  size_t index_used_ = 0;  // entries of index_ this factorisation wrote
  std::vector<char> second_;
  // Work: the front, the stack of update matrices (values; delayed variables), a local map.
  std::vector<double> front_, stack_, work_, xl_;
  size_t stack_used_ = 0;  // entries of stack_ in use
  std::vector<int> stack_delayed_, map_;
  struct Update {
    size_t offset;          // in stack_
    int size;               // rows (delayed first)
    int delayed;            // delayed variables
    size_t delayed_offset;  // in stack_delayed_
    int node;               // the supernode it comes from
  };
  std::vector<Update> updates_;
  int postponed_ = 0;
  FillReducingOrder ordering_;
  int pivot_count_ = 0;  // pivots taken so far in this factorisation
  int negative_ = 0, delayed_ = 0, two_by_two_ = 0, forced_ = 0, refinement_steps_used_ = 0;
  int64_t factor_entries_ = 0;
  double zero_pivot_ = 0.0;
  LdltSettings settings_;
};

}  // namespace disco
