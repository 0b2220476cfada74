// disco — the scene-adaptive model: which unknowns and rows a scene needs.
//
// The full model of Appendix A gives every robot six states per step and every
// pair a gap per step (plus contact forces and friction for contact pairs).
// Most of it is often idle: pairs that are far apart for the whole horizon, or
// meet only around one crossing; robots that nothing can turn. plan_model()
// decides, from the scene and the largest horizon T_max the solve considers,
// what the Layout (core/model/layout.h) builds. The decision is sound: every
// point of the full model with T_f <= T_max that satisfies the full model's
// constraints (complementarity exact) satisfies the constraints left out, with
// the unknowns left out at the values stated below. So the adaptive model IS
// the full model with the bound T_f <= T_max; the search never asks for more
// (search/objective_reduction.h: the feasibility horizon is the largest).
//
// 1. Speed bounds at states s = 0..N, with the largest step h = T_max / N
//    (every bound below grows with h, so it holds for every T_f <= T_max).
//    Fbar = sqrt(D_ef) F_max bounds |F| (the force box's corner).
//    A robot without contact pairs feels only F and floor friction f, with
//    |f| <= mu M g and, by maximum dissipation on the K-gon (core/model/
//    floor_friction.h: a sliding robot's friction sits on the vertex most
//    opposed to v, with sum beta = mu M g), f . v^{s+1} <= -mu M g c |v^{s+1}|,
//    c = cos(pi / K). From M (v^{s+1} - v^s) = h (F + f) (core/model/dynamics.h):
//        |v^{s+1}|^2 = v^{s+1} . (v^s + h F / M) + (h / M) f . v^{s+1}
//          =>  |v^{s+1}| <= |v^s| + h a,            a = (Fbar - mu M g c) / M > 0
//        |v^s| <= |v^{s+1}| + h b,                  b = (Fbar + mu M g) / M
//    so |v^s| <= u(s) = min(|v^0| + s h a,  V_T + (N - s) h b), V_T the largest
//    speed in the target velocity box (infinite if unbounded). An object (no force,
//    Robot::object) has Fbar = 0 and a = 0 (friction only slows it): alone, it keeps at
//    most its start speed; pushed, it takes its share of its component's energy below.
//    Robots joined by contact pairs (a connected component C of the graph of
//    contact-mode pairs) exchange impulses, and each impulse dissipates:
//    normal: c_n^s > 0 only if rho^{s+1} = 0, and with d = p^j - p^i its power
//    c_n N^s . (d^{s+1} - d^s) <= c_n |d^s| (R^i + R^j - |d^s|) <= 0 because
//    N^s = d^s (core/model/nonpenetration.h); contact friction, floor friction
//    and damping by maximum dissipation. So the energy
//    e^2 = sum_C (M |v|^2 + I omega^2) obeys e^{s+1} <= h G + sqrt((h G)^2 + (e^s)^2),
//    G^2 = sum_C (M a)^2 / M  (the control's power less the floor friction's,
//    F . v + f . v <= M a |v|, then Cauchy-Schwarz), and u(s) = e^s / sqrt(M)
//    for each robot of C.
// 2. Regions. With p^s = p^{s-1} + h v^s (core/model/kinematics.h), the centre
//    at state t lies within r_f(t) = h sum_{s <= t} u(s) of its start and within
//    r_b(t) = h sum_{s > t} u(s) of its target position box.
// 3. Pairs. Each region is the intersection of two rounded boxes (a disk is a
//    rounded point). The largest of the four distances between one rounded box
//    of each robot bounds the centre distance from below; state t is kept if it
//    is at most R^i + R^j + d + margin (d = d_s for avoid pairs, 0 for contact
//    pairs; margin = kReachMargin (R^i + R^j)). A pair keeps the states from
//    its first kept one to its last (the window); outside it, avoidance holds
//    and no contact force can act (c_n > 0 needs rho = 0), so gaps, avoidance
//    bounds and contact unknowns there are left out (contact forces = 0).
// 4. Rotation. Only contact-friction torques and, from a nonzero start spin,
//    damping turn a robot. A robot with omega^0 = 0 and no contact pair with
//    mu > 0 and a window keeps phi = phi^0 and omega = 0: constants, not
//    unknowns, unless its target box excludes them (then the unknowns stay, so
//    the solver reports the infeasibility as the full model would).
// Obstacles (core/model/obstacles.h) take part as pairs: a disk-obstacle pair keeps
//    the states where the disk's region comes within reach of the obstacle's place (a
//    wall's segment, or a moving disk's way up to the next state, rounded by its radius).
//    A pair tests state t with the region r_f(t + 1), r_b(t - 1), which holds the
//    straight moves from t - 1 to t and from t to t + 1 (convex regions, r_f growing and
//    r_b shrinking), so every step that can come within reach carries its swept row
//    (core/model/swept.h). That row is the one exception to "the adaptive model IS the
//    full model": it is conservative (a step near an obstacle is at most as long as the
//    obstacle-free disks around its ends cover), and the adaptive model leaves it out
//    where the move provably stays beyond reach, where the full model keeps it. A fixed
//    obstacle's impulses never add energy (the distance to a convex set is convex, so
//    the normal impulse's power is <= 0 as in item 1; friction by maximum
//    dissipation); a disk in contact with one takes the energy bound of item 1, which
//    counts spin. Contact with a moving obstacle is refused by the scene parser: it
//    could add energy.
// 5. A contact pair with mu = 0 has no friction unknowns: its complementarity
//    forces alpha_1 = alpha_2 = 0 (and gamma needs only gamma >= |v_T|).
// Contact-pair gaps are unknowns bounded below by 0 at every kept state
// (core/model/layout.h), as the full model's are, so the normal impulse's power
// bound (item 1) holds at every interval, the first of a window included.
// Left as before (already minimal in core/model/layout.h): D_ef = 1 has one
// force unknown per step, mu = 0 has no floor friction, avoid pairs no contact
// forces.
#pragma once

