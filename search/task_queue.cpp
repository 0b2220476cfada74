#include "search/task_queue.h"

#include <algorithm>
#include <cmath>

#include "core/util/numbers.h"

namespace disco {
namespace {

// A rough cost of one start: unknowns per step times steps.
double cost(const Scene& s) {
  double per_step = 0;
  for (const auto& r : s.robots) per_step += 6 + r.force_dims + (r.mu > 0 ? r.friction_edges + 1 : 0);
  for (const auto& p : s.pairs) per_step += p.mode == PairMode::kContact ? 5 : 1;
  return per_step * s.steps;
}

}  // namespace

nlohmann::json Task::to_json() const {
  nlohmann::json j = {{"scene", scene},
                      {"start", start},
                      {"stage", disco::to_string(stage)},
                      {"budget", budget},
                      {"source", disco::to_string(source)}};
  if (std::isfinite(incumbent)) j["incumbent"] = incumbent;  // JSON has no infinity
  if (!guess.is_null()) j["guess"] = guess;
  return j;
}

Task Task::from_json(const nlohmann::json& j) {
  Task t;
  t.scene = j.at("scene").get<int>();
  t.start = j.at("start").get<int>();
  t.stage = stage_from_string(j.at("stage").get<std::string>());
  t.budget = j.at("budget").get<double>();
  t.source = budget_source_from_string(j.at("source").get<std::string>());
  t.incumbent = j.value("incumbent", kInf);
  if (j.contains("guess")) t.guess = j["guess"];
  return t;
}

TaskQueue::TaskQueue(const SearchPlan& plan, double time_limit,
                     const std::set<std::pair<int, int>>& done,
                     const GuessClassFunction& guess_class, const ScreenSettings& screen,
                     const std::set<std::pair<int, int>>& screened)
    : plan_(plan), time_limit_(time_limit), screen_(screen), scenes_(plan.scenes.size()), order_(plan.scenes.size()) {
  std::vector<int> order(plan.scenes.size());
  for (std::size_t s = 0; s < order.size(); ++s) order[s] = static_cast<int>(s);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return cost(plan.scenes[a].scene) > cost(plan.scenes[b].scene);
  });
  for (int s : order) {
    std::vector<int> first, seen;  // start indices
    std::set<std::string> classes;
    for (int k = 0; k < plan.scenes[s].starts; ++k) {
      const std::string c = guess_class ? guess_class(s, k) : std::string();
      (c.empty() || classes.insert(c).second ? first : seen).push_back(k);
    }
    first.insert(first.end(), seen.begin(), seen.end());
    order_[s] = first;
    for (int k : first) {
      if (done.count({s, k}) || (screen_.on() && screened.count({s, k}))) continue;
      Task t;
      t.scene = s;
      t.start = k;
      t.stage = screen_.on() ? Stage::kScreen : Stage::kFull;
      pending_.push_back(t);
    }
  }
  total_ = plan.total_starts();
  if (screen_.on())  // every screen, and at most refine_count refines per scene
    for (const SceneJob& job : plan.scenes) total_ += std::min(screen_.refine_count, job.starts);
}

double TaskQueue::screen_end(int s) const {
  if (!screen_.on()) return kInf;
  double end = kInf;
  if (time_limit_ > 0) end = screen_.share * time_limit_;
  const SceneJob& job = plan_.scenes[s];
  if (job.time_limit > 0 && scenes_[s].started_s >= 0)
    end = std::min(end, scenes_[s].started_s + screen_.share * job.time_limit);
  return end;
}

bool TaskQueue::screens_open(int s, double now) const {
  if (!screen_.on()) return false;
  for (const auto& [task, r] : running_)
    if (task.first == s && r.stage == Stage::kScreen) return true;
  if (now >= screen_end(s)) return false;  // the pending ones will not be handed out
  for (std::size_t i = next_; i < pending_.size(); ++i)
    if (pending_[i].scene == s && pending_[i].stage == Stage::kScreen) return true;
  return false;
}

void TaskQueue::add_refines(int s, int chosen, const std::vector<Task>& tasks) {
  SceneState& sc = scenes_[s];
  if (sc.refined) return;
  sc.refined = true;
  total_ += chosen - std::min(screen_.refine_count, plan_.scenes[s].starts);
  pending_.insert(pending_.begin() + refines_end(), tasks.begin(), tasks.end());
}

std::ptrdiff_t TaskQueue::refines_end() const {
  std::size_t i = next_;
  while (i < pending_.size() && pending_[i].stage == Stage::kRefine) ++i;
  return static_cast<std::ptrdiff_t>(i);
}

