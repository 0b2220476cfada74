// disco — checking an Nlp's derivatives against central finite differences.
//
// For a point z and multipliers (sigma, lambda) it compares
//   * the gradient with central differences of f,
//   * the Jacobian with central differences of c, entry by entry over the
//     whole dense matrix, so a nonzero outside jacobian_pattern() is caught,
//   * the Hessian of the Lagrangian sigma f + lambda^T c with central
//     differences of its analytic gradient sigma grad f + J^T lambda (lower
//     triangle, dense, so a nonzero outside hessian_pattern() is caught).
// Errors are relative: |analytic - fd| / max(1, |fd|). Dense work: meant for
// tests on small instances (n up to a few thousand).
#pragma once

#include "core/nlp/nlp.h"

namespace disco {

struct DerivativeReport {
  double gradient_error = 0.0;
  double jacobian_error = 0.0;        // entries inside the pattern
  double jacobian_outside = 0.0;      // largest |fd| outside the pattern
  double hessian_error = 0.0;
  double hessian_outside = 0.0;
  bool evaluated = true;              // false if any evaluation returned false
};

// `step` is the relative finite-difference step: delta_k = step * max(1, |z_k|).
DerivativeReport check_derivatives(const Nlp& nlp, const ConstVectorRef& z, double sigma,
                                   const ConstVectorRef& lambda, double step = 1e-6);

}  // namespace disco
