// ElasticSolver::solve_branch: the branch program (smaller side of every pair fixed to 0),
// the sign test at biactive pairs, and the flips it makes, on MPCCs small enough to solve by
// hand. Each side of the pair is a variable or a row (the row gets a slack in the elastic
// program, and the fixed side is then that slack).
//
//   descent:   min (x - 1)^2 + y^2,  0 <= x _|_ y >= 0. From (0, 0.5) the branch x = 0 gives
//              (0, 0), f = 1: biactive, and the multiplier of x = 0 is 2(x - 1) = -2 < 0, so
//              releasing x descends. The flip fixes y = 0 instead: (1, 0), f = 0.
//   stationary: min (x + 1)^2 + (y + 1)^2, same pair. From (0, 0.5): (0, 0), f = 2, biactive
//              with multipliers 2 and 2: B-stationary, nothing to flip.
#include <gtest/gtest.h>

#include <memory>

#include "core/elastic/elastic_nlp.h"
#include "core/elastic/elastic_solver.h"
#include "core/nlp/polynomial_program.h"
#include "core/util/numbers.h"
#include "tests/test_support_mpcc.h"

namespace disco {
namespace {

using S = ComplementaritySide;
using test_support::disco_yaml_ipopt_settings;

// min (x - a)^2 + (y - b)^2 with 0 <= x _|_ y >= 0; `row_side`: the pair's second side is
// the row y (bounds free) instead of the variable y.
std::unique_ptr<PolynomialProgram> make(double a, double b, bool row_side) {
  auto p = std::make_unique<PolynomialProgram>();
  p->add_variable(-kInf, kInf);
  p->add_variable(-kInf, kInf);
  p->add(PolynomialProgram::kObjective, 1.0, Affine::variable(0) - Affine(a),
         Affine::variable(0) - Affine(a));
  p->add(PolynomialProgram::kObjective, 1.0, Affine::variable(1) - Affine(b),
         Affine::variable(1) - Affine(b));
  if (row_side) {
    const int r = p->add_row(-kInf, kInf);
    p->add(r, 1.0, Affine::variable(1));
    p->add_pair(S::variable(0), S::row(r));
  } else {
    p->add_pair(S::variable(0), S::variable(1));
  }
  p->finalize();
  return p;
}

// A result at MPCC point z, as solve_branch takes it (no duals: a cold start).
MpccResult at(const Mpcc& m, const ElasticSettings& s, double x, double y) {
  MpccResult r;
  r.z = (Vector(2) << x, y).finished();
  r.elastic_point.z = ElasticNlp(m, s.formulation, s.zeta).lift(r.z);
  r.status = MpccStatus::kSolved;
  return r;
}

class BranchDescent : public ::testing::TestWithParam<std::tuple<ElasticFormulation, bool>> {
 protected:
  ElasticSettings settings() const {
    ElasticSettings s = test_support::disco_yaml_elastic_settings();
    s.formulation = std::get<0>(GetParam());
    return s;
  }
  bool row_side() const { return std::get<1>(GetParam()); }
  // solve_branch on min (x - a)^2 + (y - b)^2 from (0, 0.5), where x is the smaller side.
  MpccResult descend(double a, double b, int max_flip_rounds) const {
    const auto m = make(a, b, row_side());
    IpoptSolver ipopt(disco_yaml_ipopt_settings());
    ElasticSolver solver(ipopt, settings());
    return solver.solve_branch(*m, at(*m, settings(), 0.0, 0.5), max_flip_rounds);
  }
};

TEST_P(BranchDescent, FlipsABiactivePairWhoseFixedSideHasANegativeMultiplier) {
  const MpccResult r = descend(1.0, 0.0, 5);
  ASSERT_TRUE(r.solved());
  EXPECT_TRUE(r.b_stationary);
  EXPECT_GE(r.flips, 1);
  EXPECT_GE(r.branch_solves, 2);
  EXPECT_NEAR(r.z[0], 1.0, 1e-6);
  EXPECT_NEAR(r.z[1], 0.0, 1e-6);
  EXPECT_NEAR(r.objective, 0.0, 1e-9);
  EXPECT_LE(r.certificate.max_complementarity, 1e-9);
}

TEST_P(BranchDescent, WithoutFlipsStopsAtTheBiactivePointAndSaysItIsNotBStationary) {
  const MpccResult r = descend(1.0, 0.0, 0);
  ASSERT_TRUE(r.solved());
  EXPECT_FALSE(r.b_stationary);
  EXPECT_EQ(r.branch_solves, 1);
  EXPECT_NEAR(r.z[0], 0.0, 1e-12);  // fixed
  // y is free at its bound 0: an interior-point solution leaves y ~ sqrt(mu) (1.7e-5 here).
  EXPECT_NEAR(r.z[1], 0.0, 1e-4);
  EXPECT_NEAR(r.objective, 1.0, 1e-8);
}

TEST_P(BranchDescent, KeepsABiactivePairWhoseMultipliersAreNonnegative) {
  const MpccResult r = descend(-1.0, -1.0, 5);
  ASSERT_TRUE(r.solved());
  EXPECT_TRUE(r.b_stationary);
  EXPECT_EQ(r.flips, 0);
  EXPECT_EQ(r.branch_solves, 1);
  EXPECT_NEAR(r.objective, 2.0, 1e-6);
}

TEST_P(BranchDescent, AnInfeasibleBranchReportsItsOwnStatusAndKeepsTheStartPoint) {
  // x = 0 is fixed (0 < 0.5), but a row asks x >= 1: the branch program is infeasible.
  auto p = std::make_unique<PolynomialProgram>();
  p->add_variable(-kInf, kInf);
  p->add_variable(-kInf, kInf);
  p->add(PolynomialProgram::kObjective, 1.0, Affine::variable(1), Affine::variable(1));
  const int r1 = p->add_row(1.0, kInf);
  p->add(r1, 1.0, Affine::variable(0));
  p->add_pair(S::variable(0), S::variable(1));
  p->finalize();
  IpoptSolver ipopt(disco_yaml_ipopt_settings());
  ElasticSolver solver(ipopt, settings());
  const MpccResult r = solver.solve_branch(*p, at(*p, settings(), 0.0, 0.5), 5);
  EXPECT_FALSE(r.solved());
  EXPECT_EQ(r.branch_solves, 1);
  EXPECT_DOUBLE_EQ(r.z[1], 0.5);
}

INSTANTIATE_TEST_SUITE_P(
    Textbook, BranchDescent,
    ::testing::Combine(::testing::Values(ElasticFormulation::kLumped, ElasticFormulation::kPerPair),
                       ::testing::Bool()),
    [](const auto& info) {
      return std::string(std::get<0>(info.param) == ElasticFormulation::kLumped ? "Lumped"
                                                                                 : "PerPair") +
             (std::get<1>(info.param) ? "RowSide" : "VariableSide");
    });

}  // namespace
}  // namespace disco
