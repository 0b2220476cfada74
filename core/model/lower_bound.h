// disco — the closed-form minimum time of one robot alone (the per-robot lower
// bound LB of the paper's Tables IV and VI).
//
// A robot at rest that must come to rest at a point at distance d along the
// unit direction u, pushing with its largest force along u,
//     F_u = F_max (|u_x| + |u_y|)   (D_ef = 2, infinity-norm box)
//     F_u = F_max |a . u|           (D_ef = 1, force axis a)
// against floor friction of magnitude f_u = mu M g max_k (-d_k . u) (the
// K-gon's dissipation along u; mu M g when -u is a vertex direction), moves fastest by
// bang-bang control: full force until the switching point, full reverse force
// until it stops. With a_1 = (F_u - f_u) / M (speeding up, friction against)
// and a_2 = (F_u + f_u) / M (braking, friction helping):
//     v_peak = sqrt(2 d a_1 a_2 / (a_1 + a_2)),   T = v_peak / a_1 + v_peak / a_2.
// If the final velocity is free (no braking): T = sqrt(2 d / a_1).
//
// When is T a lower bound? The straight move is optimal only if the robot
// cannot gain by moving sideways. With D_ef = 1 and u along the force axis it
// cannot (no sideways force exists). With D_ef = 2 and u on a diagonal the
// corner of the force box is the only control reaching F_u, so any sideways
// velocity costs push at first order and saves friction only at second order:
// the straight move is (locally) optimal, and disco's solutions agree to
// 0.002 %. But with D_ef = 2 and u along an axis, F_y is free: a sideways
// velocity turns part of the friction away from u at no cost in push, and the
// optimum is a curved path FASTER than T (measured: 1.6 % on a 6 m x-move).
// There disco uses the provable relaxation: friction along u lies in
// [-mu M g, 0] while moving forward, so a_1 <= F_u / M (no friction) and
// a_2 <= (F_u + mu M g) / M.
//
// For a scene, each robot's move is from its start to the nearest point of
// its target position box. A robot's time exists only when it starts at rest
// and its final velocity box is either {0} or unbounded; otherwise it is
// absent (nullopt), and +inf when the robot cannot move along u at all.
//
// The scene's lower bound is the largest time among robots that have NO
// contact pair: other robots cannot help those (avoid pairs only restrict),
// so each needs at least its own time. A robot in a contact pair can be
// pushed by a stronger partner and finish sooner than alone (measured: a
// weak robot pushed by a strong one, 1.42 s against 10.3 s alone), so it gives
// no bound; a scene whose robots are all in contact pairs has none. The
// scene's reference time is the largest finite time over all robots: not a
// bound, a scale (used to choose the first, feasibility horizon).
#pragma once

#include <optional>

#include "core/model/scene.h"

namespace disco {

// The closed form above for one straight move from rest with acceleration a_1 and, if
// stop_at_end, braking deceleration a_2; +inf if a_1 <= 0.
double bang_bang_time(double distance, double accel, double brake, bool stop_at_end);

// Is the straight bang-bang move the robot's optimum along unit direction u?
bool straight_move_is_optimal(const Robot& robot, double ux, double uy);

// What limits a robot's straight move, from rest to its target pose (target_pose,
// core/model/bounds.h): its length, the largest push along it and the floor friction
// against it (both N, as above), whether it ends at rest, and whether it is the robot's
// optimum (straight_move_is_optimal). Absent (nullopt) exactly when straight_move_time
// is.
struct MoveLimits {
  double distance = 0.0;  // m
  double push = 0.0;      // N
  double friction = 0.0;  // N
  bool stop_at_end = true;
  bool optimal = false;
  double accel(double mass) const { return (push - friction) / mass; }  // a_1
  double brake(double mass) const { return (push + friction) / mass; }  // a_2
};
std::optional<MoveLimits> straight_move_limits(const Robot& robot, double gravity);

// The robot's own time for its straight move (the closed form; off its optimal
// directions the relaxation above), absent as straight_move_limits.
std::optional<double> straight_move_time(const Robot& robot, double gravity);
std::optional<double> scene_lower_bound(const Scene& scene);

// An object's straight move (Robot::object) as if the robots of its contact component
// (contact_components, core/model/model_plan.h) pushed it as one body from the start: the
// sum of their largest pushes against the floor friction of all, over the sum of the
// masses; after the release it slides to a stop at a_2 = mu g. Exact for one robot already
// touching one coin on a line (the closed form of tests/test_closed_form.cpp); otherwise
// not a bound (the robots must first reach it, may push off-centre), a scale. Absent as
// straight_move_limits, and when no robot can push it.
std::optional<double> pushed_move_time(const Scene& scene, int object);

// A scale, not a bound: the largest finite straight_move_time over the robots and
// pushed_move_time over the objects. Objects give the scene no lower bound: they are in
// contact pairs (see scene_lower_bound), or never move.
std::optional<double> scene_reference_time(const Scene& scene);

}  // namespace disco