#include <vector>

#include "core/model/scene.h"

namespace disco {

// What to build. ModelOptions{} is the full model of Appendix A; whether disco builds the
// adaptive one is the setting model.adaptive (configs/disco.yaml, read by model_options in
// core/config/solver_settings.h), not a default kept here.
struct ModelOptions {
  bool adaptive = false;      // true: only what the scene needs (this header); false: the full model
  double horizon_max = kInf;  // T_max [s]; infinite keeps every pair at every step
};

struct PairPlan {
  // The pair's window: states first..last (1 <= first <= last <= N) where the
  // two robots may be within reach; empty (first > last) if they never are.
  int first = 1, last = 0;
  bool friction = false;  // contact friction unknowns (contact mode, and mu > 0 unless full)
  bool empty() const { return first > last; }
};

struct ModelPlan {
  std::vector<PairPlan> pairs;  // per Scene::pairs entry, then per Scene::obstacle_pairs entry
  std::vector<bool> rotates;    // per robot: phi and omega are unknowns
  int pair_states() const;      // sum of the pairs' window lengths
  int turning_robots() const;
};

// Relative safety margin of the reach test, against the certificate's tolerances.
inline constexpr double kReachMargin = 1e-3;

// The plan for `scene` (any consistent units; T_max in its time unit). Not
// adaptive: every pair at every state, every robot turns, contact pairs carry
// friction unknowns even with mu = 0 (Appendix A as written).
ModelPlan plan_model(const Scene& scene, bool adaptive, double horizon_max);

// The speed bounds u(s), s = 0..N, of every robot (item 1 above), for the
// step h. Exposed for tests.
std::vector<std::vector<double>> speed_bounds(const Scene& scene, double h);

// Connected components of the graph of contact-mode pairs: a label per disk (robot or
// object), the same for disks that may push each other, directly or through others.
std::vector<int> contact_components(const Scene& scene);

}  // namespace disco
