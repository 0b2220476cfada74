// disco — everything `disco solve` does between reading its inputs and
// writing solution.json: build the model of a scene, make the solvers from
// the settings, run the objective reduction from one start (by default start
// 0: the straight-line guess and the settings file's schedule), and certify
// the best point on the model itself. A search's starts run through the same
// function (search/run_start.h).
#pragma once

#include <limits>
#include <memory>

#include "core/config/settings.h"
#include "core/model/robot_problem.h"
#include "core/model/solution.h"
#include "search/objective_reduction.h"
#include "search/start.h"

namespace disco {

struct SceneSolve {
  std::unique_ptr<RobotProblem> problem;
  ReductionResult result;
  SolutionInfo info;  // status, certificate of the best point, timing
  Vector z;           // best point (model units), empty if none
  bool solved() const { return result.found; }
  // J (SI) and T_f (s) of the best point; NaN without one.
  double value() const { return solved() ? result.best_value : std::numeric_limits<double>::quiet_NaN(); }
  double T_f() const { return z.size() > 0 ? problem->horizon(z) : std::numeric_limits<double>::quiet_NaN(); }
};

// The steps of a coarse-to-fine start's coarse stage (feasibility.coarse_fraction):
// max(2, round(coarse_fraction N_t)), or 0 (no coarse stage) when the fraction is 0 or that is
// not fewer than N_t.
int coarse_steps(const Scene& scene, const ReductionSettings& schedule);

// Runs `start` (make_start) on `scene`. With feasibility.coarse_fraction > 0 (and a start not
// from a trajectory already), the start first runs on the scene at coarse_steps() steps, with
// its own guess and schedule and no incumbent, and the full scene then starts from that
// answer (a kGiven start, search/trajectory.h: its paths resampled to N_t, first solved at
// (1 + guess_slack) times its T_f), or from the start's own guess if the coarse stage found
// none. The coarse solves come first in the result (SolveRecord::coarse; never a best),
// their iterations and time count, and the time budget covers both stages. A time budget > 0 caps the whole
// objective reduction and every elastic solve inside it.
// Throws InputError for bad settings (Ipopt options, elastic or reduction keys) and for a
// scene whose model would exceed model.memory_limit (core/model/model_size.h), before
// building anything.
SceneSolve solve_scene(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s = 0.0, const SolveCallback& on_solve = {},
                       const IncumbentFunction& incumbent = {});
// Start 0, no budget.
SceneSolve solve_scene(const Scene& scene, const Settings& settings,
                       const SolveCallback& on_solve = {});

}  // namespace disco
