// kkt.solver (core/ipopt/kkt_solver.h): disco's LDLᵀ inside Ipopt reaches the optimum MUMPS
// reaches; a matrix it cannot solve to kkt.ldlt.residual_tolerance goes to MUMPS, counted, and
// the solve still converges; the objective reduction ends certified with it; kkt.dump writes
// the matrices in the documented format.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_nlp.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/ipopt/kkt_solver.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "search/guess.h"
#include "search/solve_scene.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

// configs/disco.yaml's Ipopt and kkt settings, with overrides.
IpoptSettings settings_with(const std::vector<std::string>& overrides) {
  Settings s = Settings::load(default_settings_path());
  for (const auto& o : overrides) s.apply_override(o);
  return ipopt_settings(s);
}

// The elastic NLP of two robots meeting in contact: the bilinear complementarity terms make its
// KKT matrices indefinite, its constraint block starts empty (δc = 0).
struct Contact {
  Scene scene = model_test::two_robots_meeting_in_contact(8);
  RobotProblem rp{scene};
  ElasticNlp elastic{rp.program(), ElasticFormulation::kLumped, 10.0};
  NlpResult solve(const IpoptSettings& settings) const {
    IpoptSolver solver(settings);
    NlpPoint start;
    start.z = elastic.lift(smoothstep_guess(rp, 4.0));
    return solver.solve(elastic, start);
  }
};

// (Both converge; not necessarily to the same local optimum of this nonconvex NLP: other
// rounding, another path. test_ipopt_solver.cpp checks a known optimum with either solver.)
TEST(KktSolver, DiscosLdltSolvesAContactNlpWithoutMumps) {
  const Contact c;
  const NlpResult mumps = c.solve(settings_with({"kkt.solver=mumps"}));
  const NlpResult ldlt = c.solve(settings_with({"kkt.solver=ldlt"}));
  ASSERT_TRUE(mumps.converged()) << describe(mumps.outcome, mumps.ipopt_status);
  ASSERT_TRUE(ldlt.converged()) << describe(ldlt.outcome, ldlt.ipopt_status);
  EXPECT_GE(ldlt.kkt.factorisations, ldlt.iterations);
  EXPECT_EQ(mumps.kkt.fallbacks, 0);  // counted for ldlt only
  // Every matrix of this solve is well posed enough for the LDLᵀ alone.
  EXPECT_EQ(ldlt.kkt.fallbacks, 0);
}

// The pivoting LDLᵀ: the same contact NLP, no matrix to MUMPS, and every wrong inertia
// answered from D's blocks (exact: no certificate, no regularisation).
TEST(KktSolver, ThePivotingLdltSolvesAContactNlpWithoutMumps) {
  const Contact c;
  const NlpResult pivoted = c.solve(settings_with({"kkt.solver=pivoted"}));
  ASSERT_TRUE(pivoted.converged()) << describe(pivoted.outcome, pivoted.ipopt_status);
  EXPECT_GE(pivoted.kkt.factorisations, pivoted.iterations);
  EXPECT_EQ(pivoted.kkt.fallbacks, 0);
}

// The pivoting LDLᵀ first factorises such a matrix again with a raised threshold (counted), up
// to kkt.ldlt.pivoting.threshold_max; from 0.01 to 0.5: u ← √u twice (0.1, 0.316), then 0.5,
// where it stays for the rest of the solve.
TEST(KktSolver, AMatrixTheLdltCannotSolveToTheToleranceGoesToMumpsCounted) {
  const Contact c;
  for (const char* solver_name : {"ldlt", "pivoted"}) {
    SCOPED_TRACE(solver_name);
    // A tolerance no solve reaches: every matrix goes to MUMPS.
    const NlpResult all = c.solve(settings_with({std::string("kkt.solver=") + solver_name,
                                                 "kkt.ldlt.fallback=mumps",
                                                 "kkt.ldlt.residual_tolerance=1e-300",
                                                 "kkt.ldlt.refinement_steps=0"}));
    ASSERT_TRUE(all.converged()) << describe(all.outcome, all.ipopt_status);
    // Every iteration's accepted matrix went to MUMPS (a wrong inertia needs no solve: it is
    // not sent), each after its own LDLᵀ factorisation.
    EXPECT_GE(all.kkt.fallbacks, all.iterations);
    EXPECT_GE(all.kkt.factorisations - all.kkt.fallbacks, all.kkt.fallbacks);
    EXPECT_EQ(all.kkt.threshold_raises, std::string(solver_name) == "pivoted" ? 3 : 0);
  }
}

