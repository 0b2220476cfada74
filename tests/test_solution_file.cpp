// The solution file (core/README.md, "The solution file") checked from the JSON alone.
//
// Small scenes are solved with disco, the document is written with
// solution_json / write_json_file and read back, and then everything below is
// recomputed from the JSON in SI units, without calling into disco's model:
//   * the schema: every documented field, its type, its length (N_t + 1 states,
//     N_t steps), nulls where documented;
//   * the physics of Appendix A as documented in core/model/*.h: start and
//     target, semi-implicit kinematics, the momentum balances (with the
//     rotational damping -sigma_d M g omega^{t+1}), the floor-friction K-gon,
//     force bounds, the gap, nonpenetration, Coulomb contact friction, Newton's
//     third law, complementarity, avoidance;
//   * a scene without a solution: status, status_detail and null trajectories.
//
// Tolerances. disco certifies its constraints to 1e-6 in the model's units
// (core/README.md, units: length = mean radius, mass = mean mass, force = mean
// F_max, time = sqrt(length mass / force)). The scales below are computed
// from the robots in the JSON with that documented rule, and each residual is
// compared with 1e-6 of its own scale (impulse = force * time, angular impulse
// = force * length * time, ...).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "core/model/solution.h"
#include "core/util/errors.h"
#include "core/util/provenance.h"
#include "search/solve_scene.h"
#include "tests/test_support_model.h"

namespace disco {
namespace {

using json = nlohmann::json;

constexpr double kCert = 1e-6;  // disco's certificate threshold (model units)

// ---------------------------------------------------------------------------
// Worst-case bookkeeping: one EXPECT per physical law, naming where it was
// worst, instead of one failure per time step.

struct Worst {
  std::string law;
  double ratio = 0.0;  // worst |residual| / tolerance; <= 1 passes
  double residual = 0.0, tolerance = 0.0;
  std::string where;
  int count = 0;  // how many instances were checked (non-vacuity)

  explicit Worst(std::string name) : law(std::move(name)) {}

  // A residual that must satisfy |residual| <= tolerance.
  void add(double r, double tol, const std::string& what, int t) {
    ++count;
    const double q = std::isfinite(r) ? std::abs(r) / tol : INFINITY;
    if (q > ratio || (count == 1 && q >= ratio)) {
      ratio = q;
      residual = r;
      tolerance = tol;
      where = what + " t=" + std::to_string(t);
    }
  }
  // A value that must be >= bound - tol.
  void at_least(double v, double bound, double tol, const std::string& what, int t) {
    add(std::min(0.0, v - bound), tol, what, t);
  }
  // A value that must be <= bound + tol.
  void at_most(double v, double bound, double tol, const std::string& what, int t) {
    add(std::max(0.0, v - bound), tol, what, t);
  }
  void expect(bool nonempty = true) const {
    EXPECT_LE(ratio, 1.0) << law << ": worst at " << where << ": residual " << residual
                          << " > tolerance " << tolerance;
    if (nonempty) {
      EXPECT_GT(count, 0) << law << ": nothing was checked";
    }
  }
};

// ---------------------------------------------------------------------------
// Schema.

// obj[key] exists and is a number; ADD_FAILURE otherwise.
bool has_number(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) {
    ADD_FAILURE() << where << ": missing '" << key << "'";
    return false;
  }
  if (!obj[key].is_number()) {
    ADD_FAILURE() << where << ": '" << key << "' is not a number: " << obj[key].dump();
    return false;
  }
  if (!std::isfinite(obj[key].get<double>())) {
    ADD_FAILURE() << where << ": '" << key << "' is not finite";
    return false;
  }
  return true;
}

bool has_integer(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key) || !obj[key].is_number_integer()) {
    ADD_FAILURE() << where << ": '" << key << "' missing or not an integer: "
                  << (obj.contains(key) ? obj[key].dump() : "(absent)");
    return false;
  }
  return true;
}

bool has_string(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key) || !obj[key].is_string()) {
    ADD_FAILURE() << where << ": '" << key << "' missing or not a string: "
                  << (obj.contains(key) ? obj[key].dump() : "(absent)");
    return false;
  }
  return true;
}

bool has_null(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) {
    ADD_FAILURE() << where << ": missing '" << key << "' (documented as null here)";
    return false;
  }
  if (!obj[key].is_null()) {
    ADD_FAILURE() << where << ": '" << key << "' should be null, is " << obj[key].dump(-1).substr(0, 80);
    return false;
  }
  return true;
}

// obj[key] is an array of n finite numbers (or null entries, if allowed).
bool has_numbers(const json& obj, const std::string& key, std::size_t n, const std::string& where,
                 bool nulls_allowed = false) {
  if (!obj.contains(key) || !obj[key].is_array()) {
    ADD_FAILURE() << where << ": '" << key << "' missing or not an array: "
                  << (obj.contains(key) ? obj[key].dump(-1).substr(0, 80) : "(absent)");
    return false;
  }
  const json& a = obj[key];
  if (a.size() != n) {
    ADD_FAILURE() << where << ": '" << key << "' has " << a.size() << " entries, expected " << n;
    return false;
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (a[k].is_null() && nulls_allowed) continue;
    if (!a[k].is_number() || !std::isfinite(a[k].get<double>())) {
      ADD_FAILURE() << where << ": '" << key << "'[" << k << "] is not a finite number: "
                    << a[k].dump();
      return false;
    }
  }
  return true;
}

const char* const kStates[] = {"x", "y", "phi", "vx", "vy", "omega"};
const char* const kSteps[] = {"Fx",        "Fy",        "friction_x",    "friction_y",
                              "contact_x", "contact_y", "contact_torque"};
