// disco — one start of the multi-start search: an initial guess, an
// objective-reduction schedule and elastic-mode settings, generated
// deterministically from (scene, seed, start index).
//
// Start 0 of every scene is the plain one: the straight-line guess with the
// settings file's schedule (exactly what `disco solve` runs). Later starts
// cycle through the guess kinds and draw their parameters from a generator
// seeded by (seed, scene name, index), so the same (scene, seed, index) gives
// the same start on any rank, in any run.
#pragma once

#include <cstdint>
#include <string>

#include "core/elastic/elastic_solver.h"
#include "core/model/robot_problem.h"
#include "search/objective_reduction.h"

namespace disco {

enum class GuessKind {
  kStraight,   // smoothstep straight lines (RobotProblem::straight_line_guess)
  kPerturbed,  // straight lines with random lateral and along-path perturbations
  kDetour,     // robots whose straight paths cross pass each other on one side
};
std::string to_string(GuessKind kind);

struct StartSpec {
  int index = 0;
  std::uint64_t seed = 0;
  GuessKind guess = GuessKind::kStraight;
  int detour_side = 0;            // kDetour: +1 left, -1 right (per crossing pair, see start.cpp)
  double perturbation = 0.0;      // kPerturbed: relative amplitude
  ReductionSettings schedule;     // feasibility horizon factor, reduction rate, grow, shrink, ...
  ElasticSettings elastic;        // zeta, formulation, ...
  std::string describe() const;   // one line, for runs.jsonl and reports
};

// The start `index` for `scene` under `seed`, varying the given base settings.
StartSpec make_start(const Scene& scene, std::uint64_t seed, int index,
                     const ReductionSettings& base_schedule, const ElasticSettings& base_elastic);

// The initial guess of `start` for horizon `seconds` (model units inside).
Vector make_guess(const RobotProblem& problem, const StartSpec& start, double seconds);

}  // namespace disco
