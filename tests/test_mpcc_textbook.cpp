// Standard MPCC test problems with known optima, solved by ElasticSolver +
// IpoptSolver (options of configs/disco.yaml), in every elastic formulation (lumped,
// per pair: with and without polishing; relaxed: with polishing, which it needs).
// Every reference optimum is recomputed here
// independently of the solver (enumeration of complementarity branches, or
// brute force over the upper-level variable with the lower level solved in
// closed form), and the literature value is asserted against it as well.
//
// Problems:
//   ScheelScholtes  min (x-1)^2 + (y-1)^2, 0 <= x _|_ y >= 0          f* = 1
//   Ralph           min x^2 + y^2 - 4xy,  0 <= x _|_ y >= 0           f* = 0 (degenerate)
//   Bard1           Bard (1988) bilevel, MacMPEC bard1                 f* = 17 at (1, 0)
//   DeSilva         MacMPEC desilva (bilevel, degenerate at optimum)  f* = -1
//   Gauvin          MacMPEC gauvin (bilevel, row sides only)          f* = 20 at (2, 14)
//   ExpSqrt         hand-written, non-polynomial Mpcc (exp, sqrt, sin)
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <cstdio>
#include <algorithm>
#include <sstream>
#include <tuple>

#include "core/elastic/elastic_solver.h"
#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/check.h"
#include "core/util/numbers.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using test_support::disco_yaml_ipopt_settings;
using test_support::expect_exact_derivatives;
using test_support::minimize_1d;
using S = ComplementaritySide;

Affine V(int k, double c = 1.0) { return Affine::variable(k, c); }

// ------------------------------------------------------------ problems ---

// The MPCC, its start point, and its reference optimum (value, point, and
// which coordinates of the point are unique and hence compared).
struct Problem {
  std::unique_ptr<Mpcc> mpcc;
  Vector start;
  double f_ref = 0.0;
  std::vector<Vector> z_refs;   // global minimizers (any one may be reached)
  std::vector<int> compare;     // coordinates compared with z_refs
  // Extra check on the solution, e.g. lower-level optimality of a bilevel
  // program: returns the error.
  std::function<double(const Vector&)> extra_error;
};

std::unique_ptr<PolynomialProgram> finalize(std::unique_ptr<PolynomialProgram> p) {
  p->finalize();
  return p;
}

// Scheel & Scholtes (2000): min (x-1)^2 + (y-1)^2, 0 <= x _|_ y >= 0.
// Two global minimizers (1, 0) and (0, 1), f* = 1; start favours (1, 0).
Problem scheel_scholtes() {
  auto p = std::make_unique<PolynomialProgram>();
  p->add_variable(-kInf, kInf, 1.0);
  p->add_variable(-kInf, kInf, 0.2);
  for (int k : {0, 1}) {
    p->add(PolynomialProgram::kObjective, 1.0, V(k) - Affine(1.0), V(k) - Affine(1.0));
  }
  p->add_pair(S::variable(0), S::variable(1));
  Problem out;
  out.start = p->initial_point();
  out.mpcc = finalize(std::move(p));
  // Branch enumeration: x = 0 (y >= 0 free) or y = 0 (x >= 0 free).
  auto f = [](double x, double y) { return (x - 1) * (x - 1) + (y - 1) * (y - 1); };
  const auto [ya, fa] = minimize_1d([&](double y) { return f(0, y); }, 0.0, 10.0);
  const auto [xb, fb] = minimize_1d([&](double x) { return f(x, 0); }, 0.0, 10.0);
  out.f_ref = std::min(fa, fb);
  if (fa <= out.f_ref + 1e-12) out.z_refs.push_back((Vector(2) << 0.0, ya).finished());
  if (fb <= out.f_ref + 1e-12) out.z_refs.push_back((Vector(2) << xb, 0.0).finished());
  out.compare = {0, 1};
  return out;
}

// Ralph's degenerate example (MacMPEC ralph2): min x^2 + y^2 - 4xy,
// 0 <= x _|_ y >= 0. f* = 0 at (0, 0), where both sides vanish.
Problem ralph() {
  auto p = std::make_unique<PolynomialProgram>();
  p->add_variable(0.0, kInf, 1.0);
  p->add_variable(0.0, kInf, 1.0);
  p->add(PolynomialProgram::kObjective, 1.0, V(0), V(0));
  p->add(PolynomialProgram::kObjective, 1.0, V(1), V(1));
  p->add(PolynomialProgram::kObjective, -4.0, V(0), V(1));
  p->add_pair(S::variable(0), S::variable(1));
  Problem out;
  out.start = p->initial_point();
  out.mpcc = finalize(std::move(p));
  auto f = [](double x, double y) { return x * x + y * y - 4 * x * y; };
  const auto [ya, fa] = minimize_1d([&](double y) { return f(0, y); }, 0.0, 10.0);
  const auto [xb, fb] = minimize_1d([&](double x) { return f(x, 0); }, 0.0, 10.0);
  out.f_ref = std::min(fa, fb);
  out.z_refs.push_back(Vector::Zero(2));
  EXPECT_NEAR(ya, 0.0, 1e-7);
  EXPECT_NEAR(xb, 0.0, 1e-7);
  out.compare = {0, 1};
  return out;
}

// Bard (1988), MacMPEC bard1, with the lower level's bound y >= 0 as a
// fourth complementarity pair:
//   min (x-5)^2 + (2y+1)^2
//   y solves min_y (y-1)^2 - 1.5 x y  s.t. g1 = 3x - y - 3 >= 0,
//            g2 = -x + 0.5y + 4 >= 0, g3 = -x - y + 7 >= 0, y >= 0.
// KKT: 2(y-1) - 1.5x + l1 - 0.5 l2 + l3 - l4 = 0, 0 <= l_i _|_ g_i >= 0,
// 0 <= l4 _|_ y >= 0. f* = 17 at (x, y) = (1, 0); the multipliers are not
// unique there (l1 - l4 = 3.5), so only (x, y) is compared.
// Variables: x, y, l1, l2, l3, l4.
double bard1_lower_level(double x) {  // closed-form y*(x), NaN if infeasible
  const double lo = std::max(0.0, 2 * x - 8);
  double hi = std::min(3 * x - 3, 7 - x);
  if (lo > hi + 1e-9) return std::nan("");  // (tolerance: x = 1 - 1e-16 is feasible enough)
  hi = std::max(hi, lo);
  return std::clamp(1 + 0.75 * x, lo, hi);  // convex 1-D QP: clamp the free minimizer
}

Problem bard1() {
  auto p = std::make_unique<PolynomialProgram>();
  const int x = p->add_variable(0.0, kInf, 1.5), y = p->add_variable(0.0, kInf, 1.0);
  int l[4];
  for (int i = 0; i < 4; ++i) l[i] = p->add_variable(-kInf, kInf, 0.0);
  const int kkt = p->add_row(0, 0);
  p->add(kkt, 1.0, 2.0 * V(y) - Affine(2.0) - 1.5 * V(x) + V(l[0]) - 0.5 * V(l[1]) + V(l[2]) -
                       V(l[3]));
  const int g1 = p->add_row(-kInf, kInf), g2 = p->add_row(-kInf, kInf),
            g3 = p->add_row(-kInf, kInf);
  p->add(g1, 1.0, 3.0 * V(x) - V(y) - Affine(3.0));
  p->add(g2, 1.0, -1.0 * V(x) + 0.5 * V(y) + Affine(4.0));
  p->add(g3, 1.0, -1.0 * V(x) - V(y) + Affine(7.0));
  p->add(PolynomialProgram::kObjective, 1.0, V(x) - Affine(5.0), V(x) - Affine(5.0));
  p->add(PolynomialProgram::kObjective, 1.0, 2.0 * V(y) + Affine(1.0), 2.0 * V(y) + Affine(1.0));
  p->add_pair(S::row(g1), S::variable(l[0]));
  p->add_pair(S::row(g2), S::variable(l[1]));
  p->add_pair(S::row(g3), S::variable(l[2]));
  p->add_pair(S::variable(y), S::variable(l[3]));
  Problem out;
  out.start = p->initial_point();
  out.mpcc = finalize(std::move(p));
  // Brute force over x with the lower level in closed form.
  auto F = [](double xv) {
    const double yv = bard1_lower_level(xv);
    if (std::isnan(yv)) return kInf;
    return (xv - 5) * (xv - 5) + (2 * yv + 1) * (2 * yv + 1);
  };
  const auto [xs, fs] = minimize_1d(F, 0.0, 10.0);
  out.f_ref = fs;
  EXPECT_NEAR(fs, 17.0, 1e-9) << "literature value (MacMPEC bard1)";
  EXPECT_NEAR(xs, 1.0, 1e-7);
  Vector zr = Vector::Zero(6);
  zr[0] = xs;
  zr[1] = bard1_lower_level(xs);
  out.z_refs.push_back(zr);
  out.compare = {0, 1};
  out.extra_error = [](const Vector& z) { return std::abs(z[1] - bard1_lower_level(z[0])); };
  return out;
}

