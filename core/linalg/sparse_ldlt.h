// disco — a sparse symmetric indefinite LDLᵀ for Ipopt's KKT matrices (issue 33).
//
// Factorises P (S A S + R) Pᵀ = L D Lᵀ, where
//   - A is the symmetric matrix as given (one triangle in triplets, repeats summed);
//   - S = diag(s) is a symmetric Ruiz scaling: `scaling_sweeps` sweeps of s_i ← s_i / √(max_j
//     |s_i a_ij s_j|), which brings every row's largest entry near 1 (Ipopt's KKT matrices span
//     1e-3…1e12 on the diagonal; without it the residuals stall at 1e-2);
//   - R is a static regularisation: a scaled diagonal entry smaller than δ = `regularisation` in
//     magnitude becomes +δ in the primal block and −δ in the constraint (dual) block, the signs
//     of a quasi-definite matrix [H + δI, Jᵀ; J, −δI]; a pivot that still falls below δ·1e-6
//     during the elimination is replaced by ±δ the same way and counted (perturbed());
//   - P is a fill-reducing ordering of the pattern (AMD, or METIS's nested dissection where that
//     needs fewer multiply-adds: permuted_symmetric.h, fill_reducing_order), computed once per
//     structure with the elimination tree, the column counts of L and the pattern of every row of
//     L (analyse()); a factorisation then only moves numbers, in arrays sized once;
//   - L is unit lower triangular, D diagonal (1×1 pivots only: no pivoting, which is what makes
//     it fast; the regularisation is what makes it possible).
//
// Growth: without pivoting nothing bounds L. A pivot that is tiny but above the floor makes
// L(:, j) large, and the roundoff of the elimination (of order ε·max_j |D_j|·max_i |L_ij|², the
// growth, against scaled entries of order 1) can then flip signs of D. Factors whose growth is
// above `growth_limit` are reported kUnstable: the caller takes that matrix elsewhere. With δ
// regularising the empty diagonals, growth is about 1/δ on Ipopt's KKT matrices (6e7–3e9 on the
// bench_kkt corpus); the one corpus matrix whose inertia depended on δ had 1.6e12.
//
// Inertia: the signs of D are the inertia of S A S + R. solve() works on A itself: it solves with
// the factors and refines iteratively against A (without S or R) until the normwise backward
// error ‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞) is at most `residual_tolerance` (at most
// `refinement_steps` steps, fewer when it stalls). Refinement converges only when R is small
// against A's smallest singular value, and then R does not change the inertia either: a solve
// that reaches the tolerance vouches for the inertia too. One that does not is reported, and the
// caller takes that matrix elsewhere (core/ipopt/kkt_solver.h: to MUMPS, counted). An inertia
// the caller rejects without a solve is vouched for by inertia_certified(): Weyl's inequality
// with the smallest |eigenvalue| of S A S + R, estimated by inverse iteration, against ‖R‖₂
// (on the bench_kkt corpus, the two matrices whose inertia R had decided, A's eigenvalue 1e-11
// against δ = 1e-8, are the ones it does not certify, with 38 others whose M has an
// eigenvalue within 2‖R‖ of zero).
//
// Deterministic: the same structure and values give the same bits. Not thread-safe (one object,
// one thread). Ideas from QDLDL and Davis's LDL (up-looking elimination over the elimination
// tree), PARDISO (static pivot perturbation plus refinement) and OSQP (quasi-definite
// regularisation); no code copied.
#pragma once

#include <cstdint>
#include <vector>

#include "core/linalg/permuted_symmetric.h"

namespace disco {

// The kkt.ldlt settings of configs/disco.yaml.
struct LdltSettings {
  int scaling_sweeps = 0;           // Ruiz sweeps (0: no scaling)
  double regularisation = 0.0;      // δ, on the scaled matrix
  double residual_tolerance = 0.0;  // backward error a solve must reach
  int refinement_steps = 0;         // at most this many refinement steps per solve
  double growth_limit = 0.0;        // factors with a larger growth() are kUnstable
  // The inertia certificate (core/ipopt/kkt_solver.h): inverse iterations of
  // smallest_eigenvalue() (0: none), and how far above regularisation_norm() its estimate must
  // be for the signs of D to count as A's inertia.
  int certificate_iterations = 0;
  double certificate_margin = 0.0;
  // kkt.solver pivoted (pivoted_ldlt.h): the threshold u of its 1×1 and 2×2 pivots, the largest
  // u Ipopt's requests for more accuracy may raise it to, and the magnitude below which a pivot
  // of the scaled matrix counts as zero.
  double pivot_threshold = 0.0;
  // kkt.solver ldlt: a matrix this LDLᵀ cannot serve goes to the pivoting LDLᵀ (true) or to
  // MUMPS (false); kkt.ldlt.fallback.
  bool fallback_pivoted = false;
  double pivot_threshold_max = 0.0;
  double zero_pivot = 0.0;
  // kkt.ldlt.ordering: the fill-reducing ordering of both solvers' analyses.
  OrderingSettings ordering;
};

class SparseLdlt {
 public:
  // Analyses the structure of an n × n symmetric matrix given as nnz triplets (rows[t], cols[t]),
  // numbered from `base` (1: Ipopt's triplets), entries of either triangle (an entry and its
  // mirror may both appear: they are summed). Rows dual_from..n−1 are the constraint block (their
  // regularisation is negative). Orders it as `ordering` says (fill_reducing_order), or as
  // given: `chosen`, fill_reducing_order's answer for this structure (e.g. from an
  // OrderingCache). Allocates everything the factorisations and solves need.
  void analyse(int n, int nnz, const int* rows, const int* cols, int base, int dual_from,
               const OrderingSettings& ordering);
  void analyse(int n, int nnz, const int* rows, const int* cols, int base, int dual_from,
               const FillReducingOrder& chosen);

