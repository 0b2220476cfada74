#include "search/run_manifest.h"

#include <spdlog/fmt/chrono.h>
#include <spdlog/spdlog.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "core/model/solution.h"
#include "core/util/clock.h"
#include "core/util/errors.h"
#include "core/util/provenance.h"

namespace disco {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kFormat = "disco-search-manifest";
// What disco itself writes into a search directory (--force removes these, and only these).
const char* const kOwnEntries[] = {"manifest.json", "runs.jsonl", "best.json", "best", "screened",
                                   "report"};

std::string short_hash(const json& h) {
  const std::string s = h.is_string() ? h.get<std::string>() : std::string("none");
  return s.size() > 12 ? s.substr(0, 12) + "…" : s;
}

std::string list_text(const json& list) {
  std::string out;
  for (const auto& v : list) out += (out.empty() ? "" : ", ") + v.get<std::string>();
  return "[" + out + "]";
}

std::string value_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// Settings values are text as written: "10", "10.0" and "1e1" are the same number.
bool same_value(const std::string& a, const std::string& b) {
  if (a == b) return true;
  try {
    std::size_t na = 0, nb = 0;
    const double x = std::stod(a, &na), y = std::stod(b, &nb);
    return na == a.size() && nb == b.size() && x == y;
  } catch (const std::exception&) {
    return false;
  }
}

void differences_in_scenes(const json& was, const json& is, std::vector<std::string>& out) {
  std::map<std::string, json> before, after;
  for (const auto& s : was) before[s.at("name").get<std::string>()] = s;
  for (const auto& s : is) after[s.at("name").get<std::string>()] = s;
  for (const auto& [name, s] : before)
    if (!after.count(name)) out.push_back("scene '" + name + "': in the earlier run, not in this one");
  for (const auto& [name, s] : after) {
    const auto it = before.find(name);
    if (it == before.end()) {
      out.push_back("scene '" + name + "': in this run, not in the earlier one");
      continue;
    }
    const json& b = it->second;
    if (b.at("sha256") != s.at("sha256"))
      out.push_back("scene '" + name + "': file content differs (" + value_text(b.at("file")) +
                    " sha256 " + short_hash(b.at("sha256")) + " there, " + value_text(s.at("file")) +
                    " sha256 " + short_hash(s.at("sha256")) + " here)");
    const json none;
    const json& g0 = b.contains("guess") ? b["guess"] : none;
    const json& g1 = s.contains("guess") ? s["guess"] : none;
    auto guess_text = [](const json& g) {
      return g.is_null() ? std::string("none")
                         : value_text(g.at("file")) + " sha256 " + short_hash(g.at("sha256"));
    };
    if ((g0.is_null() ? json() : g0.at("sha256")) != (g1.is_null() ? json() : g1.at("sha256")))
      out.push_back("scene '" + name + "': --guess " + guess_text(g0) + " there, " + guess_text(g1) +
                    " here");
    if (b.at("overrides") != s.at("overrides"))
      out.push_back("scene '" + name + "': overrides " + list_text(b.at("overrides")) + " there, " +
                    list_text(s.at("overrides")) + " here");
  }
}

void differences_in_settings(const json& was, const json& is, std::vector<std::string>& out) {
  const json& b = was.at("values");
  const json& a = is.at("values");
  std::set<std::string> keys;
  for (const auto& [k, v] : b.items()) keys.insert(k);
  for (const auto& [k, v] : a.items()) keys.insert(k);
  for (const auto& k : keys) {
    const std::string there = b.contains(k) ? value_text(b[k]) : "unset";
    const std::string here = a.contains(k) ? value_text(a[k]) : "unset";
    if (!same_value(there, here)) out.push_back("setting " + k + ": " + there + " there, " + here + " here");
  }
}

std::vector<std::string> entries_of(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) names.push_back(e.path().filename().string());
  if (ec) throw InputError("--out " + dir.string() + ": cannot read the directory (" + ec.message() + ")");
  std::sort(names.begin(), names.end());
  return names;
}

std::string names_text(const std::vector<std::string>& names) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(names.size(), 6);
  for (std::size_t k = 0; k < shown; ++k) out += (k ? ", " : "") + names[k];
  if (names.size() > shown) out += fmt::format(" and {} more", names.size() - shown);
  return out;
}

json read_manifest(const fs::path& path) {
  std::ifstream in(path);
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path.string() + ": not a readable manifest (" + e.what() + ")");
  }
}

}  // namespace

