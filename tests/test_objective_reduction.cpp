// The objective reduction (search/objective_reduction.h). Its perturbation
// hook (step 1b): a perturbed feasible start reaches a certified solution and
// records its extra solve; a perturbation that cannot be certified leaves the
// reduction exactly as without one; start 0 of the search is bit-identical to
// `disco solve`. Its schedule: no step is asked below a valid lower bound, and
// a local optimum ends the loop once a probe below it fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "search/guess.h"
#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/util/clock.h"
#include "core/util/errors.h"
#include "core/model/robot_problem.h"
#include "core/model/scene_yaml.h"
#include "search/objective_reduction.h"
#include "search/reduction_phases.h"
#include "search/run_start.h"
#include "search/solve_scene.h"
#include "search/start.h"
#include "test_support_start.h"

namespace disco {
namespace {

Scene scenario(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/" + name + ".yaml",
                    overrides);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

int count_kind(const ReductionResult& r, SolveKind kind) {
  int n = 0;
  for (const SolveRecord& s : r.solves) n += s.kind == kind;
  return n;
}

TEST(ObjectiveReduction, PerturbedFeasibleStartReachesACertifiedSolution) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  const Settings settings = Settings::load(default_settings_path());
  StartSpec start = start_test::first_start_of(scene, 3, GuessKind::kPerturbedFeasible, 0,
                                               reduction_settings(settings),
                                               elastic_settings(settings));
  ASSERT_EQ(start.guess, GuessKind::kPerturbedFeasible);
  start.schedule.max_solves = 4;  // a few reduction steps are enough here (and keep it fast)
  std::printf("%s\n", start.describe().c_str());
  RobotProblem problem(scene);
  IpoptSolver ipopt(ipopt_settings(settings));
  ElasticSolver solver(ipopt, start.elastic);
  std::vector<SolveKind> phases;
  const ReductionResult result = reduce_objective(
      problem, solver, start.schedule,
      [&](double seconds) { return make_guess(problem, start, seconds); },
      [&](const SolveRecord& r) { phases.push_back(r.kind); },
      make_perturbation(problem, start));
  for (const SolveRecord& r : result.solves)
    std::printf("  %-22s bound %.4f T_f %.4f %s%s\n", to_string(r.kind).c_str(), r.bound, r.T_f,
                to_string(r.status).c_str(), r.improved ? " *" : "");
  std::printf("T_best %.4f s, %zu solves, %d Ipopt iterations, %.2f s\n", result.best_value,
              result.solves.size(), result.iterations, result.seconds);
  ASSERT_TRUE(result.found) << to_string(result.status) << " " << result.feasibility_detail;
  EXPECT_EQ(result.status, MpccStatus::kSolved);
  EXPECT_TRUE(result.best.certificate.within(1e-6, 1e-6));
  // One perturbed re-solve, right after the certified feasibility solve, at
  // T_scale times its horizon; the callback saw every record.
  ASSERT_EQ(count_kind(result, SolveKind::kPerturbedFeasibility), 1);
  size_t k = 0;
  while (k < result.solves.size() && result.solves[k].kind != SolveKind::kPerturbedFeasibility) ++k;
  ASSERT_GE(k, 1u);
  const SolveRecord& feasible = result.solves[k - 1];
  EXPECT_EQ(feasible.kind, SolveKind::kFeasibility);
  EXPECT_TRUE(feasible.improved);
  EXPECT_NEAR(result.solves[k].bound, start.T_scale * feasible.T_f, 1e-9 * feasible.T_f);
  EXPECT_EQ(phases.size(), result.solves.size());
  // Never worse than the feasible point it started from.
  EXPECT_LE(result.best_value, feasible.T_f);
}

TEST(ObjectiveReduction, AnUncertifiedPerturbationLeavesTheReductionAsWithout) {
  const Scene scene = scenario("one_robot_axis", {"steps=20"});
  const Settings settings = Settings::load(default_settings_path());
  ReductionSettings schedule = reduction_settings(settings);
  auto run = [&](const PerturbFunction& perturb) {
    RobotProblem problem(scene);
    IpoptSolver ipopt(ipopt_settings(settings));
    ElasticSolver solver(ipopt, elastic_settings(settings));
    return reduce_objective(problem, solver, schedule, {}, {}, perturb);
  };
  const ReductionResult plain = run({});
  ASSERT_TRUE(plain.found);
  // Half the scene's lower bound: no certified point exists there.
  const RobotProblem shape(scene);
  const double impossible = 0.5 * shape.lower_bound().value();
  int calls = 0;
  const ReductionResult perturbed = run([&](const Vector&) {
    ++calls;
    return Perturbation{smoothstep_guess(shape, impossible), impossible};
  });
  EXPECT_EQ(calls, 1);
  ASSERT_TRUE(perturbed.found);
  ASSERT_EQ(perturbed.solves.size(), plain.solves.size() + 1);
  const SolveRecord& extra = perturbed.solves[1];
  EXPECT_EQ(extra.kind, SolveKind::kPerturbedFeasibility);
  EXPECT_NE(extra.status, MpccStatus::kSolved);
  EXPECT_FALSE(extra.improved);
  EXPECT_EQ(extra.bound, impossible);
  // Everything else as without the perturbation, bit for bit, but the feasibility solve's
  // polish: a feasible point that a perturbation starts from is polished, one that only starts
  // later solves is not (objective_reduction.h, "Polish"; the next test).
  EXPECT_TRUE(same_bits(perturbed.best_value, plain.best_value))
      << perturbed.best_value << " vs " << plain.best_value;
  for (size_t k = 0; k < plain.solves.size(); ++k) {
    const SolveRecord& a = plain.solves[k];
    const SolveRecord& b = perturbed.solves[k == 0 ? 0 : k + 1];
    EXPECT_EQ(a.kind, b.kind) << k;
    EXPECT_TRUE(same_bits(a.T_f, b.T_f)) << k;
    if (k > 0) {
      EXPECT_EQ(a.iterations, b.iterations) << k;
    }
  }
  EXPECT_EQ(plain.solves[0].nlp_solves, 1);
  EXPECT_EQ(perturbed.solves[0].nlp_solves, 2);
}

TEST(ObjectiveReduction, StartZeroIsBitIdenticalToDiscoSolve) {
  const Scene scene = scenario("one_robot_axis", {"steps=20"});
  const Settings settings = Settings::load(default_settings_path());
  const SceneSolve solve = solve_scene(scene, settings);
  ASSERT_TRUE(solve.solved());
  const StartSpec start =
      make_start(scene, 2024, 0, reduction_settings(settings), elastic_settings(settings));
  const StartOutcome outcome = run_start(scene, settings, start, 0.0, BudgetSource::kNone);
  ASSERT_TRUE(outcome.solved()) << to_string(outcome.status) << " " << outcome.detail;
  EXPECT_TRUE(same_bits(outcome.T_f, solve.T_f())) << outcome.T_f << " vs " << solve.T_f();
  EXPECT_EQ(outcome.iterations, solve.result.iterations);
  EXPECT_EQ(outcome.nlp_solves, solve.result.nlp_solves);
}

// Runs the settings file's schedule (first rate `rate` if > 0) on `problem`
// from the straight-line guess.
// The solvers and schedule of configs/disco.yaml.
// configs/disco.yaml with `overrides` ("key=value") applied.
Settings default_settings_with(const std::vector<std::string>& overrides) {
  Settings s = Settings::load(default_settings_path());
  for (const std::string& o : overrides) s.apply_override(o);
  return s;
}

// Some tests below need a reduction path with a given shape (a fixed step that fails before
// the end, a step that passes the optimum); two_robots_swap_avoid at 20 steps has it with
// Ipopt's own factorisation order, and the path changes with kkt.perturbed_first (which
// optimum a start ends in, and by which steps, is sensitive to the iterates), so those tests
// pin it.
const char* const kIpoptsOwnFactorisations = "kkt.perturbed_first=false";

struct DefaultSolvers {
  explicit DefaultSolvers(const std::vector<std::string>& overrides = {})
      : settings(default_settings_with(overrides)) {}
  Settings settings;
  IpoptSolver ipopt{ipopt_settings(settings)};
  ElasticSolver solver{ipopt, elastic_settings(settings)};
  ReductionSettings schedule = reduction_settings(settings);
};

ReductionResult reduce_plainly(RobotProblem& problem, double rate = 0.0) {
  DefaultSolvers d;
  if (rate > 0) d.schedule.rate = rate;
  return reduce_objective(problem, d.solver, d.schedule);
}

void print(const ReductionResult& result) {
  for (const SolveRecord& r : result.solves)
    std::printf("  %-22s bound %.6f T_f %.6f %s%s\n", to_string(r.kind).c_str(), r.bound, r.T_f,
                to_string(r.status).c_str(), r.improved ? " *" : "");
  std::printf("  best: %s\n", to_string(result.stationarity).c_str());
}

// The solve that gave the best point: the last one marked improved.
const SolveRecord& best_solve(const ReductionResult& result) {
  for (auto it = result.solves.rbegin(); it != result.solves.rend(); ++it)
    if (it->improved) return *it;
  ADD_FAILURE() << "no solve improved";
  return result.solves.back();
}

// objective_reduction.h, "Polish": a feasibility phase (objective time) whose elastic point is
// already tight below elastic.polish_fixed_above is certified as it stands, one Ipopt solve,
// unless a perturbation of it follows; with the threshold at 0 it is polished. Every later
// solve is the same either way, bit for bit: they start from the elastic point.
TEST(ObjectiveReduction, ATightFeasiblePointIsPolishedOnlyForAPerturbation) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  auto run = [&](const std::vector<std::string>& overrides, const PerturbFunction& perturb) {
    RobotProblem problem(scene);
    DefaultSolvers d(overrides);
    return reduce_objective(problem, d.solver, d.schedule, {}, {}, perturb);
  };
  const ReductionResult as_is = run({}, {});
  const ReductionResult polished = run({"elastic.polish_fixed_above=0"}, {});
  ASSERT_TRUE(as_is.found);
  ASSERT_TRUE(polished.found);
  print(as_is);
  const SolveRecord& first = as_is.solves[0];
  EXPECT_EQ(first.kind, SolveKind::kFeasibility);
  EXPECT_EQ(first.status, MpccStatus::kSolved);
  EXPECT_EQ(first.nlp_solves, 1);
  EXPECT_LE(first.certificate.max_complementarity, 1e-8);
  EXPECT_EQ(polished.solves[0].nlp_solves, 2);
  EXPECT_LT(first.iterations, polished.solves[0].iterations);
  EXPECT_TRUE(same_bits(first.T_f, polished.solves[0].T_f));
  ASSERT_EQ(as_is.solves.size(), polished.solves.size());
  ASSERT_GE(as_is.solves.size(), 3u);
  for (size_t k = 1; k < as_is.solves.size(); ++k) {
    const SolveRecord &a = as_is.solves[k], &b = polished.solves[k];
    EXPECT_EQ(a.kind, b.kind) << k;
    EXPECT_TRUE(same_bits(a.T_f, b.T_f)) << k;
    EXPECT_EQ(a.iterations, b.iterations) << k;
    EXPECT_EQ(a.nlp_solves, b.nlp_solves) << k;
  }
  EXPECT_TRUE(same_bits(as_is.best_value, polished.best_value));
  EXPECT_TRUE(as_is.best.z == polished.best.z);
  // With a perturbation next (here one that returns the feasible point's own horizon and the
  // point it was given), the feasible point is polished as always.
  RobotProblem shape(scene);
  const ReductionResult perturbed = run({}, [&](const Vector& z) {
    return Perturbation{z, shape.horizon(z)};
  });
  ASSERT_TRUE(perturbed.found);
  EXPECT_EQ(perturbed.solves[0].kind, SolveKind::kFeasibility);
  EXPECT_EQ(perturbed.solves[0].nlp_solves, 2);
  EXPECT_EQ(perturbed.solves[0].iterations, polished.solves[0].iterations);
  // Objective energy: the feasibility phase minimises J at its horizon, and polish may lower
  // it: polished as always.
  const Scene energy = scenario("one_robot_axis_energy", {"steps=20"});
  RobotProblem problem(energy);
  DefaultSolvers d;
  const ReductionResult e = reduce_objective(problem, d.solver, d.schedule);
  ASSERT_TRUE(e.found);
  EXPECT_EQ(e.solves[0].kind, SolveKind::kFeasibility);
  EXPECT_EQ(e.solves[0].nlp_solves, 2);
}

