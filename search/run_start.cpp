#include "search/run_start.h"

#include <spdlog/fmt/fmt.h>

#include <cmath>
#include <limits>
#include <exception>
#include <new>
#include <stdexcept>
#include <utility>

#include "core/config/solver_settings.h"
#include "core/model/model_size.h"
#include "core/model/solution.h"
#include "core/util/clock.h"
#include "core/util/interrupt.h"
#include "search/guess.h"
#include "search/homotopy.h"
#include "search/reduction_phases.h"
#include "search/solve_scene.h"
#include "search/trajectory.h"

namespace disco {
namespace {

using json = nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double number_or_nan(const json& j) {
  return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

constexpr std::pair<StartStatus, const char*> kStatusNames[] = {
    {StartStatus::kSolved, "solved"},         {StartStatus::kInfeasible, "infeasible"},
    {StartStatus::kFailed, "failed"},         {StartStatus::kElasticNotTight, "elastic_not_tight"},
    {StartStatus::kError, "error"},           {StartStatus::kTimeLimit, "time_limit"},
    {StartStatus::kInterrupted, "interrupted"}, {StartStatus::kDominated, "dominated"}};
constexpr std::pair<BudgetSource, const char*> kSourceNames[] = {{BudgetSource::kNone, "none"},
                                                                 {BudgetSource::kStart, "start"},
                                                                 {BudgetSource::kScene, "scene"},
                                                                 {BudgetSource::kSearch, "search"}};

constexpr std::pair<Stage, const char*> kStageNames[] = {
    {Stage::kFull, "full"}, {Stage::kScreen, "screen"}, {Stage::kRefine, "refine"}};

template <class E, std::size_t N>
std::string name_of(const std::pair<E, const char*> (&names)[N], E value) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "?";
}
template <class E, std::size_t N>
E value_of(const std::pair<E, const char*> (&names)[N], const std::string& text, const char* what) {
  for (const auto& [v, name] : names)
    if (text == name) return v;
  throw std::invalid_argument(std::string("unknown ") + what + " '" + text + "'");
}

StartStatus status_of(MpccStatus s) {
  switch (s) {
    case MpccStatus::kSolved: return StartStatus::kSolved;
    case MpccStatus::kInfeasible: return StartStatus::kInfeasible;
    case MpccStatus::kElasticNotTight: return StartStatus::kElasticNotTight;
    case MpccStatus::kFailed: return StartStatus::kFailed;
  }
  return StartStatus::kFailed;
}

}  // namespace

std::string to_string(StartStatus s) { return name_of(kStatusNames, s); }
StartStatus start_status_from_string(const std::string& text) {
  return value_of(kStatusNames, text, "start status");
}
std::string to_string(BudgetSource s) { return name_of(kSourceNames, s); }
std::string to_string(Stage s) { return name_of(kStageNames, s); }
Stage stage_from_string(const std::string& text) { return value_of(kStageNames, text, "stage"); }
BudgetSource budget_source_from_string(const std::string& text) {
  return value_of(kSourceNames, text, "budget source");
}

json StartOutcome::to_json() const {
  return {{"scene", scene},
          {"start", start},
          {"stage", to_string(stage)},
          {"seed", seed},
          {"status", to_string(status)},
          {"detail", detail},
          {"stopped", stopped},
          {"budget", {{"seconds", budget}, {"set_by", to_string(budget_source)}}},
          {"T_f", number_or_null(T_f)},
          {"value", number_or_null(value)},
          {"certificate",
           {{"max_violation", number_or_null(max_violation)},
            {"max_complementarity", number_or_null(max_complementarity)}}},
          {"nlp_solves", nlp_solves},
          {"iterations", iterations},
          {"kkt",
           {{"factorisations", kkt_factorisations},
            {"fallbacks", kkt_fallbacks},
            {"threshold_raises", kkt_threshold_raises},
            {"to_pivoted", kkt_to_pivoted},
            {"nested_dissection", kkt_nested_dissection},
            {"polish_rescues", kkt_polish_rescues}}},
          {"seconds", seconds},
          {"time_to_first_feasible", time_to_first_feasible},
          {"time_to_best", time_to_best},
          {"description", description},
          {"guess", to_string(guess)},
          {"schedule", schedule},
          {"guess_class", guess_class},
          {"class", best_class},
          {"history", history},
          {"incumbent", number_or_null(incumbent)},
          {"rank", rank},
          {"finished_s", finished_s}};
}

StartOutcome StartOutcome::from_json(const json& j) {
  StartOutcome o;
  o.scene = j.at("scene").get<std::string>();
  o.start = j.at("start").get<int>();
  o.stage = stage_from_string(j.value("stage", "full"));  // older files: no stages
  o.seed = j.at("seed").get<std::uint64_t>();
  o.status = start_status_from_string(j.at("status").get<std::string>());
  o.detail = j.value("detail", "");
  o.stopped = j.value("stopped", "");
  if (j.contains("budget")) {
    o.budget = j["budget"].at("seconds").get<double>();
    o.budget_source = budget_source_from_string(j["budget"].at("set_by").get<std::string>());
  }
  o.T_f = number_or_nan(j.at("T_f"));
  o.value = j.contains("value") ? number_or_nan(j["value"]) : o.T_f;  // older files: time only
  o.max_violation = number_or_nan(j.at("certificate").at("max_violation"));
  o.max_complementarity = number_or_nan(j.at("certificate").at("max_complementarity"));
  o.nlp_solves = j.value("nlp_solves", 0);
  o.iterations = j.value("iterations", 0);
  if (j.contains("kkt")) {  // older files: none
    o.kkt_factorisations = j["kkt"].value("factorisations", 0);
    o.kkt_fallbacks = j["kkt"].value("fallbacks", 0);
    o.kkt_threshold_raises = j["kkt"].value("threshold_raises", 0);
    o.kkt_to_pivoted = j["kkt"].value("to_pivoted", 0);
    o.kkt_nested_dissection = j["kkt"].value("nested_dissection", 0);  // older files: none
    o.kkt_polish_rescues = j["kkt"].value("polish_rescues", 0);  // older files: none
  }
  o.seconds = j.value("seconds", 0.0);
  o.time_to_first_feasible = j.value("time_to_first_feasible", -1.0);
  o.time_to_best = j.value("time_to_best", -1.0);
  o.description = j.value("description", "");
  o.guess = guess_kind_from_string(j.value("guess", "straight"));
  o.schedule = j.value("schedule", json::object());
  o.guess_class = j.value("guess_class", json());
  o.best_class = j.value("class", json());
  o.history = j.value("history", std::vector<std::array<double, 2>>{});
  if (j.contains("incumbent")) o.incumbent = number_or_nan(j["incumbent"]);
  o.rank = j.value("rank", 0);
  o.finished_s = j.value("finished_s", -1.0);
  return o;
}

bool keeps_second(const StartOutcome& first, const StartOutcome& second) {
  return second.certified() && (!first.certified() || second.value < first.value);
}

StartOutcome better_of(const StartOutcome& first, const StartOutcome& second) {
  const bool second_kept = keeps_second(first, second);
  StartOutcome o = second_kept ? second : first;
  const double dt = first.seconds;
  o.seconds = first.seconds + second.seconds;
  o.nlp_solves = first.nlp_solves + second.nlp_solves;
  o.iterations = first.iterations + second.iterations;
  o.kkt_factorisations = first.kkt_factorisations + second.kkt_factorisations;
  o.kkt_fallbacks = first.kkt_fallbacks + second.kkt_fallbacks;
  o.kkt_threshold_raises = first.kkt_threshold_raises + second.kkt_threshold_raises;
  o.kkt_to_pivoted = first.kkt_to_pivoted + second.kkt_to_pivoted;
  o.kkt_nested_dissection = first.kkt_nested_dissection + second.kkt_nested_dissection;
  o.kkt_polish_rescues = first.kkt_polish_rescues + second.kkt_polish_rescues;
  o.time_to_first_feasible = first.time_to_first_feasible >= 0 ? first.time_to_first_feasible
                             : second.time_to_first_feasible >= 0 ? dt + second.time_to_first_feasible
                                                                  : -1.0;
  if (second_kept) o.time_to_best = dt + second.time_to_best;
  o.history = first.history;
  double least = first.history.empty() ? std::numeric_limits<double>::infinity() : first.history.back()[1];
  for (const auto& [s, value] : second.history)
    if (value < least) {
      o.history.push_back({dt + s, value});
      least = value;
    }
  if (second.cut_short()) o.status = second.status;
  o.guess = first.guess;
  o.budget = first.budget;
  o.budget_source = first.budget_source;
  o.incumbent = second.incumbent;
  o.stopped = fmt::format("{} (refined from its screen: {}; from its start: {}; the {} kept)", o.stopped,
                          first.certified() ? fmt::format("{:.6f}", first.value) : to_string(first.status),
                          second.certified() ? fmt::format("{:.6f}", second.value) : to_string(second.status),
                          second_kept ? "start's" : "screen's");
  return o;
}

StartOutcome run_start(const Scene& scene, const Settings& settings, const StartSpec& start,
                       double time_budget_s, BudgetSource budget_source, json* solution,
                       const SolveCallback& on_solve, const IncumbentFunction& incumbent) {
  const auto t0 = Clock::now();
  StartOutcome out;
  out.scene = scene.name;
  out.start = start.index;
  out.seed = start.seed;
  out.description = start.describe();
  out.guess = start.guess;
  out.schedule = start.schedule_json();
  out.budget = time_budget_s;
  out.budget_source = time_budget_s > 0 ? budget_source : BudgetSource::kNone;
  try {
    out.guess_class = homotopy_class(scene, guess_paths(scene, start)).to_json(scene);
    SceneSolve run = solve_scene(scene, settings, start, time_budget_s, on_solve, incumbent);
    const ReductionResult& r = run.result;
    out.status = status_of(r.status);
    out.stopped = stop_line(r.stop, start.schedule);
    out.nlp_solves = r.nlp_solves;
    out.iterations = r.iterations;
    out.kkt_factorisations = r.kkt.factorisations;
    out.kkt_fallbacks = r.kkt.fallbacks;
    out.kkt_threshold_raises = r.kkt.threshold_raises;
    out.kkt_to_pivoted = r.kkt.to_pivoted;
    out.kkt_nested_dissection = r.kkt.nested_dissection;
    out.kkt_polish_rescues = r.kkt.polish_rescues;
    out.time_to_first_feasible = r.time_to_first_feasible;
    out.time_to_best = r.time_to_best;
    for (const auto& i : r.history) out.history.push_back({i.seconds, i.value});
    if (std::isfinite(r.incumbent)) out.incumbent = r.incumbent;
    if (r.found) {
      out.value = r.best_value;
      out.T_f = run.problem->horizon(run.z);
      out.best_class = homotopy_class(scene, paths_of(*run.problem, run.z)).to_json(scene);
    } else {
      out.detail = r.feasibility_detail;
      if (const std::string where = violations_text(run.info.violations); !where.empty())
        out.detail += "; " + where;
    }
    // Cut short: the reduction ended on the clock, not by its own rules.
    if (interrupt_requested()) {
      out.status = StartStatus::kInterrupted;
    } else if (r.found && r.stop == StopReason::kDominated) {
      out.status = StartStatus::kDominated;
    } else if (const bool budget_limits = time_budget_s > 0 && !(start.schedule.time_limit > 0 &&
                                                                  start.schedule.time_limit < time_budget_s);
               budget_limits && (r.stop == StopReason::kOutOfTime || r.seconds >= time_budget_s)) {
      // The budget set the loop's limit, and the loop stopped on it: its last solve may have
      // ended before the budget, keeping back time for a salvage (reduction.salvage_iterations).
      out.status = StartStatus::kTimeLimit;
    }
    if (!r.found) run.info.detail = out.detail;
    out.max_violation = run.info.certificate.max_violation;
    out.max_complementarity = run.info.certificate.max_complementarity;
    out.seconds = seconds_since(t0);
    run.info.wall_s = out.seconds;
    if (solution != nullptr) *solution = solution_json(*run.problem, run.z, run.info);
  } catch (const std::bad_alloc&) {
    out.status = StartStatus::kError;
    const std::string doing =
        "running start " + std::to_string(start.index) + " of scene '" + scene.name + "'";
    out.detail = out_of_memory_message(doing, scene, model_options(settings).adaptive);
  } catch (const std::exception& e) {
    out.status = StartStatus::kError;
    out.detail = e.what();
  } catch (...) {
    out.status = StartStatus::kError;
    out.detail = "unknown exception";
  }
  out.seconds = seconds_since(t0);
  return out;
}

}  // namespace disco