  enum class Factorised {
    kDone,       // L and D computed; inertia() is that of S A S + R
    kNotFinite,  // a value or a pivot was NaN or infinite: no factors
    kEmptyRow,   // a row without a nonzero: A is singular (empty_rows() says how many); no factors
    kUnstable,   // factors computed, but their growth() is above growth_limit: without pivoting,
                 // a tiny pivot made L large, and neither the inertia nor the solves are vouched
                 // for (roundoff of order ε·growth against entries of order 1)
  };
  // Factorises the matrix with values[t] at triplet t (the analysed structure).
  Factorised factor(const double* values, const LdltSettings& settings);

  // Solves A x = b in place (b overwritten by x), refining; returns the backward error reached
  // (above: at most residual_tolerance means the solve is as accurate as asked).
  double solve(double* b);

  int dimension() const { return n_; }
  int negative() const { return negative_; }    // negative pivots of the last factorisation
  int perturbed() const { return perturbed_; }  // pivots replaced by ±δ in it
  int regularised() const { return regularised_; }  // diagonal entries set to ±δ in it
  int empty_rows() const { return a_.empty_rows(); }  // rows of A without a nonzero (kEmptyRow)
  int64_t factor_entries() const { return static_cast<int64_t>(li_.size()); }  // nnz(L), no diagonal
  // Element growth of the last factorisation: max_j |D(j)| · max(1, max_i |L(i, j)|)², a lower
  // bound on the largest entry of |L| |D| |Lᵀ| (the scaled matrix's entries are at most 1).
  double growth() const { return growth_; }
  double flops() const { return flops_; }  // multiply-adds of one factorisation
  // The analysis's ordering: which one, and the multiply-adds of each one it judged (its order
  // field is empty: the order is the matrix's, inside).
  const FillReducingOrder& ordering() const { return ordering_; }
  // max_k |R(k, k)|: the 2-norm of the regularisation the last factorisation added to S A S
  // (the diagonal entries set to ±δ and the pivots replaced; at most 2δ).
  double regularisation_norm() const { return regularisation_norm_; }
  // An estimate of the smallest |eigenvalue| of the factorised matrix M = S A S + R:
  // 1 / max_t ‖M⁻¹ x_t‖₂ over `iterations` steps of inverse power iteration (x_t normalised) from
  // a fixed start vector with no structure. Never below the true value (‖M⁻¹ x‖ ≤ ‖M⁻¹‖₂ for
  // every unit x); above it by a factor c only with a probability that falls like
  // √n·(1/c)^(iterations − 1/2) for a random start (Kuczyński & Woźniakowski 1992).
  // By Weyl's inequality, A has the inertia of M (of D's signs) when this is larger than
  // regularisation_norm().
  double smallest_eigenvalue(int iterations);
  // Whether the last factorisation's inertia is certified to be A's: certificate_iterations is
  // 0 (no certificate asked for), R is zero, or smallest_eigenvalue(certificate_iterations) is
  // above certificate_margin × regularisation_norm() (Weyl; the margin covers the estimate's
  // error). Uncertified, an eigenvalue of A may lie within ‖R‖ of zero, its sign R's.
  bool inertia_certified();
  int last_refinement_steps() const { return refinement_steps_used_; }

 private:
  void apply_factors_inverse(double* x) const;  // x ← (L D Lᵀ)⁻¹ x, permuted space

  int n_ = 0;
  PermutedSymmetric a_;  // A in the elimination order, its scaling, the refined solve
  FillReducingOrder ordering_;
  std::vector<char> dual_;  // dual_[k]: permuted row k is in the constraint block
  // L by columns: lp_, li_, lx_; and by rows, in the topological order the elimination of row k
  // visits them: rp_, ri_ (the columns), rslot_ (where L(k, ri) lies in lx_).
  std::vector<int> lp_, li_, rp_, ri_, rslot_;
  std::vector<double> lx_, d_, dinv_;
  std::vector<double> column_max_;  // column_max_[j]: max(1, max_i |L(i, j)|)
  std::vector<double> y_, w1_;  // work vectors, length n
  int negative_ = 0, perturbed_ = 0, regularised_ = 0, refinement_steps_used_ = 0;
  double flops_ = 0.0;
  double growth_ = 0.0;
  double regularisation_norm_ = 0.0;
  LdltSettings settings_;
};

}  // namespace disco
