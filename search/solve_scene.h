// disco — everything `disco solve` does between reading its inputs and
// writing solution.json: build the model of a scene, make the solvers from
// the settings, run the objective reduction from the straight-line start, and
// certify the best point on the model itself.
#pragma once

#include <memory>

#include "core/config/settings.h"
#include "core/model/robot_problem.h"
#include "core/model/solution.h"
#include "search/objective_reduction.h"

namespace disco {

struct SceneSolve {
  std::unique_ptr<RobotProblem> problem;
  ReductionResult result;
  SolutionInfo info;  // status, certificate of the best point, timing
  Vector z;           // best point (model units), empty if none
  bool solved() const { return result.found; }
  double T_f() const { return result.T_best; }
};

// Throws InputError for bad settings (Ipopt options, elastic or reduction keys).
SceneSolve solve_scene(const Scene& scene, const Settings& settings,
                       const SolveCallback& on_solve = {});

}  // namespace disco