// ElasticRequest::feasibility: the feasibility phases of objective time are watched by the
// stagnation rule from elastic.stagnation.feasibility_after on; objective energy's (which
// minimise J, not eps alone) are not. A rule that fires as soon as it may (from iteration 1,
// windows of one iteration, any eps above 1e-12 that did not fall to nothing) cuts the elastic
// solve of every feasibility attempt at once, not tight and without zeta raises: each attempt
// ends in one or two iterations, and the first in far fewer than without the watch. Objective
// energy runs bit for bit as without it.
TEST(ObjectiveReduction, TheFeasibilityPhaseOfObjectiveTimeIsWatchedForAStagnantEps) {
  const std::vector<std::string> eager{
      "elastic.stagnation.feasibility_after=1", "elastic.stagnation.window=1",
      "elastic.stagnation.level=1e-12", "elastic.stagnation.decrease=0.999999"};
  std::vector<std::string> unwatched = eager;
  unwatched[0] = "elastic.stagnation.feasibility_after=0";
  auto run = [](const Scene& scene, const std::vector<std::string>& overrides) {
    RobotProblem problem(scene);
    DefaultSolvers d(overrides);
    return reduce_objective(problem, d.solver, d.schedule);
  };
  const Scene time = scenario("two_robots_swap_avoid", {"steps=20"});
  const ReductionResult cut = run(time, eager), full = run(time, unwatched);
  ASSERT_FALSE(cut.solves.empty());
  ASSERT_TRUE(full.found);
  const SolveRecord &a = cut.solves[0], &b = full.solves[0];
  std::printf("  watched: %d NLP solves, %d iterations, %s; without: %d, %d, %s\n",
              a.nlp_solves, a.iterations, to_string(a.status).c_str(), b.nlp_solves,
              b.iterations, to_string(b.status).c_str());
  EXPECT_EQ(a.kind, SolveKind::kFeasibility);
  EXPECT_NE(a.status, MpccStatus::kSolved);
  EXPECT_LT(a.iterations, b.iterations);
  for (const SolveRecord& r : cut.solves)
    if (r.kind == SolveKind::kFeasibility) {
      EXPECT_EQ(r.status, MpccStatus::kElasticNotTight);
      EXPECT_EQ(r.nlp_solves, 1);  // cut, no zeta raise (no polish: far from tight)
      EXPECT_LE(r.iterations, 2);
    }
  // Objective energy: not watched.
  const Scene energy = scenario("one_robot_axis_energy", {"steps=20"});
  const ReductionResult e_cut = run(energy, eager), e_full = run(energy, unwatched);
  ASSERT_TRUE(e_full.found);
  ASSERT_EQ(e_cut.solves.size(), e_full.solves.size());
  for (size_t k = 0; k < e_cut.solves.size(); ++k)
    EXPECT_EQ(e_cut.solves[k].iterations, e_full.solves[k].iterations) << k;
  EXPECT_TRUE(e_cut.best.z == e_full.best.z);
}

TEST(ObjectiveReduction, NoStepIsAskedBelowTheLowerBound) {
  // Alone, the diagonal robot cannot beat its closed-form time: every step
  // below it would be a wasted solve. A first rate of 0.45 would ask for
  // 0.55 x 1.5 = 0.83 times that time.
  const Scene scene = scenario("one_robot_diagonal", {"steps=30"});
  RobotProblem problem(scene);
  const double lower_bound = problem.lower_bound().value();
  const ReductionResult result = reduce_plainly(problem, 0.45);
  print(result);
  ASSERT_TRUE(result.found);
  EXPECT_GE(result.best_value, lower_bound);
  EXPECT_LE(result.best_value, lower_bound * (1 + 1e-2));
  for (const SolveRecord& r : result.solves) EXPECT_GE(r.bound, lower_bound) << to_string(r.kind);
}

