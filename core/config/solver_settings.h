// disco — typed solver settings read from a Settings document
// (configs/disco.yaml plus --set overrides): Ipopt's options and the elastic
// mode's parameters. Values out of range are InputErrors naming the key.
#pragma once

#include <vector>

#include "core/config/settings.h"
#include "core/elastic/elastic_solver.h"
#include "core/ipopt/ipopt_solver.h"
#include "core/model/adaptive.h"

namespace disco {

std::vector<IpoptOption> ipopt_options(const Settings& settings);  // the `ipopt:` section
ElasticSettings elastic_settings(const Settings& settings);        // the `elastic:` section
ModelOptions model_options(const Settings& settings);              // the `model:` section

// Path of the default settings file shipped with disco (configs/disco.yaml).
std::string default_settings_path();

}  // namespace disco