const char* const kPairSteps[] = {"normal_force", "tangential_force"};

// The fields every document has, solved or not. Returns false on any failure.
bool check_common_schema(const json& doc, const RobotProblem& problem) {
  bool ok = true;
  ok &= has_string(doc, "scenario", "doc");
  ok &= has_string(doc, "status", "doc");
  ok &= has_integer(doc, "N_t", "doc");
  ok &= has_number(doc, "g", "doc");
  if (!doc.contains("lower_bound") || !(doc["lower_bound"].is_number() || doc["lower_bound"].is_null())) {
    ADD_FAILURE() << "doc: 'lower_bound' missing or neither a number nor null";
    ok = false;
  }
  for (const char* k : {"T_f", "h"}) {
    if (!doc.contains(k)) {
      ADD_FAILURE() << "doc: missing '" << k << "' (a number, or null without a solution)";
      ok = false;
    }
  }
  if (!ok) return false;
  EXPECT_EQ(doc["scenario"].get<std::string>(), problem.scene().name);
  EXPECT_EQ(doc["N_t"].get<int>(), problem.scene().steps);
  EXPECT_EQ(doc["g"].get<double>(), problem.scene().gravity);

  // model: sizes as RobotProblem reports them.
  if (!doc.contains("model") || !doc["model"].is_object()) {
    ADD_FAILURE() << "doc: 'model' missing or not an object";
    return false;
  }
  const json& m = doc["model"];
  ok &= has_integer(m, "variables", "model") && has_integer(m, "constraints", "model") &&
        has_integer(m, "complementarity_pairs", "model");
  if (ok) {
    const ModelSize size = problem.size();
    EXPECT_EQ(m["variables"].get<int>(), size.variables);
    EXPECT_EQ(m["constraints"].get<int>(), size.constraints);
    EXPECT_EQ(m["complementarity_pairs"].get<int>(), size.complementarity_pairs);
    EXPECT_GT(size.variables, 0);
  }

  // certificate: numbers (or null when no solve produced one).
  if (!doc.contains("certificate") || !doc["certificate"].is_object()) {
    ADD_FAILURE() << "doc: 'certificate' missing or not an object";
    return false;
  }
  for (const char* k : {"max_violation", "max_complementarity", "complementarity_product"}) {
    const json& c = doc["certificate"];
    if (!c.contains(k) || !(c[k].is_number() || c[k].is_null())) {
      ADD_FAILURE() << "certificate: '" << k << "' missing or neither a number nor null";
      ok = false;
    }
  }

  // timing.
  if (!doc.contains("timing") || !doc["timing"].is_object()) {
    ADD_FAILURE() << "doc: 'timing' missing or not an object";
    return false;
  }
  ok &= has_number(doc["timing"], "wall_s", "timing");
  ok &= has_integer(doc["timing"], "nlp_solves", "timing");
  ok &= has_integer(doc["timing"], "iterations", "timing");
  if (ok) {
    EXPECT_GE(doc["timing"]["wall_s"].get<double>(), 0.0);
    EXPECT_GE(doc["timing"]["nlp_solves"].get<int>(), 1);
    EXPECT_GE(doc["timing"]["iterations"].get<int>(), 0);
  }

  // robots: the scene's data (always present).
  if (!doc.contains("robots") || !doc["robots"].is_array() ||
      doc["robots"].size() != problem.scene().robots.size()) {
    ADD_FAILURE() << "doc: 'robots' missing, not an array, or of the wrong length";
    return false;
  }
  for (std::size_t r = 0; r < doc["robots"].size(); ++r) {
    const json& jr = doc["robots"][r];
    const Robot& rb = problem.scene().robots[r];
    const std::string w = "robots[" + std::to_string(r) + "]";
    ok &= has_string(jr, "name", w) && has_string(jr, "kind", w);
    for (const char* k : {"radius", "mass", "inertia", "mu", "damping", "F_max"}) ok &= has_number(jr, k, w);
    ok &= has_integer(jr, "force_dims", w) && has_integer(jr, "K", w);
    ok &= has_numbers(jr, "start", 6, w);
    if (!jr.contains("target") || !jr["target"].is_object()) {
      ADD_FAILURE() << w << ": 'target' missing or not an object";
      ok = false;
    } else {
      ok &= has_numbers(jr["target"], "lower", 6, w + ".target", true);
      ok &= has_numbers(jr["target"], "upper", 6, w + ".target", true);
    }
    if (!ok) return false;
    // Same values as the scene (SI).
    EXPECT_EQ(jr["name"].get<std::string>(), rb.name);
    EXPECT_EQ(jr["kind"].get<std::string>(), rb.object ? "object" : "robot") << w;
    EXPECT_EQ(jr["radius"].get<double>(), rb.radius) << w;
    EXPECT_EQ(jr["mass"].get<double>(), rb.mass) << w;
    EXPECT_EQ(jr["inertia"].get<double>(), rb.inertia) << w;
    EXPECT_EQ(jr["mu"].get<double>(), rb.mu) << w;
    EXPECT_EQ(jr["damping"].get<double>(), rb.damping) << w;
    EXPECT_EQ(jr["F_max"].get<double>(), rb.force_max) << w;
    EXPECT_EQ(jr["force_dims"].get<int>(), rb.force_dims) << w;
    EXPECT_EQ(jr["K"].get<int>(), rb.friction_edges) << w;
    for (int c = 0; c < 6; ++c) {
      EXPECT_EQ(jr["start"][c].get<double>(), rb.start[c]) << w << ".start[" << c << "]";
      for (const char* side : {"lower", "upper"}) {
        const double v = std::string(side) == "lower" ? rb.target.lower[c] : rb.target.upper[c];
        const json& e = jr["target"][side][c];
        if (std::isfinite(v)) {
          EXPECT_TRUE(e.is_number() && e.get<double>() == v)
              << w << ".target." << side << "[" << c << "] = " << e.dump() << ", scene has " << v;
        } else {
          EXPECT_TRUE(e.is_null()) << w << ".target." << side << "[" << c
                                   << "] must be null (unbounded), is " << e.dump();
        }
      }
    }
  }

  // pairs: one per robot pair i < j.
  if (!doc.contains("pairs") || !doc["pairs"].is_array() ||
      doc["pairs"].size() != problem.scene().pairs.size()) {
    ADD_FAILURE() << "doc: 'pairs' missing, not an array, or of the wrong length";
    return false;
  }
  for (std::size_t p = 0; p < doc["pairs"].size(); ++p) {
    const json& jp = doc["pairs"][p];
    const Pair& pr = problem.scene().pairs[p];
    const std::string w = "pairs[" + std::to_string(p) + "]";
    ok &= has_integer(jp, "i", w) && has_integer(jp, "j", w) && has_string(jp, "mode", w);
    ok &= has_number(jp, "safe_distance", w) && has_number(jp, "mu", w);
    if (!ok) return false;
    EXPECT_EQ(jp["i"].get<int>(), pr.i) << w;
    EXPECT_EQ(jp["j"].get<int>(), pr.j) << w;
    EXPECT_EQ(jp.value("robot_i", ""), problem.scene().robots[pr.i].name) << w << ": robot_i names robot i";
    EXPECT_EQ(jp.value("robot_j", ""), problem.scene().robots[pr.j].name) << w << ": robot_j names robot j";
    EXPECT_LT(jp["i"].get<int>(), jp["j"].get<int>()) << w;
    EXPECT_EQ(jp["mode"].get<std::string>(), pr.mode == PairMode::kContact ? "contact" : "avoid") << w;
    EXPECT_EQ(jp["safe_distance"].get<double>(), pr.safe_distance) << w;
    EXPECT_EQ(jp["mu"].get<double>(), pr.mu) << w;
  }
  return ok;
}