json search_manifest(const SearchPlan& plan, const Settings& settings, const ManifestInputs& in) {
  json configs = json::array();
  for (const auto& c : in.configs) configs.push_back({{"file", c}, {"sha256", file_sha256(c)}});
  json scenes = json::array();
  for (const auto& job : plan.scenes)
    scenes.push_back({{"name", job.scene.name},
                      {"file", job.scene.source},
                      {"sha256", file_sha256(job.scene.source)},
                      {"overrides", job.overrides},
                      {"starts", job.starts},
                      {"guess", job.guess.empty() ? json(nullptr)
                                                  : json{{"file", job.guess.source},
                                                         {"sha256", file_sha256(job.guess.source)}}}});
  json values = json::object();
  for (const auto& [k, v] : settings.values()) values[k] = v;
  const std::time_t now = calendar_now();
  return {{"format", kFormat},
          {"format_version", 1},
          {"mode", "search"},
          {"version", disco_version()},
          {"configs", configs},
          {"scenes", scenes},
          {"overrides", in.overrides},
          {"seed", in.seed},
          {"starts", in.starts},
          {"time_limit", in.time_limit},
          {"settings",
           {{"file", settings.source()},
            {"sha256", sha256_hex(settings.canonical_text())},
            {"values", values}}},
          {"invocations", json::array({{{"version", disco_version()},
                                        {"utc", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(now))},
                                        {"resume", in.resume},
                                        {"starts", in.starts},
                                        {"time_limit", in.time_limit}}})}};
}

std::vector<std::string> manifest_differences(const json& earlier, const json& now) {
  std::vector<std::string> out;
  if (earlier.value("format", "") != kFormat || !earlier.contains("scenes") ||
      !earlier.contains("settings") || !earlier.contains("seed")) {
    out.push_back("the earlier manifest is not a disco search manifest");
    return out;
  }
  if (earlier.at("seed") != now.at("seed"))
    out.push_back("seed: " + earlier.at("seed").dump() + " there, " + now.at("seed").dump() + " here");
  differences_in_scenes(earlier.at("scenes"), now.at("scenes"), out);
  differences_in_settings(earlier.at("settings"), now.at("settings"), out);
  return out;
}

int prepare_out_dir(const std::string& dir, OutDirMode mode, const json& manifest) {
  const fs::path d(dir);
  std::error_code ec;
  if (fs::exists(d, ec) && !fs::is_directory(d, ec))
    throw InputError("--out " + dir + ": exists and is not a directory");
  const std::vector<std::string> held = fs::exists(d, ec) ? entries_of(d) : std::vector<std::string>{};
  json written = manifest;
  int earlier_invocations = 0;
  if (mode == OutDirMode::kForce) {
    for (const char* name : kOwnEntries) fs::remove_all(d / name, ec);
  } else if (mode == OutDirMode::kFresh && !held.empty()) {
    throw InputError("--out " + dir + ": the directory is not empty (it holds " + names_text(held) +
                     "); add --resume to continue the run it holds, --force to replace it, or "
                     "choose another --out");
  } else if (mode == OutDirMode::kResume && !held.empty()) {
    const fs::path path = d / "manifest.json";
    if (!fs::exists(path, ec))
      throw InputError("--resume: " + path.string() + " is missing, so nothing says which run " + dir +
                       " holds (" + names_text(held) +
                       "); use --force to replace it, or choose another --out");
    const json earlier = read_manifest(path);
    const std::vector<std::string> diff = manifest_differences(earlier, manifest);
    if (!diff.empty()) {
      std::string text;
      for (const auto& line : diff) text += "\n  " + line;
      throw InputError("--resume: " + dir + " holds a different run (" + path.string() +
                       " does not match this command):" + text +
                       "\nresume with the earlier command, use --force to replace the run, or "
                       "choose another --out");
    }
    if (earlier.value("version", "") != manifest.at("version").get<std::string>())
      spdlog::warn("resume: {} was made by disco {}; this is disco {}", dir,
                   earlier.value("version", "?"), manifest.at("version").get<std::string>());
    json invocations = earlier.value("invocations", json::array());
    earlier_invocations = static_cast<int>(invocations.size());
    for (const auto& i : manifest.at("invocations")) invocations.push_back(i);
    written["invocations"] = invocations;
  }
  fs::create_directories(d / "best", ec);
  if (ec) throw InputError("--out " + dir + ": cannot create the directory (" + ec.message() + ")");
  write_json_file((d / "manifest.json").string(), written);
  return earlier_invocations;
}

}  // namespace disco
