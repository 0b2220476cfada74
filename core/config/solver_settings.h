// disco — typed solver settings read from a Settings document (configs/disco.yaml plus
// --set overrides): Ipopt's options, the robot model's options, the elastic mode's
// parameters and the objective reduction's schedule. This is the one reader of the
// settings' sections; every range check lives here. Values out of range are InputErrors
// naming the file, the line and the key (or "--set" and the key).
//
// No defaults are kept in code: every value comes from the settings file (the structs
// below are zero-initialised; what a field means is said next to it).
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/config/settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/model_plan.h"
#include "core/model/model_size.h"
#include "core/util/clock.h"
#include "core/util/errors.h"

namespace disco {

// How the objective reduction minimises (reduction.minimize; search/objective_reduction.h,
// step 3 and its early call).
enum class Minimizer {
  kElastic,  // one elastic-mode minimisation, to convergence
  kBranch,   // a descent by branches: elastic segments and branch descents
};

// The objective reduction's schedule (search/objective_reduction.h): the `feasibility:` and
// `reduction:` sections.
struct ReductionSettings {
  Minimizer minimizer = Minimizer::kElastic;
  double horizon_factor = 0.0;
  double horizon_min = 0.0;  // s
  // A start from a trajectory (search/trajectory.h): its first feasibility horizon is
  // (1 + guess_slack) times the trajectory's T_f.
  double guess_slack = 0.0;
  // A start from a trajectory: right after its feasibility solve (and step 1b) it minimises
  // T_f from there, then probes below (search/reduction_phases.h), instead of the reduction's
  // steps: its answer already lies near a local optimum.
  bool guess_minimize = false;
  // > 0: a start first solves the scene at round(coarse_fraction N_t) steps, then the full
  // scene from that answer (coarse to fine, search/solve_scene.h); 0: no coarse stage.
  double coarse_fraction = 0.0;
  // Not a setting: the first feasibility horizon (s) of a start from a trajectory, set by
  // solve_scene; 0: max(horizon_min, horizon_factor * reference time).
  double horizon = 0.0;
  double rate = 0.0, grow = 0.0, shrink = 0.0, min_rate = 0.0;
  int max_solves = 0;
  int step_iterations = 0;     // cap on a minimising step before switching to fixed steps
  int segment_iterations = 0;  // kBranch: the length of an elastic segment (Ipopt iterations)
  int minimize_iterations = 0;  // kElastic: cap on the early minimisation (step 3); 0 = none
  // A minimisation that converged inside the loop is probed below with a fixed step (true),
  // or ends the loop (false); search/reduction_phases.h.
  bool probe_after_minimize = false;
  // kElastic: a minimisation starts from the best point's primal values only, its duals cold
  // (ElasticRequest::cold_start); false: from its multipliers too.
  bool cold_minimize = false;
  // kElastic: > 0: a minimisation first runs at zeta = min(this, the best point's zeta), its
  // raises up to the best point's zeta times elastic.zeta_factor; if that is not certified it
  // runs again as without (search/objective_reduction.h, "Minimisations"). 0: off.
  double minimize_zeta = 0.0;
  // kElastic, with minimize_zeta: the weak attempt runs as the relaxation homotopy
  // (ElasticRequest::relaxation; `homotopy`) instead of elastic.formulation's penalty loop
  // (`penalty`); its fallback, uncertified, runs as always (reduction.minimize_weak).
  bool weak_homotopy = false;
  int flip_rounds = 0;      // kBranch: at most this many rounds of flips per branch descent
  double time_limit = 0.0;  // s; 0 = none
  // Under a time limit: a step or minimisation cut by it has its point polished on its branch
  // in at most this many Ipopt iterations, in time kept back for it (search/objective_reduction.h,
  // "Salvage"); 0 = none.
  int salvage_iterations = 0;
  // The shared incumbent (search/reduction_phases.h): steps aim below (1 - r) min(T_best,
  // incumbent); a start whose best stays above the incumbent for dominated_after steps in a
  // row stops, dominated (0 = never).
  bool jump_to_incumbent = false;
  int dominated_after = 0;
};

std::vector<IpoptOption> ipopt_options(const Settings& settings);    // the `ipopt:` section
LdltSettings ldlt_settings(const Settings& settings);  // `kkt.ldlt`: disco's LDLᵀ
IpoptSettings ipopt_settings(const Settings& settings);  // `ipopt:` + `kkt:`: an IpoptSolver's
ElasticSettings elastic_settings(const Settings& settings);          // the `elastic:` section
ModelOptions model_options(const Settings& settings);                // the `model:` section
// model.memory_limit: `auto` (half of the machine's physical memory, or of its cgroup's
// limit when lower) or a number of GiB > 0 (.inf: none); checked by core/model/model_size.h
// before a model is built. Anything else is an InputError naming the file, line and key.
MemoryLimit memory_limit(const Settings& settings);
ReductionSettings reduction_settings(const Settings& settings);      // `feasibility:` + `reduction:`
// A weak-minimisation key (reduction.minimize_weak, search.refine_minimize_weak): true for
// `homotopy`, false for `penalty`. The homotopy relaxes the lumped row and ends in polish, so it
// is an InputError naming the key unless elastic.formulation is lumped or relaxed and
// elastic.polish is on.
bool weak_homotopy_choice(const Settings& settings, const std::string& key);
// search.share_incumbent (the `search:` section): whether a search's starts share the best
// T_f of their scene (search/coordinator.h); `disco search --deterministic` sets it false.
inline constexpr const char* kShareIncumbentKey = "search.share_incumbent";
bool share_incumbent(const Settings& settings);
// search.defer_seen_classes: whether a search hands out first the starts whose guess is of a
// homotopy class no lower start of the scene has (search/task_queue.h).
bool defer_seen_classes(const Settings& settings);
// The `clock:` section: where disco reads time (core/util/clock.h).
ClockSettings clock_settings(const Settings& settings);

// The value of the text key `key` among `choices` (name, value); any other text is an
// InputError naming the key and listing the names.
template <class E>
E choice(const Settings& s, const std::string& key,
         std::initializer_list<std::pair<const char*, E>> choices) {
  const std::string text = s.text(key);
  std::string names;
  size_t k = 0;
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
    if (k > 0) names.append(k + 1 == choices.size() ? " or " : ", ");
    names.append("'").append(name).append("'");
    ++k;
  }
  throw InputError(s.where(key) + ": key '" + key + "': must be " + names + ", got '" + text + "'");
}

}  // namespace disco