// The fields of a solved document. Returns false on any failure.
bool check_solved_schema(const json& doc) {
  bool ok = has_number(doc, "T_f", "doc") && has_number(doc, "h", "doc");
  EXPECT_EQ(doc.value("status", ""), "solved");
  EXPECT_FALSE(doc.contains("status_detail")) << "status_detail is documented only when not solved";
  const std::string stationarity = doc.value("stationarity", "");
  EXPECT_TRUE(stationarity == "B-stationary" || stationarity == "strongly stationary" ||
              stationarity == "feasible")
      << "undocumented or missing stationarity '" << stationarity << "'";
  ok = ok && !stationarity.empty();
  if (!ok) return false;
  const int N = doc["N_t"].get<int>();
  const double T = doc["T_f"].get<double>(), h = doc["h"].get<double>();
  EXPECT_GT(T, 0.0);
  EXPECT_NEAR(h, T / N, 1e-14 * T) << "h must be T_f / N_t";
  // time: the instants of the state arrays, t_k = k h from 0 to T_f.
  ok &= has_numbers(doc, "time", N + 1, "doc");
  if (!ok) return false;
  const json& time = doc["time"];
  EXPECT_EQ(time[0].get<double>(), 0.0);
  EXPECT_EQ(time[N].get<double>(), T) << "the last instant is T_f";
  for (int k = 1; k <= N; ++k)
    EXPECT_NEAR(time[k].get<double>() - time[k - 1].get<double>(), h, 1e-12 * T) << "time[" << k << "]";
  for (const char* k : {"max_violation", "max_complementarity", "complementarity_product"}) {
    const json& c = doc["certificate"][k];
    if (!c.is_number()) {
      ADD_FAILURE() << "certificate." << k << " must be a number when solved";
      ok = false;
      continue;
    }
    EXPECT_LE(std::abs(c.get<double>()), kCert) << "certificate." << k;
  }
  if (doc["lower_bound"].is_number()) {
    EXPECT_GT(doc["lower_bound"].get<double>(), 0.0);
  }
  for (std::size_t r = 0; r < doc["robots"].size(); ++r) {
    const json& jr = doc["robots"][r];
    const std::string w = "robots[" + std::to_string(r) + "]";
    for (const char* k : kStates) ok &= has_numbers(jr, k, N + 1, w);
    for (const char* k : kSteps) ok &= has_numbers(jr, k, N, w);
  }
  for (std::size_t p = 0; p < doc["pairs"].size(); ++p) {
    const json& jp = doc["pairs"][p];
    const std::string w = "pairs[" + std::to_string(p) + "]";
    ok &= has_numbers(jp, "gap", N + 1, w);
    for (const char* k : kPairSteps) ok &= has_numbers(jp, k, N, w);
  }
  return ok;
}

// ---------------------------------------------------------------------------
// Physics, from the JSON alone (SI).

struct RobotData {
  std::string name;
  bool object = false;  // kind "object": a passive disk
  double R, M, I, mu, damping, F_max;
  int dims, K;
  std::vector<double> start, lower, upper;  // lower/upper: +-inf for null
  std::vector<double> x, y, phi, vx, vy, omega;
  std::vector<double> Fx, Fy, wx, wy, cx, cy, ct;
};

struct PairData {
  int i, j;
  bool contact;
  double safe, mu;
  std::vector<double> dist, fn, ft;
};

std::vector<double> numbers(const json& a, double null_value = 0.0) {
  std::vector<double> v;
  for (const json& e : a) v.push_back(e.is_null() ? null_value : e.get<double>());
  return v;
}

