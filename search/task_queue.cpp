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
  nlohmann::json j = {
      {"scene", scene}, {"start", start}, {"budget", budget}, {"source", disco::to_string(source)}};
  if (std::isfinite(incumbent)) j["incumbent"] = incumbent;  // JSON has no infinity
  return j;
}

Task Task::from_json(const nlohmann::json& j) {
  return {j.at("scene").get<int>(), j.at("start").get<int>(), j.at("budget").get<double>(),
          budget_source_from_string(j.at("source").get<std::string>()),
          j.value("incumbent", kInf)};
}

TaskQueue::TaskQueue(const SearchPlan& plan, double time_limit,
                     const std::set<std::pair<int, int>>& done,
                     const GuessClassFunction& guess_class)
    : plan_(plan), time_limit_(time_limit), scenes_(plan.scenes.size()) {
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
    for (int k : first)
      if (!done.count({s, k})) pending_.push_back({s, k, 0.0});
  }
  total_ = plan.total_starts();
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
    t.budget = job.start_time_limit;
    t.source = job.start_time_limit > 0 ? BudgetSource::kStart : BudgetSource::kNone;
    auto cap = [&](double left, BudgetSource source) {
      if (t.budget > 0 && t.budget <= left) return;
      t.budget = left;
      t.source = source;
    };
    if (job.time_limit > 0) cap(scene_left, BudgetSource::kScene);
    if (time_limit_ > 0) cap(time_limit_ - now, BudgetSource::kSearch);
    running_[{t.scene, t.start}] = {rank, now};
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
