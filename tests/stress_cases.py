"""The stress scenes (configs/stress/) and what each must give.

Shared by tests/stress_tests.py (one CTest entry per scene) and scripts/bench_stress (the
table). Every expectation is computed here from the scene file alone, with the physics of
the model, never from disco's output.

Expected outcomes (CASES):
  solved      certified, and T_f equal (relative 1e-6) to the time computed here:
                alone    the largest of every robot's own minimum time (each robot's straight
                         move is its optimum and no pair can help or hinder: premise_alone());
                collide  for the pairs listed, two identical robots that meet head on and
                         must end touching: braking by the collision (discrete_collision_time);
                floor    nothing to do: the smallest horizon the model allows.
  infeasible  status infeasible (no certified point at any feasibility horizon), exit 3.
  failed      status failed, exit 3 (evaluation failures: non-finite values caught at the
              callback; Ipopt stops with Invalid_Number_Detected).
  input_error exit 2 and a message naming the file, the line and the key.

The minimum time of one robot (rest to rest over distance D, straight along unit u), in the
model's time discretisation (semi-implicit Euler: v_{t+1} = v_t + h a_t, x_{t+1} = x_t +
h v_{t+1}, N steps of h = T/N): a_1 = (F_u - f_u) / M accelerating, a_2 = (F_u + f_u) / M
braking, with F_u the largest push along u (D_ef 1: F |a . u|, u on the force axis; D_ef 2:
F (|u_x| + |u_y|), u on a diagonal, where the corner of the force box is the only control
reaching it) and f_u = mu M g max_k(-d_k . u) the friction of the K-gon against the motion.
Velocity increments per step lie in [-a_2 h, a_1 h] (friction opposes the motion while v > 0;
at rest at the end it is static, within the K-gon), so the largest distance in N steps is
h^2 S with S = sum_{t=1}^{N-1} min(a_1 t, a_2 (N - t)) (the pointwise largest feasible
velocity profile), and T = N sqrt(D / S). As N grows this tends to the continuous bang-bang
time v/a_1 + v/a_2, v = sqrt(2 D a_1 a_2 / (a_1 + a_2)) (core/model/lower_bound.h).
"""
import math
import os
import re

import yaml  # python3-yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "configs", "stress")
REL_TOL = 1e-6  # T_f against the expectation, and the scale triple against each other