TEST(ObjectiveReduction, NoStepIsAskedBelowTheSmallestHorizon) {
  // A robot whose target is its start has nothing to do (lower bound 0). The model keeps
  // h > 0 with a smallest T_f; fixed steps below it used to "succeed" down to T_f ~ 1e-20 s,
  // and the best point then violated the model's own bound on T_f by 1e-3 (model units)
  // while reported as solved. Now the loop stops at the smallest horizon, certified.
  const Scene scene =
      scenario("one_robot_axis", {"steps=10", "robots.0.target={x: 0, y: 0, vx: 0, vy: 0}"});
  RobotProblem problem(scene);
  ASSERT_EQ(problem.lower_bound().value(), 0.0);
  problem.limit_horizon(kInf);
  const double smallest = problem.horizon(problem.program().variable_lower());
  ASSERT_GT(smallest, 0.0);
  const ReductionResult result = reduce_plainly(problem);
  print(result);
  ASSERT_TRUE(result.found);
  for (const SolveRecord& r : result.solves) EXPECT_GE(r.bound, smallest) << to_string(r.kind);
  // Within Ipopt's absolute tolerance (1e-9 in model units) of its bound.
  EXPECT_NEAR(result.best_value, smallest, 1e-9 * problem.units().time);
  // Certified on the model as it is left (the horizon freed), as solve_scene certifies it.
  EXPECT_TRUE(certify(problem.program(), result.best.z).within(1e-6, 1e-6));
}

TEST(ObjectiveReduction, AnEvaluationFailureIsReportedAndTheNextHorizonIsTried) {
  // A guess with a NaN makes every evaluation at the start point fail: the wrapper
  // returns false, Ipopt stops with Invalid_Number_Detected. The feasibility phase records
  // that solve as failed, says why, and goes on with the next horizon.
  RobotProblem problem(scenario("one_robot_axis", {"steps=10"}));
  DefaultSolvers d;
  auto poisoned = [&](double seconds) {
    Vector z = smoothstep_guess(problem, seconds);
    z[z.size() / 2] = std::numeric_limits<double>::quiet_NaN();
    return z;
  };
  // Always poisoned: three failed horizons, and the detail names Ipopt's status.
  const ReductionResult never = reduce_objective(problem, d.solver, d.schedule, poisoned);
  print(never);
  EXPECT_FALSE(never.found);
  EXPECT_EQ(never.status, MpccStatus::kFailed);
  EXPECT_EQ(never.feasibility_detail, "failed (Ipopt: Invalid_Number_Detected)");
  ASSERT_EQ(never.solves.size(), 3u);
  for (const SolveRecord& r : never.solves) EXPECT_EQ(r.status, MpccStatus::kFailed);
  // Poisoned at the first horizon only: the second is solved and the reduction goes on.
  int calls = 0;
  const ReductionResult later = reduce_objective(problem, d.solver, d.schedule, [&](double seconds) {
    return ++calls == 1 ? poisoned(seconds) : smoothstep_guess(problem, seconds);
  });
  print(later);
  ASSERT_TRUE(later.found) << later.feasibility_detail;
  EXPECT_EQ(later.solves[0].status, MpccStatus::kFailed);
  EXPECT_EQ(later.solves[0].outcome, NlpOutcome::kInvalidNumber);
  EXPECT_EQ(ipopt_status_name(later.solves[0].ipopt_status), "Invalid_Number_Detected");
  EXPECT_EQ(later.solves[1].kind, SolveKind::kFeasibility);
  EXPECT_TRUE(later.solves[1].improved);
  EXPECT_NEAR(later.solves[1].bound, 2.0 * later.solves[0].bound, 1e-12 * later.solves[0].bound);
  EXPECT_GT(later.solves.size(), 2u);  // the reduction ran from there
  EXPECT_TRUE(later.best.certificate.within(1e-6, 1e-6));
}

// A minimisation that the stall rule (elastic.stall) ends counts as a local optimum for the
// loop (a probe follows, as after one that converged), but even certified its point is not
// shown stationary, and the solve log says so. Only minimisations are ever stalled. The rule
// here counts every iterate as settled and ends a minimisation at the first iterate from
// iteration 5 on whose objective is not 1 % below the least before it.
TEST(ObjectiveReduction, AStalledMinimisationIsALocalOptimumButNotShownStationary) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  RobotProblem problem(scene);
  // The rule on the minimisation itself: no weak attempt before it (reduction.minimize_zeta,
  // whose attempt the rule may end too: AMinimisationStartsWeakAndFallsBackUncertified).
  DefaultSolvers d({kIpoptsOwnFactorisations,  // a fixed step fails: a minimisation follows
                    "elastic.stall.after=5", "elastic.stall.window=1", "elastic.stall.decrease=0.01",
                    "elastic.stall.mu=1", "elastic.stall.infeasibility=1",
                    "reduction.minimize_zeta=0", "reduction.probe_after_minimize=true"});
  d.schedule.minimizer = Minimizer::kElastic;
  const ReductionResult result = reduce_objective(problem, d.solver, d.schedule);
  print(result);
  ASSERT_TRUE(result.found);
  int stalled = 0;
  for (size_t k = 0; k < result.solves.size(); ++k) {
    const SolveRecord& r = result.solves[k];
    if (!r.stalled) continue;
    ++stalled;
    EXPECT_EQ(r.kind, SolveKind::kMinimize) << "solve " << k;
    EXPECT_NE(solve_log_line(int(k) + 1, r).find("solved, stalled"), std::string::npos)
        << solve_log_line(int(k) + 1, r);
    if (r.status == MpccStatus::kSolved && k + 1 < result.solves.size()) {
      EXPECT_EQ(result.solves[k + 1].kind, SolveKind::kFixedStep) << "a probe below it";
      EXPECT_LT(result.solves[k + 1].bound, r.T_f);
    }
  }
  ASSERT_GE(stalled, 1) << "the rule ended no minimisation";
  const SolveRecord& b = best_solve(result);
  if (b.stalled) {
    EXPECT_EQ(result.stationarity, Stationarity::kFeasible);
  }
  // The same scene without the rule: its minimisation converges, and is strongly stationary.
  DefaultSolvers plain({kIpoptsOwnFactorisations, "elastic.stall.after=0"});
  plain.schedule.minimizer = Minimizer::kElastic;
  RobotProblem again(scene);
  const ReductionResult reference = reduce_objective(again, plain.solver, plain.schedule);
  for (const SolveRecord& r : reference.solves) EXPECT_FALSE(r.stalled);
  if (best_solve(result).stalled) {
    EXPECT_EQ(best_solve(reference).kind, SolveKind::kMinimize);
    EXPECT_EQ(reference.stationarity, Stationarity::kStrong);
  }
}

// reduction.minimize_duals: a minimisation starts cold (Ipopt's own initial multipliers) or
// warm. Only minimisations: every solve before the first one is the same bit for bit; the
// minimisation then takes another path (other iterations), and both ways the loop ends at a
// certified, strongly stationary point.
TEST(ObjectiveReduction, OnlyTheMinimisationsStartCold) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  ReductionResult results[2];
  const char* const duals[2] = {"reduction.minimize_duals=cold", "reduction.minimize_duals=warm"};
  for (int k = 0; k < 2; ++k) {
    RobotProblem problem(scene);
    DefaultSolvers d({kIpoptsOwnFactorisations, duals[k]});  // a fixed step fails: a minimisation follows
    d.schedule.minimizer = Minimizer::kElastic;
    EXPECT_EQ(d.schedule.cold_minimize, k == 0);
    results[k] = reduce_objective(problem, d.solver, d.schedule);
    std::printf("%s\n", duals[k]);
    print(results[k]);
    ASSERT_TRUE(results[k].found);
    EXPECT_EQ(results[k].stationarity, Stationarity::kStrong);
  }
  const ReductionResult &cold = results[0], &warm = results[1];
  size_t first = 0;
  while (first < cold.solves.size() && cold.solves[first].kind != SolveKind::kMinimize) ++first;
  ASSERT_LT(first, cold.solves.size()) << "no minimisation";
  ASSERT_LT(first, warm.solves.size());
  for (size_t k = 0; k < first; ++k) {
    EXPECT_EQ(cold.solves[k].kind, warm.solves[k].kind) << "solve " << k;
    EXPECT_EQ(cold.solves[k].iterations, warm.solves[k].iterations) << "solve " << k;
    EXPECT_EQ(cold.solves[k].T_f, warm.solves[k].T_f) << "solve " << k;
  }
  EXPECT_EQ(warm.solves[first].kind, SolveKind::kMinimize);
  EXPECT_EQ(cold.solves[first].bound, warm.solves[first].bound);
  EXPECT_NE(cold.solves[first].iterations, warm.solves[first].iterations)
      << "the minimisation started as the warm one";
}

