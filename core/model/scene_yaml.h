// disco — reading a scene file (YAML) into a validated Scene.
//
// ---------------------------------------------------------------------------
// Scene file reference
// ---------------------------------------------------------------------------
// A scene file is one YAML mapping. Units are SI (m, kg, s, N, rad).
//
//   scenario: one_robot_axis      # required; letters, digits, '_', '-', '.'
//   description: "free text"      # optional
//   steps: 100                    # N_t, required integer >= 1
//   gravity: 9.81                 # optional, > 0, default 9.81 [m/s^2]
//   defaults:                     # optional: any robot key except name/start/target;
//     radius: 0.5                 #   each robot may override it
//   robots:                       # required, non-empty sequence
//     - name: r1                  # required, unique; letters, digits, '_', '-', '.'
//       radius: 0.5               # required (here or in defaults), > 0 [m]
//       mass: 1.0                 # required, > 0 [kg]
//       inertia: 0.125            # optional, > 0 [kg m^2]; default 0.5 * mass * radius^2
//       mu: 0.2                   # required, >= 0 (floor friction)
//       damping: 0.05             # optional sigma_d >= 0 [m s]; default 0.1 * radius
//                                 #   (the number, taken as m s)
//       force_max: 5.0            # required, > mu * mass * gravity [N] (else the robot is
//                                 #   "too weak to move")
//       force_dims: 2             # optional, 1 or 2, default 2
//       force_axis: [1, 0]        # optional nonzero 2-vector, normalised on load; used only
//                                 #   with force_dims 1; default [1, 0]
//       K: 16                     # optional integer >= 3, default 16: vertices of the
//                                 #   floor-friction polygon (Robot::friction_edges)
//       start: {x: 0, y: 0, phi: 0, vx: 0, vy: 0, omega: 0}
//                                 # required; x and y required, the others default to 0
//       target: {x: 10, y: [-0.1, 0.1], vx: 0, vy: 0}
//                                 # optional (missing = everything free), see below
//   objects:                      # optional sequence of passive disks (Robot::object): the
//     - name: coin                #   robot keys without force_max, force_dims, force_axis
//       radius: 0.3               #   (each an error here; from defaults they are skipped)
//       mass: 0.5
//       mu: 0.3
//       start: {x: 1, y: 0}
//       target: {x: 3, vx: 0}
//   obstacles:                    # optional sequence (core/model/obstacles.h); nothing moves them
//     - name: post                #   required, unique among robots, objects and obstacles
//       disk: {x: 0, y: 0, radius: 0.5, vx: 0, vy: 0}   # a post (radius > 0) at (x, y) +
//                                 #   t (vx, vy); vx, vy optional, default 0
//       mode: contact             #   optional: the mode of every disk's pair with it; default
//                                 #   pairs.mode (contact for objects); a moving one: avoid only
//       safe_distance: 0.01       #   optional, default pairs.safe_distance
//       mu: 0.3                   #   optional, default pairs.mu
//     - name: wall
//       wall: {from: [0, 1], to: [0, 3], thickness: 0.1}  # distinct ends; thickness >= 0
//                                 #   (default 0): a capsule of radius thickness / 2
//   pairs:                        # optional mapping
//     mode: avoid                 # default mode of every robot pair: avoid | contact; default
//                                 #   avoid (a pair with an object is contact by default)
//     safe_distance: 0.01         # default d_s >= 0 [m], default 0.01 (avoid pairs)
//     mu: 0.3                     # default contact friction coefficient >= 0, default 0.3
//     overrides:                  # optional sequence of per-pair settings
//       - robots: [r1, r2]        # two distinct robot or object names; each pair at most once
//         mode: contact           # any of mode / safe_distance / mu
//
// Target components: each of x, y, phi, vx, vy, omega is optional.
//   missing (or null)  -> free, (-inf, +inf)
//   a number v         -> exact, lower = upper = v
//   [lo, hi]           -> a box; either side may be null (~) for "unbounded on that side";
//                         lo <= hi is required.
//
// Scene::robots holds the robots, then the objects; names are unique across both (and the
// obstacles). Scene::obstacle_pairs holds one Pair per (disk, obstacle), obstacle by obstacle.
// Scene::pairs holds exactly one Pair per pair of disks i < j, in (i, j) lexicographic
// order: the `pairs` defaults first, then the matching entry of `pairs.overrides`.
//
// Rules applied on load (each violation is an InputError):
//   * unknown keys anywhere (the message lists the allowed ones), duplicate keys, missing
//     required keys, wrong types (numbers must be plain, unquoted YAML scalars; integers
//     must be written as integers), non-finite numbers;
//   * the ranges given above;
//   * robots must not overlap at the start: centre distance >= R_i + R_j (relative tolerance
//     1e-12, so touching is allowed); avoid pairs need >= R_i + R_j + d_s;
//   * force_max > mu * mass * gravity for every robot;
//   * an object nothing can push keeps its start (core/model/reachability.h, kUntouched);
//   * no disk starts inside an obstacle (nor closer than an avoid pair's safe_distance); a
//     wall has distinct ends; an obstacle is a disk or a wall; a moving one is not contact.
// Optional sections (defaults, pairs, pairs.overrides, target) may be written empty (null).
//
// Overrides ("--set" on the command line, without the "scene." prefix) are "KEY=VALUE"
// strings. KEY is a dotted path into the document; a numeric component indexes a sequence
// ("robots.0.mass", "pairs.overrides.1.mode"); an index equal to the sequence length appends.
// Missing mapping keys along the path are created. VALUE is parsed as YAML ("2",
// "[0, 1]", "{x: 1, y: 2}") and replaces (or adds) that node before validation.
//
// Messages: "FILE:LINE: key 'robots[1].mass': must be > 0 (got -1)" (see
// core/util/errors.h). A problem in a value that came from an override is reported as
// "--set: key 'robots.1.mass': ...", with the override's key (plus the path below it, when
// the override set a whole mapping or sequence). A problem found at a file key whose
// contents were partly overridden (a start moved by --set robots.1.start.x=...) is reported
// at the file line and names those overrides: "... (with --set robots.1.start.x)".
#pragma once

#include <string>
#include <vector>

#include "core/model/scene.h"

namespace disco {

// Loads and validates the scene file at `path`, after applying `overrides` (see above).
// Throws InputError on any problem, including a file that cannot be opened or YAML syntax
// errors. Scene::source = path, Scene::name = the scenario.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same, from text already in memory; `source` names it in messages and in Scene::source.
Scene parse_scene(const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides = {});

}  // namespace disco
