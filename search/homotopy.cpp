#include "search/homotopy.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/model/gap.h"
#include "core/util/check.h"
#include "core/util/numbers.h"

namespace disco {
namespace {

// The share of its path length robot path `p` has covered at each state (0 for a robot
// that does not move).
std::vector<double> progress(const std::vector<Pose>& p) {
  std::vector<double> s(p.size(), 0.0);
  for (std::size_t t = 1; t < p.size(); ++t)
    s[t] = s[t - 1] + std::hypot(p[t][0] - p[t - 1][0], p[t][1] - p[t - 1][1]);
  const double total = s.back();
  for (double& v : s) v = total > 0.0 ? v / total : 0.0;
  return s;
}

}  // namespace

bool HomotopyClass::decided() const {
  return std::none_of(pairs.begin(), pairs.end(), [](const PairClass& c) { return c.turn == "?"; });
}

std::string HomotopyClass::key(const Scene& scene) const {
  std::string out;
  for (const PairClass& c : pairs) {
    if (!out.empty()) out += "; ";
    out += scene.robots[c.i].name + "/" + scene.robots[c.j].name + " " + c.turn;
    if (c.first >= 0) out += ", " + scene.robots[c.first].name + " first";
    if (c.touch) out += ", touch";
  }
  return out;
}

nlohmann::json HomotopyClass::to_json(const Scene& scene) const {
  nlohmann::json list = nlohmann::json::array();
  for (const PairClass& c : pairs)
    list.push_back({{"pair", scene.robots[c.i].name + "/" + scene.robots[c.j].name},
                    {"turn", c.turn},
                    {"first", c.first >= 0 ? nlohmann::json(scene.robots[c.first].name)
                                           : nlohmann::json(nullptr)},
                    {"touch", c.touch}});
  return {{"key", key(scene)}, {"pairs", list}};
}

HomotopyClass homotopy_class(const Scene& scene, const Paths& paths) {
  DISCO_CHECK(paths.size() == scene.robots.size(), "a path per robot");
  HomotopyClass out;
  std::vector<std::vector<double>> share(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) share[i] = progress(paths[i]);
  for (const Pair& pair : scene.pairs) {
    const auto& a = paths[pair.i];
    const auto& b = paths[pair.j];
    DISCO_CHECK(a.size() == b.size() && a.size() >= 2, "paths of the same steps");
    const double c = clearance(scene, pair);
    double closest = kInf, turn = 0.0, previous = 0.0;
    std::size_t at = 0;
    for (std::size_t t = 0; t < a.size(); ++t) {
      const double dx = b[t][0] - a[t][0], dy = b[t][1] - a[t][1];
      const double d = std::hypot(dx, dy), angle = std::atan2(dy, dx);
      if (d < closest) closest = d, at = t;
      if (t > 0) turn += std::remainder(angle - previous, 2.0 * std::numbers::pi);
      previous = angle;
    }
    if (!(closest < kReach * c) && !(std::abs(turn) >= kTurn)) continue;
    PairClass pc;
    pc.i = pair.i;
    pc.j = pair.j;
    pc.turn = closest < 0.5 * c ? "?" : turn >= kTurn ? "ccw" : turn <= -kTurn ? "cw" : "none";
    const double lead = share[pair.i][at] - share[pair.j][at];
    pc.first = lead > kOrder ? pair.i : lead < -kOrder ? pair.j : -1;
    pc.touch = pair.mode == PairMode::kContact && closest <= c * (1.0 + kTouch);
    out.pairs.push_back(pc);
  }
  return out;
}

}  // namespace disco
