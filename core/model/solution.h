// disco — the solution file (solution.json), in SI units.
//
// Schema (documented for users in core/README.md, "The solution file"):
//   scenario, status, status_detail (when not solved), violations (when not solved: [{owner,
//   family, amount}], RobotProblem::violations at the last feasibility attempt), T_f, N_t, h,
//   time (N_t + 1 values: t_k = k h, 0 to T_f; null without a solution), g, lower_bound (or null),
//   model {variables, constraints, complementarity_pairs},
//   certificate {max_violation, max_complementarity, complementarity_product, units},
//   timing {wall_s, nlp_solves, iterations, kkt {factorisations, fallbacks, threshold_raises,
//   to_pivoted, nested_dissection, polish_rescues}},
//   robots[]: name, kind ("robot", or "object": a passive disk, F_max = 0, force_dims = 0,
//     Fx = Fy = 0; objects follow the robots), radius, mass, inertia, mu, damping, F_max,
//     force_dims, K,
//     start[6], target {lower[6], upper[6]} (null where unbounded),
//     x, y, phi, vx, vy, omega (N_t + 1 values; index 0 = the start),
//     Fx, Fy, friction_x, friction_y, contact_x, contact_y, contact_torque (N_t values:
//     over the step from t to t+1; contact_* sum every contact force on the robot);
//   pairs[]: i, j, robot_i, robot_j (the robots' names), mode, safe_distance, mu,
//     gap (N_t + 1: rho, from the centres),
//     normal_force (N_t: push of i on j along the unit vector from i's centre to j's),
//     tangential_force (N_t: i's force on j along that unit vector turned +90 degrees);
//     the force on i is the opposite;
//   obstacles[]: name, shape ("disk" or "wall"), radius (a wall: half its thickness); a disk:
//     centre (at t = 0), and velocity (constant: its centre at t_k is centre + t_k velocity)
//     or path ([{t, x, y}], its waypoints: core/model/obstacle_path.h), and x, y (N_t + 1
//     values: its centre at each t_k; absent without a solution); a wall: from, to (its ends);
//   obstacle_pairs[]: i, j (indices into robots and obstacles), robot_i, obstacle, mode,
//     safe_distance, mu, gap, normal_force, tangential_force: as pairs[], with the
//     obstacle as member j (nothing moves it; its force on i is the opposite of j's);
//     swept_gap (N_t: the least gap while the disk moves straight from state t to t+1,
//     core/model/obstacles.h swept_distance; below 0 the disk passed through the obstacle
//     between two states: raise steps);
//   provenance (added by disco solve and disco search, provenance_json): mode ("solve" or
//     "search"), scene_file, scene_sha256 (of the file's bytes), scene_overrides (applied to the
//     scene: a benchmark entry's `set`, then --set scene.*, without the prefix), overrides (the
//     command's --set list as given), seed, start, settings_file, settings_sha256 (of
//     Settings::canonical_text(), after the overrides), version (disco_version()), guess (the
//     --guess file the start began from, {file, sha256}, or null); a search's best/SCENE.json
//     adds run (the start's runs.jsonl line, search/search_record.h).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/config/settings.h"

#include "core/elastic/elastic_solver.h"
#include "core/model/robot_problem.h"

namespace disco {

struct SolutionInfo {
  MpccStatus status = MpccStatus::kFailed;  // the file's "status": to_string(status)
  std::string detail;  // when not solved: the last feasibility solve's own status
  std::optional<Stationarity> stationarity;  // when solved: what the point is for min T_f
  // When not solved: where the last feasibility attempt's point breaks the model, largest
  // first (RobotProblem::violations).
  std::vector<RobotProblem::Violation> violations;
  Certificate certificate;
  double wall_s = 0.0;
  int nlp_solves = 0, iterations = 0;
  // KKT factorisations of its Ipopt solves, how many of them went to MUMPS because
  // disco's LDLᵀ could not serve the matrix, and how often the pivoting LDLᵀ raised its
  // threshold, and how many matrices the LDLᵀ passed to the pivoting one (core/ipopt/kkt_solver.h);
  // how many analyses kept nested dissection (KktCounts::nested_dissection).
  int kkt_factorisations = 0, kkt_fallbacks = 0, kkt_threshold_raises = 0, kkt_to_pivoted = 0;
  int kkt_polish_rescues = 0;
  int kkt_nested_dissection = 0;
};

// The trajectory of point z (model units) of `problem`, with `info`; z may be
// empty (no solution): then T_f and the arrays are null.
nlohmann::json solution_json(const RobotProblem& problem, const Vector& z, const SolutionInfo& info);

// Where a solution came from.
struct Provenance {
  std::string mode;                          // "solve" or "search"
  std::string scene_file;                    // as given
  std::vector<std::string> scene_overrides;  // applied to the scene (KEY=VALUE, no "scene.")
  std::vector<std::string> overrides;        // the command's --set list, as given
  std::uint64_t seed = 1;
  int start = 0;
  std::string guess;  // the --guess file the start began from ("": none)
};
// `p` with the scene file's SHA-256 (InputError if it cannot be read), the settings' file and
// SHA-256, and disco's version: the file's "provenance".
nlohmann::json provenance_json(const Provenance& p, const Settings& settings);

// "at the last attempt, the largest violations (model units): robot 'a' rotation kinematics
// 3.1e-01, ..." for the `most` largest; "" when there are none.
std::string violations_text(const std::vector<RobotProblem::Violation>& violations,
                            std::size_t most = 3);

// Writes JSON to `path` atomically (temporary file, then rename).
void write_json_file(const std::string& path, const nlohmann::json& doc);

}  // namespace disco
