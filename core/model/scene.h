// disco — a scene: the robots, their pairs and the time grid, in SI units.
//
// This is what a scene file (core/model/scene_yaml.h) describes and what the
// robot model (core/model/robot_problem.h) is built from. Every number here has
// already been validated by the parser; the model may rely on the invariants
// written beside each field.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/util/numbers.h"

namespace disco {

// The six state components of a disk robot, in this order everywhere in disco
// (state arrays, target boxes, solution files).
enum StateIndex { kX = 0, kY = 1, kPhi = 2, kVx = 3, kVy = 4, kOmega = 5 };
inline constexpr int kStateSize = 6;
// Their names, in scene files (start, target) and solution files.
inline constexpr std::array<const char*, kStateSize> kStateNames = {"x", "y", "phi", "vx", "vy", "omega"};
using State = std::array<double, kStateSize>;

// A robot's position and orientation (x, y, phi): what a path of a guess gives per state.
using Pose = std::array<double, 3>;

// A closed interval per state component; -inf / +inf where unbounded.
struct StateBox {
  State lower{-kInf, -kInf, -kInf, -kInf, -kInf, -kInf};
  State upper{kInf, kInf, kInf, kInf, kInf, kInf};
};

// A disk of the scene: a robot (it pushes with its own force) or, with `object` set, a
// passive object (a coin: no force of its own, force_dims = 0 and force_max = 0; it slides
// with floor friction and turns with damping like a robot, and moves only when a robot or
// another object pushes it through a contact pair). Scene::robots lists the robots first,
// then the objects; every model family treats both alike, with the force 0 for an object.
struct Robot {
  std::string name;         // unique within the scene (robots and objects together)
  bool object = false;      // a passive object (scene file: `objects`), not a robot
  double radius = 0;        // R > 0 [m]
  double mass = 0;          // M > 0 [kg]
  double inertia = 0;       // I > 0 [kg m^2]; 0.5 M R^2 (uniform disk) unless given
  double mu = 0;            // floor friction coefficient, >= 0
  double damping = 0;       // sigma_d >= 0 [m s]: floor torque = -sigma_d M g omega
  double force_max = 0;     // F_max > mu M g [N]: |F_x|, |F_y| <= F_max (infinity norm); 0: object
  int force_dims = 2;       // D_ef: 1 (force along force_axis only) or 2; 0: an object
  std::array<double, 2> force_axis{1.0, 0.0};  // unit vector, used when force_dims == 1
  int friction_edges = 16;  // K >= 3: vertices of the floor-friction polygon
  State start{};            // initial state (x, y, phi, vx, vy, omega)
  StateBox target;          // terminal box on the state at T_f

  // Fbar = sqrt(D_ef) F_max: the largest |F| the force box allows (its corner); 0 for an object.
  double push_bound() const { return std::sqrt(static_cast<double>(force_dims)) * force_max; }
};

enum class PairMode {
  kAvoid,    // the paper's set A: rho >= d_s at every step, no contact forces
  kContact,  // the paper's set B: 0 <= c_n _|_ rho >= 0 and Coulomb contact friction
};

struct Pair {
  int i = 0, j = 0;             // indices into Scene::robots (robots or objects), i < j; in
                                // Scene::obstacle_pairs, j indexes Scene::obstacles
  PairMode mode = PairMode::kAvoid;
  double safe_distance = 0;     // d_s >= 0 [m] (avoid mode)
  double mu = 0;                // contact friction coefficient >= 0 (contact mode)
};

// A fixed or moving obstacle (the paper's Section VI): it has no unknowns and nothing moves
// it. A disk of `radius` centred at `from` + tau `velocity` at time tau (a fixed post when
// the velocity is 0), or a wall: the segment from `from` to `to` (|to - from| > 0) thickened
// by `radius` (half the wall's thickness, >= 0), i.e. a capsule. Robots and objects meet
// it through Scene::obstacle_pairs (core/model/obstacles.h).
enum class ObstacleShape { kDisk, kWall };
// A place a moving disk obstacle passes at a given time (core/model/obstacle_path.h).
struct Waypoint {
  double t = 0;                        // [s] from the start, t = 0
  std::array<double, 2> p{0.0, 0.0};  // [m]
};

struct Obstacle {
  std::string name;             // unique within the scene (robots, objects and obstacles)
  ObstacleShape shape = ObstacleShape::kDisk;
  std::array<double, 2> from{0.0, 0.0};      // a disk's centre at tau = 0; a wall's first end
  std::array<double, 2> to{0.0, 0.0};        // a wall's second end (unused for a disk)
  std::array<double, 2> velocity{0.0, 0.0};  // a disk's constant velocity [m/s]; 0 for a wall
  // A disk that follows waypoints instead (>= 2, times increasing; velocity is then 0):
  // the smooth path through them (core/model/obstacle_path.h).
  std::vector<Waypoint> path;
  double radius = 0;            // disk: > 0; wall: half its thickness, >= 0 [m]
  bool moves() const { return velocity[0] != 0.0 || velocity[1] != 0.0 || !path.empty(); }
};

// Where a scene key was given, for messages made after the scene was read
// (located_message, core/util/errors.h): the file and its line, or "--set" and line 0
// with the override's key. An empty source: not known (a scene made in code).
struct KeyOrigin {
  std::string source;
  int line = 0;
  std::string key;
};

// What the model minimises (scene file `objective`; core/model/objective.h):
//   kTime        T_f, the paper's objective (the default);
//   kEnergy      E = sum over robots and intervals of h |F^t|^2 [N^2 s] at the fixed
//                T_f = `horizon`;
//   kTimeEnergy  T_f + w E [s], w = `energy_weight` [1/N^2], T_f free.
enum class ObjectiveKind { kTime, kEnergy, kTimeEnergy };
struct Objective {
  ObjectiveKind kind = ObjectiveKind::kTime;
  double horizon = 0;        // kEnergy: the fixed T_f > 0 [s]; 0 otherwise
  double energy_weight = 0;  // kTimeEnergy: w > 0 [1/N^2]; 0 otherwise
};

struct Scene {
  std::string name;             // the scenario's name
  std::string source;           // the file it came from (for messages)
  int steps = 100;              // N_t >= 1
  KeyOrigin steps_origin;       // where `steps` was given (core/model/model_size.h names it)
  double gravity = 9.81;        // g > 0 [m/s^2]
  std::vector<Robot> robots;    // at least one robot, then the objects (Robot::object)
  std::vector<Pair> pairs;      // exactly one per pair of disks (i < j), in (i, j) order
  std::vector<Obstacle> obstacles;
  // One per (disk, obstacle): i indexes robots, j obstacles; in (j, i) order.
  std::vector<Pair> obstacle_pairs;
  Objective objective;
};

}  // namespace disco