// kkt.ldlt.fallback pivoted: what the LDLᵀ cannot solve goes to the pivoting LDLᵀ (counted),
// which solves it; MUMPS factorises nothing. With a tolerance only the LDLᵀ misses (no
// refinement: its regularised factors alone), every accepted matrix is passed on.
TEST(KktSolver, WithThePivotedFallbackTheLdltsMissesGoToThePivotingLdlt) {
  const Contact c;
  for (const std::string fallback : {"pivoted", "mumps"}) {
    SCOPED_TRACE(fallback);
    const NlpResult r = c.solve(settings_with({"kkt.solver=ldlt", "kkt.ldlt.fallback=" + fallback,
                                               "kkt.ldlt.residual_tolerance=1e-14",
                                               "kkt.ldlt.refinement_steps=0"}));
    ASSERT_TRUE(r.converged()) << describe(r.outcome, r.ipopt_status);
    const bool pivoted = fallback == "pivoted";
    EXPECT_EQ(r.kkt.fallbacks > 0, !pivoted);
    EXPECT_EQ(r.kkt.to_pivoted > 0, pivoted);
  }
}

// The fill-reducing ordering of a structure is computed once per IpoptSolver: the LDLᵀ and
// the pivoting LDLᵀ it passes matrices to share it within a solve, and a later solve of the
// same NLP reuses it; the solve is the same bit for bit as one by a new IpoptSolver.
TEST(KktSolver, AnIpoptSolverOrdersEachStructureOnceAcrossSolversAndSolves) {
  const Contact c;
  const IpoptSettings settings = settings_with(
      {"kkt.solver=ldlt", "kkt.ldlt.fallback=pivoted", "kkt.ldlt.residual_tolerance=1e-14",
       "kkt.ldlt.refinement_steps=0"});
  IpoptSolver solver(settings);
  NlpPoint start;
  start.z = c.elastic.lift(smoothstep_guess(c.rp, 4.0));
  const NlpResult first = solver.solve(c.elastic, start);
  const NlpResult second = solver.solve(c.elastic, start);
  const NlpResult fresh = c.solve(settings);
  ASSERT_TRUE(first.converged()) << describe(first.outcome, first.ipopt_status);
  EXPECT_GT(first.kkt.to_pivoted, 0);  // both solvers analysed the structure
  EXPECT_EQ(first.kkt.orderings, 1);
  EXPECT_EQ(second.kkt.orderings, 0);
  EXPECT_EQ(fresh.kkt.orderings, 1);
  EXPECT_EQ(second.iterations, first.iterations);
  EXPECT_EQ(second.point.z, first.point.z);
  EXPECT_EQ(fresh.point.z, first.point.z);
}