// reduction.minimize_zeta: a minimisation first runs at the weak zeta, raised at most to the
// best point's zeta times zeta_factor; uncertified, it runs again as without. Here the start's
// zeta is 10 (elastic.zeta):
// - 1000 (not below 10) changes nothing, bit for bit;
// - 1: every solve before the first minimisation is the same, the minimisation takes another
//   path, and the loop ends certified and strongly stationary;
// - 1e-9: the weak attempt ends uncertified (not tight: its raises, at most to 10 times 10,
//   end first), and the minimisation then runs as without, bit for bit.
// The weak attempt here is the penalty loop (reduction.minimize_weak penalty; the homotopy's:
// AWeakMinimisationByTheRelaxationHomotopy below).
TEST(ObjectiveReduction, AMinimisationStartsWeakAndFallsBackUncertified) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  const char* const weak[4] = {"reduction.minimize_zeta=0", "reduction.minimize_zeta=1000",
                               "reduction.minimize_zeta=1", "reduction.minimize_zeta=1e-9"};
  ReductionResult results[4];
  for (int k = 0; k < 4; ++k) {
    RobotProblem problem(scene);
    DefaultSolvers d({kIpoptsOwnFactorisations, "elastic.zeta=10", "reduction.minimize_weak=penalty", weak[k]});
    d.schedule.minimizer = Minimizer::kElastic;
    results[k] = reduce_objective(problem, d.solver, d.schedule);
    std::printf("%s\n", weak[k]);
    print(results[k]);
    ASSERT_TRUE(results[k].found) << weak[k];
  }
  const ReductionResult &off = results[0], &above = results[1], &one = results[2],
                        &tiny = results[3];
  auto first_minimisation = [](const ReductionResult& r) {
    size_t k = 0;
    while (k < r.solves.size() && r.solves[k].kind != SolveKind::kMinimize) ++k;
    return k;
  };
  auto same = [](const SolveRecord& a, const SolveRecord& b) {
    return a.kind == b.kind && a.iterations == b.iterations && a.T_f == b.T_f &&
           a.status == b.status;
  };
  const size_t first = first_minimisation(off);
  ASSERT_LT(first, off.solves.size()) << "no minimisation";
  ASSERT_EQ(above.solves.size(), off.solves.size());
  for (size_t k = 0; k < off.solves.size(); ++k)
    EXPECT_TRUE(same(above.solves[k], off.solves[k])) << "zeta 1000, solve " << k;
  EXPECT_EQ(above.best_value, off.best_value);

  ASSERT_EQ(first_minimisation(one), first);
  for (size_t k = 0; k < first; ++k) EXPECT_TRUE(same(one.solves[k], off.solves[k])) << k;
  EXPECT_NE(one.solves[first].iterations, off.solves[first].iterations) << "not weak";
  EXPECT_EQ(one.stationarity, Stationarity::kStrong);

  ASSERT_EQ(first_minimisation(tiny), first);
  ASSERT_LT(first + 1, tiny.solves.size());
  for (size_t k = 0; k < first; ++k) EXPECT_TRUE(same(tiny.solves[k], off.solves[k])) << k;
  EXPECT_NE(tiny.solves[first].status, MpccStatus::kSolved) << "the weak attempt";
  EXPECT_FALSE(tiny.solves[first].improved);
  EXPECT_EQ(tiny.solves[first + 1].bound, off.solves[first].bound);
  EXPECT_TRUE(same(tiny.solves[first + 1], off.solves[first])) << "the fallback: as without";
}

// reduction.minimize_weak homotopy: the weak attempt of a minimisation runs the relaxation
// homotopy (ElasticRequest::relaxation) instead of the penalty loop. Every solve before the
// first minimisation is the same, bit for bit; that minimisation is another solve (stages of
// the homotopy and polish: more NLP solves than the penalty loop's), certified below its
// bound; and the loop ends certified and strongly stationary. Without a weak attempt
// (reduction.minimize_zeta 0) the setting changes nothing.
TEST(ObjectiveReduction, AWeakMinimisationByTheRelaxationHomotopy) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  auto run = [&](std::initializer_list<const char*> overrides) {
    std::vector<std::string> all{kIpoptsOwnFactorisations, "elastic.zeta=10"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    RobotProblem problem(scene);
    DefaultSolvers d(all);
    d.schedule.minimizer = Minimizer::kElastic;
    ReductionResult r = reduce_objective(problem, d.solver, d.schedule);
    print(r);
    return r;
  };
  const ReductionResult penalty = run({"reduction.minimize_zeta=1", "reduction.minimize_weak=penalty"});
  const ReductionResult homotopy =
      run({"reduction.minimize_zeta=1", "reduction.minimize_weak=homotopy"});
  ASSERT_TRUE(penalty.found);
  ASSERT_TRUE(homotopy.found);
  auto same = [](const SolveRecord& a, const SolveRecord& b) {
    return a.kind == b.kind && a.iterations == b.iterations && a.T_f == b.T_f &&
           a.status == b.status && a.nlp_solves == b.nlp_solves;
  };
  size_t first = 0;
  while (first < penalty.solves.size() && penalty.solves[first].kind != SolveKind::kMinimize)
    ++first;
  ASSERT_LT(first, penalty.solves.size()) << "no minimisation";
  ASSERT_LT(first, homotopy.solves.size());
  for (size_t k = 0; k < first; ++k) EXPECT_TRUE(same(homotopy.solves[k], penalty.solves[k])) << k;
  const SolveRecord &h = homotopy.solves[first], &p = penalty.solves[first];
  EXPECT_EQ(h.kind, SolveKind::kMinimize);
  EXPECT_EQ(h.bound, p.bound);
  EXPECT_GT(h.nlp_solves, p.nlp_solves) << "the homotopy's stages";
  EXPECT_EQ(h.status, MpccStatus::kSolved);
  EXPECT_TRUE(h.improved);
  EXPECT_LT(h.T_f, h.bound);
  EXPECT_EQ(homotopy.stationarity, Stationarity::kStrong);
  // The answer: both are local optima of the same MPCC, and the homotopy's is within the
  // scene's few percent of the penalty loop's (two robots swapping around each other).
  EXPECT_NEAR(homotopy.best_value, penalty.best_value, 0.05 * penalty.best_value);

  const ReductionResult off = run({"reduction.minimize_zeta=0", "reduction.minimize_weak=penalty"});
  const ReductionResult off_homotopy =
      run({"reduction.minimize_zeta=0", "reduction.minimize_weak=homotopy"});
  ASSERT_EQ(off_homotopy.solves.size(), off.solves.size());
  for (size_t k = 0; k < off.solves.size(); ++k)
    EXPECT_TRUE(same(off_homotopy.solves[k], off.solves[k])) << "no weak attempt, solve " << k;
  EXPECT_EQ(off_homotopy.best_value, off.best_value);
}

// The relaxation homotopy of a weak minimisation (core/elastic/elastic_solver.h) on a coarse
// scene, paper B1 at 50 steps (a screen's resolution at search.screen_fraction 0.5), start 1
// of seed 1: its relaxation holds at the first sigma (zeta 10), then stops holding at sigma
// 1e-2 with complementarity 1.3e-2, too far from the corner for polish (1e-2). There zeta is
// raised and the same sigma solved again, and the homotopy goes on to a certified point:
// every minimisation of the start is certified, none falls back to the penalty loop. (Ended
// there instead, the homotopy was not tight and the fallback from the best point took 680
// iterations to another optimum.) A path pinned on a real scene: the rule acts only where
// such a homotopy stops, which no textbook MPCC here does.
TEST(ObjectiveReduction, AHomotopyThatStopsHoldingFarFromTheCornerRaisesZeta) {
  const Scene scene = scenario("paper/B1", {"steps=50"});
  const Settings settings = default_settings_with({"reduction.minimize_weak=homotopy"});
  const StartSpec spec =
      make_start(scene, 1, 1, reduction_settings(settings), elastic_settings(settings));
  ASSERT_GT(spec.elastic.zeta, spec.schedule.minimize_zeta) << "start 1 has a weak attempt";
  ASSERT_TRUE(spec.schedule.weak_homotopy);
  std::vector<SolveRecord> log;
  const StartOutcome o = run_start(scene, settings, spec, 0.0, BudgetSource::kNone, nullptr,
                                   [&](const SolveRecord& r) { log.push_back(r); });
  ASSERT_TRUE(o.solved()) << to_string(o.status) << " " << o.detail;
  int minimisations = 0;
  for (const SolveRecord& r : log) {
    if (r.kind != SolveKind::kMinimize) continue;
    ++minimisations;
    EXPECT_EQ(r.status, MpccStatus::kSolved)
        << "minimisation " << minimisations << " at bound " << r.bound << " ended at T_f "
        << r.T_f << ", complementarity " << r.certificate.max_complementarity;
  }
  EXPECT_GE(minimisations, 1);
}

