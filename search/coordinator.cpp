#include "search/coordinator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <cstdio>
#include <fstream>

#include "core/util/interrupt.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

using json = nlohmann::json;

// "solved T_f 2.294182", "time limit (search, 20 s): T_f 2.380710 so far",
// "interrupted: no point yet", "infeasible"; for another objective "solved J 3.5 (T_f 2 s)".
std::string outcome_words(const StartOutcome& o) {
  const std::string value = o.value == o.T_f ? fmt::format("T_f {:.6f}", o.T_f)
                                             : fmt::format("J {:.6g} (T_f {:.6f} s)", o.value, o.T_f);
  const std::string so_far = o.certified() ? value + " so far" : std::string("no point yet");
  switch (o.status) {
    case StartStatus::kSolved: return "solved " + value;
    case StartStatus::kTimeLimit:
      return fmt::format("time limit ({}, {:.0f} s): {}", to_string(o.budget_source), o.budget, so_far);
    case StartStatus::kInterrupted: return "interrupted: " + so_far;
    case StartStatus::kDominated:
      return fmt::format("dominated at {} (another start reached {:.6f})", value, o.incumbent);
    default: return to_string(o.status);
  }
}

// A screen's outcome as the refine choices see it (its class key left out unless `with_class`).
Screened screened_of(int k, const StartOutcome& o, bool with_class) {
  const std::string key =
      with_class && o.best_class.is_object() ? o.best_class.value("key", "") : std::string();
  return {k, o.certified() ? o.value : std::numeric_limits<double>::quiet_NaN(), key};
}

std::string clock_text(double s) {
  const int t = static_cast<int>(s + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02d:%02d:%02d", t / 3600, t / 60 % 60, t % 60);
  return buf;
}

}  // namespace

Coordinator::Coordinator(const SearchPlan& plan, const std::string& out_dir, std::uint64_t seed,
                         double time_limit, bool resumed, bool share_incumbent,
                         const GuessClassFunction& guess_class, const ScreenSettings& screen)
    : plan_(plan),
      share_(share_incumbent),
      t0_(Clock::now()),
      record_(plan, out_dir, seed, resumed, share_incumbent),
      queue_(plan, time_limit, record_.done(), guess_class, screen, record_.screened_done()),
      incumbent_(plan.scenes.size(), kInf),
      improved_(plan.scenes.size(), false),
      screen_(screen),
      early_(plan.scenes.size()),
      refines_(plan.scenes.size()) {
  for (std::size_t s = 0; s < plan.scenes.size(); ++s)  // a resumed run's bests
    if (const auto b = record_.best_value(static_cast<int>(s))) lower_incumbent(static_cast<int>(s), *b);
  advance_stages(seconds());  // a resumed run's scenes whose screens all ended
  record_.write_best(queue_, seconds(), interrupt_requested());
}

std::optional<Task> Coordinator::refine_task(int s, int k) const {
  if (screen_.refine_from == RefineFrom::kStart || !certified_screen(s, k)) {  // its own guess
    Task t;
    t.scene = s;
    t.start = k;
    t.stage = Stage::kRefine;
    return t;
  }
  const std::string& name = plan_.scenes[s].scene.name;
  const std::string file = record_.screened_file(name, k);
  std::ifstream in(file);
  json doc = in ? json::parse(in, nullptr, false) : json();
  if (!doc.is_object()) {
    spdlog::warn("{}: start {}'s screened answer {} cannot be read: it is not refined", name, k, file);
    return std::nullopt;
  }
  Task t;
  t.scene = s;
  t.start = k;
  t.stage = Stage::kRefine;
  t.guess = std::move(doc);
  return t;
}

void Coordinator::add_early_refines(int s) {
  const SceneJob& job = plan_.scenes[s];
  const std::map<int, StartOutcome> screens = record_.screened(s);
  std::vector<Screened> ended;
  for (const auto& [k, o] : screens)
    if (is_final(o, job)) ended.push_back(screened_of(k, o, false));
  for (int k : early_refine_choice(ended, job.starts, screen_.early_batch, screen_.tie)) {
    if (!early_[s].insert(k).second) continue;
    refines_[s].insert(k);
    const bool done = record_.done().count({s, k}) > 0;  // refined in an earlier run
    const double value = screens.at(k).value;
    spdlog::info("{}: early refine of start {} ({:.6f}: the best of screens {}-{}){}", job.scene.name, k,
                 value, k / screen_.early_batch * screen_.early_batch,
                 std::min(job.starts, (k / screen_.early_batch + 1) * screen_.early_batch) - 1,
                 done ? ", ended in an earlier run" : "");
    queue_.add_early_refine(s, done ? std::nullopt : refine_task(s, k));
  }
}

