// disco — the elastic mode of an MPCC (paper Section IV, eqs. 3-4), as an Nlp.
//
// Given the MPCC  min f(z)  s.t.  c_lo <= c(z) <= c_hi,  z_lo <= z <= z_hi,
// 0 <= G_i(z) _|_ H_i(z) >= 0, the elastic NLP is built in two steps.
//
// 1. Lifting. Every side that is a row c_r(z) gets a slack s_r >= 0 and the
//    row becomes the equality c_r(z) - s_r = 0 (the row's own bounds move to
//    s_r). Every pair is then between two variables u_i, w_i >= 0, and the
//    products below are bilinear: their derivatives are exact and cheap.
//
// 2. Elastic complementarity, one of:
//    * kLumped (the paper):  sum_i u_i w_i <= eps,  eps >= 0,
//                            objective f(z) + zeta * eps;
//    * kPerPair:             objective f(z) + zeta * sum_i u_i w_i.
//      This is the per-pair elastic mode u_i w_i <= eps_i with penalty
//      zeta * sum_i eps_i, with each eps_i eliminated: since u_i, w_i >= 0 the
//      optimal eps_i is exactly u_i w_i, so the two have the same solutions
//      and this form needs no extra variables or rows.
//    * kRelaxed:             sum_i u_i w_i <= sigma + eps,  eps >= 0,
//                            objective f(z) + zeta * eps:
//      the lumped form with its row relaxed by sigma >= 0 (set_relaxation; 0 is kLumped).
//      A relaxed (Scholtes-type) problem with sigma > 0 has an interior near the
//      complementarity corner; ElasticSolver drives sigma to 0 together with Ipopt's
//      barrier parameter (elastic_solver.h).
//    * kBarrier:             u_i w_i - sigma <= eps for every pair i,  eps >= 0,
//                            objective f(z) + zeta * eps:
//      a Scholtes relaxation per pair (as in IPOPT-C and Leyffer, Lopez-Calva & Nocedal)
//      with one elastic eps (an l-infinity elastic mode), sigma in the rows' functions, not
//      their bounds (set_live_relaxation), so that it can move during one Ipopt run:
//      ElasticSolver moves it with Ipopt's barrier parameter at every iteration
//      (elastic_solver.h). Ipopt reads bounds once per solve, functions at every iterate.
//
// Variables: [z (n) | s (one per row side) | eps (kLumped, kRelaxed, kBarrier)].
// Rows:      [c(z), side rows minus their slack (m) | the lumped row (kLumped, kRelaxed) |
//             one row per pair (kBarrier)].
// The MPCC's Jacobian and Hessian entries come first, in the MPCC's order, so
// its values are written in place into the head of each array.
#pragma once

#include <vector>

#include "core/nlp/mpcc.h"

namespace disco {

enum class ElasticFormulation { kLumped, kPerPair, kRelaxed, kBarrier };

class ElasticNlp : public Nlp {
 public:
  ElasticNlp(const Mpcc& mpcc, ElasticFormulation formulation, double zeta);

  void set_zeta(double zeta) { zeta_ = zeta; }
  // The lumped row's upper bound sigma (kLumped, kRelaxed; 0 when made).
  void set_relaxation(double sigma);
  // kBarrier: the sigma its pair rows subtract (0 when made).
  void set_live_relaxation(double sigma);
  double live_relaxation() const { return live_sigma_; }
  double zeta() const { return zeta_; }
  ElasticFormulation formulation() const { return formulation_; }
  const Mpcc& mpcc() const { return mpcc_; }

  // The elastic point for an MPCC point: slacks = side rows, eps = sum u w.
  Vector lift(const ConstVectorRef& z) const;
  // Elastic variable index of each pair's sides (u_i, w_i).
  int u(int i) const { return u_[i]; }
  int w(int i) const { return w_[i]; }
  // Index of eps, or -1 (kPerPair).
  int eps_index() const { return eps_; }

 private:
  bool do_objective(const ConstVectorRef& x, double& f) const override;
  bool do_gradient(const ConstVectorRef& x, VectorRef grad) const override;
  bool do_constraints(const ConstVectorRef& x, VectorRef c) const override;
  bool do_jacobian(const ConstVectorRef& x, VectorRef values) const override;
  bool do_hessian(const ConstVectorRef& x, double sigma, const ConstVectorRef& lambda,
                  VectorRef values) const override;

  double product_sum(const ConstVectorRef& x) const;

  const Mpcc& mpcc_;
  ElasticFormulation formulation_;
  double zeta_;
  int n_ = 0, m_ = 0;                  // MPCC sizes
  std::vector<int> side_row_, slack_;  // row sides and their slack variables
  std::vector<int> u_, w_;             // per pair
  int eps_ = -1;
  bool pair_rows_ = false;   // kBarrier: one row per pair
  double live_sigma_ = 0.0;  // kBarrier
  // Derivatives of P(x) = sum_i u_i w_i: dP/dx_k = sum of x at `partner`
  // over the entries of k (CSR by gradient entry `grad_var_`).
  std::vector<int> grad_var_, grad_begin_, grad_partner_;
  // d2P: entry e of the Hessian gets `weight * hess_mult_` per pair listed.
  std::vector<int> pair_hess_entry_;   // per pair: Hessian entry of (u_i, w_i)
  std::vector<double> pair_hess_mult_; // 1, or 2 when u_i == w_i
  int mpcc_jac_nnz_ = 0, mpcc_hess_nnz_ = 0;
};

}  // namespace disco
