// disco — where each unknown of the robot model lives (Appendix A's variables).
//
// Time grid: states at t = 0..N (N = N_t), intervals t = 0..N-1 between them.
// The step is h = T_f / N with T_f an unknown.
//
//   per robot i, state t = 1..N:   x, y, phi, vx, vy, omega
//                  (t = 0 is the given start: constants, not unknowns)
//   per robot i, interval t:       F (1 unknown along the force axis if D_ef = 1,
//                                  else F_x, F_y); floor friction beta_1..beta_K,
//                                  gamma (only if mu > 0)
//   per pair p,  state t = 1..N:   rho, the gap between the disks (t = 0: constant)
//   per contact pair, interval t:  c_n, alpha_1, alpha_2, gamma
//
// Accessors return Affine expressions, so a constant (t = 0) and an unknown
// are used alike by the constraint families. The layout also owns the rows of
// the momentum balance of each robot and interval (core/model/dynamics.h), to
// which the force-producing families add their impulses.
#pragma once

#include <array>
#include <vector>

#include "core/model/scene.h"
#include "core/nlp/polynomial_program.h"

namespace disco {

class Layout {
 public:
  // Creates every unknown in `P` (with only the bounds its kind implies:
  // multipliers >= 0, T_f > 0) for a scene in model units.
  Layout(const Scene& model_scene, PolynomialProgram& P);

  const Scene& scene() const { return scene_; }
  int steps() const { return scene_.steps; }

  int horizon_index() const { return t_f_; }
  Affine horizon() const { return Affine::variable(t_f_); }
  Affine step() const { return Affine::variable(t_f_, 1.0 / scene_.steps); }  // h

  Affine state(int robot, int t, int component) const;
  int state_index(int robot, int t, int component) const;  // -1 at t = 0
  // World-frame control force component (axis 0 = x, 1 = y) over interval t.
  Affine force(int robot, int t, int axis) const;
  bool has_floor_friction(int robot) const { return !robots_[robot].gamma.empty(); }
  Affine beta(int robot, int t, int k) const;
  Affine floor_gamma(int robot, int t) const;
  int beta_index(int robot, int t, int k) const;
  int floor_gamma_index(int robot, int t) const;
  // Force unknowns of robot i over interval t (1 or 2).
  const std::vector<int>& force_indices(int robot, int t) const { return robots_[robot].force[t]; }

  Affine gap(int pair, int t) const;               // rho
  int gap_index(int pair, int t) const;            // -1 at t = 0
  Affine centre_distance(int pair, int t) const;   // o = rho + R_i + R_j
  // N = p_j - p_i (not unit), T = N turned +90 degrees: (-N_y, N_x).
  Affine normal(int pair, int t, int axis) const;
  Affine tangent(int pair, int t, int axis) const;
  bool has_contact(int pair) const { return !pairs_[pair].cn.empty(); }
  Affine normal_force(int pair, int t) const { return Affine::variable(pairs_[pair].cn[t]); }
  Affine alpha1(int pair, int t) const { return Affine::variable(pairs_[pair].a1[t]); }
  Affine alpha2(int pair, int t) const { return Affine::variable(pairs_[pair].a2[t]); }
  Affine contact_gamma(int pair, int t) const { return Affine::variable(pairs_[pair].gamma[t]); }
  int normal_force_index(int pair, int t) const { return pairs_[pair].cn[t]; }
  int alpha1_index(int pair, int t) const { return pairs_[pair].a1[t]; }
  int alpha2_index(int pair, int t) const { return pairs_[pair].a2[t]; }
  int contact_gamma_index(int pair, int t) const { return pairs_[pair].gamma[t]; }

  // The per-step loops every constraint family runs: f(t, robot) for every
  // interval t = 0..N-1 and robot; f(t, pair) for every interval and contact
  // pair. Families state only what holds at one step.
  template <class F>
  void for_each_robot_step(F&& f) const {
    for (int t = 0; t < steps(); ++t)
      for (int i = 0; i < static_cast<int>(scene_.robots.size()); ++i) f(t, i);
  }
  template <class F>
  void for_each_contact_step(F&& f) const {
    for (int t = 0; t < steps(); ++t)
      for (int p = 0; p < static_cast<int>(scene_.pairs.size()); ++p)
        if (has_contact(p)) f(t, p);
  }

  // Momentum rows (axis 0: x, 1: y, 2: rotation) of robot i over interval t;
  // -1 until core/model/dynamics.h creates them.
  int momentum_row(int robot, int t, int axis) const;
  void set_momentum_row(int robot, int t, int axis, int row) { momentum_[robot][t][axis] = row; }

 private:
  struct RobotVars {
    std::vector<std::array<int, kStateSize>> state;  // [t], t = 0 unused
    std::vector<std::vector<int>> force, beta;       // [t][axis or k]
    std::vector<int> gamma;                          // [t]
  };
  struct PairVars {
    std::vector<int> rho;                  // [t], t = 0 unused
    std::vector<int> cn, a1, a2, gamma;    // [t], contact pairs only
  };
  Scene scene_;
  int t_f_ = -1;
  std::vector<RobotVars> robots_;
  std::vector<PairVars> pairs_;
  std::vector<std::vector<std::array<int, 3>>> momentum_;
};

}  // namespace disco