RobotData robot_data(const json& jr) {
  RobotData d;
  d.name = jr["name"];
  d.object = jr["kind"] == "object";
  d.R = jr["radius"];
  d.M = jr["mass"];
  d.I = jr["inertia"];
  d.mu = jr["mu"];
  d.damping = jr["damping"];
  d.F_max = jr["F_max"];
  d.dims = jr["force_dims"];
  d.K = jr["K"];
  d.start = numbers(jr["start"]);
  d.lower = numbers(jr["target"]["lower"], -INFINITY);
  d.upper = numbers(jr["target"]["upper"], INFINITY);
  d.x = numbers(jr["x"]);
  d.y = numbers(jr["y"]);
  d.phi = numbers(jr["phi"]);
  d.vx = numbers(jr["vx"]);
  d.vy = numbers(jr["vy"]);
  d.omega = numbers(jr["omega"]);
  d.Fx = numbers(jr["Fx"]);
  d.Fy = numbers(jr["Fy"]);
  d.wx = numbers(jr["friction_x"]);
  d.wy = numbers(jr["friction_y"]);
  d.cx = numbers(jr["contact_x"]);
  d.cy = numbers(jr["contact_y"]);
  d.ct = numbers(jr["contact_torque"]);
  return d;
}

PairData pair_data(const json& jp) {
  PairData d;
  d.i = jp["i"];
  d.j = jp["j"];
  d.contact = jp["mode"] == "contact";
  d.safe = jp["safe_distance"];
  d.mu = jp["mu"];
  d.dist = numbers(jp["gap"]);
  d.fn = numbers(jp["normal_force"]);
  d.ft = numbers(jp["tangential_force"]);
  return d;
}

// The scales of README "Scaling", from the robots in the file.
struct Scales {
  double length, mass, force, time;
  double velocity() const { return length / time; }
  double impulse() const { return force * time; }
  double angular_impulse() const { return force * length * time; }
};

Scales scales(const std::vector<RobotData>& robots) {
  Scales s{0, 0, 0, 0};
  const double driven = static_cast<double>(
      std::count_if(robots.begin(), robots.end(), [](const RobotData& r) { return !r.object; }));
  for (const RobotData& r : robots) {
    s.length += r.R / robots.size();
    s.mass += r.M / robots.size();
    if (!r.object) s.force += r.F_max / driven;  // objects have none
  }
  s.time = std::sqrt(s.length * s.mass / s.force);
  return s;
}

struct PhysicsSummary {
  double max_normal_force = 0.0;     // over contact pairs [N]
  double max_tangential_force = 0.0;
  int moving_steps = 0;              // robot steps checked for sliding friction
};