TEST(KktSolver, BadSettingsAreRefusedNamingTheKey) {
  const auto message = [](const std::string& o) {
    try {
      settings_with({o});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("kkt.solver=pardiso").find("kkt.solver"), std::string::npos);
  EXPECT_NE(message("kkt.ldlt.regularisation=0").find("kkt.ldlt.regularisation"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.refinement_steps=-1").find("kkt.ldlt.refinement_steps"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.growth_limit=0").find("kkt.ldlt.growth_limit"), std::string::npos);
  EXPECT_NE(message("kkt.ldlt.certificate.iterations=-1").find("kkt.ldlt.certificate.iterations"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.certificate.margin=0.5").find("kkt.ldlt.certificate.margin"),
            std::string::npos);
  EXPECT_NE(message("kkt.dump.every=-2").find("kkt.dump.every"), std::string::npos);
  EXPECT_NE(message("kkt.ldlt.pivoting.threshold=0").find("kkt.ldlt.pivoting.threshold"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.pivoting.threshold=0.6").find("kkt.ldlt.pivoting.threshold"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.pivoting.threshold_max=0.001")
                .find("kkt.ldlt.pivoting.threshold_max"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.fallback=pardiso").find("kkt.ldlt.fallback"), std::string::npos);
  EXPECT_NE(message("kkt.ldlt.ordering.nested_dissection_above=-1")
                .find("kkt.ldlt.ordering.nested_dissection_above"),
            std::string::npos);
  EXPECT_NE(message("kkt.ldlt.pivoting.zero_pivot=-1").find("kkt.ldlt.pivoting.zero_pivot"),
            std::string::npos);
  EXPECT_NE(message("kkt.polish_rescue.solver=pardiso").find("kkt.polish_rescue.solver"),
            std::string::npos);
  EXPECT_NE(message("kkt.polish_rescue.after=-1").find("kkt.polish_rescue.after"),
            std::string::npos);
}

// kkt.polish_rescue: a solve with a branch fixed (NlpLimits::fixed_branch) that has not converged
// within `after` iterations by kkt.solver is started again from its start by the rescue solver
// (after 0: by it alone; solver same: never), every other solve by kkt.solver. Seen bit for
// bit against plain solves by MUMPS and by the pivoting LDLᵀ, which end at different points.
TEST(KktSolver, ASolveWithAFixedBranchIsRescuedByThePolishRescueSolver) {
  const Contact c;
  NlpPoint start;
  start.z = c.elastic.lift(smoothstep_guess(c.rp, 4.0));
  NlpLimits fixed;
  fixed.fixed_branch = true;
  const auto solver = [](const std::string& kkt, const std::string& rescue, int after) {
    return std::make_unique<IpoptSolver>(settings_with({"kkt.solver=" + kkt,
                                                        "kkt.polish_rescue.solver=" + rescue,
                                                        "kkt.polish_rescue.after=" +
                                                            std::to_string(after)}));
  };
  const NlpResult by_mumps = solver("mumps", "same", 1)->solve(c.elastic, start);
  const NlpResult by_pivoted = solver("pivoted", "same", 1)->solve(c.elastic, start);
  ASSERT_TRUE(by_mumps.converged()) << describe(by_mumps.outcome, by_mumps.ipopt_status);
  ASSERT_TRUE(by_pivoted.converged()) << describe(by_pivoted.outcome, by_pivoted.ipopt_status);
  ASSERT_NE(by_mumps.point.z, by_pivoted.point.z);  // the two solvers are told apart
  ASSERT_GT(by_mumps.iterations, 5);
  const auto same_as = [](const NlpResult& r, const NlpResult& ref, int extra_iterations) {
    EXPECT_EQ(r.point.z, ref.point.z);
    EXPECT_EQ(r.iterations, ref.iterations + extra_iterations);
  };

  {
    SCOPED_TRACE("solver same: no rescue");
    const NlpResult r = solver("mumps", "same", 1)->solve(c.elastic, start, fixed);
    same_as(r, by_mumps, 0);
    EXPECT_EQ(r.kkt.polish_rescues, 0);
  }
  {
    SCOPED_TRACE("after 0: the rescue solver alone, for a fixed branch only");
    const auto routed = solver("mumps", "pivoted", 0);
    const NlpResult plain = routed->solve(c.elastic, start);
    same_as(plain, by_mumps, 0);
    EXPECT_EQ(plain.kkt.orderings, 0);  // MUMPS orders nothing of disco's
    const NlpResult r = routed->solve(c.elastic, start, fixed);
    same_as(r, by_pivoted, 0);
    EXPECT_EQ(r.kkt.orderings, 1);
    EXPECT_EQ(r.kkt.polish_rescues, 0);
  }
  {
    SCOPED_TRACE("after 5: MUMPS's 5 iterations, then the pivoting LDLT's solve from the start");
    const NlpResult r = solver("mumps", "pivoted", 5)->solve(c.elastic, start, fixed);
    ASSERT_TRUE(r.converged());
    same_as(r, by_pivoted, 5);
    EXPECT_EQ(r.kkt.polish_rescues, 1);
  }
  {
    // (A cap of k iterations stops at iterate k before Ipopt tests it: MUMPS's solve ends
    // there with one more.)
    SCOPED_TRACE("converged within `after`: MUMPS's solve");
    const NlpResult r =
        solver("mumps", "pivoted", by_mumps.iterations + 1)->solve(c.elastic, start, fixed);
    same_as(r, by_mumps, 0);
    EXPECT_EQ(r.kkt.polish_rescues, 0);
  }
  {
    SCOPED_TRACE("the request's own iteration limit first: no rescue; later: the rest of it");
    NlpLimits capped = fixed;
    capped.iterations = 3;
    const NlpResult r = solver("mumps", "pivoted", 5)->solve(c.elastic, start, capped);
    EXPECT_EQ(r.outcome, NlpOutcome::kIterationCap);
    EXPECT_EQ(r.iterations, 3);
    EXPECT_EQ(r.kkt.polish_rescues, 0);
    capped.iterations = 8;
    const NlpResult rest = solver("mumps", "pivoted", 5)->solve(c.elastic, start, capped);
    EXPECT_EQ(rest.outcome, NlpOutcome::kIterationCap);
    EXPECT_EQ(rest.iterations, 8);
    EXPECT_EQ(rest.kkt.polish_rescues, 1);
  }
}

// The elastic solver's solves with a branch fixed, its polish and solve_branch's branch solves,
// are the ones kkt.polish_rescue applies to: with `after` 0, under kkt.solver mumps, only they
// make disco's solvers order a structure (KktCounts::orderings), and only with solver pivoted.
TEST(KktSolver, PolishAndBranchSolvesAreTheFixedBranchSolves) {
  const Contact c;
  const Vector guess = smoothstep_guess(c.rp, 4.0);
  Settings base = Settings::load(default_settings_path());
  base.apply_override("kkt.solver=mumps");
  base.apply_override("kkt.polish_rescue.after=0");
  for (const bool polish : {true, false}) {
    for (const std::string rescue : {"pivoted", "same"}) {
      SCOPED_TRACE(std::string(polish ? "polish, " : "no polish, ") + rescue);
      Settings s = base;
      s.apply_override("kkt.polish_rescue.solver=" + rescue);
      s.apply_override(std::string("elastic.polish=") + (polish ? "true" : "false"));
      IpoptSolver ipopt(ipopt_settings(s));
      const ElasticSolver solver(ipopt, elastic_settings(s));
      const MpccResult r = solver.solve(c.rp.program(), guess);
      ASSERT_TRUE(r.solved()) << to_string(r.status);
      EXPECT_EQ(r.polished, polish);
      const bool routed = rescue == "pivoted";
      EXPECT_EQ(r.kkt.orderings > 0, polish && routed);
      IpoptSolver branch_ipopt(ipopt_settings(s));
      const ElasticSolver branch(branch_ipopt, elastic_settings(s));
      const MpccResult b = branch.solve_branch(c.rp.program(), r, 0);
      EXPECT_EQ(b.branch_solves, 1);
      EXPECT_EQ(b.kkt.orderings > 0, routed);
    }
  }
}

TEST(KktSolver, TheObjectiveReductionEndsCertifiedWithTheLdlt) {
  const Scene scene = load_scene(
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/two_robots_swap_avoid.yaml", {"steps=20"});
  for (const char* solver_name : {"ldlt", "pivoted"}) {
    SCOPED_TRACE(solver_name);
    Settings settings = Settings::load(default_settings_path());
    settings.apply_override(std::string("kkt.solver=") + solver_name);
    const SceneSolve solve = solve_scene(scene, settings);
    ASSERT_EQ(solve.result.status, MpccStatus::kSolved);
    EXPECT_TRUE(solve.result.best.certificate.within(1e-6, 1e-6));
  }
}

// With the inertia certificate on and a margin no estimate can pass, every wrong inertia of the
// LDLᵀ goes to MUMPS, counted; the solve still converges. (The contact problem's KKT matrices
// are indefinite at some iterations: without the certificate, Ipopt meets wrong inertias.)
TEST(KktSolver, AnUncertifiedWrongInertiaGoesToMumpsCounted) {
  const Contact c;
  const NlpResult plain = c.solve(settings_with({"kkt.solver=ldlt", "kkt.ldlt.fallback=mumps"}));
  ASSERT_TRUE(plain.converged());
  const NlpResult strict = c.solve(
      settings_with({"kkt.solver=ldlt", "kkt.ldlt.fallback=mumps",
                     "kkt.ldlt.certificate.iterations=3", "kkt.ldlt.certificate.margin=1e300"}));
  ASSERT_TRUE(strict.converged());
  EXPECT_GT(strict.kkt.fallbacks, plain.kkt.fallbacks);
  const NlpResult usual = c.solve(
      settings_with({"kkt.solver=ldlt", "kkt.ldlt.fallback=mumps",
                     "kkt.ldlt.certificate.iterations=5", "kkt.ldlt.certificate.margin=2"}));
  ASSERT_TRUE(usual.converged());
  EXPECT_LT(usual.kkt.fallbacks, strict.kkt.fallbacks);
}

TEST(KktSolver, TheDumpWritesEveryKthMatrixInTheDocumentedFormat) {
  const Contact c;
  const std::string dir =
      (std::filesystem::temp_directory_path() / "disco_kkt_dump_test").string();
  std::filesystem::remove_all(dir);
  const NlpResult r =
      c.solve(settings_with({"kkt.solver=ldlt", "kkt.dump.every=4", "kkt.dump.dir=" + dir}));
  ASSERT_TRUE(r.converged());
  // Every matrix handed over for factorisation counts (not the degeneracy test's answered ones,
  // nor a fallback's second factorisation of the same matrix).
  const int asked = r.kkt.matrices();
  int files = 0;
  for (int k = 0; k < asked + 8; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.kkt", k);
    const auto path = std::filesystem::path(dir) / name;
    ASSERT_EQ(std::filesystem::exists(path), k % 4 == 0 && k < asked) << name;
    if (!std::filesystem::exists(path)) continue;
    ++files;
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    int32_t header[6];
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(header), sizeof header);
    ASSERT_EQ(std::memcmp(magic, kKktFileMagic, 8), 0);
    EXPECT_EQ(header[0], kKktFileVersion);
    const int n = header[1], nnz = header[2], dual_from = header[3];
    // The constraint block: one row per constraint, after the variables and the slacks.
    EXPECT_EQ(n - dual_from, c.elastic.num_constraints());
    EXPECT_LT(dual_from, n);
    // Triplets, values and one right-hand side: exactly the rest of the file.
    EXPECT_EQ(std::filesystem::file_size(path),
              8 + sizeof header + nnz * (2 * sizeof(int32_t) + sizeof(double)) +
                  n * sizeof(double));
  }
  EXPECT_GE(files, 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace disco
