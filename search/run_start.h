// disco — running one start of the search and describing its outcome.
//
// run_start() never throws: an exception inside the start (bad data, an
// internal error, running out of memory: core/model/model_size.h's message) becomes
// status "error" with the message, so a worker never takes the search down. The
// time budget caps the whole start (objective reduction) and every elastic solve
// inside it; a start it cuts short is
// status time_limit, one an interrupt cuts short (core/util/interrupt.h) is
// status interrupted. Both keep their best point so far (T_f, certificate),
// and `disco search --resume` runs them again (search/search_record.h).
#pragma once

#include <array>
#include <cmath>
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

// How a start ended. In runs.jsonl: "solved", "infeasible", "failed", "elastic_not_tight",
// "error", "time_limit", "interrupted", "dominated".
enum class StartStatus {
  kSolved,           // ran to its end with a certified point
  kInfeasible,       // ran to its end; no feasible point (MpccStatus::kInfeasible)
  kFailed,           // ran to its end; the solver failed (MpccStatus::kFailed)
  kElasticNotTight,  // ran to its end; complementarity not tight (MpccStatus::kElasticNotTight)
  kError,            // an exception; `detail` has its message
  kTimeLimit,        // cut short by its time budget; T_f is its best so far (NaN: none)
  kInterrupted,      // cut short by SIGINT or SIGTERM; T_f is its best so far (NaN: none)
  kDominated,        // stopped: its best stayed above another start's (the shared incumbent,
                     // search/reduction_phases.h); T_f is its best, certified
};
std::string to_string(StartStatus s);
// The status named by `text` (as to_string gives it); std::invalid_argument otherwise.
StartStatus start_status_from_string(const std::string& text);

// Which time limit set a start's budget (the smallest of them): the start's own
// (start_time_limit), its scene's (time_limit, from the scene's first start) or the
// search's (--time-limit). In runs.jsonl: "none", "start", "scene", "search".
enum class BudgetSource { kNone, kStart, kScene, kSearch };
std::string to_string(BudgetSource s);
BudgetSource budget_source_from_string(const std::string& text);

// Which stage of a search a start ran (search/screening.h). In runs.jsonl: "full" (a search
// without screening), "screen" (at fewer steps; never a scene's result), "refine" (at full N_t
// from the start's screened answer).
enum class Stage { kFull, kScreen, kRefine };
std::string to_string(Stage s);
Stage stage_from_string(const std::string& text);  // std::invalid_argument if unknown

struct StartOutcome {
  std::string scene;
  int start = 0;
  Stage stage = Stage::kFull;
  std::uint64_t seed = 0;
  StartStatus status = StartStatus::kError;
  std::string detail;  // error message; last feasibility status when not solved
  std::string stopped;  // why its objective reduction stopped (stop_line, reduction_phases.h)
  double budget = 0.0;  // s: the time budget the start had (0: none)
  BudgetSource budget_source = BudgetSource::kNone;
  double T_f = std::numeric_limits<double>::quiet_NaN();  // s, NaN if none
  // The objective J of the best point (core/model/objective.h; = T_f for objective time):
  // what starts and scenes are compared by. NaN if none.
  double value = std::numeric_limits<double>::quiet_NaN();
  double max_violation = std::numeric_limits<double>::quiet_NaN();
  double max_complementarity = std::numeric_limits<double>::quiet_NaN();
  int nlp_solves = 0, iterations = 0;
  // KKT factorisations, those that went to MUMPS, the pivoting LDLᵀ's threshold raises, and
  // the matrices the LDLᵀ passed to the pivoting one (core/ipopt/kkt_solver.h), the analyses
  // that kept nested dissection (KktCounts::nested_dissection)
  int kkt_factorisations = 0, kkt_fallbacks = 0, kkt_threshold_raises = 0, kkt_to_pivoted = 0;
  int kkt_polish_rescues = 0;
  int kkt_nested_dissection = 0;
  double seconds = 0.0;
  double time_to_first_feasible = -1.0, time_to_best = -1.0;  // s within the start
  std::string description;  // StartSpec::describe()
  GuessKind guess = GuessKind::kStraight;  // the initial guess's kind ("guess": to_string)
  nlohmann::json schedule;  // StartSpec::schedule_json(): the reduction schedule and zeta
  // The homotopy class (search/homotopy.h, HomotopyClass::to_json) of the initial guess's
  // paths ("guess_class") and of the best point ("class"; null without one).
  nlohmann::json guess_class, best_class;
  // Every new best of the start: [seconds within the start, J] (ReductionResult::history).
  std::vector<std::array<double, 2>> history;
  // J: the scene's shared incumbent when the start ended (NaN: none; search/reduction_phases.h)
  double incumbent = std::numeric_limits<double>::quiet_NaN();
  int rank = 0;
  double finished_s = -1.0;  // search time when rank 0 recorded it (set by the coordinator)
  bool solved() const { return status == StartStatus::kSolved; }
  // A certified point exists (solved, or cut short after finding one).
  bool certified() const { return std::isfinite(value); }
  // Cut short (time limit or interrupt): the start did not run to its end.
  bool cut_short() const {
    return status == StartStatus::kTimeLimit || status == StartStatus::kInterrupted;
  }

  nlohmann::json to_json() const;  // one runs.jsonl line (NaN -> null)
  static StartOutcome from_json(const nlohmann::json& j);
};

// One outcome of two runs of the same start one after the other (search.refine_from "both": a
// refine from its screened answer, then from its own guess in the budget `first` left): the
// second's point when it is certified and below the first's (J), else the first's; seconds,
// solves, iterations and KKT counts summed; times within the start and the history (every new
// best of the two in turn) counted from the first's start; `stopped` says which run was kept.
// Cut short if the second was (it must run again); the first's guess kind (its screen's answer:
// search/search_record.h treats the outcome as a refine from its screen) and budget.
StartOutcome better_of(const StartOutcome& first, const StartOutcome& second);
// Whether better_of keeps the second run's point (its solution file goes with it).
bool keeps_second(const StartOutcome& first, const StartOutcome& second);

// Runs `start` on `scene` with a time budget (s; 0 = none) set by `budget_source`; `solution`
// (if not null) receives the solution file of the best point (schema: core/model/solution.h);
// `on_solve` (if set) is called after every elastic-mode solve; `incumbent` (if set) gives the
// scene's best from other starts between solves (search/reduction_phases.h).
StartOutcome run_start(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s, BudgetSource budget_source,
                       nlohmann::json* solution = nullptr,
                       const SolveCallback& on_solve = {},
                       const IncumbentFunction& incumbent = {});

}  // namespace disco