// Every law listed in the file comment. `doc` must have passed check_solved_schema.
PhysicsSummary check_physics(const json& doc) {
  const int N = doc["N_t"];
  const double h = doc["h"], g = doc["g"];
  std::vector<RobotData> rob;
  for (const json& jr : doc["robots"]) rob.push_back(robot_data(jr));
  std::vector<PairData> prs;
  for (const json& jp : doc["pairs"]) prs.push_back(pair_data(jp));
  const Scales s = scales(rob);
  const double state_scale[6] = {s.length, s.length, 1.0, s.velocity(), s.velocity(), 1.0 / s.time};
  PhysicsSummary out;

  Worst start("start state == scene start"), target("final state inside the target box"),
      kin("kinematics x[t+1] - x[t] == h v[t+1]"),
      mom("momentum M dv == h (F + friction + contact)"),
      rot("rotation I domega == h (contact torque - sigma_d M g omega[t+1])"),
      fric_max("|floor friction| <= mu M g"), fric_dir("floor friction opposes v[t+1]"),
      fric_cone("sliding floor friction within pi/K of -v[t+1]"),
      fric_mag("sliding floor friction >= mu M g cos(pi/K)"), force("|F| <= F_max"),
      axis("D_ef = 1: F along force_axis"), dist("distance == |p_j - p_i| - R_i - R_j"),
      nonpen("contact pair: distance >= 0"), avoid("avoid pair: distance >= safe_distance"),
      fn_pos("normal_force >= 0"), coulomb("|tangential_force| <= mu normal_force"),
      compl_("normal_force > 0 only where distance[t+1] == 0"),
      no_force("avoid pair: no contact forces"), sum("contact_x/y == sum of pair forces"),
      torque("contact_torque == -R * tangential_force"), third("third law: contact_i == -contact_j");

  for (std::size_t r = 0; r < rob.size(); ++r) {
    const RobotData& d = rob[r];
    const std::string w = d.name;
    const std::vector<double>* st[6] = {&d.x, &d.y, &d.phi, &d.vx, &d.vy, &d.omega};
    for (int c = 0; c < 6; ++c) {
      start.add((*st[c])[0] - d.start[c], 1e-12 * (state_scale[c] + std::abs(d.start[c])),
                w + "." + kStates[c], 0);
      const double v = (*st[c])[N];
      if (std::isfinite(d.lower[c]))
        target.at_least(v, d.lower[c], kCert * (state_scale[c] + std::abs(d.lower[c])),
                        w + "." + kStates[c] + " (lower)", N);
      if (std::isfinite(d.upper[c]))
        target.at_most(v, d.upper[c], kCert * (state_scale[c] + std::abs(d.upper[c])),
                       w + "." + kStates[c] + " (upper)", N);
    }
    const double mumg = d.mu * d.M * g;
    for (int t = 0; t < N; ++t) {
      // Kinematics (semi-implicit Euler).
      kin.add(d.x[t + 1] - d.x[t] - h * d.vx[t + 1], kCert * s.length, w + ".x", t);
      kin.add(d.y[t + 1] - d.y[t] - h * d.vy[t + 1], kCert * s.length, w + ".y", t);
      kin.add(d.phi[t + 1] - d.phi[t] - h * d.omega[t + 1], kCert, w + ".phi", t);
      // Momentum.
      mom.add(d.M * (d.vx[t + 1] - d.vx[t]) - h * (d.Fx[t] + d.wx[t] + d.cx[t]),
              kCert * s.impulse(), w + ".x", t);
      mom.add(d.M * (d.vy[t + 1] - d.vy[t]) - h * (d.Fy[t] + d.wy[t] + d.cy[t]),
              kCert * s.impulse(), w + ".y", t);
      rot.add(d.I * (d.omega[t + 1] - d.omega[t]) -
                  h * (d.ct[t] - d.damping * d.M * g * d.omega[t + 1]),
              kCert * s.angular_impulse(), w, t);
      // Floor friction: inside the disk of radius mu M g; when sliding, maximum
      // dissipation on the K-gon: opposed to v[t+1], at least the K-gon's inradius.
      const double wn = std::hypot(d.wx[t], d.wy[t]);
      fric_max.at_most(wn, mumg, kCert * mumg, w, t);
      const double speed = std::hypot(d.vx[t + 1], d.vy[t + 1]);
      if (speed > 1e-6 && d.mu > 0) {
        ++out.moving_steps;
        const double cosine = (d.wx[t] * d.vx[t + 1] + d.wy[t] * d.vy[t + 1]) / (wn * speed);
        fric_dir.add(std::isfinite(cosine) && cosine < 0.0 ? 0.0 : 1.0, 0.5, w + " (dot >= 0)", t);
        // Maximum dissipation on the K-gon: within pi/K of -v.
        fric_cone.at_most(std::isfinite(cosine) ? cosine : 1.0, -std::cos(std::numbers::pi / d.K),
                          kCert, w, t);
        fric_mag.at_least(wn, mumg * std::cos(std::numbers::pi / d.K), kCert * mumg, w, t);
      }
      // Control bounds.
      if (d.dims == 0) {  // an object: no force at all
        force.add(d.Fx[t], 1e-12, w + ".Fx", t);  // [N]: written as exact zeros
        force.add(d.Fy[t], 1e-12, w + ".Fy", t);
      } else if (d.dims == 2) {
        force.at_most(std::abs(d.Fx[t]), d.F_max, 1e-12 * d.F_max, w + ".Fx", t);
        force.at_most(std::abs(d.Fy[t]), d.F_max, 1e-12 * d.F_max, w + ".Fy", t);
      } else {
        const json& a = doc["robots"][r]["force_axis"];
        const double ax = a[0], ay = a[1];
        axis.add(d.Fx[t] * ay - d.Fy[t] * ax, 1e-12 * d.F_max, w, t);
        force.at_most(std::hypot(d.Fx[t], d.Fy[t]), d.F_max, 1e-12 * d.F_max, w + ".|F|", t);
      }
    }
  }

  // Pairs. Expected contact force and torque on each robot, summed over pairs.
  std::vector<std::vector<std::array<double, 3>>> expected(
      rob.size(), std::vector<std::array<double, 3>>(N, {0.0, 0.0, 0.0}));
  int contact_pairs = 0;
  for (std::size_t p = 0; p < prs.size(); ++p) {
    const PairData& q = prs[p];
    const RobotData &a = rob[q.i], &b = rob[q.j];
    const std::string w = a.name + "-" + b.name;
    for (int t = 0; t <= N; ++t) {
      const double o = std::hypot(b.x[t] - a.x[t], b.y[t] - a.y[t]);
      dist.add(q.dist[t] - (o - a.R - b.R), kCert * s.length, w, t);
      if (q.contact)
        nonpen.at_least(q.dist[t], 0.0, kCert * s.length, w, t);
      else
        avoid.at_least(q.dist[t], q.safe, kCert * s.length, w, t);
    }
    if (!q.contact) {
      for (int t = 0; t < N; ++t) {
        no_force.add(q.fn[t], 1e-300, w + " normal_force", t);
        no_force.add(q.ft[t], 1e-300, w + " tangential_force", t);
      }
      continue;
    }
    ++contact_pairs;
    for (int t = 0; t < N; ++t) {
      out.max_normal_force = std::max(out.max_normal_force, q.fn[t]);
      out.max_tangential_force = std::max(out.max_tangential_force, std::abs(q.ft[t]));
      fn_pos.at_least(q.fn[t], 0.0, 1e-9, w, t);
      coulomb.at_most(std::abs(q.ft[t]), q.mu * q.fn[t], kCert * q.mu * q.fn[t] + 1e-12 * s.force,
                      w, t);
      if (q.fn[t] > 1e-9) compl_.at_most(q.dist[t + 1], 0.0, kCert * s.length, w, t);
      else compl_.add(0.0, 1.0, w, t);
      // Unit normal from i to j at step t, tangent = normal turned +90 degrees.
      const double nx0 = b.x[t] - a.x[t], ny0 = b.y[t] - a.y[t], o = std::hypot(nx0, ny0);
      const double nx = nx0 / o, ny = ny0 / o, tx = -ny, ty = nx;
      const double fx = q.fn[t] * nx + q.ft[t] * tx, fy = q.fn[t] * ny + q.ft[t] * ty;
      expected[q.j][t][0] += fx;
      expected[q.j][t][1] += fy;
      expected[q.i][t][0] -= fx;
      expected[q.i][t][1] -= fy;
      // The tangential force f t acts at -R_j n on j (torque -R_j f) and -f t at +R_i n on i
      // (torque -R_i f): both torques have the same sign.
      expected[q.j][t][2] += -b.R * q.ft[t];
      expected[q.i][t][2] += -a.R * q.ft[t];
    }
  }
  for (std::size_t r = 0; r < rob.size(); ++r) {
    const RobotData& d = rob[r];
    for (int t = 0; t < N; ++t) {
      const double tol = kCert * (s.force + std::abs(expected[r][t][0]) + std::abs(expected[r][t][1]));
      sum.add(d.cx[t] - expected[r][t][0], tol, d.name + ".contact_x", t);
      sum.add(d.cy[t] - expected[r][t][1], tol, d.name + ".contact_y", t);
      torque.add(d.ct[t] - expected[r][t][2], 1e-9 * s.force * s.length, d.name, t);
    }
  }
  // With a single contact pair the two robots' contact forces are opposite.
  if (contact_pairs == 1 && prs.size() == 1) {
    const RobotData &a = rob[prs[0].i], &b = rob[prs[0].j];
    for (int t = 0; t < N; ++t) {
      third.add(a.cx[t] + b.cx[t], 1e-12 * s.force + 1e-12 * std::abs(a.cx[t]), "x", t);
      third.add(a.cy[t] + b.cy[t], 1e-12 * s.force + 1e-12 * std::abs(a.cy[t]), "y", t);
    }
  }

  for (const Worst* c : {&start, &target, &kin, &mom, &rot, &fric_max, &force, &dist, &sum, &torque})
    c->expect();
  fric_dir.expect(false);
  fric_mag.expect(false);
  fric_cone.expect(false);
  axis.expect(false);
  nonpen.expect(false);
  avoid.expect(false);
  fn_pos.expect(false);
  coulomb.expect(false);
  compl_.expect(false);
  no_force.expect(false);
  third.expect(false);
  return out;
}

