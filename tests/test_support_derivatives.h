// Test-only helper shared by the derivative tests (derivative checker, polynomial program,
// elastic NLP, Ipopt solver, textbook MPCCs). Header-only; everything inline.
#pragma once

#include <gtest/gtest.h>

#include "core/nlp/derivative_checker.h"

namespace disco::test_support {

// Asserts that a check_derivatives() report shows exact derivatives: every evaluation
// succeeded (a fatal failure, which returns, if not), the gradient and Jacobian errors are
// below `tol`, the Hessian error is below `hessian_tol`, and nothing lies outside the
// sparsity patterns. Call it inside ASSERT_NO_FATAL_FAILURE(...) where the test must stop
// when the evaluation failed.
inline void expect_exact_derivatives(const DerivativeReport& rep, double tol,
                                     double hessian_tol) {
  ASSERT_TRUE(rep.evaluated);
  EXPECT_LT(rep.gradient_error, tol);
  EXPECT_LT(rep.jacobian_error, tol);
  EXPECT_LT(rep.hessian_error, hessian_tol);
  EXPECT_EQ(rep.jacobian_outside, 0.0);
  EXPECT_EQ(rep.hessian_outside, 0.0);
}

// The same with one tolerance for the gradient, Jacobian and Hessian errors.
inline void expect_exact_derivatives(const DerivativeReport& rep, double tol = 1e-6) {
  expect_exact_derivatives(rep, tol, tol);
}

// An Nlp that forwards everything to another one: tests derive from it and
// override one evaluation to corrupt it (negative controls for the checkers).
class ForwardingNlp : public Nlp {
 public:
  explicit ForwardingNlp(const Nlp& inner) : inner_(inner) {
    z_lo_ = inner.variable_lower();
    z_hi_ = inner.variable_upper();
    c_lo_ = inner.constraint_lower();
    c_hi_ = inner.constraint_upper();
    jac_ = inner.jacobian_pattern();
    hess_ = inner.hessian_pattern();
  }

 protected:
  bool do_objective(const ConstVectorRef& z, double& f) const override {
    return inner_.objective(z, f);
  }
  bool do_gradient(const ConstVectorRef& z, VectorRef g) const override {
    return inner_.gradient(z, g);
  }
  bool do_constraints(const ConstVectorRef& z, VectorRef c) const override {
    return inner_.constraints(z, c);
  }
  bool do_jacobian(const ConstVectorRef& z, VectorRef v) const override {
    return inner_.jacobian(z, v);
  }
  bool do_hessian(const ConstVectorRef& z, double s, const ConstVectorRef& l,
                  VectorRef v) const override {
    return inner_.hessian(z, s, l, v);
  }
  const Nlp& inner_;
};

}  // namespace disco::test_support
