#include "search/search_record.h"

#include "core/model/objective.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/model/lower_bound.h"
#include "core/model/solution.h"
#include "core/util/errors.h"

namespace disco {

using json = nlohmann::json;

bool is_final(const StartOutcome& o, const SceneJob& job) {
  if (o.status == StartStatus::kInterrupted) return false;
  if (o.status == StartStatus::kTimeLimit)
    return o.budget_source == BudgetSource::kStart && o.budget == job.start_time_limit;
  return true;
}

bool SearchRecord::final_outcome(int s, const StartOutcome& o) const {
  return is_final(o, plan_.scenes[s]) &&
         (o.stage != Stage::kRefine || !stale_refines_.count({s, o.start}));
}

void SearchRecord::note_refine(int s, const StartOutcome& o) {
  if (o.stage != Stage::kRefine) return;
  const auto screen = screens_.find({s, o.start});
  if (screen == screens_.end() || !is_final(screen->second, plan_.scenes[s]))
    stale_refines_.insert({s, o.start});
  else
    stale_refines_.erase({s, o.start});
}

SearchRecord::SearchRecord(const SearchPlan& plan, const std::string& out_dir, std::uint64_t seed,
                           bool resumed, bool shared)
    : plan_(plan), out_(out_dir), seed_(seed), shared_(shared), best_(plan.scenes.size()) {
  const std::string runs = out_dir + "/runs.jsonl";
  std::error_code ec;
  std::filesystem::create_directories(out_dir + "/best/.final", ec);
  if (ec) throw InputError(out_dir + "/best/.final: cannot create the directory (" + ec.message() + ")");
  if (resumed) read_earlier(runs, seed);
  finished_ = static_cast<int>(done_.size() + screened_done_.size());
  runs_ = std::fopen(runs.c_str(), resumed ? "a" : "w");
  if (runs_ == nullptr) throw InputError(runs + ": cannot open for writing");
  for (const std::string& line : recovered_) append(line);
  recovered_.clear();
}

SearchRecord::~SearchRecord() {
  if (runs_ != nullptr) std::fclose(runs_);
}

int SearchRecord::scene_index(const std::string& name) const {
  for (std::size_t s = 0; s < plan_.scenes.size(); ++s)
    if (plan_.scenes[s].scene.name == name) return static_cast<int>(s);
  return -1;
}

void SearchRecord::record(const StartOutcome& o, const json* solution, double now, double scene_started) {
  const json line = o.to_json();
  const int s = scene_index(o.scene);
  if (o.stage == Stage::kScreen) {  // its file first, as for a best (see there)
    if (solution != nullptr) {
      json doc = *solution;
      doc["provenance"]["run"] = line;
      const std::string file = screened_file(o.scene, o.start);
      std::error_code ec;
      std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
      if (ec) throw InputError(file + ": cannot create its directory (" + ec.message() + ")");
      write_json_file(file, doc);
    }
    if (s >= 0) screens_[{s, o.start}] = o;
  } else {
    record_result(o, solution, line, s, now, scene_started);
  }
  append(line.dump());
  if (s >= 0 && final_outcome(s, o)) {
    ++finished_;
  } else {
    ++cut_short_;
  }
  if (o.status == StartStatus::kInterrupted) ++interrupted_;
}

// A full start's or a refine's outcome: the scene's standing and its files.
void SearchRecord::record_result(const StartOutcome& o, const json* solution, const json& line,
                                 int s, double now, double scene_started) {
  // The solution first, then the line: a kill between the two leaves a best/SCENE.json whose
  // provenance.run is missing from runs.jsonl, and --resume appends it (read_earlier). The
  // other order would leave a recorded best without its file.
  const Standing st = update(s, o, now, scene_started);
  if (solution != nullptr && (st.best || st.final_best)) {
    json doc = *solution;
    doc["provenance"]["run"] = line;
    if (st.final_best) write_json_file(final_file(o.scene), doc);
    if (st.best) write_json_file(best_file(o.scene), doc);
  }
  if (st.back_to_final) {
    std::ifstream in(final_file(o.scene));
    const json doc = in ? json::parse(in, nullptr, false) : json();
    if (doc.is_object()) {
      write_json_file(best_file(o.scene), doc);
    } else {
      spdlog::warn("{}: start {} ended above its earlier best, and {} (the best final start's "
                   "file) cannot be read, so best/{}.json still holds start {}'s earlier point",
                   o.scene, o.start, final_file(o.scene), o.scene, o.start);
    }
  }
}

std::string SearchRecord::best_file(const std::string& scene) const { return out_ + "/best/" + scene + ".json"; }
std::string SearchRecord::screened_file(const std::string& scene, int start) const {
  return out_ + "/screened/" + scene + "/" + std::to_string(start) + ".json";
}

std::set<int> SearchRecord::ran(int s) const {
  std::set<int> out;
  for (auto it = outcomes_.lower_bound({s, 0}); it != outcomes_.end() && it->first.first == s; ++it)
    out.insert(it->first.second);
  return out;
}

std::map<int, StartOutcome> SearchRecord::screened(int s) const {
  std::map<int, StartOutcome> out;
  for (auto it = screens_.lower_bound({s, 0}); it != screens_.end() && it->first.first == s; ++it)
    out.emplace(it->first.second, it->second);
  return out;
}
std::string SearchRecord::final_file(const std::string& scene) const {
  return out_ + "/best/.final/" + scene + ".json";
}

void SearchRecord::append(const std::string& line) {
  std::fputs((line + "\n").c_str(), runs_);
  std::fflush(runs_);
  ::fsync(fileno(runs_));  // a kill (or a crash) loses no finished start
}

// Keeps `o` as its start's outcome (it replaces an earlier one: a start cut short and run
// again), recounts the scene, and says where `o` now stands (Standing).
SearchRecord::Standing SearchRecord::update(int s, const StartOutcome& o, double now,
                                            double scene_started) {
  if (s < 0) return {};
  Best& b = best_[s];
  b.last_s = now;
  outcomes_[{s, o.start}] = o;
  note_refine(s, o);
  b.run = b.solved = b.cut_short = 0;
  // The least J, ties to the lower start (map order): of all outcomes, and of the final ones.
  const StartOutcome* least = nullptr;
  const StartOutcome* least_final = nullptr;
  for (auto it = outcomes_.lower_bound({s, 0}); it != outcomes_.end() && it->first.first == s; ++it) {
    const StartOutcome& x = it->second;
    const bool is_last = final_outcome(s, x);
    ++b.run;
    if (!is_last) ++b.cut_short;
    if (!x.certified()) continue;
    ++b.solved;
    if (least == nullptr || x.value < least->value) least = &x;
    if (is_last && (least_final == nullptr || x.value < least_final->value)) least_final = &x;
  }
  Standing st;
  st.final_best = least_final != nullptr && least_final->start == o.start;
  // Scene times count from the hand-out of the scene's first start, to the
  // moment a rank found the point: the start was handed out o.seconds ago
  // and found it its own time_to_first_feasible / time_to_best after that.
  const double handed = now - o.seconds - std::max(0.0, scene_started);
  if (o.certified()) {
    const double feasible = handed + std::max(0.0, o.time_to_first_feasible);
    if (b.first_feasible_s < 0 || feasible < b.first_feasible_s)
      b.first_feasible_s = std::max(0.0, feasible);
  }
  if (least == nullptr) return st;
  if (least->start != o.start && b.start == o.start) {  // o replaced the best with a worse point
    if (least == least_final) {
      st.back_to_final = true;
    } else {  // a start cut short and not run again yet: its point is in no file
      spdlog::warn("{}: start {} ended above its earlier best, so start {} is now the best, but "
                   "best/{}.json still holds start {}'s earlier point", o.scene, o.start,
                   least->start, o.scene, o.start);
    }
  }
  b.start = least->start;
  b.value = least->value;
  b.outcome = *least;
  if (least->start != o.start || !o.certified()) return st;
  b.best_s = std::max(0.0, handed + std::max(0.0, o.time_to_best));
  st.best = true;
  return st;
}

// The starts runs.jsonl holds a final outcome for (--resume skips them). A start's later
// line replaces its earlier ones; a start cut short keeps its best so far in the scene's
// best until it runs again.
void SearchRecord::read_earlier(const std::string& path, std::uint64_t seed) {
  std::ifstream in(path);
  std::string line;
  int bad = 0;
  std::set<std::string> lines;  // as to_json() writes them, so that equal lines compare equal
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    try {
      const StartOutcome o = StartOutcome::from_json(json::parse(line));
      const int s = scene_index(o.scene);
      if (s < 0 || o.start >= plan_.scenes[s].starts || o.seed != seed) continue;
      if (o.stage == Stage::kScreen) {  // a later line replaces an earlier one here too
        screens_[{s, o.start}] = o;
        continue;
      }
      update(s, o, 0.0, 0.0);
      lines.insert(o.to_json().dump());
    } catch (const std::exception&) {
      ++bad;  // e.g. a line cut short by a kill
    }
  }
  recover_lines(path, seed, lines);
  int again = 0;
  for (const auto& [key, o] : outcomes_) {
    if (final_outcome(key.first, o)) {
      done_.insert(key);
    } else {
      ++again;
    }
  }
  for (const auto& [key, o] : screens_) {
    if (is_final(o, plan_.scenes[key.first])) {
      screened_done_.insert(key);
    } else {
      ++again;
    }
  }
  // Times of an earlier run are not comparable with this one's clock.
  for (auto& b : best_) b.first_feasible_s = b.best_s = b.start >= 0 ? 0.0 : -1.0;
  if (bad > 0) spdlog::warn("{}: skipped {} unreadable line(s)", path, bad);
  resumed_ = static_cast<int>(done_.size() + screened_done_.size());
  spdlog::info("resume: {} start(s) already in {}{}", resumed_, path,
               again > 0 ? fmt::format("; {} not final there (cut short, or refines of screens cut or left out) run again", again) : "");
}

