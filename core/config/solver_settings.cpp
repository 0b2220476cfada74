#include "core/config/solver_settings.h"

#include "core/util/errors.h"

namespace disco {

std::vector<IpoptOption> ipopt_options(const Settings& settings) {
  std::vector<IpoptOption> out;
  for (const auto& e : settings.section("ipopt"))
    out.push_back({e.name, e.value, e.line > 0 ? settings.source() + ":" + std::to_string(e.line)
                                               : std::string("--set")});
  return out;
}

namespace {

double positive(const Settings& s, const std::string& key) {
  const double v = s.number(key);
  if (!(v > 0)) throw InputError(s.where(key) + ": key '" + key + "': must be positive");
  return v;
}

}  // namespace

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
                                               {"relaxed", ElasticFormulation::kRelaxed}});
  e.zeta = positive(s, "elastic.zeta");
  e.zeta_factor = positive(s, "elastic.zeta_factor");
  if (e.zeta_factor <= 1)
    throw InputError(s.where("elastic.zeta_factor") + ": key 'elastic.zeta_factor': must exceed 1");
  e.zeta_max = positive(s, "elastic.zeta_max");
  e.stall_change = s.number("elastic.stall_change");
  e.complementarity_tol = positive(s, "elastic.complementarity_tolerance");
  e.violation_tol = positive(s, "elastic.violation_tolerance");
  e.polish = s.boolean("elastic.polish");
  e.sigma = positive(s, "elastic.sigma");
  e.sigma_factor = positive(s, "elastic.sigma_factor");
  if (e.sigma_factor >= 1)
    throw InputError(s.where("elastic.sigma_factor") + ": key 'elastic.sigma_factor': must be below 1");
  e.sigma_min = positive(s, "elastic.sigma_min");
  e.barrier_ratio = positive(s, "elastic.barrier_ratio");
  if (e.formulation == ElasticFormulation::kRelaxed && !e.polish)
    throw InputError(s.where("elastic.polish") +
                     ": key 'elastic.polish': formulation relaxed needs polish: its homotopy "
                     "ends where the relaxation stops holding, and polish fixes the branch");
  return e;
}

std::string default_settings_path() { return std::string(DISCO_SOURCE_DIR) + "/configs/disco.yaml"; }

}  // namespace disco
