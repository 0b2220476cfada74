// The complementarity relaxation moved with Ipopt's barrier parameter inside one Ipopt run
// (elastic formulation barrier; core/elastic/elastic_nlp.h, core/ipopt/ipopt_solver.h
// NlpLimits::follow_barrier; issue 34):
//   - one row per pair, u_i w_i - sigma <= eps, with exact derivatives;
//   - the live relaxation shifts the pair rows' values only (not their derivatives, not bounds);
//   - the hook is honest: at every iteration where it moves sigma, Ipopt's own inequality values
//     at its current iterate move by exactly that much (read from Ipopt's calculated quantities
//     before and after), sigma follows Ipopt's mu, and the solve still converges;
//   - the elastic solver with formulation barrier solves the Scheel-Scholtes MPCC.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/elastic/elastic_solver.h"
#include "core/nlp/derivative_checker.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/numbers.h"
#include "tests/test_support_derivatives.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using S = ComplementaritySide;

// min (x - 1)² + (y - 1)²,  0 <= x ⊥ y >= 0  (Scheel & Scholtes): f* = 1 at (0, 1) and (1, 0).
PolynomialProgram scheel_scholtes() {
  PolynomialProgram p;
  p.add_variable(-kInf, kInf, 1.0);
  p.add_variable(-kInf, kInf, 0.2);
  for (int k : {0, 1})
    p.add(PolynomialProgram::kObjective, 1.0, Affine::variable(k) - Affine(1.0),
          Affine::variable(k) - Affine(1.0));
  p.add_pair(S::variable(0), S::variable(1));
  p.finalize();
  return p;
}

// Three pairs, one with a row side: 0 <= x0 ⊥ x1 >= 0, 0 <= x2 ⊥ r0 >= 0, 0 <= x3 ⊥ x0 >= 0.
PolynomialProgram three_pairs() {
  PolynomialProgram p;
  for (int k = 0; k < 4; ++k) p.add_variable(-kInf, kInf, 0.3 + k);
  const Affine x0 = Affine::variable(0), x1 = Affine::variable(1), x2 = Affine::variable(2),
               x3 = Affine::variable(3);
  const int r0 = p.add_row(-kInf, kInf);
  p.add(r0, 1.0, x0, x1);
  p.add(r0, 1.0, x2 - Affine(0.5));
  p.add(PolynomialProgram::kObjective, 1.0, x0, x1, x3);
  p.add(PolynomialProgram::kObjective, 1.0, x2, x2);
  p.add_pair(S::variable(0), S::variable(1));
  p.add_pair(S::variable(2), S::row(r0));
  p.add_pair(S::variable(3), S::variable(0));
  p.finalize();
  return p;
}

// The pair rows' first and second derivatives, against finite differences (Ceres-style
// gradient checker, core/nlp/derivative_checker.h), at a live relaxation too.
TEST(BarrierRelaxation, ThePairRowsDerivativesAreExact) {
  const PolynomialProgram mpcc = three_pairs();
  ElasticNlp e(mpcc, ElasticFormulation::kBarrier, 7.3);
  EXPECT_EQ(e.num_constraints(), mpcc.num_constraints() + 3);  // one row per pair
  std::mt19937 rng(34);
  for (int trial = 0; trial < 6; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    e.set_live_relaxation(trial * 0.1);
    const Vector x = test_support::random_vector(rng, e.num_variables(), -2.0, 2.0);
    const Vector lambda = test_support::random_vector(rng, e.num_constraints(), -3.0, 3.0);
    const auto report = check_derivatives(e, x, 0.7, lambda);
    ASSERT_NO_FATAL_FAILURE(test_support::expect_exact_derivatives(report));
  }
  // The lift: eps is the largest product, every pair row then at most 0.
  e.set_live_relaxation(0.0);
  const Vector x = e.lift(mpcc.initial_point());
  Vector c(e.num_constraints());
  ASSERT_TRUE(e.constraints(x, c));
  EXPECT_EQ(c.tail(3).maxCoeff(), 0.0);
}