// ---------------------------------------------------------------------------
// Solving, writing, reading back.

struct Written {
  SceneSolve run;
  json doc;   // as built in memory
  json read;  // as parsed back from the file
};

std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("disco_solution_file_" + std::to_string(::getpid()) + "_" +
                               (info ? info->name() : "x"));
  std::filesystem::create_directories(dir);
  return dir;
}

// JSON has no infinities or NaNs (nlohmann writes them as null): every number
// of the document built in memory must be finite, else the file says something else.
void expect_all_finite(const json& v, const std::string& path, int& reported) {
  if (v.is_number_float() && !std::isfinite(v.get<double>())) {
    if (reported++ < 5) ADD_FAILURE() << "non-finite number " << v.get<double>() << " at " << path;
  } else if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) expect_all_finite(*it, path + "/" + it.key(), reported);
  } else if (v.is_array()) {
    for (std::size_t k = 0; k < v.size(); ++k) expect_all_finite(v[k], path + "/" + std::to_string(k), reported);
  }
}

Written solve_and_write(const std::string& yaml, const std::string& name) {
  Written w;
  const Scene scene = parse_scene(yaml, name + ".yaml");
  w.run = solve_scene(scene, Settings::load(default_settings_path()));
  w.doc = solution_json(*w.run.problem, w.run.z, w.run.info);
  int reported = 0;
  expect_all_finite(w.doc, "", reported);
  const std::filesystem::path dir = temp_dir();
  const std::string path = (dir / "solution.json").string();
  write_json_file(path, w.doc);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp")) << "temporary file left behind";
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read back " << path;
  std::stringstream text;
  text << in.rdbuf();
  try {
    w.read = json::parse(text.str());
  } catch (const std::exception& e) {
    ADD_FAILURE() << "solution.json does not parse: " << e.what();
  }
  EXPECT_TRUE(w.read == w.doc) << "the file must read back to the same document; differences "
                                   "(read -> written): "
                                << json::diff(w.read, w.doc).dump(-1).substr(0, 2000);
  std::filesystem::remove_all(dir);
  return w;
}

void print_summary(const Written& w, const PhysicsSummary& p) {
  std::printf("%s: status %s, T_f = %.6f s (lower_bound %g s), %d NLP solves, %d iterations, "
              "%.2f s wall; max normal force %.4g N, max |tangential| %.4g N, %d sliding steps\n",
              w.doc.value("scenario", "?").c_str(), w.doc.value("status", "?").c_str(),
              w.doc["T_f"].is_number() ? w.doc["T_f"].get<double>() : NAN,
              w.doc["lower_bound"].is_number() ? w.doc["lower_bound"].get<double>() : NAN,
              w.run.info.nlp_solves, w.run.info.iterations, w.run.info.wall_s,
              p.max_normal_force, p.max_tangential_force, p.moving_steps);
}

// ---------------------------------------------------------------------------
// Scenes. K = 8 and N_t = 10-12 keep each solve short (about 2 s and 0.4 s here).

// "box" can push only along y (D_ef = 1, axis [0, 1]) but its target lies 1.5 m
// or more along +x: only "pusher", starting behind it, can move it there, so
// the robots must touch and the normal force cannot be zero everywhere. The
// radii, masses, inertias, damping and gravity differ from the defaults so that
// a unit mix-up shows; box starts spinning so that damping matters.
const char* const kContactScene = R"(
scenario: push_box
steps: 10
gravity: 9.5
defaults: {mu: 0.2, K: 8}
robots:
  - name: pusher
    radius: 0.5
    mass: 1.2
    force_max: 6.0
    damping: 0.08
    start: {x: -1.2, y: 0.1}
  - name: box
    radius: 0.4
    mass: 0.8
    inertia: 0.07
    force_max: 4.0
    force_dims: 1
    force_axis: [0, 1]
    start: {x: 0, y: 0, phi: 0.3, omega: 1.0}
    target: {x: [1.5, 2.0], y: [-0.3, 0.3], vx: 0, vy: 0}
