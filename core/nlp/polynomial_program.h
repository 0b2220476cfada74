// disco — an MPCC whose objective and rows are polynomials of degree <= 3, plus
// given smooth functions of one variable.
//
// Every row is a sum of monomials  coef * z_a * z_b * z_c  (fewer factors
// allowed, repeated variables allowed) plus a constant, plus terms
// coef * g(a * z_k) with g a UnivariateFunction (below): a path given by the user
// in time, evaluated at tau = (t / N) T_f (core/model/obstacle_path.h). The robot model is of
// this form once the centre distance is a variable (see
// core/model/nonpenetration.h), so one evaluator with exact derivatives serves
// every constraint family, and each family only states its equation:
//
//     P.add(row, -1.0, h, cn, Nx);      // adds -h * c_n * N_x to the row
//
// where each factor is an Affine expression (variables with coefficients plus a
// constant) and the product is expanded into monomials when added.
//
// A function term coef * g(a z_k) has the derivatives coef * a * g'(a z_k) and
// coef * a^2 * g''(a z_k), at the (r, k) and (k, k) entries; they are as exact as g's
// own (UnivariateFunction's contract).
//
// Derivatives (exact, per Nlp's contract). For a monomial m = c * prod_p z_{v_p}:
//     dm/dz_k       = sum_{p : v_p = k} c * prod_{s != p} z_{v_s}
//     d2m/dz_k dz_l = sum_{p != q : v_p = k, v_q = l} c * prod_{s != p, q} z_{v_s}
// finalize() compiles, once, for every Jacobian and Hessian nonzero the list
// of its contributions (row, coefficient, remaining variables). Evaluation then
// writes every value in place, without allocation, in parallel (OpenMP) over
// rows and nonzeros. Each output is summed by one thread in a fixed order, so
// results are bitwise identical for any thread count.
#pragma once

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "core/nlp/mpcc.h"

namespace disco {

// sum_k coef_k * z_{var_k} + constant.
struct Affine {
  std::vector<std::pair<int, double>> terms;
  double constant = 0.0;

  Affine() = default;
  Affine(double c) : constant(c) {}  // NOLINT: a constant is an Affine
  static Affine variable(int k, double coef = 1.0) {
    Affine a;
    a.terms.push_back({k, coef});
    return a;
  }
  Affine& operator+=(const Affine& o);
  Affine& operator*=(double s);
  friend Affine operator+(Affine a, const Affine& b) { return a += b; }
  friend Affine operator-(Affine a, const Affine& b) { return a += b * -1.0; }
  friend Affine operator*(Affine a, double s) { return a *= s; }
  friend Affine operator*(double s, Affine a) { return a *= s; }
  friend Affine operator-(Affine a) { return a *= -1.0; }
  double value(const ConstVectorRef& z) const;
};

// A function of one real variable, twice continuously differentiable where a program
// evaluates it, that returns its value, first and second derivative at x, exactly (to
// roundoff). It must be safe to call from several threads at once.
class UnivariateFunction {
 public:
  virtual ~UnivariateFunction() = default;
  virtual std::array<double, 3> eval(double x) const = 0;
};

class PolynomialProgram : public Mpcc {
 public:
  static constexpr int kObjective = -1;  // row index that means "the objective"

  // --- building (before finalize) ---------------------------------------
  int add_variable(double lo, double hi, double initial = 0.0);
  // `tag` (>= 0, or -1 for none) names who the row belongs to, for reports (row_tag).
  int add_row(double lo, double hi, int tag = -1);
  int row_tag(int r) const { return row_tags_[r]; }
  // Adds coef * a (* b (* c)) to row r (or to the objective, r = kObjective).
  void add(int r, double coef, const Affine& a);
  void add(int r, double coef, const Affine& a, const Affine& b);
  void add(int r, double coef, const Affine& a, const Affine& b, const Affine& c);
  // Adds coef * g(scale * z_k) to row r (or to the objective).
  void add_function(int r, double coef, std::shared_ptr<const UnivariateFunction> g, int k,
                    double scale = 1.0);
  void add_pair(ComplementaritySide g, ComplementaritySide h);
  // Compiles the derivative structure; no building afterwards.
  void finalize();