void Coordinator::advance_stages(double now) {
  if (!screen_.on()) return;
  for (std::size_t i = 0; i < plan_.scenes.size(); ++i) {
    const int s = static_cast<int>(i);
    if (queue_.refined(s)) continue;
    if (screen_.early_batch > 0) add_early_refines(s);
    if (queue_.screens_open(s, now)) continue;
    const std::string& name = plan_.scenes[i].scene.name;
    const std::map<int, StartOutcome> screens = record_.screened(s);
    const std::vector<Screened> screened = ranked_screens(s);
    std::vector<int> chosen = refine_choice(screened, screen_.refine_count, screen_.tie);
    // A resumed run also finishes the refines an earlier run chose under a time limit, from
    // the screens it had then: they are recorded, and one cut short runs again.
    for (int k : record_.ran(s))
      if (std::find(chosen.begin(), chosen.end(), k) == chosen.end()) chosen.push_back(k);
    // The starts refined early are not refined again.
    chosen.erase(std::remove_if(chosen.begin(), chosen.end(), [&](int k) { return early_[s].count(k) > 0; }),
                 chosen.end());
    std::vector<Task> tasks;
    std::string words;
    int in_place = 0;  // starts an earlier run ran unscreened in the time left: no screen of theirs runs
    for (int k : chosen) {
      refines_[s].insert(k);
      in_place += screens.count(k) == 0;
      const auto it = screens.find(k);
      words += fmt::format("{}{} ({})", words.empty() ? "" : ", ", k,
                           it == screens.end()            ? std::string("not screened")
                           : it->second.certified() ? fmt::format("{:.6f}", it->second.value)
                                                          : std::string("no certified screen"));
      if (record_.done().count({s, k})) continue;  // refined in an earlier run
      if (auto t = refine_task(s, k)) tasks.push_back(std::move(*t));
    }
    spdlog::info("{}: {} start(s) screened, refining {}{}", name, screened.size(),
                 chosen.empty() ? std::string(early_[s].empty() ? "none (no certified screen)" : "none more")
                                : words,
                 early_[s].empty() ? std::string() : fmt::format(" ({} early)", early_[s].size()));
    queue_.add_refines(s, static_cast<int>(chosen.size()) - in_place, tasks);
  }
}

bool Coordinator::certified_screen(int s, int k) const {
  const std::map<int, StartOutcome> screens = record_.screened(s);
  const auto it = screens.find(k);
  return it != screens.end() && it->second.certified();
}

std::vector<Screened> Coordinator::ranked_screens(int s) const {
  std::vector<Screened> out;
  for (const auto& [k, o] : record_.screened(s)) out.push_back(screened_of(k, o, true));
  return out;
}

bool Coordinator::add_fill_refine(double now) {
  int best_s = -1, best_k = -1;
  for (std::size_t i = 0; i < plan_.scenes.size(); ++i) {
    const int s = static_cast<int>(i);
    if (!queue_.may_fill(s, now) || (best_s >= 0 && refines_[s].size() >= refines_[best_s].size())) continue;
    for (int k : time_left_order(ranked_screens(s), queue_.start_order(s), screen_.tie))
      if (!refines_[s].count(k) && !record_.done().count({s, k})) {
        best_s = s;
        best_k = k;
        break;
      }
  }
  if (best_s < 0) return false;
  refines_[best_s].insert(best_k);
  const auto task = refine_task(best_s, best_k);
  if (!task) return add_fill_refine(now);  // its screened answer is missing (warned): the next
  const std::map<int, StartOutcome> screens = record_.screened(best_s);
  const auto screen = screens.find(best_k);
  const bool unscreened = screen == screens.end();
  if (unscreened || !screen->second.certified())
    spdlog::info("{}: time left: running start {} at full N_t from its own guess ({})",
                 plan_.scenes[best_s].scene.name, best_k,
                 unscreened ? "not screened" : "its screen has no certified point");
  else
    spdlog::info("{}: time left: refining start {} ({:.6f}), the next best screen", plan_.scenes[best_s].scene.name,
                 best_k, screen->second.value);
  queue_.add_refine(task, unscreened);
  return true;
}

void Coordinator::lower_incumbent(int s, double value) {
  if (!share_ || s < 0 || !(value < incumbent_[s])) return;
  incumbent_[s] = value;
  improved_[s] = true;
}

double Coordinator::incumbent(int scene) {
  std::lock_guard<std::mutex> lock(mutex_);
  return incumbent_[scene];
}

void Coordinator::progress(int scene, double value) {
  std::lock_guard<std::mutex> lock(mutex_);
  lower_incumbent(scene, value);
}

void Coordinator::on_progress(const std::string& body) {
  const json msg = json::parse(body);
  progress(msg.at("scene").get<int>(), msg.at("value").get<double>());
}

