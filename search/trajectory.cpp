#include "search/trajectory.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/util/check.h"
#include "core/util/errors.h"

namespace disco {
namespace {

using json = nlohmann::json;

std::string names_of(const json& robots) {
  std::string out;
  for (const auto& r : robots)
    out += (out.empty() ? "" : ", ") + (r.contains("name") && r["name"].is_string()
                                            ? r["name"].get<std::string>()
                                            : std::string("?"));
  return out;
}
std::string names_of(const Scene& scene) {
  std::string out;
  for (const auto& r : scene.robots) out += (out.empty() ? "" : ", ") + r.name;
  return out;
}

// The numbers of array `key` of robot entry `r`: n + 1 of them. InputError otherwise.
std::vector<double> series(const json& r, const char* key, std::size_t n, const std::string& where) {
  const auto it = r.find(key);
  if (it == r.end() || !it->is_array() || it->size() != n + 1)
    throw InputError(where + ": robot '" + r.value("name", "?") + "': '" + key +
                     "' must be an array of N_t + 1 = " + std::to_string(n + 1) + " numbers");
  std::vector<double> v;
  for (const auto& x : *it) {
    if (!x.is_number() || !std::isfinite(x.get<double>()))
      throw InputError(where + ": robot '" + r.value("name", "?") + "': '" + key +
                       "' holds a value that is not a finite number");
    v.push_back(x.get<double>());
  }
  return v;
}

}  // namespace

Pose pose_at(const std::vector<Pose>& path, double u) {
  DISCO_CHECK(path.size() >= 2, "a path of at least one step");
  const int n = static_cast<int>(path.size()) - 1;
  u = std::clamp(u, 0.0, static_cast<double>(n));
  const int k = std::min(n - 1, static_cast<int>(std::floor(u)));
  const double f = u - k;
  Pose p;
  for (int d = 0; d < 3; ++d) p[d] = path[k][d] + f * (path[k + 1][d] - path[k][d]);
  return p;
}

Paths resample(const Paths& paths, int N) {
  DISCO_CHECK(N >= 1, "at least one step");
  Paths out(paths.size(), std::vector<Pose>(N + 1));
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const int n = static_cast<int>(paths[i].size()) - 1;
    for (int t = 0; t <= N; ++t) out[i][t] = pose_at(paths[i], static_cast<double>(t) * n / N);
    out[i][0] = paths[i].front();  // the ends exactly
    out[i][N] = paths[i].back();
  }
  return out;
}

Paths paths_of(const RobotProblem& problem, const Vector& z) {
  const Scene& scene = problem.scene();  // SI
  const Layout& lay = problem.layout();
  const int N = scene.steps, nr = static_cast<int>(scene.robots.size());
  const double L = problem.units().length;
  Paths paths(nr, std::vector<Pose>(N + 1));
  for (int i = 0; i < nr; ++i) {
    const State& s = scene.robots[i].start;
    paths[i][0] = {s[kX], s[kY], s[kPhi]};
    for (int t = 1; t <= N; ++t)
      paths[i][t] = {lay.state(i, t, kX).value(z) * L, lay.state(i, t, kY).value(z) * L,
                     lay.state(i, t, kPhi).value(z)};
  }
  return paths;
}

Trajectory trajectory_from_solution(const json& doc, const Scene& scene, const std::string& source) {
  const std::string where = "--guess " + source;
  if (!doc.is_object() || !doc.contains("robots") || !doc["robots"].is_array())
    throw InputError(where + ": not a solution file (no 'robots' array; a solution.json of "
                     "disco solve or a best/SCENE.json of disco search)");
  const json& robots = doc["robots"];
  const auto T = doc.find("T_f");
  if (T == doc.end() || !T->is_number() || !(T->get<double>() > 0))
    throw InputError(where + ": holds no trajectory (T_f is " + (T == doc.end() ? "missing" : T->dump()) +
                     ", status " + doc.value("status", std::string("?")) + ")");
  const auto n_t = doc.find("N_t");
  if (n_t == doc.end() || !n_t->is_number_integer() || n_t->get<int>() < 1)
    throw InputError(where + ": 'N_t' must be an integer >= 1");
  const std::size_t n = n_t->get<std::size_t>();
  if (robots.size() != scene.robots.size())
    throw InputError(fmt::format("{}: its robots do not match scene '{}': {} there ({}), {} in the "
                                 "scene ({})",
                                 where, scene.name, robots.size(), names_of(robots),
                                 scene.robots.size(), names_of(scene)));
  Trajectory out;
  out.seconds = T->get<double>();
  out.source = source;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const json& r = robots[i];
    const Robot& rb = scene.robots[i];
    const std::string name = r.contains("name") && r["name"].is_string() ? r["name"].get<std::string>() : "?";
    if (name != rb.name)
      throw InputError(fmt::format("{}: its robots do not match scene '{}': robot {} is '{}' there, "
                                   "'{}' in the scene (there: {}; scene: {})",
                                   where, scene.name, i + 1, printable(name, kEchoLimit), rb.name,
                                   names_of(robots), names_of(scene)));
    const auto x = series(r, "x", n, where), y = series(r, "y", n, where);
    // phi: a robot that cannot turn keeps its start's.
    std::vector<double> phi(n + 1, rb.start[kPhi]);
    if (r.contains("phi") && !r["phi"].is_null()) phi = series(r, "phi", n, where);
    const double tol = 1e-6 * std::max({1.0, std::abs(rb.start[kX]), std::abs(rb.start[kY])});
    if (std::hypot(x[0] - rb.start[kX], y[0] - rb.start[kY]) > tol)
      throw InputError(fmt::format("{}: robot '{}' starts at ({:g}, {:g}) there, at ({:g}, {:g}) in "
                                   "scene '{}'",
                                   where, rb.name, x[0], y[0], rb.start[kX], rb.start[kY],
                                   scene.name));
    std::vector<Pose> path(n + 1);
    for (std::size_t t = 0; t <= n; ++t) path[t] = {x[t], y[t], phi[t]};
    out.paths.push_back(std::move(path));
  }
  out.paths = resample(out.paths, scene.steps);
  return out;
}

json read_guess_document(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--guess " + path + ": cannot be read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError("--guess " + path + ": not JSON (" + e.what() + ")");
  }
}

Trajectory read_guess_file(const std::string& path, const Scene& scene) {
  return trajectory_from_solution(read_guess_document(path), scene, path);
}

}  // namespace disco