TEST(BarrierRelaxation, TheLiveRelaxationShiftsThePairRowsValuesOnly) {
  const PolynomialProgram mpcc = scheel_scholtes();
  ElasticNlp nlp(mpcc, ElasticFormulation::kBarrier, 10.0);
  const Vector x = nlp.lift(mpcc.initial_point());
  const int row = nlp.num_constraints() - 1;
  Vector c0(nlp.num_constraints()), c1 = c0, j0(nlp.jacobian_pattern().size()), j1 = j0;
  const Vector hi = nlp.constraint_upper();
  ASSERT_TRUE(nlp.constraints(x, c0) && nlp.jacobian(x, j0));
  nlp.set_live_relaxation(0.25);
  ASSERT_TRUE(nlp.constraints(x, c1) && nlp.jacobian(x, j1));
  EXPECT_EQ(c1[row], c0[row] - 0.25);
  EXPECT_EQ(j1, j0);
  EXPECT_EQ(nlp.constraint_upper(), hi);
  // Only formulation barrier has a live relaxation (a programming error elsewhere).
  ElasticNlp lumped(mpcc, ElasticFormulation::kLumped, 10.0);
  EXPECT_THROW(lumped.set_live_relaxation(0.25), std::exception);
}

TEST(BarrierRelaxation, IpoptSeesSigmaMoveWithItsOwnMuAtEveryIteration) {
  const PolynomialProgram mpcc = scheel_scholtes();
  ElasticNlp nlp(mpcc, ElasticFormulation::kBarrier, 10.0);
  // No NLP scaling, so that Ipopt's d is the rows' own values.
  std::vector<IpoptOption> options = test_support::disco_yaml_ipopt_options();
  options.push_back({"nlp_scaling_method", "none", "test"});
  IpoptSettings settings = test_support::disco_yaml_ipopt_settings();
  settings.options = options;
  IpoptSolver ipopt(settings);
  NlpPoint start;
  start.z = nlp.lift(mpcc.initial_point());
  NlpLimits limits;
  std::vector<double> set;  // every sigma the hook set, in order
  limits.follow_barrier = [&](double mu) {
    if (mu == nlp.live_relaxation()) return false;
    nlp.set_live_relaxation(mu);  // sigma = mu
    set.push_back(mu);
    return true;
  };
  const NlpResult r = ipopt.solve(nlp, start, limits);
  ASSERT_TRUE(r.converged()) << describe(r.outcome, r.ipopt_status);
  ASSERT_EQ(r.refreshes.size(), set.size());
  ASSERT_GE(r.refreshes.size(), 3u);
  double previous = 0.0;  // the NLP's sigma before the first refresh
  for (size_t k = 0; k < r.refreshes.size(); ++k) {
    const BarrierRefresh& f = r.refreshes[k];
    EXPECT_EQ(set[k], f.mu) << "refresh " << k;  // sigma is Ipopt's own mu at that iteration
    // Ipopt's d(x) at its unchanged iterate moved by exactly the change of sigma.
    EXPECT_NEAR(f.d_change, std::abs(f.mu - previous), 1e-12 * std::max(1.0, f.mu))
        << "refresh " << k << " at iteration " << f.iteration;
    if (k > 0) {
      EXPECT_GT(f.iteration, r.refreshes[k - 1].iteration);
    }
    previous = f.mu;
  }
  // Over the solve, mu and with it sigma went down by orders of magnitude.
  EXPECT_LT(r.refreshes.back().mu, 1e-3 * r.refreshes.front().mu);
}

TEST(BarrierRelaxation, TheElasticSolverSolvesScheelScholtes) {
  const PolynomialProgram mpcc = scheel_scholtes();
  ElasticSettings s = test_support::disco_yaml_elastic_settings();
  s.formulation = ElasticFormulation::kBarrier;
  IpoptSolver ipopt(test_support::disco_yaml_ipopt_settings());
  ElasticSolver solver(ipopt, s);
  const MpccResult r = solver.solve(mpcc, mpcc.initial_point());
  ASSERT_TRUE(r.solved()) << to_string(r.status);
  EXPECT_NEAR(r.objective, 1.0, 1e-6);
  EXPECT_LE(std::min(std::abs(r.z[0]), std::abs(r.z[1])), 1e-6);
}

}  // namespace
}  // namespace disco