pairs:
  mode: contact
  mu: 0.3
)";

// A robot pushes a coin (an object: no force of its own) into a target box off its line.
const char* const kObjectScene = R"(
scenario: push_coin_small
steps: 15
robots:
  - {name: finger, radius: 0.15, mass: 1.0, mu: 0.2, force_max: 6.0, start: {x: -0.45, y: -0.1}}
objects:
  - name: coin
    radius: 0.3
    mass: 0.5
    mu: 0.3
    K: 8
    start: {x: 0, y: 0}
    target: {x: [0.9, 1.1], y: [0.1, 0.3], vx: 0, vy: 0}
)";

// Two robots of different sizes swap places; their straight paths overlap, so
// one must go round the other while keeping d_s = 0.05.
const char* const kAvoidScene = R"(
scenario: swap_avoid
steps: 12
defaults: {mu: 0.2, K: 8, force_max: 5.0}
robots:
  - name: left
    radius: 0.4
    mass: 1.0
    start: {x: 0, y: 0.1, omega: 0.5}
    target: {x: 3, y: [0.0, 0.2], vx: 0, vy: 0}
  - name: right
    radius: 0.6
    mass: 1.5
    force_max: 7.0
    start: {x: 3, y: -0.1}
    target: {x: 0, y: -0.1, vx: 0, vy: 0, omega: 0}
pairs:
  mode: avoid
  safe_distance: 0.05
)";

TEST(SolutionFile, ContactSceneMatchesThePhysicsInSiUnits) {
  const Written w = solve_and_write(kContactScene, "push_box");
  ASSERT_TRUE(w.run.solved()) << to_string(w.run.info.status) << " " << w.run.info.detail;
  ASSERT_TRUE(check_common_schema(w.read, *w.run.problem));
  ASSERT_TRUE(check_solved_schema(w.read));
  EXPECT_EQ(w.read["robots"][1]["force_axis"], json({0.0, 1.0})) << "box's force axis";
  const PhysicsSummary p = check_physics(w.read);
  print_summary(w, p);
  EXPECT_GT(p.max_normal_force, 1e-3) << "the pusher must push the box: normal force never positive";
  EXPECT_GT(p.moving_steps, 0);
}

// An object obeys the same laws with F = 0: its momentum changes only by floor friction and
// contact impulses (check_physics's momentum rows with Fx = Fy = 0), within its friction
// cone, without penetration; and it moved only because it was pushed.
TEST(SolutionFile, ObjectSceneMatchesThePhysicsInSiUnits) {
  const Written w = solve_and_write(kObjectScene, "push_coin_small");
  ASSERT_TRUE(w.run.solved()) << to_string(w.run.info.status) << " " << w.run.info.detail;
  ASSERT_TRUE(check_common_schema(w.read, *w.run.problem));
  ASSERT_TRUE(check_solved_schema(w.read));
  const json& coin = w.read["robots"][1];
  EXPECT_EQ(coin["kind"], "object");
  EXPECT_EQ(coin["F_max"].get<double>(), 0.0);
  EXPECT_EQ(coin["force_dims"].get<int>(), 0);
  for (const char* k : {"Fx", "Fy"})
    for (const json& v : coin[k]) EXPECT_EQ(v.get<double>(), 0.0) << "coin." << k;
  const PhysicsSummary p = check_physics(w.read);
  print_summary(w, p);
  EXPECT_GT(p.max_normal_force, 1e-3) << "the finger must push the coin";
  double moved = 0.0;
  for (const json& v : coin["vx"]) moved = std::max(moved, std::abs(v.get<double>()));
  EXPECT_GT(moved, 0.1) << "the coin slid";
}

TEST(SolutionFile, AvoidSceneMatchesThePhysicsInSiUnits) {
  const Written w = solve_and_write(kAvoidScene, "swap_avoid");
  ASSERT_TRUE(w.run.solved()) << to_string(w.run.info.status) << " " << w.run.info.detail;
  ASSERT_TRUE(check_common_schema(w.read, *w.run.problem));
  ASSERT_TRUE(check_solved_schema(w.read));
  const PhysicsSummary p = check_physics(w.read);
  print_summary(w, p);
  EXPECT_EQ(p.max_normal_force, 0.0);
  EXPECT_GT(p.moving_steps, 0);
  // No contact at all: every robot's contact force and torque is zero.
  for (const json& jr : w.read["robots"])
    for (const char* k : {"contact_x", "contact_y", "contact_torque"})
      for (const json& v : jr[k]) EXPECT_EQ(v.get<double>(), 0.0) << jr["name"] << "." << k;
}

