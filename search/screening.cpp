// disco — a screened search (search/screening.h says what and why).
#include "search/screening.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "core/config/solver_settings.h"
#include "core/util/errors.h"

namespace disco {

ScreenSettings screen_settings(const Settings& s) {
  auto refuse = [&](const std::string& key, const std::string& what) {
    throw InputError(s.where(key) + ": key '" + key + "': " + what);
  };
  ScreenSettings out;
  out.fraction = s.number("search.screen_fraction");
  if (!(out.fraction >= 0 && out.fraction < 1))
    refuse("search.screen_fraction", "must be >= 0 and below 1 (0: no screening)");
  out.refine_count = s.integer("search.refine_count");
  if (out.refine_count < 1) refuse("search.refine_count", "must be >= 1");
  out.share = s.number("search.screen_share");
  if (!(out.share > 0 && out.share < 1)) refuse("search.screen_share", "must be above 0 and below 1");
  out.early_batch = s.integer("search.early_refine_batch");
  if (out.early_batch < 0) refuse("search.early_refine_batch", "must be >= 0 (0: no early refines)");
  out.refine_from = choice<RefineFrom>(s, "search.refine_from",
                                       {{"screen", RefineFrom::kScreen}, {"start", RefineFrom::kStart}, {"both", RefineFrom::kBoth}});
  out.tie = s.number("search.screen_tie");
  if (!(out.tie >= 0 && out.tie < 1e-2))
    refuse("search.screen_tie", "must be >= 0 and below 1e-2 (a relative difference; 0: only equal values tie)");
  out.refine_weak_homotopy = weak_homotopy_choice(s, "search.refine_minimize_weak");
  return out;
}

int screen_steps(const Scene& scene, double fraction) {
  const int n = std::max(2, static_cast<int>(std::lround(fraction * scene.steps)));
  return std::min(n, scene.steps);
}

bool screen_below(double a, double b, double tie) {
  return b - a > tie * std::max(std::abs(a), std::abs(b));
}

std::vector<int> refine_choice(std::vector<Screened> screened, int count, double tie) {
  screened.erase(std::remove_if(screened.begin(), screened.end(),
                                [](const Screened& x) { return !std::isfinite(x.value); }),
                 screened.end());
  std::sort(screened.begin(), screened.end(), [](const Screened& a, const Screened& b) {
    return a.value != b.value ? a.value < b.value : a.start < b.start;
  });
  // Groups of values within the tie of their lowest, each ranked by start.
  for (std::size_t first = 0; first < screened.size();) {
    std::size_t end = first + 1;
    while (end < screened.size() && !screen_below(screened[first].value, screened[end].value, tie)) ++end;
    std::sort(screened.begin() + first, screened.begin() + end,
              [](const Screened& a, const Screened& b) { return a.start < b.start; });
    first = end;
  }
  std::vector<int> out;
  std::vector<char> taken(screened.size(), 0);
  std::set<std::string> classes;
  for (std::size_t i = 0; i < screened.size() && static_cast<int>(out.size()) < count; ++i) {
    const std::string& c = screened[i].class_key;
    if (!c.empty() && !classes.insert(c).second) continue;
    out.push_back(screened[i].start);
    taken[i] = 1;
  }
  for (std::size_t i = 0; i < screened.size() && static_cast<int>(out.size()) < count; ++i)
    if (!taken[i]) out.push_back(screened[i].start);
  return out;
}

std::vector<int> time_left_order(const std::vector<Screened>& screened, const std::vector<int>& hand_out_order,
                                 double tie) {
  std::vector<int> out = refine_choice(screened, static_cast<int>(screened.size()), tie);
  std::map<int, bool> certified;  // start -> whether its screen has a certified point
  for (const Screened& x : screened) certified[x.start] = std::isfinite(x.value);
  for (const bool with_screen : {false, true})
    for (int k : hand_out_order) {
      const auto it = certified.find(k);
      if ((it != certified.end()) == with_screen && (it == certified.end() || !it->second)) out.push_back(k);
    }
  return out;
}

std::vector<int> early_refine_choice(const std::vector<Screened>& ended, int starts, int batch, double tie) {
  std::vector<int> out;
  if (batch <= 0) return out;
  std::map<int, double> value;  // start -> its screen's value (NaN: not certified)
  for (const Screened& x : ended) value[x.start] = x.value;
  double best = std::numeric_limits<double>::infinity();  // the earlier batches' best
  for (int first = 0; first < starts; first += batch) {
    const int end = std::min(first + batch, starts);
    int chosen = -1;
    for (int k = first; k < end; ++k) {
      const auto it = value.find(k);
      if (it == value.end()) return out;  // not ended yet: no later batch is decided either
      if (std::isfinite(it->second) && (chosen < 0 || screen_below(it->second, value[chosen], tie))) chosen = k;
    }
    if (chosen < 0) continue;
    if (std::isinf(best) || screen_below(value[chosen], best, tie)) out.push_back(chosen);
    best = std::min(best, value[chosen]);
  }
  return out;
}

}  // namespace disco
