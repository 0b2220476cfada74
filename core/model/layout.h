// disco — where each unknown of the robot model lives (Appendix A's variables).
//
// Time grid: states at t = 0..N (N = N_t), intervals t = 0..N-1 between them.
// The step is h = T_f / N with T_f an unknown.
//
//   per robot i, state t = 1..N:   x, y, phi, vx, vy, omega
//                  (t = 0 is the given start: constants, not unknowns;
//                  phi, omega stay constants of a robot that does not turn)
//   per robot i, interval t:       F (1 unknown along the force axis if D_ef = 1,
//                                  else F_x, F_y); floor friction beta_1..beta_K,
//                                  gamma (only if mu > 0)
//   per pair p,  state t:          the gap rho between the disks, at the states of
//                                  the pair's window (t = 0: constant)
//   per contact pair, interval t:  c_n (and alpha_1, alpha_2, gamma with friction)
//                                  for the intervals ending in the window
//   per wall pair, state t:        the closest point's parameter s and its two
//                                  projection multipliers (core/model/obstacles.h)
//   per pair with an obstacle that follows waypoints, state t: its centre q^t
//                                  (core/model/obstacle_path.h)
//
// Pairs. A pair index p runs over Scene::pairs (two disks) and then over
// Scene::obstacle_pairs (a disk and an obstacle): pair(p) is either. Member i is
// always a disk; member j is a disk or an obstacle, whose "state" other_state()
// gives: its centre (a wall: its point nearest to disk i, a + s d; a path obstacle: the
// unknown q^t), its constant velocity, and phi = omega = 0. Nothing pushes an obstacle: its member has no
// momentum rows (other_disk() is -1), so the families add impulses to i only.
//
// What exists is decided by a ModelPlan (core/model/model_plan.h): the full
// model of Appendix A, or only what the scene needs. For a contact pair with
// window [first, last], the contact intervals are first-1 .. last-1 (c_n^t
// pairs with rho^{t+1}) and rho exists at states first-1 .. last (contact
// friction at interval t uses rho^t); an avoid pair has rho at first .. last.
//
// Accessors return Affine expressions, so a constant (t = 0) and an unknown
// are used alike by the constraint families. The layout also owns the rows of
// the momentum balance of each robot and interval (core/model/dynamics.h), to
// which the force-producing families add their impulses.
#pragma once

#include <array>
#include <cstring>
#include <vector>

#include "core/model/model_plan.h"
#include "core/model/scene.h"
#include "core/nlp/polynomial_program.h"

namespace disco {

class Layout {
 public:
  // Creates the unknowns `plan` asks for in `P` (with only the bounds their
  // kind implies: multipliers >= 0, T_f > 0) for a scene in model units.
  Layout(const Scene& model_scene, const ModelPlan& plan, PolynomialProgram& P);

  // The scene in model units (core/model/units.h); RobotProblem::scene() is the same
  // scene in SI units, as the user wrote it.
  const Scene& model_scene() const { return scene_; }
  int steps() const { return scene_.steps; }

  int horizon_index() const { return t_f_; }
  Affine horizon() const { return Affine::variable(t_f_); }
  Affine step() const { return Affine::variable(t_f_, 1.0 / scene_.steps); }  // h

  // A constant at t = 0, and for phi and omega of a robot that does not turn.
  Affine state(int robot, int t, int component) const;
  int state_index(int robot, int t, int component) const;  // -1 where state() is a constant
  bool rotates(int robot) const { return robots_[robot].rotates; }
  // World-frame control force component (axis 0 = x, 1 = y) over interval t; the constant 0
  // for an object (Robot::object: no force unknowns).
  Affine force(int robot, int t, int axis) const;
  bool has_floor_friction(int robot) const { return !robots_[robot].gamma.empty(); }
  Affine beta(int robot, int t, int k) const;
  Affine floor_gamma(int robot, int t) const;
  int beta_index(int robot, int t, int k) const;
  int floor_gamma_index(int robot, int t) const;
  // Force unknowns of robot i over interval t (1 or 2; none for an object).
  const std::vector<int>& force_indices(int robot, int t) const { return robots_[robot].force[t]; }

  // Pairs: Scene::pairs, then Scene::obstacle_pairs (see the header).
  int num_pairs() const { return static_cast<int>(pairs_.size()); }
  bool with_obstacle(int pair) const { return pair >= static_cast<int>(scene_.pairs.size()); }
  const Pair& pair(int p) const {
    return with_obstacle(p) ? scene_.obstacle_pairs[p - scene_.pairs.size()] : scene_.pairs[p];
  }
  const Obstacle& obstacle(int pair) const;  // needs with_obstacle
  int other_disk(int pair) const { return with_obstacle(pair) ? -1 : this->pair(pair).j; }
  double radius_sum(int pair) const;        // R_i + R_j, or R_i + the obstacle's radius
  // Member j's state component c at state t (a disk's state(), or the obstacle's, above).
  Affine other_state(int pair, int t, int component) const;
  // A wall pair's projection unknowns at state t >= 1 in its window (-1 otherwise).
  bool is_wall_pair(int pair) const;
  int wall_parameter_index(int pair, int t) const { return t == 0 ? -1 : pairs_[pair].s[t]; }
  int wall_low_index(int pair, int t) const { return t == 0 ? -1 : pairs_[pair].low[t]; }
  int wall_high_index(int pair, int t) const { return t == 0 ? -1 : pairs_[pair].high[t]; }
  Affine wall_parameter(int pair, int t) const;  // s: the constant projection at t = 0
  // A pair whose obstacle follows waypoints: the unknown centre q^t (axis 0: x, 1: y) at a
  // state t >= 1 in its window (-1 otherwise).
  bool follows_path(int pair) const { return with_obstacle(pair) && !obstacle(pair).path.empty(); }
  int path_point_index(int pair, int t, int axis) const { return t == 0 ? -1 : pairs_[pair].q[axis][t]; }

