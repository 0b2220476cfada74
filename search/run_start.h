// disco — running one start of the search and describing its outcome.
//
// run_start() never throws: an exception inside the start (bad data, an
// internal error) becomes status "error" with the message, so a worker never
// takes the search down. The time budget caps the whole start (objective
// reduction) and every elastic solve inside it.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/model/scene.h"
#include "search/objective_reduction.h"
#include "search/start.h"

namespace disco {

struct StartOutcome {
  std::string scene;
  int start = 0;
  std::uint64_t seed = 0;
  std::string status;  // solved | infeasible | failed | error
  std::string detail;  // error message; last feasibility status when not solved;
                       // "time budget reached" when the budget cut the start short
  double T_f = std::numeric_limits<double>::quiet_NaN();  // s, NaN if none
  double max_violation = std::numeric_limits<double>::quiet_NaN();
  double max_complementarity = std::numeric_limits<double>::quiet_NaN();
  int nlp_solves = 0, iterations = 0;
  double seconds = 0.0;
  double time_to_first_feasible = -1.0, time_to_best = -1.0;  // s within the start
  std::string description;  // StartSpec::describe()
  std::string guess;        // the initial guess's kind, to_string(GuessKind), e.g. "detour"
  nlohmann::json schedule;  // StartSpec::schedule_json(): the reduction schedule and zeta
  // Every new best of the start: [seconds within the start, T_f] (ReductionResult::history).
  std::vector<std::array<double, 2>> history;
  int rank = 0;
  double finished_s = -1.0;  // search time when rank 0 recorded it (set by the coordinator)
  bool solved() const { return status == "solved"; }

  nlohmann::json to_json() const;  // one runs.jsonl line (NaN -> null)
  static StartOutcome from_json(const nlohmann::json& j);
};

// Runs `start` on `scene`; `solution` (if not null) receives the solution
// file of the best point (schema: core/model/solution.h); `on_solve` (if set)
// is called after every elastic-mode solve.
StartOutcome run_start(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s, nlohmann::json* solution = nullptr,
                       const SolveCallback& on_solve = {});

}  // namespace disco