# name -> expectation. "why" is the one-line reason shown in the table.
CASES = {
    "scale_m": {"outcome": "solved", "collide": [("ram_a", "ram_b")],
                "why": "max(alone, head-on collision); same T_f as scale_mm, scale_mass1000"},
    "scale_mm": {"outcome": "solved", "collide": [("ram_a", "ram_b")],
                 "why": "scale_m in millimetres (g = 9810 mm/s^2, N -> mN)"},
    "scale_mass1000": {"outcome": "solved", "collide": [("ram_a", "ram_b")],
                       "why": "scale_m with masses and forces x1000"},
    "touching_start": {"outcome": "solved", "why": "touching contact pair separates: each alone"},
    "touching_avoid": {"outcome": "solved", "why": "touching avoid pair (d_s 0) separates: each alone"},
    "friction_kink": {"outcome": "solved", "why": "move along a K-gon edge normal: friction mu M g cos(pi/4)"},
    "target_is_start": {"outcome": "solved", "floor": True, "why": "nothing to do: smallest horizon"},
    "stay_still": {"outcome": "solved", "why": "runner through a gate of two robots at rest: runner alone"},
    "forced_contact": {"outcome": "solved", "collide": [("a", "b")],
                       "why": "targets touch: the collision brakes both"},
    "mu_0": {"outcome": "solved", "why": "no floor friction: T = 2 sqrt(D M / F) (discrete)"},
    "mu_2": {"outcome": "solved", "why": "mu 2, diagonal move"},
    "K_3": {"outcome": "solved", "why": "triangle: friction along +x is mu M g / 2"},
    "K_64": {"outcome": "solved", "why": "64-gon, diagonal move"},
    "steps_5": {"outcome": "solved", "why": "N_t 5: the discrete optimum, 2.4 % above the continuous"},
    "steps_1000": {"outcome": "solved", "why": "N_t 1000"},
    "twelve_robots": {"outcome": "solved", "why": "12 robots, 66 avoid pairs, clear paths: slowest alone"},
    "mass_ratio_1000": {"outcome": "solved", "why": "1 kg and 1000 kg pass 0.01 m apart: slowest alone"},
    "radius_ratio_100": {"outcome": "solved", "why": "R 0.05 passes R 5.0 at rest: small alone"},
    # Start 0 alone may stop on a stop-and-go local optimum (which one it reaches changes
    # with roundoff: the full model at 32.33 s, the adaptive one at 33.17 s): its T_f must
    # not beat the optimum, and a search of `starts` starts must reach it.
    "weak_force": {"outcome": "solved", "why": "F_max = 1.001 mu M g: a_1 = 0.00196 m/s^2", "starts": 4},
    # Unreachable for a reason the scene shows: rejected before solving (core/model/reachability.h).
    "unreachable_target": {"outcome": "input_error", "key": "robots[0].target",
                           "message": "unreachable: robot 'r1' cannot turn",
                           "why": "phi target: a lone robot has no torque"},
    "off_axis_target": {"outcome": "input_error", "key": "robots[0].target",
                        "message": "unreachable: robot 'r1' is driven along its force_axis (1, 0) only",
                        "why": "D_ef 1 along x, target off the axis"},
    "overlapping_targets": {"outcome": "input_error", "key": "robots[1].target",
                            "message": "unreachable: robots 'a' and 'b' (an avoid pair): their targets "
                                       "keep their centres at most 0.8 m apart",
                            "why": "avoid pair, targets 0.8 m apart < R+R+d_s"},
    "target_in_obstacle": {"outcome": "input_error", "key": "objects[0].target",
                           "message": "unreachable: object 'coin' and obstacle 'post' (a contact pair): "
                                      "its target keeps its centre at most 0.5 m from the obstacle's centre",
                           "why": "a coin's target 0.5 m from a post's centre < R+R_obstacle"},
    # Unreachable for a reason the checks do not cover: the solve finds no feasible point.
    "object_at_target": {"outcome": "solved", "why": "an object at rest in its target, off the robot's way (avoid pair): the robot alone"},
    "heavy_object": {"outcome": "infeasible", "why": "a disk no push can slide: momentum 313 kg m/s needed, 11.3 N T_f available, T_f >= 27.7 s"},
    "walled_in": {"outcome": "infeasible", "why": "target outside a closed box of thin walls: "
                                                  "no step may jump a wall (swept rows)"},
    "spin_short": {"outcome": "infeasible", "why": "a lone robot spinning at the start: damping "
                                                   "stops it 0.025 rad on, short of its phi target"},
    "too_weak": {"outcome": "input_error", "key": "robots[0].force_max", "message": "too weak to move",
                 "why": "F_max <= mu M g: rejected by the parser"},
    "overflow": {"outcome": "failed", "why": "a swap across 1e160 m: the gap row overflows (Inf)"},
}
SCALE_GROUP = ("scale_m", "scale_mm", "scale_mass1000")  # same T_f (s) within REL_TOL


def scene_path(name):
    return os.path.join(SCENES, name + ".yaml")


def load_scene(name):
    """The scene as plain data: gravity, steps, robots (defaults merged; then the objects, with
    object True, force_max 0, force_dims 0 and no force keys from defaults), pairs (a pair
    with an object is contact unless overridden)."""
    with open(scene_path(name)) as f:
        doc = yaml.safe_load(f)
    defaults = doc.get("defaults") or {}
    robots = []
    for r in doc["robots"]:
        rb = {"K": 16, "force_dims": 2, "force_axis": [1.0, 0.0], **defaults, **r}
        ax = rb["force_axis"]
        n = math.hypot(ax[0], ax[1])
        rb["force_axis"] = [ax[0] / n, ax[1] / n]
        robots.append(rb)
    for o in doc.get("objects") or []:
        plain = {k: v for k, v in defaults.items() if k not in ("force_max", "force_dims", "force_axis")}
        robots.append({"K": 16, **plain, **o, "object": True, "force_max": 0.0, "force_dims": 0,
                       "force_axis": [1.0, 0.0]})
    pairs_doc = doc.get("pairs") or {}
    by_name = {r["name"]: i for i, r in enumerate(robots)}
    pairs = {}
    for i in range(len(robots)):
        for j in range(i + 1, len(robots)):
            with_object = robots[i].get("object") or robots[j].get("object")
            pairs[(i, j)] = {"mode": "contact" if with_object else pairs_doc.get("mode", "avoid"),
                             "safe_distance": pairs_doc.get("safe_distance", 0.01)}
    for o in pairs_doc.get("overrides") or []:
        i, j = sorted(by_name[n] for n in o["robots"])
        pairs[(i, j)].update({k: v for k, v in o.items() if k != "robots"})
    return {"name": doc["scenario"], "steps": doc["steps"], "gravity": doc.get("gravity", 9.81),
            "robots": robots, "pairs": pairs}