// A best/SCENE.json is written before its start's line (record()), so a kill between the two
// leaves a file whose provenance.run is in no line: that start ended, and its line is
// appended now (by the constructor, once runs.jsonl is open). Then every scene's recorded
// best must be the start its file holds; a mismatch is only warned of (it needs a file
// written before this order, or by hand).
void SearchRecord::recover_lines(const std::string& path, std::uint64_t seed,
                                 const std::set<std::string>& lines) {
  for (std::size_t s = 0; s < plan_.scenes.size(); ++s) {
    const std::string file = best_file(plan_.scenes[s].scene.name);
    std::ifstream in(file);
    const json doc = in ? json::parse(in, nullptr, false) : json();
    if (in && doc.is_discarded()) spdlog::warn("resume: {}: not valid JSON", file);
    const json prov = doc.is_object() ? doc.value("provenance", json::object()) : json::object();
    if (prov.contains("run") && prov["run"].is_object()) {
      try {
        const StartOutcome o = StartOutcome::from_json(prov["run"]);
        const std::string text = o.to_json().dump();
        if (scene_index(o.scene) == static_cast<int>(s) && o.seed == seed &&
            o.start < plan_.scenes[s].starts && lines.count(text) == 0) {
          spdlog::warn("resume: {} start {} ended, but a kill came before its line reached {}; "
                       "the line is taken from {} (provenance.run)", o.scene, o.start, path, file);
          update(static_cast<int>(s), o, 0.0, 0.0);
          recovered_.push_back(text);
        }
      } catch (const std::exception& e) {
        spdlog::warn("resume: {}: provenance.run unreadable ({})", file, e.what());
      }
    }
    const Best& b = best_[s];
    // The file's J: its objective's value (files of an older disco: T_f, objective time).
    const json held = !doc.is_object()                                   ? json()
                      : doc.contains("objective") && doc["objective"].is_object()
                          ? doc["objective"].value("value", json())
                          : doc.value("T_f", json());
    if (b.start >= 0 && !(held == json(b.value) && prov.value("start", -1) == b.start))
      spdlog::warn("resume: {}'s best in {} is start {} ({} {:.6f}), but {} does not hold it",
                   plan_.scenes[s].scene.name, path, b.start,
                   to_string(plan_.scenes[s].scene.objective.kind), b.value, file);
  }
}