  bool has_gap(int pair, int t) const;             // t = 0, or rho^t is an unknown
  Affine gap(int pair, int t) const;               // rho; needs has_gap
  int gap_index(int pair, int t) const;            // -1 at t = 0
  Affine centre_distance(int pair, int t) const;   // o = rho + R_i + R_j; needs has_gap
  // N = p_j - p_i (not unit), T = N turned +90 degrees: (-N_y, N_x).
  Affine normal(int pair, int t, int axis) const;
  Affine tangent(int pair, int t, int axis) const;
  bool is_contact(int pair) const { return pair_mode(pair) == PairMode::kContact; }
  PairMode pair_mode(int p) const { return pair(p).mode; }
  // Contact interval t: c_n^t exists (and, with friction, alpha_1, alpha_2, gamma).
  bool has_contact(int pair, int t) const { return pairs_[pair].cn[t] >= 0; }
  bool has_contact_friction(int pair) const { return pairs_[pair].friction; }
  // Contact unknowns of interval t; the constant 0 outside the window (no force acts).
  // c_n is the normal force's multiplier, not the force: the push on j is c_n N, of
  // magnitude c_n o (core/model/nonpenetration.h).
  Affine normal_multiplier(int pair, int t) const { return contact_value(pairs_[pair].cn, t); }
  Affine alpha1(int pair, int t) const { return contact_value(pairs_[pair].a1, t); }
  Affine alpha2(int pair, int t) const { return contact_value(pairs_[pair].a2, t); }
  Affine contact_gamma(int pair, int t) const { return contact_value(pairs_[pair].gamma, t); }
  int normal_multiplier_index(int pair, int t) const { return pairs_[pair].cn[t]; }  // -1 if none
  int alpha1_index(int pair, int t) const { return pairs_[pair].a1[t]; }
  int alpha2_index(int pair, int t) const { return pairs_[pair].a2[t]; }
  int contact_gamma_index(int pair, int t) const { return pairs_[pair].gamma[t]; }

  // The per-step loops every constraint family runs: f(t, robot) for every
  // interval t = 0..N-1 and robot; f(t, pair) for every contact interval of
  // every contact pair (its window); f(t, pair) for every state t = 1..N with
  // a gap unknown. Families state only what holds at one step.
  template <class F>
  void for_each_robot_step(F&& f) const {
    for (int t = 0; t < steps(); ++t)
      for (int i = 0; i < static_cast<int>(scene_.robots.size()); ++i) f(t, i);
  }
  template <class F>
  void for_each_contact_step(F&& f) const {
    for (int t = 0; t < steps(); ++t)
      for (int p = 0; p < num_pairs(); ++p)
        if (has_contact(p, t)) f(t, p);
  }
  template <class F>
  void for_each_gap_state(F&& f) const {
    for (int t = 1; t <= steps(); ++t)
      for (int p = 0; p < num_pairs(); ++p)
        if (pairs_[p].gap[t] >= 0) f(t, p);
  }

  // Momentum rows (axis 0: x, 1: y, 2: rotation) of robot i over interval t;
  // -1 until core/model/dynamics.h creates them.
  int momentum_row(int robot, int t, int axis) const;
  void set_momentum_row(int robot, int t, int axis, int row) { momentum_[robot][t][axis] = row; }

  // Who a row belongs to, for reports (PolynomialProgram::add_row's tag): a family's name
  // ("dynamics", "kinematics", ...) and a robot or a pair. row_tag() gives the same tag
  // for the same owner; row_owner() reads it back.
  struct RowOwner {
    const char* family;
    bool pair;  // index is a pair's, else a robot's
    int index;
  };
  int robot_row_tag(const char* family, int robot) { return row_tag({family, false, robot}); }
  int pair_row_tag(const char* family, int pair) { return row_tag({family, true, pair}); }
  const RowOwner& row_owner(int tag) const { return owners_[tag]; }

 private:
  Affine contact_value(const std::vector<int>& index, int t) const {
    return index[t] >= 0 ? Affine::variable(index[t]) : Affine(0.0);
  }

  struct RobotVars {
    bool rotates = true;
    std::vector<std::array<int, kStateSize>> state;  // [t], t = 0 unused; -1: constant
    std::vector<std::vector<int>> force, beta;       // [t][axis or k]
    std::vector<int> gamma;                          // [t]
  };
  struct PairVars {
    bool friction = false;
    std::vector<int> gap;                  // [state t], -1: none (t = 0: the constant)
    std::vector<int> cn, a1, a2, gamma;    // [interval t], -1: none
    std::vector<int> s, low, high;         // [state t], wall pairs only, -1: none
    std::array<std::vector<int>, 2> q;     // [axis][state t], path obstacle pairs only
  };
  Scene scene_;
  int t_f_ = -1;
  std::vector<RobotVars> robots_;
  std::vector<PairVars> pairs_;
  std::vector<std::vector<std::array<int, 3>>> momentum_;
  std::vector<RowOwner> owners_;  // by tag

  int row_tag(const RowOwner& o) {
    for (std::size_t k = 0; k < owners_.size(); ++k)
      if (owners_[k].index == o.index && owners_[k].pair == o.pair &&
          std::strcmp(owners_[k].family, o.family) == 0)
        return static_cast<int>(k);
    owners_.push_back(o);
    return static_cast<int>(owners_.size()) - 1;
  }
};

}  // namespace disco
