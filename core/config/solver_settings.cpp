// disco — typed solver settings. See solver_settings.h.
#include "core/config/solver_settings.h"

#include <cmath>

#include "core/util/errors.h"
#include "core/util/machine.h"

namespace disco {

namespace {

// The range checks of every section: each reads `key` and refuses a value out of its
// range with "WHERE: key 'KEY': must ...".
[[noreturn]] void refuse(const Settings& s, const std::string& key, const std::string& what) {
  throw InputError(s.where(key) + ": key '" + key + "': " + what);
}

double positive(const Settings& s, const std::string& key) {
  const double v = s.number(key);
  if (!(v > 0)) refuse(s, key, "must be positive");
  return v;
}

// A factor that grows something: > 1.
double above_one(const Settings& s, const std::string& key) {
  const double v = positive(s, key);
  if (v <= 1) refuse(s, key, "must exceed 1");
  return v;
}

// A fraction or a factor that shrinks something: 0 < v < 1.
double below_one(const Settings& s, const std::string& key) {
  const double v = positive(s, key);
  if (v >= 1) refuse(s, key, "must be below 1");
  return v;
}

// A fraction where 0 means none: 0 <= v < 1.
double fraction_or_none(const Settings& s, const std::string& key) {
  const double v = s.number(key);
  if (!(v >= 0 && v < 1)) refuse(s, key, "must be >= 0 and below 1 (0: none)");
  return v;
}

// A count with a lower bound.
int integer_at_least(const Settings& s, const std::string& key, int min) {
  const int v = s.integer(key);
  if (v < min) refuse(s, key, "must be >= " + std::to_string(min));
  return v;
}

// A duration or a limit where 0 means none.
double non_negative(const Settings& s, const std::string& key) {
  const double v = s.number(key);
  if (v < 0) refuse(s, key, "must be >= 0");
  return v;
}

// One rule of ElasticSettings::Stagnation: the keys after, window, level and decrease under
// `prefix` (which ends with a dot).
ElasticSettings::Stagnation::Rule stagnation_rule(const Settings& s, const std::string& prefix) {
  ElasticSettings::Stagnation::Rule r;
  r.after = integer_at_least(s, prefix + "after", 0);
  r.window = integer_at_least(s, prefix + "window", 1);
  r.level = positive(s, prefix + "level");
  r.decrease = below_one(s, prefix + "decrease");
  return r;
}

}  // namespace

std::vector<IpoptOption> ipopt_options(const Settings& settings) {
  std::vector<IpoptOption> out;
  for (const auto& e : settings.section("ipopt"))
    out.push_back({e.name, e.value, e.line > 0 ? settings.source() + ":" + std::to_string(e.line)
                                               : std::string("--set")});
  return out;
}

LdltSettings ldlt_settings(const Settings& s) {
  LdltSettings l;
  l.scaling_sweeps = integer_at_least(s, "kkt.ldlt.scaling_sweeps", 0);
  l.regularisation = positive(s, "kkt.ldlt.regularisation");
  if (l.regularisation >= 1) refuse(s, "kkt.ldlt.regularisation", "must be below 1");
  l.residual_tolerance = positive(s, "kkt.ldlt.residual_tolerance");
  l.refinement_steps = integer_at_least(s, "kkt.ldlt.refinement_steps", 0);
  l.growth_limit = positive(s, "kkt.ldlt.growth_limit");
  l.certificate_iterations = integer_at_least(s, "kkt.ldlt.certificate.iterations", 0);
  l.certificate_margin = s.number("kkt.ldlt.certificate.margin");
  if (!(l.certificate_margin >= 1))  // below 1, Weyl's inequality no longer vouches
    refuse(s, "kkt.ldlt.certificate.margin", "must be >= 1");
  l.pivot_threshold = positive(s, "kkt.ldlt.pivoting.threshold");
  if (l.pivot_threshold > 0.5) refuse(s, "kkt.ldlt.pivoting.threshold", "must be at most 0.5");
  l.pivot_threshold_max = s.number("kkt.ldlt.pivoting.threshold_max");
  if (!(l.pivot_threshold_max >= l.pivot_threshold && l.pivot_threshold_max <= 0.5))
    refuse(s, "kkt.ldlt.pivoting.threshold_max", "must lie in [kkt.ldlt.pivoting.threshold, 0.5]");
  l.zero_pivot = positive(s, "kkt.ldlt.pivoting.zero_pivot");
  l.ordering.nested_dissection_above = non_negative(s, "kkt.ldlt.ordering.nested_dissection_above");
  l.fallback_pivoted =
      choice<bool>(s, "kkt.ldlt.fallback", {{"pivoted", true}, {"mumps", false}});
  return l;
}

IpoptSettings ipopt_settings(const Settings& s) {
  IpoptSettings i;
  i.options = ipopt_options(s);
  i.perturbed_first = s.boolean("kkt.perturbed_first");
  i.kkt_solver = choice<KktSolverKind>(
      s, "kkt.solver", {{"mumps", KktSolverKind::kMumps},
                                    {"ldlt", KktSolverKind::kLdlt},
                                    {"pivoted", KktSolverKind::kPivoted}});
  i.polish_rescue_solver = choice<std::optional<KktSolverKind>>(
                               s, "kkt.polish_rescue.solver",
                               {{"same", std::nullopt},
                                {"mumps", KktSolverKind::kMumps},
                                {"ldlt", KktSolverKind::kLdlt},
                                {"pivoted", KktSolverKind::kPivoted}})
                               .value_or(i.kkt_solver);
  i.polish_rescue_after = integer_at_least(s, "kkt.polish_rescue.after", 0);
  i.ldlt = ldlt_settings(s);
  i.dump.every = integer_at_least(s, "kkt.dump.every", 0);
  i.dump.dir = s.text("kkt.dump.dir");
  if (i.dump.every > 0 && i.dump.dir.empty()) refuse(s, "kkt.dump.dir", "must name a folder");
  return i;
}

MemoryLimit memory_limit(const Settings& s) {
  constexpr double kAutoShare = 0.5;  // auto: this share of the machine's memory
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  const std::string text = s.text(kMemoryLimitKey);  // a missing key fails here, named
  MemoryLimit m;
  m.where = s.where(kMemoryLimitKey);
  if (text == "auto") {
    const double machine = physical_memory_bytes();
    m.bytes = kAutoShare * machine;
    m.auto_meaning = "auto = half of the machine's " + memory_text(machine);
    return m;
  }
  double gib = NAN;
  try {
    gib = s.number(kMemoryLimitKey);
  } catch (const InputError&) {  // not a number: the message below says what is allowed
  }
  if (!(gib > 0))
    throw InputError(located_message(m.where, 0, kMemoryLimitKey,
                                     "must be 'auto' or a number of GiB > 0 (got '" +
                                         printable(text, kEchoLimit) + "')"));
  m.bytes = gib * kGiB;
  return m;
}

ModelOptions model_options(const Settings& s) {
  ModelOptions m;
  m.adaptive = s.boolean("model.adaptive");
  return m;
}

ElasticSettings elastic_settings(const Settings& s) {
  ElasticSettings e;
  e.formulation = choice<ElasticFormulation>(s, "elastic.formulation",
                                              {{"lumped", ElasticFormulation::kLumped},
                                               {"per_pair", ElasticFormulation::kPerPair},
                                               {"relaxed", ElasticFormulation::kRelaxed},
                                               {"barrier", ElasticFormulation::kBarrier}});
  e.zeta = positive(s, "elastic.zeta");
  e.zeta_factor = above_one(s, "elastic.zeta_factor");
  e.zeta_max = positive(s, "elastic.zeta_max");
  e.stall_change = s.number("elastic.stall_change");
  e.complementarity_tol = positive(s, "elastic.complementarity_tolerance");
  e.violation_tol = positive(s, "elastic.violation_tolerance");
  e.polish = s.boolean("elastic.polish");
  e.polish_fixed_above = non_negative(s, "elastic.polish_fixed_above");
  e.sigma = positive(s, "elastic.sigma");
  e.sigma_factor = below_one(s, "elastic.sigma_factor");
  e.sigma_min = positive(s, "elastic.sigma_min");
  e.barrier_ratio = positive(s, "elastic.barrier_ratio");
  e.barrier_sigma_factor = positive(s, "elastic.barrier_sigma_factor");
  e.barrier_sigma_exponent = positive(s, "elastic.barrier_sigma_exponent");
  e.barrier_monotone_mu =
      choice<bool>(s, "elastic.barrier_mu", {{"monotone", true}, {"adaptive", false}});
  e.stagnation.first = stagnation_rule(s, "elastic.stagnation.");
  e.stagnation.feasibility_after = integer_at_least(s, "elastic.stagnation.feasibility_after", 0);
  e.stagnation.late = stagnation_rule(s, "elastic.stagnation.late.");
  e.stall.after = integer_at_least(s, "elastic.stall.after", 0);
  e.stall.window = integer_at_least(s, "elastic.stall.window", 1);
  e.stall.decrease = below_one(s, "elastic.stall.decrease");
  e.stall.mu = positive(s, "elastic.stall.mu");
  e.stall.infeasibility = positive(s, "elastic.stall.infeasibility");
  if (e.formulation == ElasticFormulation::kRelaxed && !e.polish)
    refuse(s, "elastic.polish",
           "formulation relaxed needs polish: its homotopy ends where the relaxation stops "
           "holding, and polish fixes the branch");
  if (e.formulation == ElasticFormulation::kBarrier && !e.polish)
    refuse(s, "elastic.polish",
           "formulation barrier needs polish: at a corner where both sides of a pair vanish "
           "its relaxation leaves both near sqrt(sigma), and polish fixes the branch");
  return e;
}

bool weak_homotopy_choice(const Settings& s, const std::string& key) {
  const bool homotopy = choice<bool>(s, key, {{"penalty", false}, {"homotopy", true}});
  if (homotopy) {
    // ElasticSolver::run's condition for a relaxation request, on the parsed formulation.
    const ElasticSettings e = elastic_settings(s);
    if (e.formulation != ElasticFormulation::kLumped &&
        e.formulation != ElasticFormulation::kRelaxed)
      refuse(s, key,
             "homotopy relaxes the lumped row: it needs elastic.formulation lumped or relaxed, "
             "not " + s.text("elastic.formulation") + " (with it, set " + key + " penalty)");
    if (!e.polish)
      refuse(s, key,
             "homotopy needs elastic.polish: its homotopy ends where the relaxation stops "
             "holding, and polish fixes the branch (without it, set " + key + " penalty)");
  }
  return homotopy;
}

ReductionSettings reduction_settings(const Settings& s) {
  ReductionSettings r;
  r.horizon_factor = positive(s, "feasibility.horizon_factor");
  r.horizon_min = positive(s, "feasibility.horizon_min");
  r.guess_slack = non_negative(s, "feasibility.guess_slack");
  r.guess_minimize = s.boolean("feasibility.guess_minimize");
  r.coarse_fraction = fraction_or_none(s, "feasibility.coarse_fraction");
  r.rate = below_one(s, "reduction.rate");
  r.grow = positive(s, "reduction.grow");
  r.shrink = below_one(s, "reduction.shrink");
  r.min_rate = positive(s, "reduction.min_rate");
  r.max_solves = integer_at_least(s, "reduction.max_solves", 0);
  r.step_iterations = integer_at_least(s, "reduction.step_iterations", 1);
  r.segment_iterations = integer_at_least(s, "reduction.segment_iterations", 1);
  r.minimize_iterations = integer_at_least(s, "reduction.minimize_iterations", 0);
  r.probe_after_minimize = s.boolean("reduction.probe_after_minimize");
  r.cold_minimize = choice<bool>(s, "reduction.minimize_duals", {{"cold", true}, {"warm", false}});
  r.minimize_zeta = non_negative(s, "reduction.minimize_zeta");
  r.weak_homotopy = weak_homotopy_choice(s, "reduction.minimize_weak");
  r.minimizer = choice<Minimizer>(s, "reduction.minimize",
                                  {{"elastic", Minimizer::kElastic}, {"branch", Minimizer::kBranch}});
  r.flip_rounds = integer_at_least(s, "reduction.flip_rounds", 0);
  r.time_limit = non_negative(s, "reduction.time_limit");
  r.salvage_iterations = integer_at_least(s, "reduction.salvage_iterations", 0);
  r.jump_to_incumbent = s.boolean("reduction.jump_to_incumbent");
  r.dominated_after = integer_at_least(s, "reduction.dominated_after", 0);
  return r;
}

bool share_incumbent(const Settings& s) { return s.boolean(kShareIncumbentKey); }
bool defer_seen_classes(const Settings& s) { return s.boolean("search.defer_seen_classes"); }

ClockSettings clock_settings(const Settings& s) {
  ClockSettings c;
  c.kind = choice<ClockKind>(s, "clock.kind",
                             {{"wall", ClockKind::kWall}, {"iterations", ClockKind::kIterations}});
  c.seconds_per_iteration = positive(s, "clock.seconds_per_iteration");
  // The simulated clock counts in nanoseconds: a microsecond is the least step it keeps exact.
  if (!(c.seconds_per_iteration >= 1e-6 && std::isfinite(c.seconds_per_iteration)))
    refuse(s, "clock.seconds_per_iteration", "must be finite and at least 1e-6 (seconds)");
  return c;
}

}  // namespace disco