class PremiseError(Exception):
    """The scene is not one the closed form here applies to (the scene file changed?)."""


def straight_move(rb, g):
    """(D, a_1, a_2) of robot rb's rest-to-rest straight move; PremiseError unless the move is
    the robot's optimum (see the module doc)."""
    s, t = rb["start"], rb.get("target") or {}
    if s.get("vx", 0) != 0 or s.get("vy", 0) != 0 or t.get("vx") != 0 or t.get("vy") != 0:
        raise PremiseError(f"{rb['name']}: not rest to rest")
    if not all(isinstance(t.get(k), (int, float)) for k in ("x", "y")):
        raise PremiseError(f"{rb['name']}: target position not exact")
    dx, dy = t["x"] - s["x"], t["y"] - s["y"]
    d = math.hypot(dx, dy)
    if d == 0:
        return 0.0, 1.0, 1.0
    ux, uy = dx / d, dy / d
    if rb["force_dims"] == 1:
        along = rb["force_axis"][0] * ux + rb["force_axis"][1] * uy
        if abs(abs(along) - 1) > 1e-12:
            raise PremiseError(f"{rb['name']}: D_ef 1 and the move is not along the force axis")
        push = rb["force_max"]
    else:
        if abs(abs(ux) - abs(uy)) > 1e-12:
            raise PremiseError(f"{rb['name']}: D_ef 2 and the move is not diagonal")
        push = rb["force_max"] * (abs(ux) + abs(uy))
    K = rb["K"]
    support = max(-(math.cos(2 * math.pi * k / K) * ux + math.sin(2 * math.pi * k / K) * uy)
                  for k in range(K))
    friction = rb["mu"] * rb["mass"] * g * support
    return d, (push - friction) / rb["mass"], (push + friction) / rb["mass"]


def discrete_rest_time(d, n, a1, a2):
    """Minimum T of a rest-to-rest move of length d in n steps (module doc)."""
    if d == 0:
        return 0.0
    s = sum(min(a1 * t, a2 * (n - t)) for t in range(1, n))
    return n * math.sqrt(d / s)


def continuous_rest_time(d, a1, a2):
    v = math.sqrt(2 * d * a1 * a2 / (a1 + a2))
    return v / a1 + v / a2


def discrete_collision_time(d, n, a1):
    """Two identical robots meet head on and must end touching at rest: each accelerates
    the whole way (v_t = a_1 h t for t < n) and the contact impulse of the last step stops
    both (an impulse is unbounded, and contact can only slow a robot moving toward its
    partner, so no robot moves faster). Distance h^2 a_1 n (n - 1) / 2."""
    return n * math.sqrt(2 * d / (a1 * n * (n - 1)))


def segment_distance(p, q, r, s):
    """Distance between segments pq and rs in the plane."""
    def point_seg(a, b, c):
        bx, by = c[0] - b[0], c[1] - b[1]
        ll = bx * bx + by * by
        u = 0.0 if ll == 0 else max(0.0, min(1.0, ((a[0] - b[0]) * bx + (a[1] - b[1]) * by) / ll))
        return math.hypot(a[0] - b[0] - u * bx, a[1] - b[1] - u * by)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    if cross(p, q, r) * cross(p, q, s) < 0 and cross(r, s, p) * cross(r, s, q) < 0:
        return 0.0
    return min(point_seg(p, r, s), point_seg(q, r, s), point_seg(r, p, q), point_seg(s, p, q))


def premise_alone(scene, skip=()):
    """Robots cannot interact: every pair's swept segments (start to target) stay at least
    R_i + R_j (+ d_s for avoid pairs) apart, so straight moves at any timing never conflict,
    and every contact pair moves apart (mirrored_apart)."""
    rs = scene["robots"]
    for (i, j), p in scene["pairs"].items():
        if (i, j) in skip:
            continue
        a, b = rs[i], rs[j]
        if p["mode"] == "contact":
            mirrored_apart(a, b)
        seg = segment_distance((a["start"]["x"], a["start"]["y"]), (a["target"]["x"], a["target"]["y"]),
                               (b["start"]["x"], b["start"]["y"]), (b["target"]["x"], b["target"]["y"]))
        need = a["radius"] + b["radius"] + (p["safe_distance"] if p["mode"] == "avoid" else 0.0)
        if seg < need * (1 - 1e-12):
            raise PremiseError(f"{a['name']} and {b['name']} may meet ({seg:.4g} < {need:.4g})")


