// disco — one start of the multi-start search: an initial guess, an
// objective-reduction schedule and elastic-mode settings, generated
// deterministically from (scene, seed, start index).
//
// Start 0 of every scene is the plain one: the straight-line guess with the
// settings file's schedule (exactly what `disco solve` runs). Later starts
// cycle through the guess kinds and draw their parameters from a generator
// seeded by (seed, scene name, index), so the same (scene, seed, index) gives
// the same start on any rank, in any run.
//
// A kPerturbedFeasible start runs the feasibility phase from the straight-line
// guess, then re-solves it once from a perturbation of the feasible point
// (reduce_objective's PerturbFunction, step 1b in objective_reduction.h): each
// robot's feasible path re-timed by a smooth monotone time warp, velocities
// and the rest completed from the warped positions, at T_scale times the
// feasible horizon. The reduction continues from that point if it is
// certified, else from the feasible point itself.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/elastic/elastic_solver.h"
#include "core/model/robot_problem.h"
#include "search/objective_reduction.h"

namespace disco {

enum class GuessKind {
  kStraight,   // smoothstep straight lines (RobotProblem::straight_line_guess); a robot too
               // weak for the smoothstep moves on its own bang-bang timing (start.cpp)
  kPerturbed,  // straight lines with random lateral and along-path perturbations
  kDetour,     // robots whose straight paths cross pass each other on one side
  kPerturbedFeasible,  // straight lines, then the feasible point re-timed and re-solved
  kYield,      // straight lines; in a random priority order, robots wait until the way is clear
};
std::string to_string(GuessKind kind);

struct StartSpec {
  int index = 0;
  std::uint64_t seed = 0;
  GuessKind guess = GuessKind::kStraight;
  int detour_side = 0;            // kDetour: +1 left, -1 right (per crossing pair, see start.cpp)
  double perturbation = 0.0;      // kPerturbed: relative amplitude; kPerturbedFeasible: of the warp
  double T_scale = 1.0;           // kPerturbedFeasible: re-solve horizon / feasible horizon
  double margin = 1.0;            // kYield: clearance multiple kept from higher-priority robots
  ReductionSettings schedule;     // feasibility horizon factor, reduction rate, grow, shrink, ...
  ElasticSettings elastic;        // zeta, formulation, ...
  std::string describe() const;   // one line, for runs.jsonl and reports
  // {horizon_factor, rate, grow, shrink, min_rate, zeta}: the schedule that varies by start.
  nlohmann::json schedule_json() const;
};

// The start `index` for `scene` under `seed`, varying the given base settings.
StartSpec make_start(const Scene& scene, std::uint64_t seed, int index,
                     const ReductionSettings& base_schedule, const ElasticSettings& base_elastic);

// The initial guess of `start` for horizon `seconds` (model units inside).
Vector make_guess(const RobotProblem& problem, const StartSpec& start, double seconds);

// kPerturbedFeasible: the perturbation of the feasible point `feasible`
// (model-unit z): its paths re-timed, completed by guess_from_paths, at
// T_scale times its horizon. Deterministic in (start, feasible).
Perturbation perturb_feasible(const RobotProblem& problem, const StartSpec& start,
                              const Vector& feasible);
// The PerturbFunction for reduce_objective: perturb_feasible for a
// kPerturbedFeasible start, empty (no step 1b) for every other kind.
// `problem` must outlive the function.
PerturbFunction make_perturbation(const RobotProblem& problem, const StartSpec& start);

}  // namespace disco
