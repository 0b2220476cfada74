#include "core/nlp/derivative_checker.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace disco {
namespace {

using Dense = Eigen::MatrixXd;

double rel_error(double analytic, double fd) {
  return std::abs(analytic - fd) / std::max(1.0, std::abs(fd));
}

}  // namespace

DerivativeReport check_derivatives(const Nlp& nlp, const ConstVectorRef& z, double sigma,
                                   const ConstVectorRef& lambda, double step) {
  DerivativeReport rep;
  const int n = nlp.num_variables(), m = nlp.num_constraints();
  const auto& jp = nlp.jacobian_pattern();
  const auto& hp = nlp.hessian_pattern();

  // Analytic values at z.
  Vector grad(n), jv(jp.size()), hv(hp.size());
  rep.evaluated = nlp.gradient(z, grad) && nlp.jacobian(z, jv) && nlp.hessian(z, sigma, lambda, hv);
  if (!rep.evaluated) return rep;
  Dense J = Dense::Zero(m, n), H = Dense::Zero(n, n);
  Eigen::MatrixXi inJ = Eigen::MatrixXi::Zero(m, n), inH = Eigen::MatrixXi::Zero(n, n);
  for (int e = 0; e < jp.size(); ++e) {
    J(jp.rows[e], jp.cols[e]) += jv[e];
    inJ(jp.rows[e], jp.cols[e]) = 1;
  }
  for (int e = 0; e < hp.size(); ++e) {
    H(hp.rows[e], hp.cols[e]) += hv[e];
    inH(hp.rows[e], hp.cols[e]) = 1;
  }

  // Analytic gradient of the Lagrangian at a point.
  auto lagrangian_gradient = [&](const Vector& x, Vector& out) {
    Vector g(n), v(jp.size());
    if (!nlp.gradient(x, g) || !nlp.jacobian(x, v)) return false;
    out = sigma * g;
    for (int e = 0; e < jp.size(); ++e) out[jp.cols[e]] += lambda[jp.rows[e]] * v[e];
    return true;
  };

  Vector x = z;
  Vector cp(m), cm(m), lp(n), lm(n);
  for (int k = 0; k < n; ++k) {
    const double d = step * std::max(1.0, std::abs(z[k]));
    double fp = 0, fm = 0;
    x[k] = z[k] + d;
    bool ok = nlp.objective(x, fp) && nlp.constraints(x, cp) && lagrangian_gradient(x, lp);
    x[k] = z[k] - d;
    ok = ok && nlp.objective(x, fm) && nlp.constraints(x, cm) && lagrangian_gradient(x, lm);
    x[k] = z[k];
    if (!ok) {
      rep.evaluated = false;
      return rep;
    }
    rep.gradient_error = std::max(rep.gradient_error, rel_error(grad[k], (fp - fm) / (2 * d)));
    for (int r = 0; r < m; ++r) {
      const double fd = (cp[r] - cm[r]) / (2 * d);
      if (inJ(r, k))
        rep.jacobian_error = std::max(rep.jacobian_error, rel_error(J(r, k), fd));
      else
        rep.jacobian_outside = std::max(rep.jacobian_outside, std::abs(fd));
    }
    // Column k of the Hessian; compare on the lower triangle (row >= k).
    for (int r = k; r < n; ++r) {
      const double fd = (lp[r] - lm[r]) / (2 * d);
      if (inH(r, k))
        rep.hessian_error = std::max(rep.hessian_error, rel_error(H(r, k), fd));
      else
        rep.hessian_outside = std::max(rep.hessian_outside, std::abs(fd));
    }
  }
  return rep;
}

}  // namespace disco