void TaskQueue::add_early_refine(int s, const std::optional<Task>& task) {
  if (!scenes_[s].refined) add_refine(task);
}

void TaskQueue::add_refine(const std::optional<Task>& task, bool in_place_of_screen) {
  if (in_place_of_screen && task) {  // its screen, if still pending, is not handed out any more
    const auto screen = std::find_if(pending_.begin() + static_cast<std::ptrdiff_t>(next_), pending_.end(),
                                     [&](const Task& t) {
                                       return t.stage == Stage::kScreen && t.scene == task->scene &&
                                              t.start == task->start;
                                     });
    if (screen != pending_.end()) pending_.erase(screen);
  } else {
    ++total_;
  }
  if (task) pending_.insert(pending_.begin() + refines_end(), *task);
}

bool TaskQueue::may_fill(int s, double now) const {
  const SceneJob& job = plan_.scenes[s];
  const SceneState& sc = scenes_[s];
  if (!screen_.on() || !sc.refined || !(time_limit_ > 0 || job.time_limit > 0)) return false;
  if (time_limit_ > 0 && now >= time_limit_) return false;
  return !(job.time_limit > 0 && sc.started_s >= 0 && now - sc.started_s >= job.time_limit);
}

bool TaskQueue::refines_to_come(double now) const {
  if (!screen_.on() || (time_limit_ > 0 && now >= time_limit_)) return false;
  for (std::size_t s = 0; s < scenes_.size(); ++s) {
    if (scenes_[s].refined) continue;
    const SceneJob& job = plan_.scenes[s];
    const bool scene_over = job.time_limit > 0 && scenes_[s].started_s >= 0 &&
                            now - scenes_[s].started_s >= job.time_limit;
    if (!scene_over) return true;
  }
  return false;
}

std::optional<Task> TaskQueue::next(int rank, double now) {
  if (time_limit_ > 0 && now >= time_limit_) {
    if (next_ < pending_.size()) time_limited_ = true;
    return std::nullopt;
  }
  while (next_ < pending_.size()) {
    Task t = pending_[next_++];
    const SceneJob& job = plan_.scenes[t.scene];
    SceneState& sc = scenes_[t.scene];
    if (sc.started_s < 0) sc.started_s = now;
    const double scene_left = job.time_limit > 0 ? job.time_limit - (now - sc.started_s) : 0.0;
    if (job.time_limit > 0 && scene_left <= 0) {
      sc.time_limited = true;
      continue;
    }
    if (t.stage == Stage::kScreen && now >= screen_end(t.scene)) continue;  // screening is over
    t.budget = job.start_time_limit;
    t.source = job.start_time_limit > 0 ? BudgetSource::kStart : BudgetSource::kNone;
    auto cap = [&](double left, BudgetSource source) {
      if (t.budget > 0 && t.budget <= left) return;
      t.budget = left;
      t.source = source;
    };
    if (job.time_limit > 0) cap(scene_left, BudgetSource::kScene);
    if (time_limit_ > 0) cap(time_limit_ - now, BudgetSource::kSearch);
    if (t.stage == Stage::kScreen) {  // a screen ends with the screening share
      const double end = screen_end(t.scene);
      const bool by_search = time_limit_ > 0 && end == screen_.share * time_limit_;
      if (std::isfinite(end)) cap(end - now, by_search ? BudgetSource::kSearch : BudgetSource::kScene);
    }
    running_[{t.scene, t.start}] = {rank, now, t.stage};
    return t;
  }
  return std::nullopt;
}

void TaskQueue::finished(int scene, int start, BudgetSource cut) {
  running_.erase({scene, start});
  if (cut == BudgetSource::kSearch) time_limited_ = true;
  if (cut == BudgetSource::kScene) scenes_[scene].time_limited = true;
}

void TaskQueue::finish() {
  if (next_ < pending_.size()) time_limited_ = true;
}

double TaskQueue::time_left(double now) const {
  double scenes = 0.0;
  for (std::size_t s = 0; s < plan_.scenes.size(); ++s) {
    const double limit = plan_.scenes[s].time_limit;
    if (!(limit > 0)) {
      scenes = kInf;
      break;
    }
    const double started = scenes_[s].started_s;
    scenes += started < 0 ? limit : std::max(0.0, limit - (now - started));
  }
  const double search = time_limit_ > 0 ? std::max(0.0, time_limit_ - now) : kInf;
  return std::min(scenes, search);
}

}  // namespace disco
