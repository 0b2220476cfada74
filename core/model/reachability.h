// disco — targets a scene makes unreachable for a reason visible in the scene itself, found
// before any solve (scene files are checked by core/model/scene_yaml.cpp, which reports the
// first of these as an InputError naming the robot's target).
//
// Each rule holds for every horizon, so a scene it flags has no feasible point at all:
//  * kOffAxis: a robot with force_dims 1 and no contact pair with a disk or an obstacle
//    (nothing can push it; a slanted wall's normal force could), at rest across its axis at
//    the start, whose friction polygon is symmetric about its axis (mu = 0,
//    or the axis at a multiple of pi/K): across the axis the floor friction never pushes (by
//    the symmetry, maximum dissipation picks a vertex on the side opposite to any sideways
//    velocity, so none can start), so the robot stays on the line through its start along the
//    axis, with no velocity across it (Section III-A.1, Appendix A). A target box that misses
//    that line, or a velocity box that excludes every velocity along the axis, is unreachable.
//  * kNoTurn: a robot with no contact pair with a disk or an obstacle (rubbing a contact
//    obstacle turns it), at rest in rotation (omega = 0) at the start: its force acts at its
//    centre and the floor's only torque is the damping -sigma_d M g omega,
//    so omega stays 0 and phi stays at its start. A phi target without the start's phi, or an
//    omega target without 0, is unreachable.
//  * kUntouched: an object (Robot::object: no force of its own) with no contact pair with a
//    disk (a fixed obstacle never sets a disk at rest moving), at rest at the start: no force
//    ever acts on it but floor friction, which only opposes
//    motion, so it stays where it is. A target box without its start position, or a
//    velocity box without 0, is unreachable (phi and omega: kNoTurn).
//  * kOverlap: two robots whose target boxes keep their centres closer than the pair allows
//    at T_f: R_i + R_j + safe_distance (avoid pair) or R_i + R_j (contact pair).
//  * kInObstacle: a robot or object whose target box keeps its centre closer to a fixed
//    obstacle's centre (a wall's centre line) than the pair allows at T_f: R + R_obstacle +
//    safe_distance (avoid pair) or R + R_obstacle (contact pair). The distance to a point or
//    a segment is convex, so over a box it is largest at a corner: the rule holds when every
//    corner is that close (a box unbounded in x or y escapes). Moving obstacles are left to
//    the solve (where one is at T_f depends on T_f).
// Not covered (the solve reports them as infeasible): anything that depends on the dynamics
// over time, e.g. a robot spinning at the start whose damping stops it short of its phi target.
#pragma once

#include <string>
#include <vector>

#include "core/model/scene.h"

namespace disco {

struct Unreachable {
  enum class Rule { kOffAxis, kUntouched, kNoTurn, kOverlap, kInObstacle };
  Rule rule;
  int robot = 0;   // the robot whose target is unreachable (for kOverlap, the second robot)
  int other = -1;  // kOverlap: the first robot of the pair
  std::string reason;  // a sentence naming the robots, the quantities and the rule
};

// Every unreachable target of `scene`, robots in order, then pairs, then obstacle pairs.
std::vector<Unreachable> unreachable_targets(const Scene& scene);

// "robot 'a'" or "object 'a'", and "robots 'a' and 'b'", "objects 'a' and 'b'" or "robot 'a'
// and object 'b'": how messages name disks (names made printable and cut, core/util/errors.h).
std::string disk_name(const Robot& r);
std::string disk_pair_names(const Robot& a, const Robot& b);

// True when some robot's target bounds at least one state component.
bool has_any_target(const Scene& scene);

}  // namespace disco