TEST(ObjectiveReduction, ALocalOptimumEndsTheLoopOnceAProbeBelowItFails) {
  // With reduction.probe_after_minimize: a minimising step that converges strictly inside its bound, or a
  // `minimize` phase that converges, is a local optimum: at most one fixed
  // step follows it, and if that fails it is the last solve.
  for (const char* name : {"one_robot_axis", "two_robots_swap_avoid"}) {
    const Scene scene = scenario(name, {"steps=20"});
    RobotProblem problem(scene);
    // The elastic minimiser: its converged "minimize" solve is the local optimum checked here
    // (the branch minimiser's are checked in TheBranchMinimizerDescends...).
    DefaultSolvers d({"reduction.probe_after_minimize=true"});
    d.schedule.minimizer = Minimizer::kElastic;
    const ReductionResult result = reduce_objective(problem, d.solver, d.schedule);
    std::printf("%s\n", name);
    print(result);
    ASSERT_TRUE(result.found) << name;
    int optima = 0;
    for (size_t k = 0; k < result.solves.size(); ++k) {
      const SolveRecord& r = result.solves[k];
      const bool converged = r.status == MpccStatus::kSolved;
      if (!((r.kind == SolveKind::kReduction && converged && r.T_f < r.bound * (1 - 1e-6)) ||
            (r.kind == SolveKind::kMinimize && converged)))
        continue;
      ++optima;
      if (k + 1 == result.solves.size()) continue;
      const SolveRecord& probe = result.solves[k + 1];
      EXPECT_EQ(probe.kind, SolveKind::kFixedStep) << name << " after solve " << k;
      EXPECT_LT(probe.bound, result.solves[k].T_f) << name;
      if (!probe.improved) {
        EXPECT_EQ(k + 2, result.solves.size()) << name << ": solves after a failed probe";
      }
    }
    EXPECT_GE(optima, 1) << name << ": no local optimum reached";
    // A step of the homotopy in T_f is only feasible; a minimisation that converged inside its
    // bound is a KKT point of the elastic NLP at eps = 0.
    const SolveRecord& b = best_solve(result);
    if (b.kind == SolveKind::kFixedStep || b.kind == SolveKind::kFeasibility) {
      EXPECT_EQ(result.stationarity, Stationarity::kFeasible) << name;
    } else if (b.T_f < b.bound * (1 - 1e-6)) {
      EXPECT_EQ(result.stationarity, Stationarity::kStrong) << name;
    }
    // Two robots: the minimisation is no longer the last solve; a probe follows.
    if (std::string(name) == "two_robots_swap_avoid") {
      EXPECT_EQ(result.solves.back().kind, SolveKind::kFixedStep) << name << ": no probe below the optimum";
    }
  }
}

// reduction.probe_after_minimize false (the default): a minimisation that converges is the
// loop's last solve. With the setting the same run makes the same solves up to it, then a
// probe below it (which fails on this scene), and ends at the same best.
TEST(ObjectiveReduction, WithoutProbingAConvergedMinimisationIsTheLastSolve) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  RobotProblem problem(scene);
  DefaultSolvers d({kIpoptsOwnFactorisations});  // a fixed step fails: a minimisation follows
  d.schedule.minimizer = Minimizer::kElastic;
  ASSERT_FALSE(d.schedule.probe_after_minimize) << "configs/disco.yaml";
  const ReductionResult result = reduce_objective(problem, d.solver, d.schedule);
  print(result);
  ASSERT_TRUE(result.found);
  const SolveRecord& last = result.solves.back();
  EXPECT_EQ(last.kind, SolveKind::kMinimize);
  EXPECT_EQ(last.status, MpccStatus::kSolved);
  EXPECT_EQ(result.stop, StopReason::kMinimized);

  DefaultSolvers probing({kIpoptsOwnFactorisations, "reduction.probe_after_minimize=true"});
  probing.schedule.minimizer = Minimizer::kElastic;
  const ReductionResult probed = reduce_objective(problem, probing.solver, probing.schedule);
  print(probed);
  ASSERT_EQ(probed.solves.size(), result.solves.size() + 1);
  for (size_t k = 0; k < result.solves.size(); ++k) {
    EXPECT_EQ(probed.solves[k].kind, result.solves[k].kind) << "solve " << k;
    EXPECT_EQ(probed.solves[k].T_f, result.solves[k].T_f) << "solve " << k;
  }
  EXPECT_EQ(probed.solves.back().kind, SolveKind::kFixedStep);
  EXPECT_LT(probed.solves.back().bound, last.T_f);
  EXPECT_FALSE(probed.solves.back().improved);
  EXPECT_EQ(probed.best_value, result.best_value);
}

// A fixed step fixes T_f, the whole objective: the elastic NLP then minimises eps alone
// whatever zeta (ElasticRequest::objective_fixed), so a fixed step that ends not tight takes
// one elastic solve and no zeta raise (plus polish only when complementarity came within
// 1e-2). Before, the zeta rule raised at least once there, to the same answer.
TEST(ObjectiveReduction, AFixedStepThatCannotBeTightTakesOneElasticSolve) {
  RobotProblem problem(scenario("two_robots_swap_avoid"));
  const ReductionResult result = reduce_plainly(problem);
  print(result);
  ASSERT_TRUE(result.found);
  int not_tight = 0;
  for (const SolveRecord& r : result.solves) {
    if (r.kind != SolveKind::kFixedStep || r.status != MpccStatus::kElasticNotTight) continue;
    ++not_tight;
    const bool polish_tried = r.certificate.max_complementarity < 1e-2;
    EXPECT_EQ(r.nlp_solves, polish_tried ? 2 : 1) << "fixed step at " << r.bound;
  }
  EXPECT_GE(not_tight, 1) << "no fixed step ended not tight: the test checks nothing";
}

TEST(ObjectiveReduction, ACappedEarlyMinimisationHandsBackToTheFixedSteps) {
  // reduction.minimize_iterations caps the minimisation after the first failed
  // fixed step; cut short, it leaves the best point as it was, the fixed steps
  // go on, and the loop minimises again, uncapped, at its end.
  // Without weak attempts (reduction.minimize_zeta), so that each minimisation is one record
  // (a weak attempt that the cap ends is not followed by another).
  RobotProblem problem(scenario("two_robots_swap_avoid", {"steps=20"}));
  DefaultSolvers d({kIpoptsOwnFactorisations,  // a fixed step fails before the end
                    "reduction.minimize_zeta=0"});
  d.schedule.minimizer = Minimizer::kElastic;  // the cap is the elastic minimisation's
  d.schedule.minimize_iterations = 3;
  const ReductionResult result = reduce_objective(problem, d.solver, d.schedule);
  print(result);
  ASSERT_TRUE(result.found);
  std::vector<size_t> minimizations;
  for (size_t k = 0; k < result.solves.size(); ++k)
    if (result.solves[k].kind == SolveKind::kMinimize) minimizations.push_back(k);
  ASSERT_EQ(minimizations.size(), 2u);
  const SolveRecord& capped = result.solves[minimizations[0]];
  EXPECT_NE(capped.status, MpccStatus::kSolved);
  // The log says the cap ended it, in words, not as a failure of Ipopt's.
  const std::string line = solve_log_line(1, capped);
  EXPECT_NE(line.find("cap reached"), std::string::npos) << line;
  EXPECT_EQ(line.find("failed"), std::string::npos) << line;
  EXPECT_EQ(line.find("Ipopt"), std::string::npos) << line;
  EXPECT_FALSE(capped.improved);
  EXPECT_LE(capped.iterations, 3 * capped.nlp_solves);
  EXPECT_EQ(result.solves[minimizations[0] + 1].kind, SolveKind::kFixedStep);
  const SolveRecord& last = result.solves[minimizations[1]];
  EXPECT_EQ(last.status, MpccStatus::kSolved);
  EXPECT_GT(last.iterations, 3);
  EXPECT_EQ(minimizations[1] + 1, result.solves.size());
  EXPECT_NE(result.stop, StopReason::kNone) << "a finished loop says why it stopped";
}

