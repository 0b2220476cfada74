#include "search/search_plan.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "core/config/yaml_nodes.h"
#include "core/model/scene_yaml.h"
#include "core/util/errors.h"
#include "search/trajectory.h"

namespace disco {
namespace {

[[noreturn]] void fail(const std::string& source, const YAML::Node& n, const std::string& key,
                       const std::string& what) {
  throw InputError(located_message(source, yaml::line_of(n), key, what));
}

int read_int(const std::string& source, const YAML::Node& n, const std::string& key, int min) {
  int v = 0;
  if (!n.IsScalar() || !YAML::convert<int>::decode(n, v))
    fail(source, n, key, "must be an integer (got " + yaml::describe(n) + ")");
  if (v < min) fail(source, n, key, "must be >= " + std::to_string(min));
  return v;
}

double read_seconds(const std::string& source, const YAML::Node& n, const std::string& key) {
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v))
    fail(source, n, key, "must be a number (got " + yaml::describe(n) + ")");
  if (v < 0) fail(source, n, key, "must be >= 0");
  return v;
}

void check_keys(const std::string& source, const YAML::Node& map, const std::string& where,
                const std::set<std::string>& allowed) {
  for (const auto& kv : map) {
    const std::string k = kv.first.as<std::string>();
    if (!allowed.count(k)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(source, kv.first, where.empty() ? k : where + "." + k,
           "unknown key (allowed: " + list + ")");
    }
  }
}

}  // namespace

int SearchPlan::total_starts() const {
  int n = 0;
  for (const auto& s : scenes) n += s.starts;
  return n;
}

SearchPlan load_search_plan(const std::vector<std::string>& configs, int starts_override,
                            int default_starts, const std::vector<std::string>& scene_overrides) {
  SearchPlan plan;
  auto add = [&](const std::string& path, std::vector<std::string> sets, int starts,
                 double time_limit, double start_time_limit) {
    sets.insert(sets.end(), scene_overrides.begin(), scene_overrides.end());
    SceneJob job{load_scene(path, sets), sets, starts_override > 0 ? starts_override : starts,
                 time_limit, start_time_limit, {}};
    plan.scenes.push_back(std::move(job));
  };
  for (const auto& path : configs) {
    const YAML::Node root = yaml::load(yaml::read_file(path, "config file"), path);
    if (!root.IsMap() || !root["benchmark"]) {
      add(path, {}, default_starts, 0.0, 0.0);
      continue;
    }
    check_keys(path, root, "",
               {"benchmark", "description", "starts", "time_limit", "start_time_limit", "scenes"});
    const int starts = root["starts"] ? read_int(path, root["starts"], "starts", 1) : default_starts;
    auto seconds_or = [&](const YAML::Node& n, const std::string& key, double fallback) {
      return n ? read_seconds(path, n, key) : fallback;
    };
    const double limit = seconds_or(root["time_limit"], "time_limit", 0.0);
    const double start_limit = seconds_or(root["start_time_limit"], "start_time_limit", 0.0);
    const YAML::Node scenes = root["scenes"];
    if (!scenes || !scenes.IsSequence() || scenes.size() == 0)
      fail(path, scenes ? scenes : root, "scenes", "must be a non-empty list of scene entries");
    const auto dir = std::filesystem::path(path).parent_path();
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      const YAML::Node e = scenes[k];
      const std::string where = "scenes[" + std::to_string(k) + "]";
      if (!e.IsMap()) fail(path, e, where, "must be a mapping with a 'file' key");
      check_keys(path, e, where, {"file", "starts", "time_limit", "start_time_limit", "set"});
      if (!e["file"] || !e["file"].IsScalar()) fail(path, e, where + ".file", "missing scene file");
      std::vector<std::string> sets;
      if (e["set"]) {
        if (!e["set"].IsSequence()) fail(path, e["set"], where + ".set", "must be a list of KEY=VALUE");
        for (const auto& s : e["set"]) sets.push_back(s.as<std::string>());
      }
      add((dir / e["file"].as<std::string>()).string(), sets,
          e["starts"] ? read_int(path, e["starts"], where + ".starts", 1) : starts,
          seconds_or(e["time_limit"], where + ".time_limit", limit),
          seconds_or(e["start_time_limit"], where + ".start_time_limit", start_limit));
    }
  }
  std::set<std::string> names;
  for (const auto& job : plan.scenes)
    if (!names.insert(job.scene.name).second)
      throw InputError(job.scene.source + ": key 'scenario': the name '" + job.scene.name +
                       "' appears twice in this search; scene names must be unique");
  return plan;
}

void attach_guesses(SearchPlan& plan, const std::vector<std::string>& files) {
  for (const std::string& file : files) {
    const nlohmann::json doc = read_guess_document(file);
    const std::string scenario =
        doc.is_object() && doc.contains("scenario") && doc["scenario"].is_string()
            ? doc["scenario"].get<std::string>()
            : std::string();
    SceneJob* job = nullptr;
    std::string names;
    for (SceneJob& j : plan.scenes) {
      names += (names.empty() ? "" : ", ") + j.scene.name;
      if (j.scene.name == scenario) job = &j;
    }
    if (job == nullptr && plan.scenes.size() == 1) job = &plan.scenes.front();
    if (job == nullptr)
      throw InputError("--guess " + file + ": its scenario '" + printable(scenario, kEchoLimit) +
                       "' is not a scene of this search (" + names + ")");
    if (!job->guess.empty())
      throw InputError("--guess " + file + ": scene '" + job->scene.name + "' already has one (" +
                       job->guess.source + ")");
    job->guess = trajectory_from_solution(doc, job->scene, file);
  }
}

}  // namespace disco