  bool finalized() const { return finalized_; }
  // Loops over fewer outputs (rows, nonzeros) than this run on one thread:
  // below it forking costs more than the work (evaluation is ~1 % of a solve
  // here; MUMPS is the rest). Tests lower it to exercise the parallel path.
  static constexpr int kDefaultParallelMin = 16384;
  void set_parallel_threshold(int outputs) { parallel_min_ = outputs; }
  int parallel_threshold() const { return parallel_min_; }
  // A starting point stored with the variables (add_variable's `initial`).
  const Vector& initial_point() const { return z0_; }
  Vector& initial_point() { return z0_; }
  int num_monomials() const { return static_cast<int>(mono_coef_.size()); }
  int num_function_terms() const { return static_cast<int>(fterm_.size()); }

 private:
  struct Monomial {
    double coef;
    int v[3];  // sorted, -1 for absent factors (at the end)
  };
  void add_monomial(int r, double coef, int a, int b, int c);
  void add_expanded(int r, double coef, const Affine* const* factors, int count);

  bool do_objective(const ConstVectorRef& z, double& f) const override;
  bool do_gradient(const ConstVectorRef& z, VectorRef grad) const override;
  bool do_constraints(const ConstVectorRef& z, VectorRef c) const override;
  bool do_jacobian(const ConstVectorRef& z, VectorRef values) const override;
  bool do_hessian(const ConstVectorRef& z, double sigma, const ConstVectorRef& lambda,
                  VectorRef values) const override;

  double row_value(int r, const ConstVectorRef& z) const;
  // Derivative `order` (1 or 2) of function term f at z, with its coefficient and scale.
  double function_derivative(int f, const ConstVectorRef& z, int order) const;

  bool finalized_ = false;
  int parallel_min_ = kDefaultParallelMin;
  Vector z0_;
  // Building: monomials per row (index m = objective) and row constants.
  std::vector<std::vector<Monomial>> building_;
  std::vector<Monomial> objective_;
  double objective_constant_ = 0.0;
  std::vector<double> constant_;  // per row; after finalize, index m = objective
  std::vector<int> row_tags_;     // per row (add_row's tag)

  // Compiled rows: monomials of row r are [row_begin_[r], row_begin_[r+1]); row m = objective.
  std::vector<int> row_begin_;
  std::vector<double> mono_coef_;
  std::vector<int> mono_v_;  // 3 per monomial

  // Function terms coef * g(scale * z_var); those of row r are [fterm_begin_[r],
  // fterm_begin_[r+1]) after finalize (sorted by row; row m = objective).
  struct FunctionTerm {
    int row;
    double coef;
    const UnivariateFunction* g;
    int var;
    double scale;
  };
  std::vector<FunctionTerm> fterm_;
  std::vector<int> fterm_begin_;
  std::vector<std::shared_ptr<const UnivariateFunction>> functions_;  // owns every g

  // A contribution to one derivative entry: weight(row) * coef * z_u * z_w
  // (u, w = -1 when absent; w is always -1 for the Hessian), or, where fn >= 0,
  // weight(row) times the derivative of function term fn.
  struct Contributions {
    std::vector<int> begin;  // per entry, CSR into the arrays below
    std::vector<int> row;
    std::vector<double> coef;
    std::vector<int> u, w;
    std::vector<int> fn;
  };
  Contributions jac_c_;   // per Jacobian nonzero
  Contributions grad_c_;  // per gradient entry (objective row)
  std::vector<int> grad_var_;
  Contributions hess_c_;  // per Hessian nonzero
};

}  // namespace disco