TEST(ObjectiveReduction, TheSolveLogSaysHowEachSolveEndedInWords) {
  EXPECT_EQ(solve_outcome_words(MpccStatus::kSolved, NlpOutcome::kConverged), "solved");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kElasticNotTight, NlpOutcome::kConverged), "not tight");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kInfeasible, NlpOutcome::kInfeasible), "infeasible");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kFailed, NlpOutcome::kIterationCap), "cap reached");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kFailed, NlpOutcome::kTimeLimit), "time limit");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kFailed, NlpOutcome::kInvalidNumber), "invalid number");
  EXPECT_EQ(solve_outcome_words(MpccStatus::kFailed, NlpOutcome::kFailed), "failed");
  // Only a real failure names Ipopt's status.
  SolveRecord r;
  r.kind = SolveKind::kReduction;
  r.status = MpccStatus::kFailed;
  r.outcome = NlpOutcome::kFailed;
  r.ipopt_status = -2;  // Restoration_Failed
  EXPECT_NE(solve_log_line(3, r).find("failed            "), std::string::npos) << solve_log_line(3, r);
  EXPECT_NE(solve_log_line(3, r).find("(Ipopt: Restoration_Failed)"), std::string::npos) << solve_log_line(3, r);
  r.outcome = NlpOutcome::kIterationCap;
  EXPECT_EQ(solve_log_line(3, r).find("Ipopt"), std::string::npos) << solve_log_line(3, r);
}

}  // namespace
}  // namespace disco

