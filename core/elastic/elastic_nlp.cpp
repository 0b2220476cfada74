#include "core/elastic/elastic_nlp.h"

#include <algorithm>
#include <map>

#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {

void ElasticNlp::set_relaxation(double sigma) {
  DISCO_CHECK(eps_ >= 0 && sigma >= 0, "a relaxation needs the lumped row and sigma >= 0");
  set_constraint_bounds(m_, -kInf, sigma);
}

void ElasticNlp::set_live_relaxation(double sigma) {
  DISCO_CHECK(formulation_ == ElasticFormulation::kBarrier && sigma >= 0,
              "a live relaxation needs formulation barrier and sigma >= 0");
  live_sigma_ = sigma;
}

ElasticNlp::ElasticNlp(const Mpcc& mpcc, ElasticFormulation formulation, double zeta)
    : mpcc_(mpcc), formulation_(formulation), zeta_(zeta) {
  n_ = mpcc.num_variables();
  m_ = mpcc.num_constraints();
  const auto& pairs = mpcc.complementarity_pairs();

  // Variables: z, then one slack per distinct row side, then eps.
  std::map<int, int> slack_of_row;
  int nvar = n_;
  auto side_var = [&](const ComplementaritySide& s) {
    if (s.kind == ComplementaritySide::Kind::kVariable) {
      DISCO_CHECK(s.index >= 0 && s.index < n_, "complementarity variable out of range");
      return s.index;
    }
    DISCO_CHECK(s.index >= 0 && s.index < m_, "complementarity row out of range");
    auto [it, inserted] = slack_of_row.emplace(s.index, nvar);
    if (inserted) {
      side_row_.push_back(s.index);
      slack_.push_back(nvar++);
    }
    return it->second;
  };
  for (const auto& p : pairs) {
    u_.push_back(side_var(p.g));
    w_.push_back(side_var(p.h));
  }
  const bool lumped_row = formulation_ == ElasticFormulation::kLumped ||
                          formulation_ == ElasticFormulation::kRelaxed;
  pair_rows_ = formulation_ == ElasticFormulation::kBarrier;
  if (lumped_row || pair_rows_) eps_ = nvar++;
  const int np = static_cast<int>(pairs.size());
  const int nrow = m_ + (lumped_row ? 1 : 0) + (pair_rows_ ? np : 0);

  z_lo_.resize(nvar);
  z_hi_.resize(nvar);
  z_lo_.head(n_) = mpcc.variable_lower();
  z_hi_.head(n_) = mpcc.variable_upper();
  c_lo_.resize(nrow);
  c_hi_.resize(nrow);
  c_lo_.head(m_) = mpcc.constraint_lower();
  c_hi_.head(m_) = mpcc.constraint_upper();
  for (size_t k = 0; k < side_row_.size(); ++k) {
    const int r = side_row_[k], s = slack_[k];
    z_lo_[s] = std::max(0.0, c_lo_[r]);
    z_hi_[s] = c_hi_[r];
    c_lo_[r] = c_hi_[r] = 0.0;
  }
  for (int i = 0; i < static_cast<int>(pairs.size()); ++i) {
    for (int v : {u_[i], w_[i]}) {
      z_lo_[v] = std::max(z_lo_[v], 0.0);
      DISCO_CHECK(z_lo_[v] <= z_hi_[v], "complementarity side with an upper bound below 0");
    }
  }
  if (eps_ >= 0) {
    z_lo_[eps_] = 0.0;
    z_hi_[eps_] = kInf;
    c_lo_.tail(nrow - m_).setConstant(-kInf);
    c_hi_.tail(nrow - m_).setZero();
  }

  // Jacobian: the MPCC's entries, then -1 per slack, then the lumped row.
  jac_ = mpcc.jacobian_pattern();
  mpcc_jac_nnz_ = jac_.size();
  for (size_t k = 0; k < side_row_.size(); ++k) jac_.add(side_row_[k], slack_[k]);
  // Gradient structure of P(x) = sum u_i w_i, by variable.
  std::map<int, std::vector<int>> partners;
  for (size_t i = 0; i < u_.size(); ++i) {
    partners[u_[i]].push_back(w_[i]);
    partners[w_[i]].push_back(u_[i]);
  }
  grad_begin_.push_back(0);
  for (const auto& [var, list] : partners) {
    grad_var_.push_back(var);
    grad_partner_.insert(grad_partner_.end(), list.begin(), list.end());
    grad_begin_.push_back(static_cast<int>(grad_partner_.size()));
  }
  if (pair_rows_) {
    for (int i = 0; i < np; ++i) {
      DISCO_CHECK(u_[i] != w_[i], "a pair's two sides are one variable");
      jac_.add(m_ + i, u_[i]);
      jac_.add(m_ + i, w_[i]);
      jac_.add(m_ + i, eps_);
    }
  } else if (eps_ >= 0) {
    for (int var : grad_var_) jac_.add(m_, var);
    jac_.add(m_, eps_);
  }

  // Hessian: the MPCC's entries, then the (u_i, w_i) entries not yet present.
  hess_ = mpcc.hessian_pattern();
  mpcc_hess_nnz_ = hess_.size();
  std::map<std::pair<int, int>, int> entry;
  for (int e = 0; e < hess_.size(); ++e) entry[{hess_.rows[e], hess_.cols[e]}] = e;
  for (size_t i = 0; i < u_.size(); ++i) {
    const int a = std::max(u_[i], w_[i]), b = std::min(u_[i], w_[i]);
    auto [it, inserted] = entry.emplace(std::make_pair(a, b), hess_.size());
    if (inserted) hess_.add(a, b);
    pair_hess_entry_.push_back(it->second);
    pair_hess_mult_.push_back(a == b ? 2.0 : 1.0);
  }
}

