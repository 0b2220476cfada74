#include "core/nlp/polynomial_program.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/util/check.h"

namespace disco {

// ---------------------------------------------------------------- Affine ---

Affine& Affine::operator+=(const Affine& o) {
  terms.insert(terms.end(), o.terms.begin(), o.terms.end());
  constant += o.constant;
  return *this;
}

Affine& Affine::operator*=(double s) {
  for (auto& t : terms) t.second *= s;
  constant *= s;
  return *this;
}

double Affine::value(const ConstVectorRef& z) const {
  double v = constant;
  for (const auto& [k, c] : terms) v += c * z[k];
  return v;
}

// ------------------------------------------------------------- building ---

int PolynomialProgram::add_variable(double lo, double hi, double initial) {
  DISCO_CHECK(!finalized_, "add_variable after finalize");
  DISCO_CHECK(lo <= hi, "variable bounds lo > hi");
  const int k = num_variables();
  z_lo_.conservativeResize(k + 1);
  z_hi_.conservativeResize(k + 1);
  z0_.conservativeResize(k + 1);
  z_lo_[k] = lo;
  z_hi_[k] = hi;
  z0_[k] = initial;
  return k;
}

int PolynomialProgram::add_row(double lo, double hi, int tag) {
  DISCO_CHECK(!finalized_, "add_row after finalize");
  DISCO_CHECK(lo <= hi, "row bounds lo > hi");
  const int r = num_constraints();
  c_lo_.conservativeResize(r + 1);
  c_hi_.conservativeResize(r + 1);
  c_lo_[r] = lo;
  c_hi_[r] = hi;
  row_tags_.push_back(tag);
  building_.emplace_back();
  constant_.push_back(0.0);
  return r;
}

void PolynomialProgram::add(int r, double coef, const Affine& a) {
  const Affine* f[] = {&a};
  add_expanded(r, coef, f, 1);
}

void PolynomialProgram::add(int r, double coef, const Affine& a, const Affine& b) {
  const Affine* f[] = {&a, &b};
  add_expanded(r, coef, f, 2);
}

void PolynomialProgram::add(int r, double coef, const Affine& a, const Affine& b,
                            const Affine& c) {
  const Affine* f[] = {&a, &b, &c};
  add_expanded(r, coef, f, 3);
}

void PolynomialProgram::add_expanded(int r, double coef, const Affine* const* factors,
                                     int count) {
  DISCO_CHECK(!finalized_, "add after finalize");
  // Each factor contributes either one of its terms or its constant: expand
  // the product over all choices. Index t == terms.size() means "constant".
  int choice[3] = {0, 0, 0};
  while (true) {
    double c = coef;
    int v[3] = {-1, -1, -1};
    int nv = 0;
    for (int f = 0; f < count; ++f) {
      const Affine& a = *factors[f];
      if (choice[f] < static_cast<int>(a.terms.size())) {
        c *= a.terms[choice[f]].second;
        v[nv++] = a.terms[choice[f]].first;
      } else {
        c *= a.constant;
      }
    }
    if (c != 0.0) add_monomial(r, c, v[0], v[1], v[2]);
    // Next choice (odometer).
    int f = 0;
    for (; f < count; ++f) {
      if (++choice[f] <= static_cast<int>(factors[f]->terms.size())) break;
      choice[f] = 0;
    }
    if (f == count) break;
  }
}

void PolynomialProgram::add_monomial(int r, double coef, int a, int b, int c) {
  DISCO_CHECK(r == kObjective || (r >= 0 && r < num_constraints()), "row out of range");
  for (int k : {a, b, c}) DISCO_CHECK(k < num_variables(), "variable out of range");
  if (a < 0 && b < 0 && c < 0) {  // a constant
    if (r == kObjective) {
      objective_constant_ += coef;
    } else {
      constant_[r] += coef;
    }
    return;
  }
  Monomial m{coef, {a, b, c}};
  // Sort with -1 (absent) last.
  auto key = [](int x) { return x < 0 ? INT32_MAX : x; };
  std::sort(m.v, m.v + 3, [&](int x, int y) { return key(x) < key(y); });
  (r == kObjective ? objective_ : building_[r]).push_back(m);
}

void PolynomialProgram::add_function(int r, double coef, std::shared_ptr<const UnivariateFunction> g,
                                     int k, double scale) {
  DISCO_CHECK(!finalized_, "add_function after finalize");
  DISCO_CHECK(r == kObjective || (r >= 0 && r < num_constraints()), "row out of range");
  DISCO_CHECK(k >= 0 && k < num_variables(), "variable out of range");
  DISCO_CHECK(g != nullptr, "a function term without a function");
  if (coef == 0.0) return;
  fterm_.push_back({r, coef, g.get(), k, scale});
  functions_.push_back(std::move(g));
}

void PolynomialProgram::add_pair(ComplementaritySide g, ComplementaritySide h) {
  DISCO_CHECK(!finalized_, "add_pair after finalize");
  pairs_.push_back({g, h});
}

// ------------------------------------------------------------- compiling ---

namespace {

// Entries keyed by (row, col) -> list of contributions, kept in insertion order.
struct Contribution {
  int row;
  double coef;
  int u, w;
  int fn = -1;  // a function term's derivative instead of coef * z_u * z_w
};
using EntryMap = std::map<std::pair<int, int>, std::vector<Contribution>>;

}  // namespace

void PolynomialProgram::finalize() {
  DISCO_CHECK(!finalized_, "finalize twice");
  const int m = num_constraints();
  row_begin_.assign(1, 0);
  EntryMap jac, hess;
  // Function terms by row (the objective, kObjective, is row m), in the order added.
  for (auto& f : fterm_)
    if (f.row == kObjective) f.row = m;
  std::stable_sort(fterm_.begin(), fterm_.end(),
                   [](const FunctionTerm& a, const FunctionTerm& b) { return a.row < b.row; });
  fterm_begin_.assign(m + 2, 0);
  for (const auto& f : fterm_) ++fterm_begin_[f.row + 1];
  for (int r = 0; r <= m; ++r) fterm_begin_[r + 1] += fterm_begin_[r];
  for (int r = 0; r <= m; ++r) {
    auto& monos = r < m ? building_[r] : objective_;
    // Merge equal monomials of a row (same variables), keeping first-seen order.
    std::map<std::tuple<int, int, int>, int> seen;
    std::vector<Monomial> merged;
    for (const auto& mo : monos) {
      auto key = std::make_tuple(mo.v[0], mo.v[1], mo.v[2]);
      auto it = seen.find(key);
      if (it == seen.end()) {
        seen.emplace(key, static_cast<int>(merged.size()));
        merged.push_back(mo);
      } else {
        merged[it->second].coef += mo.coef;
      }
    }
    for (const auto& mo : merged) {
      if (mo.coef == 0.0) continue;
      mono_coef_.push_back(mo.coef);
      mono_v_.insert(mono_v_.end(), mo.v, mo.v + 3);
      const int deg = (mo.v[0] >= 0) + (mo.v[1] >= 0) + (mo.v[2] >= 0);
      // First derivatives: one contribution per factor position p.
      for (int p = 0; p < deg; ++p) {
        int rest[2] = {-1, -1}, nr = 0;
        for (int s = 0; s < deg; ++s)
          if (s != p) rest[nr++] = mo.v[s];
        jac[{r, mo.v[p]}].push_back({r, mo.coef, rest[0], rest[1]});
      }
      // Second derivatives: one contribution per unordered position pair
      // {p, q}, on the lower triangle; a diagonal entry gets both orders.
      for (int p = 0; p < deg; ++p) {
        for (int q = p + 1; q < deg; ++q) {
          int rest = -1;
          for (int s = 0; s < deg; ++s)
            if (s != p && s != q) rest = mo.v[s];
          const int a = std::max(mo.v[p], mo.v[q]), b = std::min(mo.v[p], mo.v[q]);
          hess[{a, b}].push_back({r, a == b ? 2.0 * mo.coef : mo.coef, rest, -1});
        }
      }
    }
    for (int f = fterm_begin_[r]; f < fterm_begin_[r + 1]; ++f) {
      const int k = fterm_[f].var;
      jac[{r, k}].push_back({r, 0.0, -1, -1, f});
      hess[{k, k}].push_back({r, 0.0, -1, -1, f});
    }
    row_begin_.push_back(static_cast<int>(mono_coef_.size()));
  }
  constant_.push_back(objective_constant_);
  building_.clear();
  building_.shrink_to_fit();
  objective_.clear();

  auto compile = [](const std::vector<Contribution>& list, Contributions& out) {
    for (const auto& c : list) {
      out.row.push_back(c.row);
      out.coef.push_back(c.coef);
      out.u.push_back(c.u);
      out.w.push_back(c.w);
      out.fn.push_back(c.fn);
    }
    out.begin.push_back(static_cast<int>(out.row.size()));
  };
  jac_c_.begin.assign(1, 0);
  grad_c_.begin.assign(1, 0);
  hess_c_.begin.assign(1, 0);
  for (const auto& [rc, list] : jac) {  // map order: by row, then column
    if (rc.first == m) {
      grad_var_.push_back(rc.second);
      compile(list, grad_c_);
    } else {
      jac_.add(rc.first, rc.second);
      compile(list, jac_c_);
    }
  }
  for (const auto& [rc, list] : hess) {
    hess_.add(rc.first, rc.second);
    compile(list, hess_c_);
  }
  finalized_ = true;
}

// ------------------------------------------------------------ evaluating ---

namespace {

inline double factor(const ConstVectorRef& z, int k) { return k >= 0 ? z[k] : 1.0; }

}  // namespace

double PolynomialProgram::row_value(int r, const ConstVectorRef& z) const {
  double v = constant_[r];
  for (int i = row_begin_[r]; i < row_begin_[r + 1]; ++i) {
    const int* var = &mono_v_[3 * i];
    v += mono_coef_[i] * factor(z, var[0]) * factor(z, var[1]) * factor(z, var[2]);
  }
  for (int f = fterm_begin_[r]; f < fterm_begin_[r + 1]; ++f) {
    const FunctionTerm& ft = fterm_[f];
    v += ft.coef * ft.g->eval(ft.scale * z[ft.var])[0];
  }
  return v;
}

double PolynomialProgram::function_derivative(int f, const ConstVectorRef& z, int order) const {
  const FunctionTerm& ft = fterm_[f];
  const double d = ft.g->eval(ft.scale * z[ft.var])[order];
  return order == 1 ? ft.coef * ft.scale * d : ft.coef * ft.scale * ft.scale * d;
}

bool PolynomialProgram::do_objective(const ConstVectorRef& z, double& f) const {
  DISCO_CHECK(finalized_, "evaluate before finalize");
  f = row_value(num_constraints(), z);
  return true;
}

bool PolynomialProgram::do_gradient(const ConstVectorRef& z, VectorRef grad) const {
  DISCO_CHECK(finalized_, "evaluate before finalize");
  grad.setZero();
  const auto& C = grad_c_;
  for (size_t e = 0; e < grad_var_.size(); ++e) {
    double v = 0.0;
    for (int i = C.begin[e]; i < C.begin[e + 1]; ++i)
      v += C.fn[i] >= 0 ? function_derivative(C.fn[i], z, 1)
                        : C.coef[i] * factor(z, C.u[i]) * factor(z, C.w[i]);
    grad[grad_var_[e]] = v;
  }
  return true;
}

bool PolynomialProgram::do_constraints(const ConstVectorRef& z, VectorRef c) const {
  DISCO_CHECK(finalized_, "evaluate before finalize");
  const int m = num_constraints();
#pragma omp parallel for schedule(static) if (m >= parallel_min_)
  for (int r = 0; r < m; ++r) c[r] = row_value(r, z);
  return true;
}

bool PolynomialProgram::do_jacobian(const ConstVectorRef& z, VectorRef values) const {
  DISCO_CHECK(finalized_, "evaluate before finalize");
  const auto& C = jac_c_;
  const int nnz = jac_.size();
#pragma omp parallel for schedule(static) if (nnz >= parallel_min_)
  for (int e = 0; e < nnz; ++e) {
    double v = 0.0;
    for (int i = C.begin[e]; i < C.begin[e + 1]; ++i)
      v += C.fn[i] >= 0 ? function_derivative(C.fn[i], z, 1)
                        : C.coef[i] * factor(z, C.u[i]) * factor(z, C.w[i]);
    values[e] = v;
  }
  return true;
}

bool PolynomialProgram::do_hessian(const ConstVectorRef& z, double sigma,
                                   const ConstVectorRef& lambda, VectorRef values) const {
  DISCO_CHECK(finalized_, "evaluate before finalize");
  const auto& C = hess_c_;
  const int m = num_constraints();
  const int nnz = hess_.size();
#pragma omp parallel for schedule(static) if (nnz >= parallel_min_)
  for (int e = 0; e < nnz; ++e) {
    double v = 0.0;
    for (int i = C.begin[e]; i < C.begin[e + 1]; ++i) {
      const double weight = C.row[i] == m ? sigma : lambda[C.row[i]];
      v += C.fn[i] >= 0 ? weight * function_derivative(C.fn[i], z, 2) : weight * C.coef[i] * factor(z, C.u[i]);
    }
    values[e] = v;
  }
  return true;
}

}  // namespace disco