def mirrored_apart(a, b):
    """Contact pair a, b: identical robots, each pushing only along the line of centres
    (D_ef 1), moving the same distance straight away from each other. A partner can push a
    robot only away from itself, i.e. along the robot's own move, and while they touch the
    two move as one body of the same acceleration bound: neither gains, neither can brake
    the other (the discrete bound holds step by step)."""
    for k in ("radius", "mass", "mu", "force_max", "K"):
        if a[k] != b[k]:
            raise PremiseError(f"{a['name']}, {b['name']}: contact pair, not identical ({k})")
    ax, ay = b["start"]["x"] - a["start"]["x"], b["start"]["y"] - a["start"]["y"]
    n = math.hypot(ax, ay)
    ux, uy = ax / n, ay / n
    da = (a["target"]["x"] - a["start"]["x"], a["target"]["y"] - a["start"]["y"])
    db = (b["target"]["x"] - b["start"]["x"], b["target"]["y"] - b["start"]["y"])
    for rb, d, sign in ((a, da, -1), (b, db, 1)):
        along = d[0] * ux + d[1] * uy
        axis = rb["force_axis"][0] * ux + rb["force_axis"][1] * uy
        if rb["force_dims"] != 1 or abs(abs(axis) - 1) > 1e-12 or sign * along <= 0 or \
                abs(d[0] * uy - d[1] * ux) > 1e-12 * abs(along):
            raise PremiseError(f"{rb['name']}: contact pair not moving apart along the line of centres")
    if abs(math.hypot(*da) - math.hypot(*db)) > 1e-12 * math.hypot(*da):
        raise PremiseError(f"{a['name']}, {b['name']}: contact pair, different distances")


def time_unit(scene):
    """The model's time unit sqrt(L M / F) (core/model/units.h): means of R and M over robots
    and objects, of F_max over the robots."""
    def mean(k, rs):
        return sum(r[k] for r in rs) / len(rs)
    driven = [r for r in scene["robots"] if not r.get("object")]
    return math.sqrt(mean("radius", scene["robots"]) * mean("mass", scene["robots"])
                     / mean("force_max", driven))


def expected_T(name):
    """The expected T_f [s] of a `solved` case, or None (other outcomes)."""
    case = CASES[name]
    if case["outcome"] != "solved":
        return None
    scene = load_scene(name)
    g, n, rs = scene["gravity"], scene["steps"], scene["robots"]
    if case.get("floor"):
        # Nothing to do (T* = 0): the model keeps h > 0 with T_f >= 1e-3 time units
        # (kHorizonMin, core/model/robot_problem.cpp).
        for rb in rs:
            if straight_move(rb, g)[0] != 0:
                raise PremiseError(f"{rb['name']} has somewhere to go")
        return 1e-3 * time_unit(scene)
    index = {r["name"]: i for i, r in enumerate(rs)}
    times, paired = {}, set()
    for a, b in case.get("collide", []):
        i, j = sorted((index[a], index[b]))
        ra, rb = rs[i], rs[j]
        for k in ("radius", "mass", "mu", "force_max", "force_dims", "K"):
            if ra[k] != rb[k]:
                raise PremiseError(f"{a}, {b}: not identical ({k})")
        if scene["pairs"][(i, j)]["mode"] != "contact":
            raise PremiseError(f"{a}, {b}: not a contact pair")
        da, a1, _ = straight_move(ra, g)
        db, _, _ = straight_move(rb, g)
        gap = math.hypot(ra["target"]["x"] - rb["target"]["x"], ra["target"]["y"] - rb["target"]["y"])
        start_gap = math.hypot(ra["start"]["x"] - rb["start"]["x"], ra["start"]["y"] - rb["start"]["y"])
        if abs(da - db) > 1e-12 * da or abs(gap - ra["radius"] - rb["radius"]) > 1e-12 or \
                abs(start_gap - (da + db + gap)) > 1e-9 * start_gap:
            raise PremiseError(f"{a}, {b}: not a symmetric head-on move to touching targets")
        times[a] = times[b] = discrete_collision_time(da, n, a1)
        paired.add((i, j))
    premise_alone(scene, skip=paired)
    for rb in rs:
        if rb["name"] not in times:
            d, a1, a2 = straight_move(rb, g)
            times[rb["name"]] = discrete_rest_time(d, n, a1, a2)
    return max(times.values())