Vector ElasticNlp::lift(const ConstVectorRef& z) const {
  DISCO_CHECK(z.size() == n_, "lift: wrong size");
  Vector x = Vector::Zero(num_variables());
  x.head(n_) = z;
  Vector c(m_);
  if (!mpcc_.constraints(z, c)) c.setZero();
  for (size_t k = 0; k < side_row_.size(); ++k) x[slack_[k]] = c[side_row_[k]];
  if (pair_rows_) {
    for (size_t i = 0; i < u_.size(); ++i) x[eps_] = std::max(x[eps_], x[u_[i]] * x[w_[i]]);
  } else if (eps_ >= 0) {
    x[eps_] = std::max(0.0, product_sum(x));
  }
  return x;
}

double ElasticNlp::product_sum(const ConstVectorRef& x) const {
  double p = 0.0;
  for (size_t i = 0; i < u_.size(); ++i) p += x[u_[i]] * x[w_[i]];
  return p;
}

bool ElasticNlp::do_objective(const ConstVectorRef& x, double& f) const {
  if (!mpcc_.objective(x.head(n_), f)) return false;
  f += zeta_ * (eps_ >= 0 ? x[eps_] : product_sum(x));
  return true;
}

bool ElasticNlp::do_gradient(const ConstVectorRef& x, VectorRef grad) const {
  grad.setZero();
  if (!mpcc_.gradient(x.head(n_), grad.head(n_))) return false;
  if (eps_ >= 0) {
    grad[eps_] = zeta_;
    return true;
  }
  for (size_t k = 0; k < grad_var_.size(); ++k) {
    double d = 0.0;
    for (int i = grad_begin_[k]; i < grad_begin_[k + 1]; ++i) d += x[grad_partner_[i]];
    grad[grad_var_[k]] += zeta_ * d;
  }
  return true;
}

bool ElasticNlp::do_constraints(const ConstVectorRef& x, VectorRef c) const {
  if (!mpcc_.constraints(x.head(n_), c.head(m_))) return false;
  for (size_t k = 0; k < side_row_.size(); ++k) c[side_row_[k]] -= x[slack_[k]];
  if (pair_rows_) {
    for (size_t i = 0; i < u_.size(); ++i)
      c[m_ + i] = x[u_[i]] * x[w_[i]] - live_sigma_ - x[eps_];
  } else if (eps_ >= 0) {
    c[m_] = product_sum(x) - x[eps_];
  }
  return true;
}

bool ElasticNlp::do_jacobian(const ConstVectorRef& x, VectorRef values) const {
  if (!mpcc_.jacobian(x.head(n_), values.head(mpcc_jac_nnz_))) return false;
  int e = mpcc_jac_nnz_;
  for (size_t k = 0; k < side_row_.size(); ++k) values[e++] = -1.0;
  if (pair_rows_) {
    for (size_t i = 0; i < u_.size(); ++i) {
      values[e++] = x[w_[i]];
      values[e++] = x[u_[i]];
      values[e++] = -1.0;
    }
  } else if (eps_ >= 0) {
    for (size_t k = 0; k < grad_var_.size(); ++k) {
      double d = 0.0;
      for (int i = grad_begin_[k]; i < grad_begin_[k + 1]; ++i) d += x[grad_partner_[i]];
      values[e++] = d;
    }
    values[e++] = -1.0;
  }
  return true;
}

bool ElasticNlp::do_hessian(const ConstVectorRef& x, double sigma, const ConstVectorRef& lambda,
                            VectorRef values) const {
  values.setZero();
  if (!mpcc_.hessian(x.head(n_), sigma, lambda.head(m_), values.head(mpcc_hess_nnz_)))
    return false;
  // d2/du dw of weight * u * w: the pair's row's multiplier, the lumped row's, or sigma * zeta.
  const double weight = eps_ >= 0 ? lambda[m_] : sigma * zeta_;
  for (size_t i = 0; i < u_.size(); ++i)
    values[pair_hess_entry_[i]] += (pair_rows_ ? lambda[m_ + i] : weight) * pair_hess_mult_[i];
  return true;
}

}  // namespace disco