// MacMPEC desilva (DeSilva, 1978):
//   min x1^2 - 2x1 + x2^2 - 2x2 + y1^2 + y2^2,  0 <= x <= 2,
//   y_i solves min (y_i - x_i)^2 s.t. 0.25 - (y_i - 1)^2 >= 0,
// KKT: 2y_i - 2x_i + 2(y_i - 1) l_i = 0, 0 <= 0.25 - (y_i - 1)^2 _|_ l_i >= 0.
// f* = -1 at x = y = (0.5, 0.5), l = 0: both sides of each pair vanish.
// Variables: x1, x2, y1, y2, l1, l2.
Problem desilva() {
  auto p = std::make_unique<PolynomialProgram>();
  for (int i = 0; i < 2; ++i) p->add_variable(0.0, 2.0, 1.0 + 0.2 * i);
  for (int i = 0; i < 2; ++i) p->add_variable(-kInf, kInf, 1.0 + 0.2 * i);
  for (int i = 0; i < 2; ++i) p->add_variable(-kInf, kInf, 0.1);
  for (int i = 0; i < 2; ++i) {
    const int x = i, y = 2 + i, l = 4 + i;
    p->add(PolynomialProgram::kObjective, 1.0, V(x), V(x) - Affine(2.0));
    p->add(PolynomialProgram::kObjective, 1.0, V(y), V(y));
    const int kkt = p->add_row(0, 0);
    p->add(kkt, 1.0, 2.0 * V(y) - 2.0 * V(x));
    p->add(kkt, 2.0, V(y) - Affine(1.0), V(l));
    const int side = p->add_row(-kInf, kInf);
    p->add(side, 1.0, Affine(0.25));
    p->add(side, -1.0, V(y) - Affine(1.0), V(y) - Affine(1.0));
    p->add_pair(S::row(side), S::variable(l));
  }
  Problem out;
  out.start = p->initial_point();
  out.mpcc = finalize(std::move(p));
  // Separable: brute force over each x_i with y_i = clamp(x_i, 0.5, 1.5).
  auto g = [](double x) {
    const double y = std::clamp(x, 0.5, 1.5);
    return x * x - 2 * x + y * y;
  };
  const auto [xs, gs] = minimize_1d(g, 0.0, 2.0);
  out.f_ref = 2 * gs;
  EXPECT_NEAR(out.f_ref, -1.0, 1e-9) << "literature value (MacMPEC desilva)";
  Vector zr(6);
  zr << xs, xs, std::clamp(xs, 0.5, 1.5), std::clamp(xs, 0.5, 1.5), 0.0, 0.0;
  out.z_refs.push_back(zr);
  out.compare = {0, 1, 2, 3, 4, 5};
  out.extra_error = [](const Vector& z) {
    return std::max(std::abs(z[2] - std::clamp(z[0], 0.5, 1.5)),
                    std::abs(z[3] - std::clamp(z[1], 0.5, 1.5)));
  };
  return out;
}

// MacMPEC gauvin (Gauvin & Savard 1992):
//   min x^2 + (y-10)^2,  0 <= x <= 15,
//   0 <= 4(x + 2y - 30) + u _|_ y >= 0,   0 <= 20 - x - y _|_ u >= 0.
// (y minimizes (x + 2y - 30)^2 over 0 <= y <= 20 - x.) f* = 20 at (2, 14, 0).
// Variables: x, y, u. Start from the MacMPEC data (x = 7.5, u = 1).
Problem gauvin() {
  auto p = std::make_unique<PolynomialProgram>();
  const int x = p->add_variable(0.0, 15.0, 7.5), y = p->add_variable(0.0, kInf, 0.0),
            u = p->add_variable(0.0, kInf, 1.0);
  const int fy = p->add_row(-kInf, kInf), fu = p->add_row(-kInf, kInf);
  p->add(fy, 4.0, V(x) + 2.0 * V(y) - Affine(30.0));
  p->add(fy, 1.0, V(u));
  p->add(fu, 1.0, Affine(20.0) - V(x) - V(y));
  p->add(PolynomialProgram::kObjective, 1.0, V(x), V(x));
  p->add(PolynomialProgram::kObjective, 1.0, V(y) - Affine(10.0), V(y) - Affine(10.0));
  p->add_pair(S::row(fy), S::variable(y));
  p->add_pair(S::row(fu), S::variable(u));
  Problem out;
  out.start = p->initial_point();
  out.mpcc = finalize(std::move(p));
  auto lower = [](double xv) { return std::clamp((30 - xv) / 2, 0.0, 20 - xv); };
  auto F = [&](double xv) {
    const double yv = lower(xv);
    return xv * xv + (yv - 10) * (yv - 10);
  };
  const auto [xs, fs] = minimize_1d(F, 0.0, 15.0);
  out.f_ref = fs;
  EXPECT_NEAR(fs, 20.0, 1e-9) << "literature value (MacMPEC gauvin)";
  out.z_refs.push_back((Vector(3) << xs, lower(xs), 0.0).finished());
  out.compare = {0, 1, 2};
  out.extra_error = [lower](const Vector& z) { return std::abs(z[1] - lower(z[0])); };
  return out;
}

// A hand-written, non-polynomial MPCC (exact derivatives by hand):
//   min  f = (x-1)^2 + sqrt(1 + (y-2)^2) + 0.1 x sin(y)
//   s.t. c1 = sqrt(1 + x^2 + y^2) <= 3,
//        0 <= x _|_ c0 = exp(y) - 3 >= 0.
// Branch x = 0: f = 1 + sqrt(1 + (y-2)^2), y >= ln 3: min 2 at y = 2.
// Branch c0 = 0: y = ln 3, f convex in x >= 0: x* = 1 - 0.05 sin(ln 3),
// f* = sqrt(1 + (2 - ln 3)^2) + 0.1 sin(ln 3) - 0.0025 sin^2(ln 3) = 1.43337.
class ExpSqrtMpcc : public Mpcc {
 public:
  ExpSqrtMpcc() {
    z_lo_ = (Vector(2) << -10.0, -10.0).finished();
    z_hi_ = (Vector(2) << 10.0, 10.0).finished();
    c_lo_ = (Vector(2) << -kInf, -kInf).finished();
    c_hi_ = (Vector(2) << kInf, 3.0).finished();
    jac_.add(0, 1);
    jac_.add(1, 0);
    jac_.add(1, 1);
    hess_.add(0, 0);
    hess_.add(1, 0);
    hess_.add(1, 1);
    pairs_.push_back({S::variable(0), S::row(0)});
  }
  static double f(double x, double y) {
    return (x - 1) * (x - 1) + std::sqrt(1 + (y - 2) * (y - 2)) + 0.1 * x * std::sin(y);
  }

 private:
  bool do_objective(const ConstVectorRef& z, double& out) const override {
    out = f(z[0], z[1]);
    return true;
  }
  bool do_gradient(const ConstVectorRef& z, VectorRef g) const override {
    const double x = z[0], y = z[1], q = std::sqrt(1 + (y - 2) * (y - 2));
    g[0] = 2 * (x - 1) + 0.1 * std::sin(y);
    g[1] = (y - 2) / q + 0.1 * x * std::cos(y);
    return true;
  }
  bool do_constraints(const ConstVectorRef& z, VectorRef c) const override {
    c[0] = std::exp(z[1]) - 3;
    c[1] = std::sqrt(1 + z[0] * z[0] + z[1] * z[1]);
    return true;
  }
  bool do_jacobian(const ConstVectorRef& z, VectorRef v) const override {
    const double r = std::sqrt(1 + z[0] * z[0] + z[1] * z[1]);
    v[0] = std::exp(z[1]);
    v[1] = z[0] / r;
    v[2] = z[1] / r;
    return true;
  }
  bool do_hessian(const ConstVectorRef& z, double sigma, const ConstVectorRef& lambda,
                  VectorRef v) const override {
    const double x = z[0], y = z[1], q = std::sqrt(1 + (y - 2) * (y - 2));
    const double r = std::sqrt(1 + x * x + y * y), r3 = r * r * r;
    v[0] = sigma * 2.0 + lambda[1] * (1 + y * y) / r3;
    v[1] = sigma * 0.1 * std::cos(y) - lambda[1] * x * y / r3;
    v[2] = sigma * (1 / (q * q * q) - 0.1 * x * std::sin(y)) + lambda[0] * std::exp(y) +
           lambda[1] * (1 + x * x) / r3;
    return true;
  }
};

// Reference for ExpSqrtMpcc with x <= x_max, by branch enumeration.
std::pair<double, Vector> exp_sqrt_reference(double x_max) {
  const double ln3 = std::log(3.0);
  const auto [ya, fa] =
      minimize_1d([](double y) { return ExpSqrtMpcc::f(0.0, y); }, ln3, 10.0);  // x = 0
  const auto [xb, fb] =
      minimize_1d([&](double x) { return ExpSqrtMpcc::f(x, ln3); }, 0.0, x_max);  // c0 = 0
  if (fa < fb) return {fa, (Vector(2) << 0.0, ya).finished()};
  return {fb, (Vector(2) << xb, ln3).finished()};
}