std::optional<double> SearchRecord::best_value(int s) const {
  if (best_[s].start < 0) return std::nullopt;
  return best_[s].value;
}

bool SearchRecord::all_solved() const {
  return std::all_of(best_.begin(), best_.end(), [](const Best& b) { return b.start >= 0; });
}

std::string SearchRecord::best_summary(int s) const {
  auto one = [&](std::size_t k) {
    const Best& b = best_[k];
    return plan_.scenes[k].scene.name + " " +
           (b.start >= 0 ? fmt::format("{:.6f}", b.value) : std::string("-"));
  };
  if (best_.size() > 4) {
    if (s >= 0) return one(static_cast<std::size_t>(s));
    const auto solved = std::count_if(best_.begin(), best_.end(), [](const Best& b) { return b.start >= 0; });
    return fmt::format("{} of {} scenes solved", solved, best_.size());
  }
  std::string out;
  for (std::size_t k = 0; k < best_.size(); ++k) out += (k ? ", " : "") + one(k);
  return out;
}

void SearchRecord::write_best(const TaskQueue& queue, double now, bool interrupted) const {
  json scenes = json::object();
  for (std::size_t s = 0; s < plan_.scenes.size(); ++s) {
    const Best& b = best_[s];
    const double started = queue.scene_started(static_cast<int>(s));
    json j = {{"starts", plan_.scenes[s].starts},
              {"starts_run", b.run},
              {"starts_solved", b.solved},
              {"starts_cut_short", b.cut_short},
              {"starts_screened", screened(static_cast<int>(s)).size()},
              {"time_to_first_feasible_s", b.first_feasible_s >= 0 ? json(b.first_feasible_s) : json(nullptr)},
              {"time_to_best_s", b.best_s >= 0 ? json(b.best_s) : json(nullptr)},
              {"started_s", started >= 0 ? json(started) : json(nullptr)},
              {"wall_s", started >= 0 ? json(b.last_s - started) : json(nullptr)},
              {"time_limit_s", plan_.scenes[s].time_limit},
              {"time_limit_reached", queue.scene_time_limited(static_cast<int>(s))}};
    const Scene& scene = plan_.scenes[s].scene;
    const auto lb = scene_lower_bound(scene), ref = scene_reference_time(scene);
    j["lower_bound"] = lb && std::isfinite(*lb) ? json(*lb) : json(nullptr);
    j["reference_time"] = ref ? json(*ref) : json(nullptr);
    j["objective"] = to_string(scene.objective.kind);
    j["objective_unit"] = objective_unit(scene.objective.kind);
    if (b.start >= 0) {
      j["value"] = b.value;
      j["T_f"] = b.outcome.T_f;
      j["start"] = b.start;
      j["description"] = b.outcome.description;
      j["certificate"] = {{"max_violation", b.outcome.max_violation},
                          {"max_complementarity", b.outcome.max_complementarity}};
      j["solution"] = "best/" + scene.name + ".json";
    } else {
      j["value"] = nullptr;
      j["T_f"] = nullptr;
    }
    scenes[scene.name] = j;
  }
  const json doc = {{"seed", seed_},
                    {"mode", shared_ ? "shared" : "deterministic"},
                    {"elapsed_s", now},
                    {"starts_total", queue.total()},
                    {"starts_finished", finished_},
                    {"interrupted", interrupted},
                    {"time_limit_s", queue.time_limit()},
                    {"time_limit_reached", queue.time_limited()},
                    {"scenes", scenes}};
  write_json_file(out_ + "/best.json", doc);
}

}  // namespace disco
