#include "core/nlp/nlp.h"

#include <exception>

#include "core/util/check.h"

namespace disco {
namespace {

// Runs an evaluation: any exception or non-finite output becomes `false`, except a
// failed internal check (core/util/check.h), which is a bug and goes on up.
template <class Eval>
bool guarded(Eval&& eval, const VectorRef* out) {
  bool ok = false;
  try {
    ok = eval();
  } catch (const InternalError&) {
    throw;
  } catch (const std::exception&) {
    return false;
  } catch (...) {
    return false;
  }
  if (ok && out != nullptr) ok = out->allFinite();
  return ok;
}

}  // namespace

void Nlp::set_variable_bounds(int k, double lo, double hi) {
  DISCO_CHECK(k >= 0 && k < num_variables(), "variable index out of range");
  z_lo_[k] = lo;
  z_hi_[k] = hi;
}

void Nlp::set_constraint_bounds(int r, double lo, double hi) {
  DISCO_CHECK(r >= 0 && r < num_constraints(), "constraint index out of range");
  c_lo_[r] = lo;
  c_hi_[r] = hi;
}

bool Nlp::objective(const ConstVectorRef& z, double& f) const {
  DISCO_CHECK(z.size() == num_variables(), "objective: z has the wrong size");
  bool ok = guarded([&] { return do_objective(z, f); }, nullptr);
  return ok && std::isfinite(f);
}

bool Nlp::gradient(const ConstVectorRef& z, VectorRef grad) const {
  DISCO_CHECK(z.size() == num_variables(), "gradient: z has the wrong size");
  DISCO_CHECK(grad.size() == num_variables(), "gradient: output has the wrong size");
  return guarded([&] { return do_gradient(z, grad); }, &grad);
}

bool Nlp::constraints(const ConstVectorRef& z, VectorRef c) const {
  DISCO_CHECK(z.size() == num_variables(), "constraints: z has the wrong size");
  DISCO_CHECK(c.size() == num_constraints(), "constraints: output has the wrong size");
  return guarded([&] { return do_constraints(z, c); }, &c);
}

bool Nlp::jacobian(const ConstVectorRef& z, VectorRef values) const {
  DISCO_CHECK(z.size() == num_variables(), "jacobian: z has the wrong size");
  DISCO_CHECK(values.size() == jac_.size(), "jacobian: output has the wrong size");
  return guarded([&] { return do_jacobian(z, values); }, &values);
}

bool Nlp::hessian(const ConstVectorRef& z, double sigma, const ConstVectorRef& lambda,
                  VectorRef values) const {
  DISCO_CHECK(z.size() == num_variables(), "hessian: z has the wrong size");
  DISCO_CHECK(lambda.size() == num_constraints(), "hessian: lambda has the wrong size");
  DISCO_CHECK(values.size() == hess_.size(), "hessian: output has the wrong size");
  return guarded([&] { return do_hessian(z, sigma, lambda, values); }, &values);
}

}  // namespace disco