Problem exp_sqrt() {
  Problem out;
  out.mpcc = std::make_unique<ExpSqrtMpcc>();
  out.start = (Vector(2) << 1.0, 1.0).finished();  // exp(1) - 3 < 0: favours c0 = 0
  const auto [fr, zr] = exp_sqrt_reference(10.0);
  out.f_ref = fr;
  out.z_refs.push_back(zr);
  // Closed form of the winning branch.
  const double s = std::sin(std::log(3.0)), q = std::sqrt(1 + std::pow(2 - std::log(3.0), 2));
  EXPECT_NEAR(fr, q + 0.1 * s - 0.0025 * s * s, 1e-12);
  EXPECT_NEAR(zr[0], 1 - 0.05 * s, 1e-7);
  out.compare = {0, 1};
  return out;
}

enum class ProblemId { kScheelScholtes, kRalph, kBard1, kDeSilva, kGauvin, kExpSqrt };

Problem make_problem(ProblemId id) {
  switch (id) {
    case ProblemId::kScheelScholtes: return scheel_scholtes();
    case ProblemId::kRalph: return ralph();
    case ProblemId::kBard1: return bard1();
    case ProblemId::kDeSilva: return desilva();
    case ProblemId::kGauvin: return gauvin();
    case ProblemId::kExpSqrt: return exp_sqrt();
  }
  return scheel_scholtes();
}

std::string problem_name(ProblemId id) {
  switch (id) {
    case ProblemId::kScheelScholtes: return "ScheelScholtes";
    case ProblemId::kRalph: return "Ralph";
    case ProblemId::kBard1: return "Bard1";
    case ProblemId::kDeSilva: return "DeSilva";
    case ProblemId::kGauvin: return "Gauvin";
    case ProblemId::kExpSqrt: return "ExpSqrt";
  }
  return "?";
}

// ------------------------------------------------------------- helpers ---

// Independent certificate (does not use disco::certify).
struct MyCertificate {
  double violation = 0.0, complementarity = 0.0;
};
MyCertificate my_certificate(const Mpcc& m, const Vector& z) {
  MyCertificate out;
  Vector c(m.num_constraints());
  EXPECT_TRUE(m.constraints(z, c));
  for (int k = 0; k < z.size(); ++k) {
    out.violation = std::max(out.violation, m.variable_lower()[k] - z[k]);
    out.violation = std::max(out.violation, z[k] - m.variable_upper()[k]);
  }
  for (int r = 0; r < c.size(); ++r) {
    out.violation = std::max(out.violation, m.constraint_lower()[r] - c[r]);
    out.violation = std::max(out.violation, c[r] - m.constraint_upper()[r]);
  }
  for (const auto& p : m.complementarity_pairs()) {
    auto val = [&](const S& s) { return s.kind == S::Kind::kVariable ? z[s.index] : c[s.index]; };
    const double g = val(p.g), h = val(p.h);
    out.violation = std::max({out.violation, -g, -h});  // sides must be >= 0
    out.complementarity = std::max(out.complementarity, std::abs(std::min(g, h)));
  }
  return out;
}

std::string describe(const MpccResult& r) {
  std::ostringstream s;
  s << "status " << to_string(r.status) << " ipopt " << r.ipopt_status << " ("
    << ipopt_status_name(r.ipopt_status) << ") f " << r.objective << " viol "
    << r.certificate.max_violation << " compl " << r.certificate.max_complementarity << " zeta "
    << r.zeta << " solves " << r.nlp_solves << " iters " << r.iterations << " polished "
    << r.polished << " z [" << r.z.transpose() << "]";
  return s.str();
}

void expect_solved_to_reference(const Problem& pb, const MpccResult& r) {
  SCOPED_TRACE(describe(r));
  ASSERT_EQ(r.status, MpccStatus::kSolved);
  EXPECT_TRUE(r.solved());
  EXPECT_LE(r.certificate.max_violation, 1e-6);
  EXPECT_LE(r.certificate.max_complementarity, 1e-6);
  const auto mine = my_certificate(*pb.mpcc, r.z);
  EXPECT_LE(mine.violation, 1e-6);
  EXPECT_LE(mine.complementarity, 1e-6);
  double f = 0.0;
  ASSERT_TRUE(pb.mpcc->objective(r.z, f));
  EXPECT_NEAR(r.objective, f, 1e-12);
  EXPECT_NEAR(r.objective, pb.f_ref, 1e-6);
  // Close to one of the reference minimizers.
  double best = kInf;
  for (const auto& zr : pb.z_refs) {
    double d = 0.0;
    for (int k : pb.compare) d = std::max(d, std::abs(r.z[k] - zr[k]));
    best = std::min(best, d);
  }
  EXPECT_LE(best, 1e-4);
  if (pb.extra_error) {
    EXPECT_LE(pb.extra_error(r.z), 1e-6);
  }
}

// configs/disco.yaml's elastic parameters, with this formulation and polish.
ElasticSettings settings_for(ElasticFormulation form, bool polish) {
  ElasticSettings s = test_support::disco_yaml_elastic_settings();
  s.formulation = form;
  s.polish = polish;
  return s;
}

std::string mode_name(ElasticFormulation form, bool polish) {
  const char* name = form == ElasticFormulation::kLumped    ? "Lumped"
                     : form == ElasticFormulation::kPerPair ? "PerPair"
                     : form == ElasticFormulation::kBarrier ? "Barrier"
                                                            : "Relaxed";
  return std::string(name) + (polish ? "Polish" : "NoPolish");
}

// Solves `m` from `start` with `s`, on a fresh IpoptSolver with the options of
// configs/disco.yaml (its ipopt: and kkt: sections).
MpccResult solve_fresh(const Mpcc& m, const ConstVectorRef& start, const ElasticSettings& s) {
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSolver solver(ipopt, s);
  return solver.solve(m, start);
}

// The parameters of the suites below that run one problem in every mode: the
// elastic formulation and whether to polish.
using FormPolish = std::tuple<ElasticFormulation, bool>;

// Lumped and per pair, with and without polish; relaxed only with polish, which it needs
// (its homotopy ends where the relaxation stops holding and polish fixes the branch: the
// settings refuse relaxed without polish).
std::vector<FormPolish> form_polish_list(bool with_relaxed) {
  std::vector<FormPolish> out;
  for (auto form : {ElasticFormulation::kLumped, ElasticFormulation::kPerPair})
    for (bool polish : {false, true}) out.emplace_back(form, polish);
  if (with_relaxed) out.emplace_back(ElasticFormulation::kRelaxed, true);
  return out;
}
auto all_form_polish() { return ::testing::ValuesIn(form_polish_list(true)); }
// The penalty loop's own rules (zeta raising, stall): lumped and per pair.
auto penalty_form_polish() { return ::testing::ValuesIn(form_polish_list(false)); }

std::string form_polish_name(const ::testing::TestParamInfo<FormPolish>& info) {
  return mode_name(std::get<0>(info.param), std::get<1>(info.param));
}

// ---------------------------------------------------------------- tests ---

using Mode = std::tuple<ProblemId, ElasticFormulation, bool>;

class MpccTextbook : public ::testing::TestWithParam<Mode> {};

TEST_P(MpccTextbook, SolvesToKnownOptimum) {
  const auto [id, form, polish] = GetParam();
  const Problem pb = make_problem(id);
  const MpccResult r = solve_fresh(*pb.mpcc, pb.start, settings_for(form, polish));
  expect_solved_to_reference(pb, r);
  if (!polish) {
    EXPECT_FALSE(r.polished);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Textbook, MpccTextbook,
    ::testing::ValuesIn([] {
      std::vector<Mode> modes;
      for (auto id : {ProblemId::kScheelScholtes, ProblemId::kRalph, ProblemId::kBard1,
                      ProblemId::kDeSilva, ProblemId::kGauvin, ProblemId::kExpSqrt}) {
        for (const auto& [form, polish] : form_polish_list(true))
          modes.emplace_back(id, form, polish);
        // The relaxation moved with Ipopt's barrier parameter (issue 34; its own tests in
        // tests/test_barrier_relaxation.cpp): with polish, which it needs, as relaxed does, and
        // disco.yaml's elastic.barrier_mu (monotone; adaptive ends ExpSqrt at f = 2).
        modes.emplace_back(id, ElasticFormulation::kBarrier, true);
      }
      return modes;
    }()),
    [](const ::testing::TestParamInfo<Mode>& info) {
      return problem_name(std::get<0>(info.param)) + "_" +
             mode_name(std::get<1>(info.param), std::get<2>(info.param));
    });

// The hand-written MPCC's derivatives are right (else the solve above
// proves little), alone and inside both elastic formulations.
TEST(MpccTextbookExpSqrt, HandDerivativesMatchFiniteDifferences) {
  const ExpSqrtMpcc m;
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Vector z = test_support::random_vector(rng, 2, -2.0, 2.0);
    const Vector lambda = test_support::random_vector(rng, 2, -2.0, 2.0);
    const auto rep = check_derivatives(m, z, 0.7, lambda);
    ASSERT_NO_FATAL_FAILURE(expect_exact_derivatives(rep));
    for (auto form : {ElasticFormulation::kLumped, ElasticFormulation::kPerPair}) {
      const ElasticNlp e(m, form, 13.0);
      const Vector x = test_support::random_vector(rng, e.num_variables(), -2.0, 2.0);
      const Vector l = test_support::random_vector(rng, e.num_constraints(), -2.0, 2.0);
      const auto re = check_derivatives(e, x, 1.3, l);
      ASSERT_NO_FATAL_FAILURE(expect_exact_derivatives(re));
    }
  }
}

