// Test-only helpers shared by the MPCC-layer tests (polynomial program,
// elastic NLP, Ipopt solver, textbook MPCCs). Header-only; everything inline.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/nlp/polynomial_program.h"

namespace disco::test_support {

// The `ipopt:` section of configs/disco.yaml (the settings file the test binary finds): the
// MPCC-layer tests solve with disco's own options, not a copy of them.
inline std::vector<IpoptOption> disco_yaml_ipopt_options() {
  return ipopt_options(Settings::load(default_settings_path()));
}

// The `ipopt:` and `kkt:` sections of configs/disco.yaml: an IpoptSolver as disco makes it.
inline IpoptSettings disco_yaml_ipopt_settings() {
  return ipopt_settings(Settings::load(default_settings_path()));
}

// disco.yaml's ipopt options with warm-started points pushed only 1e-9 inside their bounds
// (disco.yaml pushes 1e-3): for the tests of the adapter's warm start, which check that a
// solve restarted from a converged point and its duals is done at once (1-2 iterations);
// with 1e-3 pushes the point first moves off the optimum and takes an iteration or two more.
inline std::vector<IpoptOption> tight_warm_start_options() {
  std::vector<IpoptOption> options = disco_yaml_ipopt_options();
  for (const char* name : {"warm_start_bound_push", "warm_start_bound_frac", "warm_start_slack_bound_push",
                           "warm_start_slack_bound_frac", "warm_start_mult_bound_push"})
    options.push_back({name, "1e-9", "test: tight warm start"});
  return options;
}

// The `elastic:` section of configs/disco.yaml (the settings file the test binary finds).
inline ElasticSettings disco_yaml_elastic_settings() {
  return elastic_settings(Settings::load(default_settings_path()));
}

// A random polynomial program together with an independent record of what
// was added, so its rows can be evaluated without PolynomialProgram.
struct RandomProgram {
  struct Term {
    int row;  // PolynomialProgram::kObjective for the objective
    double coef;
    std::vector<Affine> factors;  // 1 to 3
  };
  PolynomialProgram program;
  std::vector<Term> terms;

  // Direct evaluation: sum of coef * prod factor values, in double.
  double reference_value(int row, const Eigen::VectorXd& z) const {
    double v = 0.0;
    for (const auto& t : terms) {
      if (t.row != row) continue;
      double p = t.coef;
      for (const auto& a : t.factors) p *= a.value(z);
      v += p;
    }
    return v;
  }
};

struct RandomProgramShape {
  int variables = 30;
  int rows = 20;
  int min_terms = 1, max_terms = 6;  // terms added per row / objective
  double repeat_probability = 0.35;  // a factor reuses the previous variable
  double affine_probability = 0.3;   // a factor is a 2-term affine + constant
};

// Rows and objective are sums of products of 1-3 factors; a factor is a
// single variable (often the previous factor's variable, giving x^2, x^3,
// x^2 y) or an affine expression with a constant.
inline RandomProgram make_random_program(unsigned seed, const RandomProgramShape& shape) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> var(0, shape.variables - 1);
  std::uniform_int_distribution<int> degree(1, 3);
  std::uniform_int_distribution<int> nterms(shape.min_terms, shape.max_terms);
  std::uniform_real_distribution<double> coef(-2.0, 2.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  RandomProgram out;
  auto& p = out.program;
  for (int k = 0; k < shape.variables; ++k) p.add_variable(-10.0, 10.0, 0.0);
  auto add_terms = [&](int row) {
    const int count = nterms(rng);
    for (int t = 0; t < count; ++t) {
      RandomProgram::Term term{row, coef(rng), {}};
      const int d = degree(rng);
      int last = var(rng);
      for (int f = 0; f < d; ++f) {
        if (f > 0 && unit(rng) >= shape.repeat_probability) last = var(rng);
        if (unit(rng) < shape.affine_probability) {
          Affine a = Affine::variable(last, coef(rng)) + Affine::variable(var(rng), coef(rng)) +
                     Affine(coef(rng));
          term.factors.push_back(a);
        } else {
          term.factors.push_back(Affine::variable(last));
        }
      }
      const auto& f = term.factors;
      if (d == 1) p.add(row, term.coef, f[0]);
      if (d == 2) p.add(row, term.coef, f[0], f[1]);
      if (d == 3) p.add(row, term.coef, f[0], f[1], f[2]);
      out.terms.push_back(std::move(term));
    }
  };
  for (int r = 0; r < shape.rows; ++r) {
    p.add_row(-1.0, 1.0);
    add_terms(r);
  }
  add_terms(PolynomialProgram::kObjective);
  p.finalize();
  return out;
}

inline Eigen::VectorXd random_vector(std::mt19937& rng, int n, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

// Minimum of a 1-D function on [a, b] by brute force: a grid of `cells`
// intervals, then golden-section refinement around the best grid point.
// `f` may return +inf for infeasible points; the function is assumed
// unimodal within one grid cell of its minimum. Returns {argmin, min}.
inline std::pair<double, double> minimize_1d(const std::function<double(double)>& f, double a,
                                             double b, int cells = 20000) {
  double best_x = a, best_f = std::numeric_limits<double>::infinity();
  const double h = (b - a) / cells;
  for (int i = 0; i <= cells; ++i) {
    const double x = (i == cells) ? b : a + i * h;
    const double v = f(x);
    if (v < best_f) {
      best_f = v;
      best_x = x;
    }
  }
  double lo = std::max(a, best_x - h), hi = std::min(b, best_x + h);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::abs(lo)); ++it) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  for (double x : {x1, x2, lo, hi}) {
    const double v = f(x);
    if (v < best_f) {
      best_f = v;
      best_x = x;
    }
  }
  return {best_x, best_f};
}

}  // namespace disco::test_support
