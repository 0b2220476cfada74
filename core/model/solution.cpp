#include "core/model/solution.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/model/contact_friction.h"
#include "core/model/floor_friction.h"
#include "core/model/objective.h"
#include "core/model/gap.h"
#include "core/model/lower_bound.h"
#include "core/model/obstacles.h"
#include "core/util/provenance.h"

namespace disco {
namespace {

using json = nlohmann::json;

json bound(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json state_json(const State& s) { return json(std::vector<double>(s.begin(), s.end())); }

}  // namespace

json solution_json(const RobotProblem& problem, const Vector& z, const SolutionInfo& info) {
  const Scene& si = problem.scene();
  const Layout& L = problem.layout();
  const Units& u = problem.units();
  const int N = si.steps;
  const bool has = z.size() == problem.program().num_variables();
  const auto size = problem.size();
  const auto lb = problem.lower_bound();

  json doc;
  doc["scenario"] = si.name;
  doc["status"] = to_string(info.status);
  if (!info.detail.empty()) doc["status_detail"] = info.detail;
  if (info.status != MpccStatus::kSolved) {
    json v = json::array();
    for (const auto& w : info.violations)
      v.push_back({{"owner", w.owner}, {"family", w.family}, {"amount", w.amount}});
    doc["violations"] = v;
  }
  if (info.stationarity) doc["stationarity"] = to_string(*info.stationarity);
  doc["T_f"] = has ? json(problem.horizon(z)) : json(nullptr);
  {
    const Objective& o = si.objective;
    json obj = {{"kind", to_string(o.kind)},
                {"unit", objective_unit(o.kind)},
                {"value", has ? json(problem.objective(z)) : json(nullptr)}};
    if (o.kind == ObjectiveKind::kEnergy) obj["horizon"] = o.horizon;
    if (o.kind == ObjectiveKind::kTimeEnergy) obj["energy_weight"] = o.energy_weight;
    doc["objective"] = obj;
  }
  doc["N_t"] = N;
  doc["h"] = has ? json(problem.horizon(z) / N) : json(nullptr);
  if (has) {
    std::vector<double> time(N + 1);
    const double T = problem.horizon(z);
    for (int t = 0; t <= N; ++t) time[t] = t == N ? T : T * t / N;
    doc["time"] = time;
  } else {
    doc["time"] = nullptr;
  }
  doc["g"] = si.gravity;
  doc["lower_bound"] = lb ? bound(*lb) : json(nullptr);
  doc["model"] = {{"variables", size.variables},
                  {"constraints", size.constraints},
                  {"complementarity_pairs", size.complementarity_pairs}};
  doc["certificate"] = {
      {"max_violation", bound(info.certificate.max_violation)},
      {"max_complementarity", bound(info.certificate.max_complementarity)},
      {"complementarity_product", bound(info.certificate.complementarity_product)},
      {"units", "dimensionless: length = mean radius, mass = mean mass, force = mean F_max"}};
  doc["timing"] = {
      {"wall_s", info.wall_s},
      {"nlp_solves", info.nlp_solves},
      {"iterations", info.iterations},
      {"kkt",
       {{"factorisations", info.kkt_factorisations},
        {"fallbacks", info.kkt_fallbacks},
        {"threshold_raises", info.kkt_threshold_raises},
        {"to_pivoted", info.kkt_to_pivoted},
        {"nested_dissection", info.kkt_nested_dissection},
        {"polish_rescues", info.kkt_polish_rescues}}}};

  const State unit{u.length, u.length, 1.0, u.velocity(), u.velocity(), 1.0 / u.time};
  auto value = [&](const Affine& a) { return a.value(z); };
  const int nr = static_cast<int>(si.robots.size());
  const int np = L.num_pairs();

  // Contact forces and torques on each robot, in model units, per step.
  std::vector<std::vector<std::array<double, 3>>> contact(
      nr, std::vector<std::array<double, 3>>(N, {0.0, 0.0, 0.0}));
  json pairs = json::array(), obstacle_pairs = json::array();
  for (int p = 0; p < np; ++p) {
    // The scene's own pair (SI: safe_distance in metres), not the model's.
    const Pair& pr = L.with_obstacle(p) ? si.obstacle_pairs[p - si.pairs.size()] : si.pairs[p];
    const int j = L.other_disk(p);  // -1: an obstacle
    json jp = {{"i", pr.i},
               {"j", pr.j},
               {"robot_i", si.robots[pr.i].name},
               {j >= 0 ? "robot_j" : "obstacle", j >= 0 ? si.robots[j].name : si.obstacles[pr.j].name},
               {"mode", pr.mode == PairMode::kContact ? "contact" : "avoid"},
               {"safe_distance", pr.safe_distance},
               {"mu", pr.mu}};
    if (has) {
      std::vector<double> gap(N + 1), fn(N, 0.0), ft(N, 0.0);
      for (int t = 0; t <= N; ++t)  // from the centres: outside its window a pair has no gap unknown
        gap[t] = centre_gap(L, z, p, t) * u.length;
      for (int t = 0; t < N; ++t) {
        const ContactForce f = contact_force(L, z, p, t);  // zero where no force acts
        fn[t] = f.normal * u.force();
        ft[t] = f.tangential * u.force();
        for (int a = 0; a < 2; ++a) {
          if (j >= 0) contact[j][t][a] += f.on_j[a];
          contact[pr.i][t][a] -= f.on_j[a];
        }
        if (j >= 0) contact[j][t][2] += f.torque_j;
        contact[pr.i][t][2] += f.torque_i;
      }
      jp["gap"] = gap;
      jp["normal_force"] = fn;
      jp["tangential_force"] = ft;
      if (j < 0) {  // between the states, where the rows do not look (core/model/obstacles.h)
        const Obstacle& ob = si.obstacles[pr.j];
        const double h = value(L.step()) * u.time;
        auto centre = [&](int k) {
          return std::array<double, 2>{value(L.state(pr.i, k, kX)) * u.length, value(L.state(pr.i, k, kY)) * u.length};
        };
        std::vector<double> swept(N);
        for (int t = 0; t < N; ++t)
          swept[t] = swept_distance(ob, centre(t), centre(t + 1), t * h, (t + 1) * h) - si.robots[pr.i].radius - ob.radius;
        jp["swept_gap"] = swept;
      }
    } else {
      jp["gap"] = jp["normal_force"] = jp["tangential_force"] = nullptr;
      if (j < 0) jp["swept_gap"] = nullptr;
    }
    (j >= 0 ? pairs : obstacle_pairs).push_back(jp);
  }

  json robots = json::array();
  for (int i = 0; i < nr; ++i) {
    const Robot& rb = si.robots[i];
    json lower = json::array(), upper = json::array();
    for (int c = 0; c < kStateSize; ++c) {
      lower.push_back(bound(rb.target.lower[c]));
      upper.push_back(bound(rb.target.upper[c]));
    }
    json jr = {{"name", rb.name},     {"kind", rb.object ? "object" : "robot"}, {"radius", rb.radius},       {"mass", rb.mass},
               {"inertia", rb.inertia}, {"mu", rb.mu},             {"damping", rb.damping},
               {"F_max", rb.force_max}, {"force_dims", rb.force_dims}, {"K", rb.friction_edges},
               {"start", state_json(rb.start)}, {"target", {{"lower", lower}, {"upper", upper}}}};
    if (rb.force_dims == 1) jr["force_axis"] = {rb.force_axis[0], rb.force_axis[1]};
    if (has) {
      for (int c = 0; c < kStateSize; ++c) {
        std::vector<double> v(N + 1);
        for (int t = 0; t <= N; ++t) v[t] = value(L.state(i, t, c)) * unit[c];
        jr[kStateNames[c]] = v;
      }
      std::vector<double> fx(N), fy(N), wx(N, 0.0), wy(N, 0.0), cx(N), cy(N), ct(N);
      for (int t = 0; t < N; ++t) {
        fx[t] = value(L.force(i, t, 0)) * u.force();
        fy[t] = value(L.force(i, t, 1)) * u.force();
        const std::array<double, 2> w = floor_friction_force(L, z, i, t);
        wx[t] = w[0] * u.force();
        wy[t] = w[1] * u.force();
        cx[t] = contact[i][t][0] * u.force();
        cy[t] = contact[i][t][1] * u.force();
        ct[t] = contact[i][t][2] * u.torque();
      }
      jr["Fx"] = fx;
      jr["Fy"] = fy;
      jr["friction_x"] = wx;
      jr["friction_y"] = wy;
      jr["contact_x"] = cx;
      jr["contact_y"] = cy;
      jr["contact_torque"] = ct;
    } else {
      for (const char* key : {"x", "y", "phi", "vx", "vy", "omega", "Fx", "Fy", "friction_x",
                              "friction_y", "contact_x", "contact_y", "contact_torque"})
        jr[key] = nullptr;
    }
    robots.push_back(jr);
  }
  doc["robots"] = robots;
  doc["pairs"] = pairs;
  json obstacles = json::array();
  for (const Obstacle& ob : si.obstacles) {
    const bool wall = ob.shape == ObstacleShape::kWall;
    json jo = {{"name", ob.name}, {"shape", wall ? "wall" : "disk"}, {"radius", ob.radius}};
    jo[wall ? "from" : "centre"] = {ob.from[0], ob.from[1]};
    if (wall) {
      jo["to"] = {ob.to[0], ob.to[1]};
    } else if (ob.path.empty()) {
      jo["velocity"] = {ob.velocity[0], ob.velocity[1]};
    } else {
      json path = json::array();
      for (const Waypoint& w : ob.path) path.push_back({{"t", w.t}, {"x", w.p[0]}, {"y", w.p[1]}});
      jo["path"] = path;
    }
    if (!wall && has) {  // where the disk is at each state t_k = k h
      const double h = value(L.step()) * u.time;
      std::vector<double> x(N + 1), y(N + 1);
      for (int t = 0; t <= N; ++t) {
        const auto c = obstacle_centre(ob, t * h);
        x[t] = c[0], y[t] = c[1];
      }
      jo["x"] = x;
      jo["y"] = y;
    }
    obstacles.push_back(jo);
  }
  doc["obstacles"] = obstacles;
  doc["obstacle_pairs"] = obstacle_pairs;
  return doc;
}

json provenance_json(const Provenance& p, const Settings& settings) {
  return {{"mode", p.mode},
          {"scene_file", p.scene_file},
          {"scene_sha256", file_sha256(p.scene_file)},
          {"scene_overrides", p.scene_overrides},
          {"overrides", p.overrides},
          {"seed", p.seed},
          {"start", p.start},
          {"settings_file", settings.source()},
          {"settings_sha256", sha256_hex(settings.canonical_text())},
          {"version", disco_version()},
          {"guess", p.guess.empty() ? json(nullptr)
                                    : json{{"file", p.guess}, {"sha256", file_sha256(p.guess)}}}};
}

std::string violations_text(const std::vector<RobotProblem::Violation>& v, std::size_t most) {
  if (v.empty()) return "";
  std::string text = "at the last attempt, the largest violations (model units): ";
  for (std::size_t k = 0; k < std::min(most, v.size()); ++k)
    text += fmt::format("{}{} {} {:.1e}", k ? ", " : "", v[k].owner, v[k].family, v[k].amount);
  if (v.size() > most) text += fmt::format(" and {} more", v.size() - most);
  return text;
}

void write_json_file(const std::string& path, const json& doc) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << doc.dump(1) << '\n';
    if (!out) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace disco