namespace disco {
namespace {

// Runs the reduction loop with `settings` on `problem` (a fresh Ipopt), prints and returns it.
ReductionResult reduce_with(const Settings& settings, RobotProblem& problem, const char* name) {
  IpoptSolver ipopt(ipopt_settings(settings));
  ElasticSolver solver(ipopt, elastic_settings(settings));
  const ReductionResult result = reduce_objective(problem, solver, reduction_settings(settings));
  std::printf("%s\n", name);
  print(result);
  return result;
}

// The loop found a best, and it is certified.
void expect_certified_best(const ReductionResult& result, const char* name) {
  ASSERT_TRUE(result.found) << name;
  EXPECT_TRUE(result.best.solved()) << name;
  EXPECT_LE(result.best.certificate.max_complementarity, 1e-6) << name;
  EXPECT_LE(result.best.certificate.max_violation, 1e-6) << name;
}

// reduction.minimize=branch (search/objective_reduction.h): the loop minimises by branch
// descents. On a two-robot scene the fixed steps pass the optimum and a descent follows
// (a "minimize" segment, then a "branch" solve); the answer is certified, no worse than the
// best fixed step, and every "branch" record that improved is certified. On one robot the
// answer is the closed-form optimum (the scene's lower bound) within the discretisation error
// of N_t = 20 (1e-3).
TEST(ObjectiveReduction, TheBranchMinimizerDescendsAndReachesTheOneRobotOptimum) {
  // Two robots: the fixed steps pass the optimum, with Ipopt's own factorisation order.
  const Settings settings =
      default_settings_with({"reduction.minimize=branch", kIpoptsOwnFactorisations});
  const ReductionSettings schedule = reduction_settings(settings);
  ASSERT_EQ(schedule.minimizer, Minimizer::kBranch);
  for (const char* name : {"one_robot_axis", "two_robots_swap_avoid"}) {
    RobotProblem problem(scenario(name, {"steps=20"}));
    const ReductionResult result = reduce_with(settings, problem, name);
    ASSERT_NO_FATAL_FAILURE(expect_certified_best(result, name));
    double best_fixed = kInf;
    bool branch = false;
    for (const SolveRecord& r : result.solves) {
      if (r.kind == SolveKind::kFixedStep && r.status == MpccStatus::kSolved)
        best_fixed = std::min(best_fixed, r.T_f);
      if (r.kind == SolveKind::kBranch) {
        branch = true;
        if (r.improved) {
          EXPECT_EQ(r.status, MpccStatus::kSolved) << name;
        }
      }
    }
    EXPECT_LE(result.best_value, best_fixed) << name;
    // A best from a branch descent is B-stationary only when no flip was left.
    const SolveRecord& b = best_solve(result);
    if (b.kind == SolveKind::kBranch && result.stationarity == Stationarity::kB) {
      EXPECT_TRUE(result.best.b_stationary) << name;
    }
    if (b.kind == SolveKind::kBranch && !result.best.b_stationary) {
      EXPECT_EQ(result.stationarity, Stationarity::kFeasible) << name;
    }
    // The one robot reaches its optimum by a minimisation: a stationary point.
    if (std::string(name) == "one_robot_axis") {
      EXPECT_NE(result.stationarity, Stationarity::kFeasible) << name;
    }
    if (std::string(name) == "one_robot_axis") {
      const double lb = problem.lower_bound().value();
      EXPECT_GE(result.best_value, lb * (1 - 1e-9));
      EXPECT_LE(result.best_value, lb * (1 + 1e-3));
    } else {
      EXPECT_TRUE(branch) << name << ": no branch descent";
    }
  }
}

// reduction.segment_iterations, not reduction.step_iterations, is the length of the branch
// minimiser's elastic segments: with segments of 3 iterations and minimising steps of 200,
// every "minimize" record (a segment) took at most 3 Ipopt iterations and some took 3.
TEST(ObjectiveReduction, TheBranchMinimizersSegmentsAreSegmentIterationsLong) {
  const Settings settings =
      default_settings_with({"reduction.minimize=branch", "reduction.segment_iterations=3",
                             "reduction.step_iterations=200", kIpoptsOwnFactorisations});
  RobotProblem problem(scenario("two_robots_swap_avoid", {"steps=20"}));
  const ReductionResult result = reduce_with(settings, problem, "two_robots_swap_avoid");
  int segments = 0, capped = 0;
  for (const SolveRecord& r : result.solves) {
    if (r.kind != SolveKind::kMinimize) continue;
    ++segments;
    EXPECT_LE(r.iterations, 3) << "segment " << segments;
    if (r.iterations == 3) ++capped;
  }
  EXPECT_GE(segments, 1);
  EXPECT_GE(capped, 1) << "no segment reached its cap";
}

// The relaxation homotopy (elastic.formulation relaxed) drives the loop to the same answers:
// the one robot's closed-form optimum (its lower bound, within the discretisation error of
// N_t = 20), every best certified, and the swap scene solved.
TEST(ObjectiveReduction, TheRelaxedFormulationReachesTheOneRobotOptimum) {
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("elastic.formulation=relaxed");
  ASSERT_EQ(elastic_settings(settings).formulation, ElasticFormulation::kRelaxed);
  for (const char* name : {"one_robot_axis", "two_robots_swap_avoid"}) {
    RobotProblem problem(scenario(name, {"steps=20"}));
    const ReductionResult result = reduce_with(settings, problem, name);
    ASSERT_NO_FATAL_FAILURE(expect_certified_best(result, name));
    if (std::string(name) == "one_robot_axis") {
      const double lb = problem.lower_bound().value();
      EXPECT_GE(result.best_value, lb * (1 - 1e-9));
      EXPECT_LE(result.best_value, lb * (1 + 1e-3));
    }
  }
}

// Each relaxed solve ends where the relaxation stops holding and polish fixes the branch:
// without polish it would not end certified, so the settings refuse it, naming the key; so
// does a barrier solve at a corner where both sides vanish (Ralph's).
TEST(ObjectiveReduction, RelaxedWithoutPolishIsAnErrorNamingTheKey) {
  // The message elastic_settings gives for these overrides ("" if none).
  auto error_for = [](std::initializer_list<const char*> overrides) -> std::string {
    Settings settings = Settings::load(default_settings_path());
    for (const char* o : overrides) settings.apply_override(o);
    try {
      elastic_settings(settings);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string polish = error_for({"elastic.formulation=relaxed", "elastic.polish=false"});
  EXPECT_NE(polish.find("key 'elastic.polish'"), std::string::npos) << polish;
  EXPECT_NE(polish.find("relaxed needs polish"), std::string::npos) << polish;
  EXPECT_EQ(polish.find("minimize_weak"), std::string::npos)
      << "the relaxed formulation itself needs polish, whatever the weak minimisation: " << polish;
  const std::string barrier = error_for({"elastic.formulation=barrier", "elastic.polish=false"});
  EXPECT_NE(barrier.find("key 'elastic.polish'"), std::string::npos) << barrier;
  EXPECT_NE(barrier.find("barrier needs polish"), std::string::npos) << barrier;
  EXPECT_EQ(error_for({"elastic.formulation=barrier"}), "");
  const std::string factor = error_for({"elastic.formulation=relaxed", "elastic.sigma_factor=1.5"});
  EXPECT_NE(factor.find("key 'elastic.sigma_factor'"), std::string::npos) << factor;
  EXPECT_NE(factor.find("must be below 1"), std::string::npos) << factor;
  EXPECT_EQ(error_for({"elastic.formulation=relaxed"}), "");
}

// The shared incumbent (search/reduction_phases.h). An incumbent above every point the start
// reaches changes nothing, bit for bit.
TEST(ObjectiveReductionIncumbent, AnIncumbentAboveEveryPointChangesNothing) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  DefaultSolvers d;
  d.schedule.jump_to_incumbent = true;
  d.schedule.dominated_after = 1;
  RobotProblem alone(scene), shared(scene);
  const ReductionResult a = reduce_objective(alone, d.solver, d.schedule);
  const ReductionResult b =
      reduce_objective(shared, d.solver, d.schedule, {}, {}, {}, [] { return 1e9; });
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.solves.size(), b.solves.size());
  EXPECT_TRUE(same_bits(a.best_value, b.best_value)) << a.best_value << " vs " << b.best_value;
  EXPECT_EQ(a.stop, b.stop);
  EXPECT_EQ(b.incumbent, 1e9);
}

// A start whose best stays above another start's for dominated_after steps stops there,
// dominated, with its certified best; until then it runs exactly as alone.
TEST(ObjectiveReductionIncumbent, AStartThatStaysAboveTheIncumbentStopsDominated) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  DefaultSolvers d({kIpoptsOwnFactorisations});  // alone, the start takes more than 2 steps
  d.schedule.jump_to_incumbent = false;  // steps aim below its own best, as alone
  d.schedule.dominated_after = 2;
  RobotProblem alone(scene), shared(scene);
  const ReductionResult a = reduce_objective(alone, d.solver, d.schedule);
  const double unreachable = 0.5 * *alone.lower_bound();  // no start gets there
  const ReductionResult b = reduce_objective(shared, d.solver, d.schedule, {}, {}, {},
                                             [&] { return unreachable; });
  print(b);
  ASSERT_TRUE(b.found);
  EXPECT_EQ(b.stop, StopReason::kDominated);
  // The feasibility phase (one solve or more: how many depends on the path), then the two
  // steps dominated_after allows.
  auto steps = [](const ReductionResult& r) {
    return std::count_if(r.solves.begin(), r.solves.end(), [](const SolveRecord& s) {
      return s.kind != SolveKind::kFeasibility && s.kind != SolveKind::kPerturbedFeasibility;
    });
  };
  ASSERT_EQ(steps(b), 2) << "feasibility, then two steps";
  ASSERT_GT(steps(a), 2) << "alone, the start takes more steps";
  ASSERT_GT(a.solves.size(), b.solves.size());
  for (std::size_t k = 0; k < b.solves.size(); ++k)
    EXPECT_TRUE(same_bits(a.solves[k].T_f, b.solves[k].T_f)) << "solve " << k;
  EXPECT_GT(b.best_value, unreachable);
  EXPECT_NE(stop_line(b.stop, d.schedule).find("dominated"), std::string::npos);
  // As a start of the search: status dominated, its certified best and the incumbent recorded.
  Settings settings = d.settings;
  settings.apply_override("reduction.jump_to_incumbent=false");
  settings.apply_override("reduction.dominated_after=2");
  const StartSpec spec = make_start(scene, 1, 0, reduction_settings(settings), elastic_settings(settings));
  const StartOutcome o = run_start(scene, settings, spec, 0.0, BudgetSource::kNone, nullptr, {},
                                   [&] { return unreachable; });
  EXPECT_EQ(o.status, StartStatus::kDominated);
  EXPECT_TRUE(std::isfinite(o.T_f) && o.T_f > unreachable) << o.T_f;  // (the adaptive model)
  EXPECT_EQ(o.incumbent, unreachable);
  EXPECT_TRUE(std::isfinite(o.max_violation));
}

// Aiming below the incumbent (jump_to_incumbent): the first step after the feasible point
// asks for (1 - rate) times the incumbent, not the start's own best.
TEST(ObjectiveReductionIncumbent, WithJumpsTheFirstStepAimsBelowTheIncumbent) {
  const Scene scene = scenario("two_robots_swap_avoid", {"steps=20"});
  DefaultSolvers d;
  d.schedule.jump_to_incumbent = true;
  d.schedule.dominated_after = 3;
  RobotProblem problem(scene);
  const double incumbent = 2.4;  // below the feasible point (at 1.5 x the reference time)
  const ReductionResult r = reduce_objective(problem, d.solver, d.schedule, {}, {}, {},
                                             [&] { return incumbent; });
  print(r);
  ASSERT_TRUE(r.found);
  ASSERT_GE(r.solves.size(), 2u);
  ASSERT_GT(r.solves[0].T_f, incumbent);
  EXPECT_DOUBLE_EQ(r.solves[1].bound, (1.0 - d.schedule.rate) * incumbent);
  // It either got below the incumbent or stopped as dominated.
  EXPECT_TRUE(r.best_value < incumbent || r.stop == StopReason::kDominated) << r.best_value;
}

// The solves of `a` and `b` agree (phase, bound, T_f, status, iterations) up to `count`: one
// start followed the same path.
void expect_same_path(const ReductionResult& a, const ReductionResult& b, size_t count) {
  ASSERT_GE(a.solves.size(), count);
  ASSERT_GE(b.solves.size(), count);
  for (size_t k = 0; k < count; ++k) {
    const SolveRecord &x = a.solves[k], &y = b.solves[k];
    EXPECT_TRUE(x.kind == y.kind && same_bits(x.bound, y.bound) && same_bits(x.T_f, y.T_f) &&
                x.status == y.status && x.iterations == y.iterations)
        << "solve " << k + 1 << ": " << to_string(x.kind) << " " << x.T_f << " (" << x.iterations
        << " it) against " << to_string(y.kind) << " " << y.T_f << " (" << y.iterations << " it)";
  }
}

// Time limits on a simulated clock (core/util/clock.h: 10 ms per Ipopt iteration report), so
// where a limit falls is a fact of the test, not of the machine. A run without a limit gives
// each solve's span on that clock; the limit is put halfway through the solve that spans the
// first third of the time after the feasibility phase (solve j), between two of its reports.
// - Without salvage (reduction.salvage_iterations 0) the limit cuts solve j itself: the solves
//   before it are the run's own, j ends "time limit" and nothing follows it.
// - With salvage, every solve after the feasible point ends early enough for one: the first of a
//   few limits (a third, half, ... of the way) whose run cuts a solve among the steps is taken;
//   the cut solve is followed by its salvage, a branch solve that ends by the limit itself, and
//   only a certified point is ever the best.
TEST(ObjectiveReductionSalvage, ASolveCutByTheTimeLimitIsSalvagedOnItsBranch) {
  RobotProblem problem(scenario("paper/B1", {"steps=20"}));
  DefaultSolvers d;
  ASSERT_GT(d.schedule.salvage_iterations, 0) << "configs/disco.yaml salvages";
  constexpr double kTick = 0.01;  // s per Ipopt iteration report
  IterationTime time(kTick);
  const ScopedTimeSource clock(time);
  const ReductionResult full = reduce_objective(problem, d.solver, d.schedule);
  ASSERT_TRUE(full.found);
  const double feasibility = full.solves.front().seconds;
  ASSERT_GT(full.seconds - feasibility, 2.0 * feasibility) << "room after the feasibility phase";
  // A limit between two reports (a limit on a report is passed only at the next one) halfway
  // through the solve j that spans `fraction` of the time after the feasibility phase.
  auto limit_at = [&](double fraction, size_t& j) {
    const double at = feasibility + fraction * (full.seconds - feasibility);
    double begin = 0.0;
    for (j = 0; j + 1 < full.solves.size() && begin + full.solves[j].seconds <= at; ++j)
      begin += full.solves[j].seconds;
    const double reports = std::round(full.solves[j].seconds / kTick);
    return begin + (std::floor(0.5 * reports) + 0.5) * kTick;
  };
  size_t j = 0;
  const double limit = limit_at(1.0 / 3.0, j);
  ASSERT_GT(j, 0u);
  ASSERT_GE(full.solves[j].iterations, 4) << "a solve long enough to be cut inside";
  std::printf("  without a limit: feasibility %.2f s, all %.2f s; limit %.3f s, in solve %zu (%s)\n",
              feasibility, full.seconds, limit, j + 1, to_string(full.solves[j].kind).c_str());

  ReductionSettings cut = d.schedule;
  cut.time_limit = limit;
  cut.salvage_iterations = 0;
  const ReductionResult lost = reduce_objective(problem, d.solver, cut);
  ASSERT_TRUE(lost.found);
  EXPECT_EQ(lost.stop, StopReason::kOutOfTime);
  ASSERT_EQ(lost.solves.size(), j + 1) << "the limit cuts solve j, and the loop ends there";
  expect_same_path(lost, full, j);
  EXPECT_EQ(lost.solves[j].kind, full.solves[j].kind);
  EXPECT_EQ(lost.solves[j].outcome, NlpOutcome::kTimeLimit);
  EXPECT_FALSE(lost.solves[j].improved) << "a cut solve is lost without salvage";
  EXPECT_EQ(count_kind(lost, SolveKind::kSalvage), 0);
  // Cut at the first report past the limit.
  EXPECT_GT(lost.seconds, limit);
  EXPECT_LE(lost.seconds, limit + kTick + 1e-9);

  // With salvage the cut falls earlier, where the time kept back for the salvage begins; a solve
  // that converged just there instead ends the loop uncut (its polish skipped), with nothing to
  // salvage. So the first of these limits whose run cuts a solve is taken (a fact of the path
  // on the simulated clock, the same on any machine).
  cut.salvage_iterations = d.schedule.salvage_iterations;
  ReductionResult result;
  double salvage_limit = 0.0;
  for (double fraction : {1.0 / 3.0, 0.5, 2.0 / 3.0, 0.8, 0.9, 0.95}) {
    size_t k = 0;
    cut.time_limit = salvage_limit = limit_at(fraction, k);
    result = reduce_objective(problem, d.solver, cut);
    const bool cut_one =
        std::any_of(result.solves.begin() + 1, result.solves.end(),
                    [](const SolveRecord& r) { return r.outcome == NlpOutcome::kTimeLimit; });
    if (cut_one) break;
    std::printf("  limit %.3f s: no solve cut, the next limit\n", salvage_limit);
  }
  print(result);
  ASSERT_TRUE(result.found);
  EXPECT_EQ(result.stop, StopReason::kOutOfTime);
  // The salvage ends by the limit itself: past it by at most one report.
  EXPECT_LE(result.seconds, salvage_limit + kTick + 1e-9);
  int salvages = 0;
  for (size_t k = 0; k < result.solves.size(); ++k) {
    const SolveRecord& r = result.solves[k];
    if (r.kind == SolveKind::kSalvage) {
      ++salvages;
      ASSERT_GT(k, 1u) << "past the feasibility phase";
      expect_same_path(result, full, k - 1);  // the start's own path until the cut
      EXPECT_EQ(result.solves[k - 1].outcome, NlpOutcome::kTimeLimit) << "only a cut solve is salvaged";
      EXPECT_LE(r.iterations, d.schedule.salvage_iterations * r.nlp_solves);
      EXPECT_EQ(k + 1, result.solves.size()) << "a salvage ends the loop";
      if (r.improved) {
        EXPECT_EQ(r.status, MpccStatus::kSolved);
        EXPECT_EQ(result.best_value, r.value);
        EXPECT_EQ(result.stationarity, Stationarity::kFeasible) << "a salvage is not a minimum";
      }
    } else if (r.outcome == NlpOutcome::kTimeLimit && k > 0) {
      ASSERT_LT(k + 1, result.solves.size()) << "a cut solve is followed by its salvage";
      EXPECT_EQ(result.solves[k + 1].kind, SolveKind::kSalvage);
    }
  }
  EXPECT_EQ(salvages, 1) << "one of the limits falls inside a solve among the steps: it is cut";
  // The best is the best certified record, and it is certified on the MPCC.
  double best = kInf;
  for (const SolveRecord& r : result.solves)
    if (r.improved) best = std::min(best, r.value);
  EXPECT_EQ(result.best_value, best);
  EXPECT_TRUE(result.best.certificate.within(d.solver.settings().violation_tol,
                                             d.solver.settings().complementarity_tol));
}

// A minimisation that stalls at Ipopt's max_iter is salvaged on its branch, without a time
// limit, and the loop goes on from there; with salvage_iterations 0 the stalled point is lost.
// Ipopt's max_iter is made small so that a minimisation of paper B1 (20 steps) stalls; the first
// of a few values that stalls one is taken (a fact of the path, the same on any machine).
TEST(ObjectiveReductionSalvage, AMinimisationStalledAtMaxIterIsSalvagedAndTheLoopGoesOn) {
  RobotProblem problem(scenario("paper/B1", {"steps=20"}));
  auto stalled = [](const SolveRecord& r) {
    return r.kind == SolveKind::kMinimize && r.outcome == NlpOutcome::kMaxIterations;
  };
  for (const char* max_iter : {"100", "60", "150", "80"}) {
    // No weak attempt (reduction.minimize_zeta): one that stalls is followed by the
    // minimisation as without it, not salvaged.
    DefaultSolvers d({std::string("ipopt.max_iter=") + max_iter, "reduction.minimize_zeta=0"});
    ASSERT_GT(d.schedule.salvage_iterations, 0) << "configs/disco.yaml salvages";
    ASSERT_EQ(d.schedule.time_limit, 0.0);
    const ReductionResult result = reduce_objective(problem, d.solver, d.schedule);
    const auto first = std::find_if(result.solves.begin(), result.solves.end(), stalled);
    if (first == result.solves.end()) {
      std::printf("  max_iter %s: no minimisation stalled, the next value\n", max_iter);
      continue;
    }
    std::printf("  max_iter %s\n", max_iter);
    print(result);
    ASSERT_TRUE(result.found);
    EXPECT_NE(result.stop, StopReason::kOutOfTime) << "no limit: the loop ends on its own";
    int salvages = 0, improved = 0;
    for (size_t k = 0; k < result.solves.size(); ++k) {
      const SolveRecord& r = result.solves[k];
      if (stalled(r)) {
        ASSERT_LT(k + 1, result.solves.size()) << "a stalled minimisation is followed by its salvage";
        EXPECT_EQ(result.solves[k + 1].kind, SolveKind::kSalvage);
      }
      if (r.kind != SolveKind::kSalvage) continue;
      ++salvages;
      ASSERT_GT(k, 0u);
      EXPECT_TRUE(stalled(result.solves[k - 1])) << "only a stalled (or cut) solve is salvaged";
      EXPECT_LE(r.iterations, d.schedule.salvage_iterations * r.nlp_solves);
      if (r.improved) {
        ++improved;
        EXPECT_EQ(r.status, MpccStatus::kSolved);
        EXPECT_LT(r.value, r.bound) << "below the best it was asked to beat";
      }
    }
    EXPECT_GE(salvages, 1);
    ASSERT_GE(improved, 1) << "the stalled point was within reach of its branch";
    // The loop did not end at a salvage that improved: it went on from the salvaged point.
    const auto last_improving_salvage =
        std::find_if(result.solves.rbegin(), result.solves.rend(), [](const SolveRecord& r) {
          return r.kind == SolveKind::kSalvage && r.improved;
        });
    EXPECT_NE(last_improving_salvage, result.solves.rbegin()) << "the loop goes on";
    EXPECT_TRUE(result.best.certificate.within(d.solver.settings().violation_tol,
                                               d.solver.settings().complementarity_tol));

    // Without salvage the same path up to the first stall, whose point is lost.
    ReductionSettings none = d.schedule;
    none.salvage_iterations = 0;
    const ReductionResult lost = reduce_objective(problem, d.solver, none);
    const size_t j = static_cast<size_t>(first - result.solves.begin());
    expect_same_path(lost, result, j + 1);
    EXPECT_EQ(count_kind(lost, SolveKind::kSalvage), 0);
    return;
  }
  FAIL() << "no max_iter tried stalled a minimisation of paper B1 at 20 steps";
}

TEST(ObjectiveReduction, AnUnknownMinimizerIsAnErrorNamingTheKey) {
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("reduction.minimize=fast");
  try {
    reduction_settings(settings);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("reduction.minimize"), std::string::npos) << what;
    EXPECT_NE(what.find("'elastic' or 'branch', got 'fast'"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace disco
