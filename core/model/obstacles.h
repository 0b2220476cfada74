// disco — fixed and moving obstacles (the paper's Section VI): disks, and walls as capsules.
//
// An obstacle (Scene::obstacles, core/model/scene.h) has no unknowns and nothing pushes
// it. Each (disk, obstacle) pair is a pair like two disks (core/model/layout.h: member j
// is the obstacle), so the same families hold for it:
//   gap             (rho + R_i + R_o)^2 = |q^t - p^t|^2          (core/model/gap.h)
//   avoid           rho^t >= d_s                                   (core/model/avoidance.h)
//   contact         0 <= c_n^t _|_ rho^{t+1} >= 0, Coulomb friction with the obstacle's
//                   velocity and omega = 0; impulses act on the disk only
//                   (core/model/nonpenetration.h, core/model/contact_friction.h)
// with q^t the obstacle's point nearest to the disk's centre p^t and R_o its radius:
//   disk  q^t = q^0 + t h v,  h = T_f / N: affine in the unknown T_f, so a moving disk
//         (constant velocity v, the paper's "moving obstacles") keeps every row polynomial
//         and its derivatives exact; or, for a disk that follows waypoints, q^t unknowns
//         defined by rows q^t = Q(t h) on a smooth path Q (core/model/obstacle_path.h);
//   wall  q^t = a + s^t d,  d = b - a, R_o = half the thickness: a capsule.
//
// The nearest point of a wall. Its distance |p - a - s d| is not smooth in p where the
// centre passes a wall's end (the nearest point switches from the segment's inside to
// the end), and a closed form with a min or a clamp would have unbounded or missing
// second derivatives there. disco makes s^t an unknown in [0, 1] defined by the
// first-order conditions of min_s |a + s d - p|^2 (convex in s, |d| > 0, so exactly
// one minimiser):
//     N . d / |d| - lambda_lo + lambda_hi = 0,     N = a + s d - p
//     0 <= lambda_lo _|_ s >= 0,      0 <= lambda_hi _|_ 1 - s >= 0
// Every row is polynomial (degree 2), so derivatives are exact and bounded everywhere,
// the ends of a wall included; the two complementarity pairs are the MPCC's own, solved
// and certified like the contact conditions (core/elastic/). The rows exist at the
// pair's gap states (its window, core/model/model_plan.h); at t = 0 s is the
// projection of the start, a constant.
#pragma once

#include <array>

#include "core/model/layout.h"
#include "core/model/scene.h"

namespace disco {

// The projection rows above for every wall pair's gap state (the gap family builds them).
void add_wall_projection(Layout& L, PolynomialProgram& P);

// s in [0, 1] of the point of wall `ob` nearest to `p` (any consistent units).
double wall_projection(const Obstacle& ob, const std::array<double, 2>& p);
// A disk obstacle's centre at time tau (a wall's first end).
std::array<double, 2> obstacle_centre(const Obstacle& ob, double tau);
// The box [lo, hi] (per axis) of the obstacle's core over times [tau0, tau1]: a wall's
// segment, a disk's centres.
std::array<std::array<double, 2>, 2> obstacle_box(const Obstacle& ob, double tau0, double tau1);
// The obstacle's point nearest to `p` at time tau (a disk's centre, a wall's nearest point).
std::array<double, 2> obstacle_point(const Obstacle& ob, const std::array<double, 2>& p, double tau);
// |p - obstacle_point|: the disk's centre distance to the obstacle's centre or centre line.
double obstacle_distance(const Obstacle& ob, const std::array<double, 2>& p, double tau);
// The least such distance an obstacle pair allows: R_i + R_o (+ d_s for an avoid pair).
double obstacle_clearance(const Scene& scene, const Pair& pair);

// Between the states. The rows above hold at the N_t states, like the paper's pair
// constraints: a disk that moves farther in one step than an obstacle is thick can jump
// over it (a thin wall, few steps). swept_distance() measures what the rows do not: the
// least distance from the obstacle's core to the disk's centre moving straight from p0 (at
// time tau0) to p1 (at tau1), the obstacle moving on as well (straight between its places
// at tau0 and tau1, for a path obstacle too). The solution file reports it
// per step (obstacle_pairs[].swept_gap) and `disco solve` warns when it is below the
// clearance.
double swept_distance(const Obstacle& ob, const std::array<double, 2>& p0,
                      const std::array<double, 2>& p1, double tau0, double tau1);

// Sets the projection unknowns (s, lambda_lo, lambda_hi) of every wall pair in z from the
// disk centres in z: the exact projection and its multipliers; and a path obstacle's
// centres q^t from the T_f in z (for guesses and transfers).
void complete_obstacle_unknowns(const Layout& L, VectorRef z);

}  // namespace disco
