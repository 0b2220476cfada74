// The derivative checker itself must catch wrong derivatives and missing
// sparsity entries, or every derivative test built on it proves nothing.
#include <gtest/gtest.h>

#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "tests/test_support_derivatives.h"

namespace disco {
namespace {

using test_support::expect_exact_derivatives;

// f = x0 * x1 (objective), c0 = x0^2 x1 + 3 x2, c1 = x1 * x2 * x0 - 2.
PolynomialProgram small_program() {
  PolynomialProgram p;
  for (int k = 0; k < 3; ++k) p.add_variable(-10, 10);
  const Affine x0 = Affine::variable(0), x1 = Affine::variable(1), x2 = Affine::variable(2);
  p.add(PolynomialProgram::kObjective, 1.0, x0, x1);
  const int r0 = p.add_row(0, 0), r1 = p.add_row(0, 0);
  p.add(r0, 1.0, x0, x0, x1);
  p.add(r0, 3.0, x2);
  p.add(r1, 1.0, x1, x2, x0);
  p.add(r1, -2.0, Affine(1.0));
  p.finalize();
  return p;
}

// Wraps an Nlp and corrupts one derivative, to prove the checker notices.
class Corrupted : public test_support::ForwardingNlp {
 public:
  enum What { kJacobianValue, kHessianValue, kDropJacobianEntry, kDropHessianEntry };
  Corrupted(const Nlp& inner, What what) : ForwardingNlp(inner), what_(what) {
    if (what == kDropJacobianEntry) {
      jac_.rows.pop_back();
      jac_.cols.pop_back();
    }
    if (what == kDropHessianEntry) {
      hess_.rows.pop_back();
      hess_.cols.pop_back();
    }
  }

 private:
  bool do_jacobian(const ConstVectorRef& z, VectorRef v) const override {
    Vector full(inner_.jacobian_pattern().size());
    if (!inner_.jacobian(z, full)) return false;
    v = full.head(v.size());
    if (what_ == kJacobianValue) v[0] += 1e-3;
    return true;
  }
  bool do_hessian(const ConstVectorRef& z, double s, const ConstVectorRef& l,
                  VectorRef v) const override {
    Vector full(inner_.hessian_pattern().size());
    if (!inner_.hessian(z, s, l, full)) return false;
    v = full.head(v.size());
    if (what_ == kHessianValue) v[0] += 1e-3;
    return true;
  }
  What what_;
};

TEST(DerivativeChecker, AcceptsExactDerivatives) {
  const auto p = small_program();
  Vector z(3), lambda(2);
  z << 0.7, -1.3, 2.1;
  lambda << 0.4, -2.5;
  const auto rep = check_derivatives(p, z, 1.5, lambda);
  expect_exact_derivatives(rep, 1e-8, 1e-7);
}

TEST(DerivativeChecker, CatchesEveryKindOfCorruption) {
  const auto p = small_program();
  Vector z(3), lambda(2);
  z << 0.7, -1.3, 2.1;
  lambda << 0.4, -2.5;
  EXPECT_GT(check_derivatives(Corrupted(p, Corrupted::kJacobianValue), z, 1, lambda).jacobian_error,
            1e-4);
  EXPECT_GT(check_derivatives(Corrupted(p, Corrupted::kHessianValue), z, 1, lambda).hessian_error,
            1e-4);
  EXPECT_GT(
      check_derivatives(Corrupted(p, Corrupted::kDropJacobianEntry), z, 1, lambda).jacobian_outside,
      1e-3);
  EXPECT_GT(
      check_derivatives(Corrupted(p, Corrupted::kDropHessianEntry), z, 1, lambda).hessian_outside,
      1e-3);
}

}  // namespace
}  // namespace disco