// ------------------------------------------------- infeasible MPCCs ---

class MpccInfeasible : public ::testing::TestWithParam<FormPolish> {};

// min (x-2)^2 + (y-2)^2, 0 <= x _|_ y >= 0 with x >= 1, y >= 1: the elastic
// NLP is feasible, but complementarity can never be tight (min(x, y) >= 1).
PolynomialProgram never_tight_problem() {
  PolynomialProgram p;
  p.add_variable(1.0, kInf, 1.5);
  p.add_variable(1.0, kInf, 1.5);
  for (int k : {0, 1}) {
    p.add(PolynomialProgram::kObjective, 1.0, V(k) - Affine(2.0), V(k) - Affine(2.0));
  }
  p.add_pair(S::variable(0), S::variable(1));
  p.finalize();
  return p;
}

TEST_P(MpccInfeasible, ComplementarityCannotBeTight) {
  const auto [form, polish] = GetParam();
  const auto p = never_tight_problem();
  const MpccResult r = solve_fresh(p, p.initial_point(), settings_for(form, polish));
  SCOPED_TRACE(describe(r));
  EXPECT_FALSE(r.solved());
  EXPECT_TRUE(r.status == MpccStatus::kElasticNotTight || r.status == MpccStatus::kInfeasible);
  EXPECT_GE(r.certificate.max_complementarity, 1.0 - 1e-6);  // honest certificate
  EXPECT_FALSE(r.polished);
}

// 0 <= x _|_ y >= 0 with the row x + y <= -1: even the elastic NLP is infeasible.
TEST_P(MpccInfeasible, ConstraintsCannotBeMet) {
  const auto [form, polish] = GetParam();
  PolynomialProgram p;
  p.add_variable(-kInf, kInf, 0.5);
  p.add_variable(-kInf, kInf, 0.5);
  const int r0 = p.add_row(-kInf, -1.0);
  p.add(r0, 1.0, V(0) + V(1));
  p.add(PolynomialProgram::kObjective, 1.0, V(0), V(1));
  p.add(PolynomialProgram::kObjective, 1.0, V(0) - Affine(1.0));
  p.add_pair(S::variable(0), S::variable(1));
  p.finalize();
  const MpccResult r = solve_fresh(p, p.initial_point(), settings_for(form, polish));
  SCOPED_TRACE(describe(r));
  EXPECT_FALSE(r.solved());
  EXPECT_TRUE(r.status == MpccStatus::kElasticNotTight || r.status == MpccStatus::kInfeasible);
  EXPECT_GT(r.certificate.max_violation, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Textbook, MpccInfeasible, all_form_polish(), form_polish_name);

// ------------------------------------------------------ the zeta rule ---

// min (x-1)^2 + (y-4)^2, 0 <= x _|_ y >= 0. Branches: x = 0 -> (0, 4), f = 1;
// y = 0 -> (1, 0), f = 16. The elastic objective f + zeta x y has the MPCC
// solution (0, 4) as its minimizer only for zeta > 1/2 (d/dx at (0, 4) is
// -2 + 4 zeta); below, the penalty is outweighed by the gain in f and the
// elastic minimizer has x, y > 0. (1, 0) would need zeta >= 8.
PolynomialProgram zeta_problem() {
  PolynomialProgram p;
  p.add_variable(-kInf, kInf, 0.5);
  p.add_variable(-kInf, kInf, 3.0);
  p.add(PolynomialProgram::kObjective, 1.0, V(0) - Affine(1.0), V(0) - Affine(1.0));
  p.add(PolynomialProgram::kObjective, 1.0, V(1) - Affine(4.0), V(1) - Affine(4.0));
  p.add_pair(S::variable(0), S::variable(1));
  p.finalize();
  return p;
}

class MpccZetaRule : public ::testing::TestWithParam<FormPolish> {};

// A stall_change that never triggers the stall rule.
constexpr double kNoStall = -1.0;

// Settings that start zeta far too low for zeta_problem() and raise it tenfold.
ElasticSettings low_zeta_settings(ElasticFormulation form, bool polish) {
  ElasticSettings s = settings_for(form, polish);
  s.zeta = 1e-3;
  s.zeta_factor = 10.0;
  return s;
}

void expect_zeta_raised_and_solved(const ElasticSettings& s, const MpccResult& r) {
  SCOPED_TRACE(describe(r));
  ASSERT_EQ(r.status, MpccStatus::kSolved);
  EXPECT_GT(r.zeta, s.zeta);
  EXPECT_GE(r.zeta, 0.5);      // below 1/2 the elastic solution is not complementary
  EXPECT_GE(r.nlp_solves, 4);  // 1e-3, 1e-2, 1e-1 were all too small
  EXPECT_LE(r.certificate.max_complementarity, 1e-6);
  EXPECT_LE(r.certificate.max_violation, 1e-6);
  EXPECT_NEAR(r.objective, 1.0, 1e-6);
  EXPECT_NEAR(r.z[0], 0.0, 1e-4);
  EXPECT_NEAR(r.z[1], 4.0, 1e-4);
}

// The raising mechanism itself: 1e-3 -> 1e-2 -> 1e-1 -> 1, solved at 1.
// (The elastic residual max|min(x, y)| is 0.998, 0.980, 0.802, then 0: the
// exact penalty has a threshold, it does not shrink the residual gradually.)
TEST_P(MpccZetaRule, RaisesZetaUntilTight) {
  const auto [form, polish] = GetParam();
  const auto p = zeta_problem();
  ElasticSettings s = low_zeta_settings(form, polish);
  s.stall_change = kNoStall;
  expect_zeta_raised_and_solved(s, solve_fresh(p, p.initial_point(), s));
}

// The same with the default stall_change: an MPCC that is solved at zeta = 1
// must not be given up at zeta = 1e-2 because the residual only fell from
// 0.998 to 0.980 (see the report: the stall rule contradicts the threshold
// behaviour of the exact penalty).
TEST_P(MpccZetaRule, RaisesZetaUntilTightWithDefaultStallRatio) {
  const auto [form, polish] = GetParam();
  const auto p = zeta_problem();
  const ElasticSettings s = low_zeta_settings(form, polish);
  expect_zeta_raised_and_solved(s, solve_fresh(p, p.initial_point(), s));
}

TEST_P(MpccZetaRule, ReportsNotTightWhenZetaMaxIsTooSmall) {
  const auto [form, polish] = GetParam();
  const auto p = zeta_problem();
  ElasticSettings s = low_zeta_settings(form, polish);
  s.zeta_max = 0.05;  // the problem needs zeta > 0.5
  s.stall_change = kNoStall;  // so that zeta_max, and only it, stops the raising
  const MpccResult r = solve_fresh(p, p.initial_point(), s);
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.status, MpccStatus::kElasticNotTight);
  EXPECT_FALSE(r.solved());
  EXPECT_FALSE(r.polished);
  EXPECT_DOUBLE_EQ(r.zeta, 1e-2);  // 1e-3, 1e-2; 1e-1 would exceed zeta_max
  EXPECT_EQ(r.nlp_solves, 2);
  EXPECT_GT(r.certificate.max_complementarity, s.complementarity_tol);  // honest
  EXPECT_NEAR(r.certificate.max_complementarity, 0.98, 0.01);
}