def input_error_line(name, key):
    """The line of the scene file that holds the last component of `key` (1-based); for a key
    of robots[i], its (i+1)-th occurrence (each robot of these scenes gives it once)."""
    leaf = key.split(".")[-1]
    m = re.match(r"robots\[(\d+)\]\.", key)
    skip = int(m.group(1)) if m else 0
    with open(scene_path(name)) as f:
        for k, line in enumerate(f, 1):
            if re.match(rf"\s*{re.escape(leaf)}\s*:", line):
                if skip == 0:
                    return k
                skip -= 1
    raise PremiseError(f"{name}: no line with '{leaf}:'")


def certificate_tolerances():
    with open(os.path.join(ROOT, "configs", "disco.yaml")) as f:
        e = yaml.safe_load(f)["elastic"]
    return float(e["violation_tolerance"]), float(e["complementarity_tolerance"])


def load_solution(path):
    """solution.json, and the non-finite number tokens (NaN, Infinity) found in it."""
    import json
    bad = []
    with open(path) as f:
        doc = json.load(f, parse_constant=lambda c: bad.append(c) or 0.0)

    def walk(v):
        if isinstance(v, float) and not math.isfinite(v):
            bad.append(repr(v))
        elif isinstance(v, dict):
            for x in v.values():
                walk(x)
        elif isinstance(v, list):
            for x in v:
                walk(x)
    walk(doc)
    return doc, bad


TRAJECTORY_KEYS = ("x", "y", "phi", "vx", "vy", "omega", "Fx", "Fy")


def assess(name, returncode, stderr, solution_path):
    """The checks of one `disco solve` run on scene `name` against its expected outcome:
    a list of (passed, what). Also returns solution.json's document (None if absent)."""
    if name not in CASES:
        return [(False, f"{name}: configs/stress/{name}.yaml has an expectation in "
                        "tests/stress_cases.py")], None
    case = CASES[name]
    outcome = case["outcome"]
    checks = []
    add = lambda ok, what: checks.append((bool(ok), f"{name}: {what}"))  # noqa: E731
    if outcome == "input_error":
        where = f"{scene_path(name)}:{input_error_line(name, case['key'])}: key '{case['key']}'"
        add(returncode == 2, f"exit 2 for bad input (got {returncode})")
        add(where in stderr and case["message"] in stderr,
            f"the message names {where!r} and says {case['message']!r}")
        add(not os.path.exists(solution_path), "no solution written")
        return checks, None
    if not os.path.isfile(solution_path):
        add(False, f"solution.json written (exit {returncode})")
        return checks, None
    doc, bad = load_solution(solution_path)
    add(not bad, f"no NaN or Inf in solution.json (found {bad[:3]})")
    add(doc["status"] == outcome, f"status {outcome} (got {doc['status']}, {doc.get('status_detail', '')})")
    if outcome == "solved":
        add(returncode == 0, f"exit 0 (got {returncode})")
        viol_tol, compl_tol = certificate_tolerances()
        v, c = doc["certificate"]["max_violation"], doc["certificate"]["max_complementarity"]
        add(v is not None and c is not None and v <= viol_tol and c <= compl_tol,
            f"certificate: violation {v} <= {viol_tol}, complementarity {c} <= {compl_tol}")
        expected, T = expected_T(name), doc["T_f"]
        if "starts" in case:  # the search's best is checked by the caller
            add(T is not None and T >= expected * (1 - REL_TOL),
                f"T_f {T} not below the optimum {expected:.12g} ({case['why']})")
            return checks, doc
        diff = None if T is None else abs(T - expected) / expected
        add(diff is not None and diff <= REL_TOL,
            f"T_f {T} = expected {expected:.12g} ({case['why']}), relative "
            f"{'n/a' if diff is None else format(diff, '.2g')} <= {REL_TOL}")
        return checks, doc
    add(returncode == 3, f"exit 3 without a solution (got {returncode})")
    add(doc["T_f"] is None and doc["h"] is None, "T_f and h are null")
    add(all(rb[k] is None for rb in doc["robots"] for k in TRAJECTORY_KEYS), "every trajectory is null")
    detail = doc.get("status_detail", "")
    if outcome == "infeasible":
        add(detail in ("infeasible", "elastic_not_tight"), f"status_detail says why ({detail!r})")
    elif outcome == "failed":
        ipopt = "failed (Ipopt: Invalid_Number_Detected)"
        add(detail == ipopt, f"status_detail {ipopt!r} (got {detail!r})")
        add("Invalid_Number_Detected" in stderr, "the solve log names Invalid_Number_Detected")
    return checks, doc
