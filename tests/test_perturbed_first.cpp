// kkt.perturbed_first (core/ipopt/kkt_solver.h): disco answers Ipopt's degeneracy test so
// that Ipopt tries an unperturbed KKT matrix in its first three iterations only and then starts
// every factorisation from a Hessian perturbation. Checked on Ipopt's own factorisation log
// (print_level 7 prints every trial factorisation's delta_x): with it, exactly the four trials
// disco answers have delta_x = 0 and the solve still converges; without it, every iteration
// first tries delta_x = 0. The objective reduction ends certified with it.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/elastic/elastic_nlp.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/robot_problem.h"
#include "search/guess.h"
#include "search/solve_scene.h"
#include "core/model/scene_yaml.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

// What one traced solve did.
struct Trace {
  NlpResult result;
  int unperturbed = 0;  // trial factorisations Ipopt made with delta_x = 0
  int trials = 0;       // trial factorisations Ipopt made
};

// Solves `nlp` from `start` (cold) with configs/disco.yaml's Ipopt options and kkt.perturbed_first
// as given, reading Ipopt's factorisation log.
Trace solve_traced(bool perturbed_first, const Nlp& nlp, const Vector& start) {
  IpoptSettings settings = ipopt_settings(Settings::load(default_settings_path()));
  settings.perturbed_first = perturbed_first;
  settings.options.push_back({"print_level", "7", "test: the factorisation log"});
  IpoptSolver solver(settings);
  NlpPoint point;
  point.z = start;
  testing::internal::CaptureStdout();
  Trace t;
  t.result = solver.solve(nlp, point);
  std::fflush(stdout);
  const std::string log = testing::internal::GetCapturedStdout();
  const std::string zero = "Solving system with delta_x=0.000000e+00";
  for (size_t at = log.find(zero); at != std::string::npos; at = log.find(zero, at + 1))
    ++t.unperturbed;
  const std::string trial = "Solving system with delta_x=";
  for (size_t at = log.find(trial); at != std::string::npos; at = log.find(trial, at + 1))
    ++t.trials;
  return t;
}

// Two robots meeting in contact mode: the elastic NLP's bilinear complementarity terms make
// the KKT matrix indefinite.
TEST(PerturbedFirst, IpoptTriesTheUnperturbedMatrixOnlyInItsFirstThreeIterations) {
  const Scene scene = model_test::two_robots_meeting_in_contact(8);
  const RobotProblem rp(scene);
  const ElasticNlp elastic(rp.program(), ElasticFormulation::kLumped, 10.0);
  const Vector x0 = elastic.lift(smoothstep_guess(rp, 4.0));

  const Trace off = solve_traced(false, elastic, x0);
  ASSERT_TRUE(off.result.converged()) << describe(off.result.outcome, off.result.ipopt_status);
  EXPECT_EQ(off.result.kkt.answered, 0);
  // Ipopt as configured: every iteration's first trial has delta_x = 0.
  EXPECT_GE(off.unperturbed, off.result.iterations);

  const Trace on = solve_traced(true, elastic, x0);
  ASSERT_TRUE(on.result.converged()) << describe(on.result.outcome, on.result.ipopt_status);
  ASSERT_GT(on.result.iterations, 6);
  // Iteration 0: delta_x = delta_c = 0, then delta_c > 0; iterations 1 and 2: delta_x = 0.
  // All four answered; after them Ipopt never tries delta_x = 0 again.
  EXPECT_EQ(on.result.kkt.answered, 4);
  EXPECT_EQ(on.unperturbed, 4);
  // Every iteration factorised at least once, and at most the trials Ipopt logs (with the
  // option, less those answered), plus the cold start's least-squares multiplier estimate,
  // which Ipopt does not log as a trial.
  // (A matrix disco's LDLᵀ passes on is one trial factorised twice: KktCounts::matrices.)
  const int on_trials = on.result.kkt.matrices();
  const int off_trials = off.result.kkt.matrices();
  EXPECT_GE(on_trials, on.result.iterations);
  EXPECT_LE(on_trials, on.trials - 4 + 1);
  EXPECT_LE(off_trials, off.trials + 1);
  // Whether the option saves factorisations in all is not a property of one solve: the two
  // paths part through roundoff, and how many iterations and inertia corrections each takes
  // differs with them (at 7a3d158: 166 factorisations in 109 iterations with the option, 150
  // in 82 without). The saving is measured on the start set (scripts/results/bench_starts.md,
  // section "kkt.perturbed_first=true vs baseline kkt.perturbed_first=false").
}

// A start of the objective reduction (start 0 of a small swap scene) ends with a certified
// answer with the option on, as without it. (Not necessarily at the same local optimum: the
// perturbations change the iterates, and which optimum a start ends in is sensitive to them;
// the whole start set measures that, scripts/results/bench_starts.md.)
TEST(PerturbedFirst, TheObjectiveReductionEndsCertified) {
  const Scene scene = load_scene(
      std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/two_robots_swap_avoid.yaml", {"steps=20"});
  for (bool on : {false, true}) {
    Settings settings = Settings::load(default_settings_path());
    settings.apply_override(std::string("kkt.perturbed_first=") + (on ? "true" : "false"));
    const SceneSolve solve = solve_scene(scene, settings);
    ASSERT_EQ(solve.result.status, MpccStatus::kSolved) << (on ? "on" : "off");
    EXPECT_TRUE(solve.result.best.certificate.within(1e-6, 1e-6));
  }
}

}  // namespace
}  // namespace disco