std::vector<Coordinator::Outgoing> Coordinator::take_outbox() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Outgoing> out;
  for (const auto& [task, r] : queue_.running())
    if (improved_[task.first] && r.rank != 0 && r.stage != Stage::kScreen)
      out.push_back({r.rank, MessageKind::kIncumbent,
                     json{{"scene", task.first}, {"value", incumbent_[task.first]}}.dump()});
  std::fill(improved_.begin(), improved_.end(), false);
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    if (const auto t = next_locked(*it)) {
      out.push_back({*it, MessageKind::kTask, t->to_json().dump()});
    } else if (interrupt_requested() || !queue_.refines_to_come(seconds())) {
      out.push_back({*it, MessageKind::kStop, ""});
    } else {
      ++it;
      continue;
    }
    it = waiting_.erase(it);
  }
  return out;
}

double Coordinator::seconds() const {
  return seconds_since(t0_);
}

int Coordinator::scene_index(const std::string& name) const {
  for (std::size_t s = 0; s < plan_.scenes.size(); ++s)
    if (plan_.scenes[s].scene.name == name) return static_cast<int>(s);
  return -1;
}

std::optional<Task> Coordinator::next(int rank) {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_locked(rank);
}

std::optional<Task> Coordinator::next_locked(int rank) {
  if (interrupt_requested()) return std::nullopt;
  const double now = seconds();
  advance_stages(now);
  auto task = queue_.next(rank, now);
  if (!task && add_fill_refine(now)) task = queue_.next(rank, now);
  if (task) task->incumbent = task->stage == Stage::kScreen ? kInf : incumbent_[task->scene];
  return task;
}

bool Coordinator::await_work() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (interrupt_requested() || !queue_.refines_to_come(seconds())) return false;
  recorded_.wait_for(lock, std::chrono::milliseconds(200));
  return true;
}

void Coordinator::record(StartOutcome o, const json* solution) {
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = seconds();
  o.finished_s = now;
  const int s = scene_index(o.scene);
  const bool screen = o.stage == Stage::kScreen;
  // A screen cut by the screening share did not meet the search's or the scene's limit.
  if (s >= 0)
    queue_.finished(s, o.start,
                    o.status == StartStatus::kTimeLimit && !screen ? o.budget_source : BudgetSource::kNone);
  record_.record(o, solution, now, s >= 0 ? queue_.scene_started(s) : 0.0);
  if (o.certified() && !screen) lower_incumbent(s, o.value);
  advance_stages(now);
  record_.write_best(queue_, now, interrupt_requested());
  spdlog::info("[{}/{}] {} start {}{} (rank {}): {} in {:.1f} s | best {} | {}", record_.finished(),
               queue_.total(), o.scene, o.start,
               o.stage == Stage::kFull ? std::string() : fmt::format(" {}", to_string(o.stage)), o.rank,
               outcome_words(o), o.seconds, record_.best_summary(s), clock_locked());
  recorded_.notify_all();
}

Coordinator::Reply Coordinator::on_result(int rank, const std::string& body) {
  const json msg = json::parse(body);
  if (msg.contains("outcome"))
    record(StartOutcome::from_json(msg["outcome"]), msg.contains("solution") ? &msg["solution"] : nullptr);
  std::lock_guard<std::mutex> lock(mutex_);
  if (const auto t = next_locked(rank)) return {MessageKind::kTask, t->to_json().dump()};
  if (!interrupt_requested() && queue_.refines_to_come(seconds())) {
    waiting_.insert(rank);
    return {MessageKind::kStop, "", true};
  }
  return {MessageKind::kStop, ""};
}

void Coordinator::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.finish();
  record_.write_best(queue_, seconds(), interrupt_requested());
}

bool Coordinator::all_solved() {
  std::lock_guard<std::mutex> lock(mutex_);
  return record_.all_solved();
}

Coordinator::Kept Coordinator::kept() {
  std::lock_guard<std::mutex> lock(mutex_);
  return {record_.finished(), record_.interrupted(), queue_.total(), record_.cut_short()};
}

std::string Coordinator::status_text() {
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = seconds();
  std::string running;
  for (const auto& [task, r] : queue_.running())
    running += fmt::format("{}{} #{}{} r{} {:.0f}s", running.empty() ? "" : ", ",
                           plan_.scenes[task.first].scene.name, task.second,
                           r.stage == Stage::kFull ? std::string() : fmt::format(" {}", to_string(r.stage)), r.rank,
                           now - r.handed_s);
  return fmt::format("[{}/{}] {} | best {} | running: {}", record_.finished(), queue_.total(),
                     clock_locked(), record_.best_summary(-1), running.empty() ? "-" : running);
}

// The ETA from the mean time per start run here, capped by the time limits left.
std::string Coordinator::clock_locked() const {
  const double elapsed = seconds();
  const int ran_now = record_.finished() - record_.resumed();
  double eta = ran_now > 0 ? elapsed / ran_now * (queue_.total() - record_.finished()) : 0.0;
  eta = std::min(eta, queue_.time_left(elapsed));
  return "elapsed " + clock_text(elapsed) + " ETA " + (ran_now > 0 ? clock_text(eta) : "-");
}

}  // namespace disco