// Where the stall rule is right: complementarity cannot be tight (x, y >= 1),
// the residual stays 1, and the raising stops after one raise instead of
// running up to zeta_max.
TEST_P(MpccZetaRule, StallRuleStopsEarlyWhenTheResidualDoesNotMove) {
  const auto [form, polish] = GetParam();
  const auto p = never_tight_problem();
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSettings s = settings_for(form, polish);  // zeta 10, factor 10, max 1e6
  const MpccResult stalled = ElasticSolver(ipopt, s).solve(p, p.initial_point());
  s.stall_change = kNoStall;
  const MpccResult full = ElasticSolver(ipopt, s).solve(p, p.initial_point());
  SCOPED_TRACE("stall: " + describe(stalled) + "\nno stall: " + describe(full));
  EXPECT_EQ(stalled.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(full.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(stalled.nlp_solves, 2);
  EXPECT_EQ(full.nlp_solves, 6);  // zeta = 10, 100, ..., 1e6
  EXPECT_DOUBLE_EQ(full.zeta, 1e6);
}

// ElasticRequest::zeta and zeta_limit (the reduction's weak minimisations): the request's zeta
// replaces a warm result's (here 10, where zeta_problem() is solved at once) and the settings'
// from a point; its limit stops the raises below the settings' zeta_max.
TEST_P(MpccZetaRule, ARequestsZetaAndLimitReplaceTheWarmResultsAndZetaMax) {
  const auto [form, polish] = GetParam();
  const auto p = zeta_problem();
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSettings s = settings_for(form, polish);  // zeta 10, factor 10, max 1e6
  s.stall_change = kNoStall;
  const ElasticSolver solver(ipopt, s);
  const MpccResult first = solver.solve(p, p.initial_point());
  ASSERT_EQ(first.status, MpccStatus::kSolved) << describe(first);
  ASSERT_DOUBLE_EQ(first.zeta, 10.0);
  ElasticRequest weak;
  weak.zeta = 1e-3;
  const MpccResult raised = solver.solve(p, first, weak);
  const MpccResult from_point = solver.solve(p, p.initial_point(), weak);
  weak.zeta_limit = 1e-2;
  const MpccResult limited = solver.solve(p, first, weak);
  SCOPED_TRACE("raised: " + describe(raised) + "\nfrom a point: " + describe(from_point) +
               "\nlimited: " + describe(limited));
  for (const MpccResult* r : {&raised, &from_point}) {
    ASSERT_EQ(r->status, MpccStatus::kSolved);
    EXPECT_DOUBLE_EQ(r->zeta, 1.0);  // 1e-3, 1e-2, 1e-1 too small (the threshold is 1/2), 1
    EXPECT_GE(r->nlp_solves, 4);
    EXPECT_NEAR(r->objective, 1.0, 1e-6);
  }
  EXPECT_EQ(limited.status, MpccStatus::kElasticNotTight);
  EXPECT_DOUBLE_EQ(limited.zeta, 1e-2);  // 1e-3, 1e-2; 1e-1 would pass the limit
  EXPECT_EQ(limited.nlp_solves, 2);
}

INSTANTIATE_TEST_SUITE_P(Textbook, MpccZetaRule, penalty_form_polish(), form_polish_name);

// The relaxation homotopy raises zeta only while the relaxation has never held: at
// zeta = 1e-3 the penalty prefers eps > sigma at the first sigma, so zeta rises (same rule as
// above) until it holds; the homotopy and polish then reach the optimum. (With the default
// stall_change the raise stops at zeta = 1e-2 here: relaxed by sigma = 0.1 the residual
// moves from 0.9989 by less than 1e-3, the threshold behaviour of the exact penalty that the
// stall rule cannot tell from a bound below the optimum.)
TEST(MpccRelaxed, RaisesZetaUntilTheRelaxationHoldsThenSolves) {
  const auto p = zeta_problem();
  ElasticSettings s = low_zeta_settings(ElasticFormulation::kRelaxed, true);
  s.stall_change = kNoStall;
  const MpccResult r = solve_fresh(p, p.initial_point(), s);
  SCOPED_TRACE(describe(r));
  ASSERT_EQ(r.status, MpccStatus::kSolved);
  EXPECT_GT(r.zeta, s.zeta);
  EXPECT_TRUE(r.polished);
  EXPECT_LE(r.certificate.max_complementarity, 1e-6);
  EXPECT_LE(r.certificate.max_violation, 1e-6);
  EXPECT_NEAR(r.objective, 1.0, 1e-6);
  EXPECT_NEAR(r.z[0], 0.0, 1e-4);
  EXPECT_NEAR(r.z[1], 4.0, 1e-4);
}

// ElasticRequest::relaxation (reduction.minimize_weak homotopy): under formulation lumped, a
// request with it runs the relaxed formulation's homotopy on the same NLP, so its answer is
// the relaxed formulation's, bit for bit, and another solve than the lumped penalty loop's.
TEST(MpccRelaxed, ARelaxationRequestUnderLumpedIsTheRelaxedSolve) {
  const auto p = zeta_problem();
  ElasticSettings lumped = low_zeta_settings(ElasticFormulation::kLumped, true);
  ElasticSettings relaxed = low_zeta_settings(ElasticFormulation::kRelaxed, true);
  lumped.stall_change = relaxed.stall_change = kNoStall;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticRequest relaxation;
  relaxation.relaxation = true;
  const MpccResult requested = ElasticSolver(ipopt, lumped).solve(p, p.initial_point(), relaxation);
  const MpccResult formulation = ElasticSolver(ipopt, relaxed).solve(p, p.initial_point());
  const MpccResult penalty = ElasticSolver(ipopt, lumped).solve(p, p.initial_point());
  SCOPED_TRACE("requested: " + describe(requested) + "\nrelaxed: " + describe(formulation) +
               "\nlumped: " + describe(penalty));
  ASSERT_EQ(requested.status, MpccStatus::kSolved);
  EXPECT_EQ(requested.nlp_solves, formulation.nlp_solves);
  EXPECT_EQ(requested.iterations, formulation.iterations);
  EXPECT_EQ(requested.zeta, formulation.zeta);
  ASSERT_EQ(requested.z.size(), formulation.z.size());
  for (int k = 0; k < requested.z.size(); ++k) EXPECT_EQ(requested.z[k], formulation.z[k]) << k;
  EXPECT_NE(requested.iterations, penalty.iterations) << "the penalty loop's solve";
  EXPECT_NEAR(requested.objective, 1.0, 1e-6);
  EXPECT_NEAR(penalty.objective, 1.0, 1e-6);
  // Per pair has no lumped row to relax: a programming error, refused by the settings first.
  const ElasticSettings per_pair = settings_for(ElasticFormulation::kPerPair, true);
  try {
    ElasticSolver(ipopt, per_pair).solve(p, p.initial_point(), relaxation);
    ADD_FAILURE() << "per pair solved a relaxation request";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("a relaxation request needs"), std::string::npos)
        << e.what();
  }
}

// ------------------------------------------------ a fixed objective ---

// ElasticRequest::objective_fixed: an MPCC whose objective is constant on its feasible set
// (here f = t with t fixed at 2, as T_f in a fixed step of the objective reduction). The
// elastic NLP then minimises eps alone whatever zeta, so the first solve's answer is final.
class MpccFixedObjective : public ::testing::TestWithParam<FormPolish> {};

// x, y >= 1, 0 <= x _|_ y >= 0 (never tight), f = t, t = 2; `tight_possible`: x, y >= 0 and
// x + y >= 1 instead, from (1.5, 0.5), where complementarity can be tight ((1, 0) or (0, 1)).
PolynomialProgram fixed_objective_problem(bool tight_possible) {
  PolynomialProgram p;
  const double lo = tight_possible ? 0.0 : 1.0;
  p.add_variable(lo, kInf, 1.5);
  p.add_variable(lo, kInf, tight_possible ? 0.5 : 1.5);
  p.add_variable(2.0, 2.0, 2.0);
  p.add(PolynomialProgram::kObjective, 1.0, V(2));
  if (tight_possible) {
    const int row = p.add_row(1.0, kInf);
    p.add(row, 1.0, V(0) + V(1));
  }
  p.add_pair(S::variable(0), S::variable(1));
  p.finalize();
  return p;
}

// `p` solved from its initial point with ElasticRequest::objective_fixed, then without it
// (the zeta rule), on one IpoptSolver with disco.yaml's options.
std::pair<MpccResult, MpccResult> solve_both_ways(const PolynomialProgram& p,
                                                  const ElasticSettings& s) {
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  const ElasticSolver solver(ipopt, s);
  ElasticRequest fixed;
  fixed.objective_fixed = true;
  std::pair<MpccResult, MpccResult> out{solver.solve(p, p.initial_point(), fixed),
                                        solver.solve(p, p.initial_point())};
  return out;
}

// Not tight: one elastic solve, no raise, and the same smallest residual (min(x, y) = 1) as
// the zeta rule reaches after its raises.
TEST_P(MpccFixedObjective, EndsNotTightAfterOneSolveWithoutRaisingZeta) {
  const auto [form, polish] = GetParam();
  const ElasticSettings s = settings_for(form, polish);
  const auto [once, raised] = solve_both_ways(fixed_objective_problem(false), s);
  SCOPED_TRACE("objective_fixed: " + describe(once) + "\nzeta rule: " + describe(raised));
  EXPECT_EQ(once.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(raised.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(once.nlp_solves, 1);
  EXPECT_DOUBLE_EQ(once.zeta, s.zeta);
  EXPECT_GE(raised.nlp_solves, 2);  // the zeta rule raised at least once
  EXPECT_GT(raised.zeta, s.zeta);
  EXPECT_FALSE(once.polished);
  // min(x, y) >= 1 is the least there is; the penalty forms reach it to Ipopt's tolerance, the
  // relaxed form's stages end at the barrier level mu = barrier_ratio * sigma, ~1e-4 inside.
  const double reach = form == ElasticFormulation::kRelaxed ? 1e-3 : 1e-6;
  for (const MpccResult* r : {&once, &raised}) {
    EXPECT_GE(r->certificate.max_complementarity, 1.0 - 1e-9);
    EXPECT_LE(r->certificate.max_complementarity, 1.0 + reach);
  }
}

// Where complementarity can be tight, the request changes nothing: solved by the first
// elastic solve (and polish), on the branch y = 0. (From a symmetric start, x = y,
// Ipopt stops at the stationary point (0.5, 0.5) of eps = x y on x + y = 1 with either rule.)
// (With polish_fixed_above 0: every tight point polished, as under the zeta rule.)
TEST_P(MpccFixedObjective, SolvesATightProblemAsTheZetaRuleDoes) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.polish_fixed_above = 0.0;
  const auto [once, rule] = solve_both_ways(fixed_objective_problem(true), s);
  SCOPED_TRACE("objective_fixed: " + describe(once) + "\nzeta rule: " + describe(rule));
  ASSERT_EQ(once.status, MpccStatus::kSolved);
  ASSERT_EQ(rule.status, MpccStatus::kSolved);
  EXPECT_EQ(once.nlp_solves, rule.nlp_solves);
  EXPECT_LE(once.certificate.max_complementarity, 1e-6);
  EXPECT_LE(once.certificate.max_violation, 1e-6);
  EXPECT_GE(once.z[0], 1.0 - 1e-6);  // on the branch y = 0, x + y >= 1
  EXPECT_NEAR(once.z[1], 0.0, 1e-6);
  // No raise was due, so both took the same path: the same point, bit for bit.
  EXPECT_EQ((once.z - rule.z).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_NEAR(once.objective, 2.0, 1e-12);
}

// ElasticSettings::polish_fixed_above: a fixed objective's point that ends tight below it is
// certified as it stands, without polish; the same solve under the zeta rule (an objective
// that is not fixed) is polished, and with the setting at 0 so is the fixed one. The elastic
// solve before polish is the same in all three, bit for bit. (The relaxed form's homotopy
// ends at the barrier level mu = barrier_ratio * sigma_min, its point above the threshold:
// polished as always.)
TEST_P(MpccFixedObjective, ATightFixedPointBelowTheThresholdIsNotPolished) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.polish_fixed_above = 1e-8;
  ElasticSettings always = s;
  always.polish_fixed_above = 0.0;
  const PolynomialProgram p = fixed_objective_problem(true);
  const auto [once, rule] = solve_both_ways(p, s);
  const auto [polished, unused] = solve_both_ways(p, always);
  SCOPED_TRACE("fixed: " + describe(once) + "\nzeta rule: " + describe(rule) +
               "\nfixed, always polished: " + describe(polished));
  ASSERT_EQ(once.status, MpccStatus::kSolved);
  ASSERT_EQ(rule.status, MpccStatus::kSolved);
  ASSERT_EQ(polished.status, MpccStatus::kSolved);
  if (form == ElasticFormulation::kRelaxed) {
    EXPECT_TRUE(once.polished);
    EXPECT_EQ(once.nlp_solves, polished.nlp_solves);
    EXPECT_EQ((once.z - polished.z).cwiseAbs().maxCoeff(), 0.0);
    return;
  }
  EXPECT_FALSE(once.polished);
  EXPECT_EQ(once.nlp_solves, 1);
  EXPECT_LE(once.certificate.max_complementarity, 1e-8);
  EXPECT_LE(once.certificate.max_violation, 1e-6);
  EXPECT_NEAR(once.objective, 2.0, 1e-12);
  EXPECT_EQ(rule.polished, polish);
  EXPECT_EQ(polished.polished, polish);
  EXPECT_EQ(polished.nlp_solves, polish ? 2 : 1);
  EXPECT_EQ((once.elastic_point.z - polished.elastic_point.z).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((once.elastic_point.z - rule.elastic_point.z).cwiseAbs().maxCoeff(), 0.0);
  // Above the threshold the point is polished as before.
  ElasticSettings strict = s;
  strict.polish_fixed_above = 0.1 * once.certificate.max_complementarity;
  const auto [above, unused2] = solve_both_ways(p, strict);
  EXPECT_EQ(above.polished, polish);
}

// ElasticRequest::objective_constant (the reduction's feasibility phases): the zeta rule as
// without it, but a point that ends tight below polish_fixed_above is not polished, as a fixed
// step's: the same elastic solves, one polish fewer, the same elastic point bit for bit.
TEST_P(MpccFixedObjective, AConstantObjectiveKeepsTheZetaRuleAndSkipsATightPolish) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.polish_fixed_above = 1e-8;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  const ElasticSolver solver(ipopt, s);
  ElasticRequest constant;
  constant.objective_constant = true;
  const PolynomialProgram tight = fixed_objective_problem(true);
  const MpccResult as_is = solver.solve(tight, tight.initial_point(), constant);
  const MpccResult plain = solver.solve(tight, tight.initial_point());
  SCOPED_TRACE("constant: " + describe(as_is) + "\nplain: " + describe(plain));
  ASSERT_EQ(as_is.status, MpccStatus::kSolved);
  ASSERT_EQ(plain.status, MpccStatus::kSolved);
  EXPECT_EQ(plain.polished, polish);
  if (form == ElasticFormulation::kRelaxed) {  // its homotopy ends above the threshold
    EXPECT_EQ(as_is.polished, polish);
    EXPECT_EQ(as_is.nlp_solves, plain.nlp_solves);
  } else {
    EXPECT_FALSE(as_is.polished);
    EXPECT_EQ(as_is.nlp_solves, plain.nlp_solves - (polish ? 1 : 0));
    EXPECT_LE(as_is.certificate.max_complementarity, 1e-8);
    EXPECT_EQ((as_is.elastic_point.z - plain.elastic_point.z).cwiseAbs().maxCoeff(), 0.0);
  }
  // Not tight at the first zeta: raised as without the flag (a fixed objective is not).
  const PolynomialProgram loose = fixed_objective_problem(false);
  const MpccResult raised = solver.solve(loose, loose.initial_point(), constant);
  const MpccResult rule = solver.solve(loose, loose.initial_point());
  EXPECT_EQ(raised.nlp_solves, rule.nlp_solves);
  EXPECT_EQ(raised.zeta, rule.zeta);
  EXPECT_GT(raised.zeta, s.zeta);
}

// Per pair (no eps) and relaxed (its own homotopy): the stagnation rule changes nothing.
void expect_same_run(const MpccResult& a, const MpccResult& b) {
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ((a.z - b.z).cwiseAbs().maxCoeff(), 0.0);
}

// A request without objective_fixed or feasibility (the zeta rule) is not watched: the same
// solve with the rule's settings `s` as with `never`.
void expect_unwatched_without_flag(IpoptSolver& ipopt, const PolynomialProgram& p,
                                   const ElasticSettings& s, const ElasticSettings& never) {
  const MpccResult rule = ElasticSolver(ipopt, s).solve(p, p.initial_point());
  const MpccResult rule_off = ElasticSolver(ipopt, never).solve(p, p.initial_point());
  EXPECT_EQ(rule.iterations, rule_off.iterations);
  EXPECT_EQ(rule.nlp_solves, rule_off.nlp_solves);
}

// The never-tight problem above (fixed_objective_problem(false)) solved under `request` with
// a rule's settings `s` (cut) and without it (`never`: full).
struct CutAndFull {
  MpccResult cut, full;
};
CutAndFull solve_with_and_without(IpoptSolver& ipopt, const ElasticSettings& s,
                                  const ElasticSettings& never, const ElasticRequest& request) {
  const PolynomialProgram p = fixed_objective_problem(false);
  return {ElasticSolver(ipopt, s).solve(p, p.initial_point(), request),
          ElasticSolver(ipopt, never).solve(p, p.initial_point(), request)};
}
// Both end not tight; the rule cut the lumped solve (stagnated, in fewer iterations) and left
// the other formulations' runs (per pair: no eps; relaxed: its own homotopy) as they were.
void expect_cut_if_lumped(ElasticFormulation form, const CutAndFull& r) {
  SCOPED_TRACE("with the rule: " + describe(r.cut) + "\nwithout: " + describe(r.full));
  EXPECT_EQ(r.cut.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(r.full.status, MpccStatus::kElasticNotTight);
  if (form == ElasticFormulation::kLumped) {
    EXPECT_EQ(r.cut.outcome, NlpOutcome::kStagnated);
    EXPECT_LT(r.cut.iterations, r.full.iterations);
  } else {
    expect_same_run(r.cut, r.full);
  }
}

// ElasticSettings::Stagnation: a fixed step's eps that stopped falling far from tight ends the
// solve (lumped and barrier formulations, which have an eps). On the problem above that cannot
// be tight (eps = x y >= 1), a rule that looks from iteration 1 at windows of one iteration
// stops the lumped solve as soon as eps falls by less than a fifth above 0.5: not tight, as the
// converged solve, in fewer iterations and with a residual as large. Per pair (no eps) and
// relaxed (its own homotopy) solve as without the rule.
TEST_P(MpccFixedObjective, AStagnantEpsEndsANotTightSolveEarly) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.stagnation.first = {.after = 1, .window = 1, .level = 0.5, .decrease = 0.2};
  const ElasticSettings off = settings_for(form, polish);
  const PolynomialProgram p = fixed_objective_problem(false);
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticRequest fixed;
  fixed.objective_fixed = true;
  ElasticSettings never = off;
  never.stagnation.first.after = 0;
  const MpccResult cut = ElasticSolver(ipopt, s).solve(p, p.initial_point(), fixed);
  const MpccResult full = ElasticSolver(ipopt, never).solve(p, p.initial_point(), fixed);
  SCOPED_TRACE("stagnation: " + describe(cut) + "\nwithout: " + describe(full));
  ASSERT_EQ(full.outcome, NlpOutcome::kConverged);
  EXPECT_EQ(cut.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(full.status, MpccStatus::kElasticNotTight);
  EXPECT_EQ(cut.nlp_solves, 1);
  EXPECT_GE(cut.certificate.max_complementarity, 1.0 - 1e-9);
  if (form == ElasticFormulation::kLumped) {
    EXPECT_EQ(cut.outcome, NlpOutcome::kStagnated);
    EXPECT_LT(cut.iterations, full.iterations);
  } else {
    expect_same_run(cut, full);
  }
  // Without objective_fixed (the zeta rule, which raises zeta) the rule never applies.
  expect_unwatched_without_flag(ipopt, p, s, never);
}

// ElasticRequest::feasibility: a feasibility phase's eps is watched from feasibility_after on,
// and a stagnant eps ends the call as a fixed step's does: not tight, one NLP solve, no zeta
// raise. On the problem above (never tight) the lumped solve ends not tight, as without the
// watch (where the zeta rule raises), in fewer iterations; `after` (the fixed steps' rule)
// plays no part, nor does the watch without the flag. Per pair (no eps) and relaxed (its own
// homotopy) solve as without it.
TEST_P(MpccFixedObjective, AFeasibilityPhasesStagnantEpsEndsItNotTight) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.stagnation = {.first = {.after = 0, .window = 1, .level = 0.5, .decrease = 0.2},
                  .feasibility_after = 1};
  ElasticSettings never = s;
  never.stagnation.feasibility_after = 0;
  const PolynomialProgram p = fixed_objective_problem(false);
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticRequest feasibility;
  feasibility.feasibility = true;
  const CutAndFull r = solve_with_and_without(ipopt, s, never, feasibility);
  expect_cut_if_lumped(form, r);
  EXPECT_GE(r.cut.certificate.max_complementarity, 1.0 - 1e-9);
  if (form == ElasticFormulation::kLumped) {
    EXPECT_EQ(r.cut.nlp_solves, 1);  // no zeta raise after a stagnant solve
    EXPECT_DOUBLE_EQ(r.cut.zeta, s.zeta);
    EXPECT_GE(r.full.nlp_solves, 2);  // unwatched, the zeta rule raises
    EXPECT_FALSE(r.cut.stalled);      // not a minimisation's stall
  }
  // The same settings without the flag: not watched.
  expect_unwatched_without_flag(ipopt, p, s, never);
}

// ElasticSettings::Stagnation::late: the second rule watches fixed steps alone. With the first
// rule off (after 0) and a late rule that looks from iteration 1 at windows of one iteration, a
// fixed step on the problem above (never tight) is cut as by the first rule; a feasibility
// phase (not watched: feasibility_after 0) and a request without either flag solve as with no
// rule at all.
TEST_P(MpccFixedObjective, TheLateRuleWatchesFixedStepsAlone) {
  const auto [form, polish] = GetParam();
  ElasticSettings s = settings_for(form, polish);
  s.stagnation = {.first = {.after = 0, .window = 1, .level = 0.5, .decrease = 0.2},
                  .feasibility_after = 0};
  s.stagnation.late = {.after = 1, .window = 1, .level = 0.5, .decrease = 0.2};
  ElasticSettings never = s;
  never.stagnation.late.after = 0;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticRequest fixed;
  fixed.objective_fixed = true;
  expect_cut_if_lumped(form, solve_with_and_without(ipopt, s, never, fixed));
  ElasticRequest feasibility;
  feasibility.feasibility = true;
  const CutAndFull unwatched = solve_with_and_without(ipopt, s, never, feasibility);
  expect_same_run(unwatched.cut, unwatched.full);
  expect_unwatched_without_flag(ipopt, fixed_objective_problem(false), s, never);
}

INSTANTIATE_TEST_SUITE_P(Textbook, MpccFixedObjective, all_form_polish(), form_polish_name);

// The rule itself, on sequences of eps (one value per Ipopt iteration, the last at `iteration`).
TEST(ElasticStagnation, StopsOnlyAStagnantEpsAboveTheLevelPastTheFirstIterations) {
  const ElasticSettings::Stagnation rule{
      .first = {.after = 4, .window = 2, .level = 0.1, .decrease = 0.2}};
  const std::vector<double> flat{3.0, 3.0, 3.0, 3.0, 3.0};
  EXPECT_TRUE(rule.stagnated(4, flat));
  EXPECT_FALSE(rule.stagnated(3, flat)) << "not before iteration `after`";
  EXPECT_FALSE(rule.stagnated(4, {3.0, 3.0, 3.0})) << "two windows are needed";
  // The least of the last window against the least of the one before: 2.5 vs 3.0 is a fall by
  // 1/6 < 0.2, stagnant; 2.3 vs 3.0 by 0.233, still falling.
  EXPECT_TRUE(rule.stagnated(4, {9.0, 3.0, 3.1, 2.5, 2.6}));
  EXPECT_FALSE(rule.stagnated(4, {9.0, 3.0, 3.1, 2.3, 2.6}));
  EXPECT_TRUE(rule.stagnated(4, {9.0, 3.0, 3.1, 4.0, 5.0})) << "a rising eps is stagnant";
  EXPECT_FALSE(rule.stagnated(4, {0.09, 0.09, 0.09, 0.09, 0.09})) << "below the level: may still close";
  EXPECT_FALSE((ElasticSettings::Stagnation{
                   .first = {.after = 0, .window = 2, .level = 0.1, .decrease = 0.2}})
                   .stagnated(40, std::vector<double>(40, 3.0)))
      << "after = 0: never";
}

// The late rule, beside the first: it watches from its own `after`, at its own level, so a
// plateau below the first rule's level is stagnant by it alone, and only from late.after on.
TEST(ElasticStagnation, TheLateRuleStopsALowPlateauFromItsOwnIteration) {
  ElasticSettings::Stagnation rule{
      .first = {.after = 4, .window = 2, .level = 0.1, .decrease = 0.2}};
  rule.late = {.after = 6, .window = 3, .level = 1e-3, .decrease = 0.1};
  const std::vector<double> low(7, 0.05);  // below 0.1, above 1e-3, flat
  EXPECT_FALSE((ElasticSettings::Stagnation{
                   .first = {.after = 4, .window = 2, .level = 0.1, .decrease = 0.2}})
                   .stagnated(6, low))
      << "the first rule alone: below its level";
  EXPECT_TRUE(rule.stagnated(6, low));
  EXPECT_FALSE(rule.stagnated(5, std::vector<double>(6, 0.05))) << "not before late.after";
  // The least of the last 3 against the least of the 3 before: 0.046 vs 0.05 is a fall by 8 %
  // (< 10 %), stagnant; 0.044 vs 0.05 by 12 %, still falling.
  EXPECT_TRUE(rule.stagnated(6, {0.9, 0.05, 0.05, 0.05, 0.046, 0.047, 0.048}));
  EXPECT_FALSE(rule.stagnated(6, {0.9, 0.05, 0.05, 0.05, 0.044, 0.047, 0.048}));
  EXPECT_FALSE(rule.stagnated(6, std::vector<double>(7, 5e-4))) << "below late.level";
  EXPECT_TRUE(rule.stagnated(6, std::vector<double>(7, 3.0))) << "the first rule still stops";
}

// ElasticSettings::Stall, on (iteration, objective) of settled iterates, the last at `iteration`.
TEST(ElasticStall, StopsOnlyAtASettledIterateWhoseObjectiveHasCrept) {
  const ElasticSettings::Stall rule{
      .after = 10, .window = 5, .decrease = 1e-3, .mu = 1e-10, .infeasibility = 1e-8};
  using Settled = std::vector<std::pair<int, double>>;
  // The least of the last 5 iterations (k > 12 - 5) against the least before: 9.995 against
  // 10.0 is a fall by 5e-4 < 1e-3, crept; 9.98 by 2e-3, still falling.
  EXPECT_TRUE(rule.stalled(12, Settled{{3, 10.0}, {6, 10.0}, {9, 9.999}, {12, 9.995}}));
  EXPECT_FALSE(rule.stalled(12, Settled{{3, 10.0}, {6, 10.0}, {9, 9.999}, {12, 9.98}}));
  EXPECT_TRUE(rule.stalled(12, Settled{{3, 10.0}, {12, 10.5}})) << "a rising objective has crept";
  EXPECT_FALSE(rule.stalled(9, Settled{{3, 10.0}, {9, 10.0}})) << "not before iteration `after`";
  EXPECT_FALSE(rule.stalled(12, Settled{{8, 10.0}, {12, 10.0}})) << "nothing settled before the window";
  EXPECT_FALSE(rule.stalled(13, Settled{{3, 10.0}, {12, 10.0}})) << "only at a settled iterate";
  EXPECT_FALSE((ElasticSettings::Stall{.after = 0, .window = 5, .decrease = 1e-3, .mu = 1e-10,
                                       .infeasibility = 1e-8})
                   .stalled(40, Settled{{3, 10.0}, {40, 10.0}}))
      << "after = 0: never";
  // Settled: Ipopt's mu and primal infeasibility both at most the rule's.
  EXPECT_TRUE(rule.settled({.iteration = 1, .infeasibility = 1e-9, .mu = 1e-11}));
  EXPECT_FALSE(rule.settled({.iteration = 1, .infeasibility = 1e-9, .mu = 1e-9}));
  EXPECT_FALSE(rule.settled({.iteration = 1, .infeasibility = 1e-7, .mu = 1e-11}));
}

// A minimisation (ElasticRequest::stall) that the rule ends is judged as if it had converged:
// here tight, polished and certified at ExpSqrt's optimum (from (1, 1)), and marked stalled (not
// shown stationary). Every iterate counts as settled, and a window of one iteration ends the
// solve at the first iterate from iteration 3 on whose objective is not 1 % below the least
// before it: another path than the full solve's (its iterations differ), to the same answer.
// Without ElasticRequest::stall the rule does not apply: the full solve, bit for bit.
TEST(ElasticStall, EndsAMinimisationAsIfConvergedAndMarksItStalled) {
  ExpSqrtMpcc m;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSettings s = settings_for(ElasticFormulation::kLumped, true);
  s.stall = {.after = 3, .window = 1, .decrease = 0.01, .mu = 1.0, .infeasibility = 1.0};
  ElasticSettings off = s;
  off.stall.after = 0;
  const Vector start = (Vector(2) << 1.0, 1.0).finished();
  ElasticRequest minimise;
  minimise.stall = true;
  const MpccResult cut = ElasticSolver(ipopt, s).solve(m, start, minimise);
  const MpccResult full = ElasticSolver(ipopt, off).solve(m, start, minimise);
  const MpccResult unasked = ElasticSolver(ipopt, s).solve(m, start);
  SCOPED_TRACE("stall: " + describe(cut) + "\nwithout: " + describe(full));
  ASSERT_EQ(full.status, MpccStatus::kSolved);
  EXPECT_FALSE(full.stalled);
  EXPECT_EQ(cut.status, MpccStatus::kSolved);
  EXPECT_TRUE(cut.stalled);
  EXPECT_TRUE(cut.polished);
  EXPECT_NE(cut.iterations, full.iterations) << "the rule ended a solve";
  EXPECT_TRUE(cut.certificate.within(1e-6, 1e-6));
  EXPECT_NEAR(cut.objective, full.objective, 1e-6);
  EXPECT_FALSE(unasked.stalled);
  EXPECT_EQ(unasked.iterations, full.iterations);
  EXPECT_EQ((unasked.z - full.z).cwiseAbs().maxCoeff(), 0.0);
}

// ------------------------------------------------------- warm starts ---

class MpccWarmStart : public ::testing::TestWithParam<FormPolish> {};

TEST_P(MpccWarmStart, AfterTighteningABound) {
  const auto [form, polish] = GetParam();
  ExpSqrtMpcc m;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSolver solver(ipopt, settings_for(form, polish));
  const MpccResult first = solver.solve(m, (Vector(2) << 1.0, 1.0).finished());
  ASSERT_EQ(first.status, MpccStatus::kSolved) << describe(first);

  // Tighten x <= 0.7: the optimum moves to (0.7, ln 3).
  m.set_variable_bounds(0, -10.0, 0.7);
  const auto [f_ref, z_ref] = exp_sqrt_reference(0.7);
  EXPECT_NEAR(z_ref[0], 0.7, 1e-9);
  const MpccResult warm = solver.solve(m, first);
  const MpccResult cold = solver.solve(m, first.z);
  const std::string msg = "warm: " + describe(warm) + "\ncold: " + describe(cold);
  RecordProperty("warm_iterations", warm.iterations);
  RecordProperty("cold_iterations", cold.iterations);
  std::printf("[ warm start ] %s: warm %d iterations (%d NLP solves), cold %d (%d)\n",
              mode_name(form, polish).c_str(), warm.iterations, warm.nlp_solves, cold.iterations,
              cold.nlp_solves);
  for (const MpccResult* r : {&warm, &cold}) {
    ASSERT_EQ(r->status, MpccStatus::kSolved) << msg;
    EXPECT_NEAR(r->objective, f_ref, 1e-6) << msg;
    EXPECT_NEAR(r->z[0], z_ref[0], 1e-4) << msg;
    EXPECT_NEAR(r->z[1], z_ref[1], 1e-4) << msg;
  }
  // Asserted without polishing only: a polished result carries zero bound
  // multipliers for the sides it fixed (Ipopt 3.11 reports none for fixed
  // variables), so its warm start is not reliably better than a cold one
  // (see the report).
  if (!polish) {
    EXPECT_LE(warm.iterations, cold.iterations) << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(Textbook, MpccWarmStart, all_form_polish(), form_polish_name);

// ElasticRequest::cold_start: from a result, only its primal point is used. Its multipliers are
// not read at all (the same solve bit for bit with them scaled by 10, which moves a warm start),
// Ipopt starts cold (other iterations than the warm start's), and the answer is the optimum.
TEST(MpccColdStart, FromAResultUsesItsPrimalPointOnly) {
  ExpSqrtMpcc m;
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSolver solver(ipopt, settings_for(ElasticFormulation::kLumped, true));
  const MpccResult first = solver.solve(m, (Vector(2) << 1.0, 1.0).finished());
  ASSERT_EQ(first.status, MpccStatus::kSolved) << describe(first);
  ASSERT_TRUE(first.elastic_point.has_duals());
  m.set_variable_bounds(0, -10.0, 0.7);  // the optimum moves to (0.7, ln 3)
  const auto [f_ref, z_ref] = exp_sqrt_reference(0.7);
  MpccResult scaled = first;  // the same primal point, other multipliers
  scaled.elastic_point.lambda *= 10.0;
  scaled.elastic_point.z_lo *= 10.0;
  scaled.elastic_point.z_hi *= 10.0;
  ElasticRequest cold;
  cold.cold_start = true;
  const MpccResult a = solver.solve(m, first, cold);
  const MpccResult b = solver.solve(m, scaled, cold);
  const MpccResult warm = solver.solve(m, first);
  const MpccResult warm_scaled = solver.solve(m, scaled);
  SCOPED_TRACE("cold: " + describe(a) + "\nwarm: " + describe(warm) +
               "\nwarm, scaled multipliers: " + describe(warm_scaled));
  ASSERT_EQ(a.status, MpccStatus::kSolved);
  EXPECT_NEAR(a.objective, f_ref, 1e-6);
  EXPECT_NEAR(a.z[0], z_ref[0], 1e-4);
  EXPECT_NEAR(a.z[1], z_ref[1], 1e-4);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ((a.z - b.z).cwiseAbs().maxCoeff(), 0.0) << "the multipliers were read";
  EXPECT_NE(warm.iterations, warm_scaled.iterations) << "a warm start reads them";
  EXPECT_NE(a.iterations, warm.iterations) << "started as the warm start";
}

// elastic.barrier_mu reaches Ipopt: with adaptive mu the barrier form's mu falls from 1 to
// 4e-6 at ExpSqrt's second iteration, sigma with it, and the solve settles on the branch x = 0
// (f = 2 at (0, 2), a local optimum); monotone mu (the suite above) reaches f* = 1.43337.
TEST(MpccBarrier, AdaptiveMuEndsExpSqrtOnItsOtherBranch) {
  const Problem pb = make_problem(ProblemId::kExpSqrt);
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSettings s = settings_for(ElasticFormulation::kBarrier, true);
  ASSERT_TRUE(s.barrier_monotone_mu) << "configs/disco.yaml's elastic.barrier_mu";
  s.barrier_monotone_mu = false;
  const MpccResult r = solve_fresh(*pb.mpcc, pb.start, s);
  ASSERT_EQ(r.status, MpccStatus::kSolved) << describe(r);
  EXPECT_NEAR(r.objective, 2.0, 1e-6) << describe(r);
  EXPECT_NEAR(r.z[0], 0.0, 1e-6);
  EXPECT_NEAR(r.z[1], 2.0, 1e-4);
}

// Polish fixes the smaller side of every pair, so every product is zero and the elastic
// variable's optimum is 0 whatever its weight; polish weighs it with at most Ipopt's
// nlp_scaling_max_gradient (100). Weighed with a raised zeta (1e6 here), the penalty's
// gradient made Ipopt scale the objective by 100 / zeta, which loosened the polished point's
// optimality as much: Ralph's polish ended at x = 0.002 (f = 4e-6).
TEST(MpccPolish, AtARaisedZetaItStillReachesTheOptimum) {
  const Problem pb = make_problem(ProblemId::kRalph);
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ASSERT_EQ(ipopt.scaling_max_gradient(), 100.0) << "Ipopt's default";
  ElasticSolver solver(ipopt, settings_for(ElasticFormulation::kLumped, true));
  ElasticRequest raised;
  raised.zeta = 1e6;
  const MpccResult r = solver.solve(*pb.mpcc, pb.start, raised);
  EXPECT_TRUE(r.polished) << describe(r);
  EXPECT_EQ(r.zeta, 1e6) << "the elastic solve's zeta, reported as before";
  expect_solved_to_reference(pb, r);
}

}  // namespace
}  // namespace disco
