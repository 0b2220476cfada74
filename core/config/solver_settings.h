// disco — typed solver settings read from a Settings document
// (configs/disco.yaml plus --set overrides): Ipopt's options and the elastic
// mode's parameters. Values out of range are InputErrors naming the key.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/config/settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/model_plan.h"
#include "core/util/errors.h"

namespace disco {

std::vector<IpoptOption> ipopt_options(const Settings& settings);  // the `ipopt:` section
ElasticSettings elastic_settings(const Settings& settings);        // the `elastic:` section
ModelOptions model_options(const Settings& settings);              // the `model:` section

// Path of the default settings file shipped with disco (configs/disco.yaml).
std::string default_settings_path();

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
