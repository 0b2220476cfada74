// disco — a smooth nonlinear program with exact first and second derivatives.
//
//     minimize    f(z)
//     subject to  c_lo <= c(z) <= c_hi,      z_lo <= z <= z_hi,
//
// with z in R^n and c: R^n -> R^m. Equalities have c_lo == c_hi; a missing side
// is +-infinity.
//
// Derivative contract (what every implementation must deliver, what the tests
// check against central finite differences):
//   * gradient(z)   = df/dz, dense, length n;
//   * jacobian(z)   = dc_r/dz_k at the (r, k) of jacobian_pattern(), in that order;
//   * hessian(z, sigma, lambda) = sigma * d2f/dz2 + sum_r lambda_r * d2c_r/dz2, LOWER
//     triangle only (row >= col), at the entries of hessian_pattern(), in that order.
//   A derivative that is nonzero anywhere must have its entry in the pattern; a
//   pattern entry may hold an exact zero. Patterns never change after
//   construction, and may not repeat an entry.
//
// Public evaluation is non-virtual: it checks sizes (a failed check throws
// InternalError, core/util/check.h), calls the private implementation, and turns
// every other exception and every non-finite value into `false`. An InternalError
// (a bug, not a bad point) goes on up; the Ipopt adapter keeps it out of Ipopt and
// rethrows it after the solve (core/ipopt/ipopt_solver.h).
// (The shape follows Drake's solvers: checked public calls around a private
// implementation.)
#pragma once

#include <Eigen/Core>
#include <vector>

namespace disco {

using Vector = Eigen::VectorXd;
using VectorRef = Eigen::Ref<Vector>;
using ConstVectorRef = Eigen::Ref<const Vector>;

// A list of (row, col) entries of a sparse matrix.
struct SparsityPattern {
  std::vector<int> rows;
  std::vector<int> cols;
  int size() const { return static_cast<int>(rows.size()); }
  void add(int r, int c) { rows.push_back(r); cols.push_back(c); }
};

class Nlp {
 public:
  virtual ~Nlp() = default;

  int num_variables() const { return static_cast<int>(z_lo_.size()); }
  int num_constraints() const { return static_cast<int>(c_lo_.size()); }

  const Vector& variable_lower() const { return z_lo_; }
  const Vector& variable_upper() const { return z_hi_; }
  const Vector& constraint_lower() const { return c_lo_; }
  const Vector& constraint_upper() const { return c_hi_; }
  const SparsityPattern& jacobian_pattern() const { return jac_; }
  const SparsityPattern& hessian_pattern() const { return hess_; }

  // Bounds may change between solves (e.g. T_f <= (1 - r) T_best); the
  // structure may not.
  void set_variable_bounds(int k, double lo, double hi);
  void set_constraint_bounds(int r, double lo, double hi);

  bool objective(const ConstVectorRef& z, double& f) const;
  bool gradient(const ConstVectorRef& z, VectorRef grad) const;
  bool constraints(const ConstVectorRef& z, VectorRef c) const;
  bool jacobian(const ConstVectorRef& z, VectorRef values) const;
  bool hessian(const ConstVectorRef& z, double sigma, const ConstVectorRef& lambda,
               VectorRef values) const;

 protected:
  // Derived classes size and fill these in their constructor.
  Vector z_lo_, z_hi_, c_lo_, c_hi_;
  SparsityPattern jac_, hess_;

 private:
  virtual bool do_objective(const ConstVectorRef& z, double& f) const = 0;
  virtual bool do_gradient(const ConstVectorRef& z, VectorRef grad) const = 0;
  virtual bool do_constraints(const ConstVectorRef& z, VectorRef c) const = 0;
  virtual bool do_jacobian(const ConstVectorRef& z, VectorRef values) const = 0;
  virtual bool do_hessian(const ConstVectorRef& z, double sigma, const ConstVectorRef& lambda,
                          VectorRef values) const = 0;
};

}  // namespace disco