TEST(SolutionFile, SceneWithoutSolutionHasStatusAndNullTrajectories) {
  // A robot that cannot reach its phi target (damping stops its spin short): no feasible point.
  const Written w = solve_and_write(model_test::kSpinShortScene, "spin_short");
  EXPECT_FALSE(w.run.solved());
  EXPECT_EQ(w.run.z.size(), 0);
  const json& doc = w.read;
  ASSERT_TRUE(check_common_schema(doc, *w.run.problem));
  EXPECT_EQ(doc["status"], "infeasible");
  EXPECT_FALSE(doc.contains("stationarity")) << "stationarity is documented only when solved";
  ASSERT_TRUE(doc.contains("status_detail")) << "status_detail is documented when not solved";
  EXPECT_TRUE(doc["status_detail"].is_string());
  const std::string detail = doc["status_detail"].get<std::string>();
  std::printf("spin_short: status %s, status_detail %s\n", doc["status"].dump().c_str(), detail.c_str());
  EXPECT_TRUE(detail == "infeasible" || detail == "elastic_not_tight" || detail == "failed")
      << "undocumented status_detail '" << detail << "'";
  has_null(doc, "T_f", "doc");
  has_null(doc, "h", "doc");
  has_null(doc, "time", "doc");
  for (std::size_t r = 0; r < doc["robots"].size(); ++r) {
    std::string missing, not_null;
    std::vector<const char*> keys(std::begin(kStates), std::end(kStates));
    keys.insert(keys.end(), std::begin(kSteps), std::end(kSteps));
    for (const char* k : keys) {
      if (!doc["robots"][r].contains(k)) missing += std::string(" ") + k;
      else if (!doc["robots"][r][k].is_null()) not_null += std::string(" ") + k;
    }
    EXPECT_TRUE(missing.empty() && not_null.empty())
        << "robots[" << r << "]: trajectory arrays must be present and null; missing:" << missing
        << "; not null:" << not_null;
  }
  ASSERT_EQ(doc["pairs"].size(), 1u);
  for (const char* k : {"gap", "normal_force", "tangential_force"})
    has_null(doc["pairs"][0], k, "pairs[0]");
  // Where the last attempt broke the model: robot a's rotation (its phi target is out of
  // reach), not robot b, which can reach its own target.
  ASSERT_TRUE(doc.contains("violations") && doc["violations"].is_array() && !doc["violations"].empty())
      << "violations are documented when not solved";
  const json& worst = doc["violations"][0];
  EXPECT_EQ(worst.value("owner", ""), "robot 'a'") << doc["violations"].dump();
  EXPECT_EQ(worst.value("family", "").rfind("rotation", 0), 0u) << doc["violations"].dump();
  EXPECT_GT(worst.value("amount", 0.0), 1e-6);
  for (const json& v : doc["violations"]) EXPECT_NE(v.value("owner", ""), "robot 'b'") << v.dump();
}

TEST(SolutionFile, ViolationsNameTheRobotAndTheFamilyOfEveryBrokenRowAndTarget) {
  const Written w = solve_and_write(kAvoidScene, "swap_avoid_violations");
  ASSERT_TRUE(w.run.solved());
  EXPECT_FALSE(w.read.contains("violations")) << "a solved file has none";
  const RobotProblem& problem = *w.run.problem;
  const double tol = 1e-6;
  EXPECT_TRUE(problem.violations(w.run.z, tol).empty()) << "a certified point breaks nothing";
  // Move robot 'right' (index 1) at step 5 by 0.1 (model units) in x: only its kinematics
  // rows (and the gap rows of its pair) can break; robot 'left' stays clean.
  Vector z = w.run.z;
  const int x5 = problem.layout().state_index(1, 5, kX);
  ASSERT_GE(x5, 0);
  z[x5] += 0.1;
  const auto v = problem.violations(z, tol);
  ASSERT_FALSE(v.empty());
  bool kinematics = false;
  for (const auto& e : v) {
    EXPECT_TRUE(e.owner == "robot 'right'" || e.owner == "pair ('left', 'right')") << e.owner << " " << e.family;
    kinematics = kinematics || (e.owner == "robot 'right'" && e.family == "kinematics");
  }
  EXPECT_TRUE(kinematics);
  // Its final x outside the target (x = 0): "target".
  z = w.run.z;
  const int xN = problem.layout().state_index(1, problem.scene().steps, kX);
  ASSERT_GE(xN, 0);
  z[xN] += 0.25;
  bool target = false;
  for (const auto& e : problem.violations(z, tol))
    target = target || (e.owner == "robot 'right'" && e.family == "target" && std::abs(e.amount - 0.25) < 1e-12);
  EXPECT_TRUE(target);
  EXPECT_NE(violations_text(problem.violations(z, tol)).find("robot 'right' target 2.5e-01"), std::string::npos)
      << violations_text(problem.violations(z, tol));
}

TEST(SolutionFile, ProvenanceNamesTheInputsWithTheirHashesAndTheVersion) {
  const std::string scene = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/one_robot_axis.yaml";
  Settings settings = Settings::load(default_settings_path());
  settings.apply_override("elastic.zeta=20");
  const json p = provenance_json({"search", scene, {"steps=20"}, {"scene.steps=20", "elastic.zeta=20"}, 7, 3, ""},
                                 settings);
  EXPECT_EQ(p.at("mode"), "search");
  EXPECT_EQ(p.at("scene_file"), scene);
  EXPECT_EQ(p.at("scene_sha256"), file_sha256(scene));
  EXPECT_EQ(p.at("scene_overrides"), json::array({"steps=20"}));
  EXPECT_EQ(p.at("overrides"), json::array({"scene.steps=20", "elastic.zeta=20"}));
  EXPECT_EQ(p.at("seed"), 7);
  EXPECT_EQ(p.at("start"), 3);
  EXPECT_EQ(p.at("settings_file"), default_settings_path());
  EXPECT_EQ(p.at("settings_sha256"), sha256_hex(settings.canonical_text()));
  EXPECT_NE(p.at("settings_sha256"), sha256_hex(Settings::load(default_settings_path()).canonical_text()))
      << "the settings hash is of the settings after the overrides";
  EXPECT_EQ(p.at("version"), disco_version());
  EXPECT_THROW(provenance_json({"solve", scene + ".missing", {}, {}, 1, 0, ""}, settings), InputError);
}

}  // namespace
}  // namespace disco
