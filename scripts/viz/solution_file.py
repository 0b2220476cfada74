"""Reading a disco solution file (`disco solve`'s solution.json, a search's best/SCENE.json;
schema in core/README.md, "The solution file") into plain lists, with every key checked, and the
geometry the drawings share (poses between states, contact points, the scene's extent).

load(path) raises BadInput with a message naming the key, e.g. "missing key 'robots[0].phi'".
"""
import json
import math
import os

class BadInput(Exception):
    pass



# --- reading and checking the solution file -------------------------------------------------

def need(obj, key, where):
    """obj[key], or BadInput naming the full key path."""
    name = f"{where}.{key}" if where else key
    if not isinstance(obj, dict):
        raise BadInput(f"'{where or 'top level'}' is not an object")
    if key not in obj:
        raise BadInput(f"missing key '{name}'")
    return obj[key]


def number(v, name, allow_null=False):
    if v is None and allow_null:
        return None
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise BadInput(f"'{name}' is {json.dumps(v)}, expected a finite number")
    return float(v)


def series(obj, key, where, length):
    v = need(obj, key, where)
    name = f"{where}.{key}"
    if not isinstance(v, list):
        raise BadInput(f"'{name}' is {type(v).__name__}, expected a list of {length} numbers")
    if len(v) != length:
        raise BadInput(f"'{name}' has {len(v)} entries, expected {length}")
    return [number(x, f"{name}[{k}]") for k, x in enumerate(v)]


# With full=True (the report's time plots), these are read and checked too.
ROBOT_STATES = ("vx", "vy", "omega")                       # N_t + 1 entries
ROBOT_STEPS = ("Fx", "Fy", "friction_x", "friction_y", "contact_x", "contact_y",
               "contact_torque")                           # N_t entries
ROBOT_NUMBERS = ("mass", "mu")
PAIR_STATES = ("gap",)
PAIR_STEPS = ("normal_force", "tangential_force")


def load(path, full=False):
    """The solution file at `path` as plain lists. Always: scenario, status, T_f (None without
    a trajectory), N_t, lower_bound, robots (name, object (kind "object": a passive disk, no
    force; robots first), radius, F_max, start [x, y, phi], target
    [[x, y] lower, [x, y] upper] with None for free, x, y, phi) and pairs (i, j,
    normal_force). full=True adds g, certificate, model, timing, status_detail, each robot's
    mass, mu, force_bound [bx, by] (|F_x| <= bx, |F_y| <= by), vx, vy, omega and per-step forces, and each pair's mode, safe_distance, mu,
    gap and tangential_force."""
    try:
        with open(path) as f:
            doc = json.load(f)
    except OSError as e:
        raise BadInput(f"cannot open: {e.strerror}")
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise BadInput(f"not valid JSON: {e}")
    if not isinstance(doc, dict):
        raise BadInput("top level is not an object")
    if "scenario" not in doc and isinstance(doc.get("scenes"), dict):
        # A search's best.json: it names the solution files, one per scene.
        files = [e.get("solution") for e in doc["scenes"].values()
                 if isinstance(e, dict) and e.get("solution")]
        where = os.path.dirname(path) or "."
        raise BadInput("a search's best.json, not a solution file: give one of its scenes' "
                       + (", ".join(os.path.join(where, f) for f in files[:4])
                          + (", ..." if len(files) > 4 else "")
                          if files else "best/SCENE.json files (none of its scenes has one)"))

    sol = {"scenario": str(need(doc, "scenario", "")), "status": str(need(doc, "status", ""))}
    sol["T_f"] = number(need(doc, "T_f", ""), "T_f", allow_null=True)
    n_t = need(doc, "N_t", "")
    if isinstance(n_t, bool) or not isinstance(n_t, int) or n_t < 1:
        raise BadInput(f"'N_t' is {json.dumps(n_t)}, expected an integer >= 1")
    sol["N_t"] = n_t
    sol["lower_bound"] = doc.get("lower_bound") if isinstance(doc.get("lower_bound"), (int, float)) else None
    has_traj = sol["T_f"] is not None
    if has_traj and sol["T_f"] <= 0:
        raise BadInput(f"'T_f' is {sol['T_f']}, expected > 0")

    robots = need(doc, "robots", "")
    if not isinstance(robots, list) or not robots:
        raise BadInput("'robots' is not a non-empty list")
    sol["robots"] = []
    for i, r in enumerate(robots):
        w = f"robots[{i}]"
        rob = {"name": str(need(r, "name", w)),
               "radius": number(need(r, "radius", w), f"{w}.radius"),
               "F_max": number(r.get("F_max", 1.0), f"{w}.F_max") if isinstance(r, dict) else 1.0}
        if rob["radius"] <= 0:
            raise BadInput(f"'{w}.radius' is {rob['radius']}, expected > 0")
        kind = r.get("kind", "robot") if isinstance(r, dict) else "robot"  # older files: robots
        if kind not in ("robot", "object"):
            raise BadInput(f"'{w}.kind' is {json.dumps(kind)}, expected \"robot\" or \"object\"")
        rob["object"] = kind == "object"
        start = need(r, "start", w)
        if not isinstance(start, list) or len(start) < 3:
            raise BadInput(f"'{w}.start' is not a list [x, y, phi, ...]")
        rob["start"] = [number(v, f"{w}.start[{k}]") for k, v in enumerate(start[:3])]
        target = need(r, "target", w)
        lo, hi = need(target, "lower", f"{w}.target"), need(target, "upper", f"{w}.target")
        for name, b in (("lower", lo), ("upper", hi)):
            if not isinstance(b, list) or len(b) < 2:
                raise BadInput(f"'{w}.target.{name}' is not a list [x, y, ...]")
        rob["target"] = [[number(b[k], f"{w}.target.{name}[{k}]", allow_null=True) for k in (0, 1)]
                         for name, b in (("lower", lo), ("upper", hi))]
        for key in ("x", "y", "phi") + (ROBOT_STATES if full else ()):
            if has_traj:
                rob[key] = series(r, key, w, n_t + 1)
            else:
                need(r, key, w)
        if full:
            for key in ROBOT_STEPS:
                if has_traj:
                    rob[key] = series(r, key, w, n_t)
                else:
                    need(r, key, w)
            for key in ROBOT_NUMBERS:
                rob[key] = number(need(r, key, w), f"{w}.{key}")
            # The box of F: +-F_max per component; along the axis for force_dims 1.
            dims = need(r, "force_dims", w)
            allowed = (0,) if rob["object"] else (1, 2)
            if dims not in allowed or isinstance(dims, bool):
                raise BadInput(f"'{w}.force_dims' is {json.dumps(dims)}, expected "
                               + " or ".join(map(str, allowed)))
            axis = [0.0, 0.0] if dims == 0 else [1.0, 1.0]
            if dims == 1:
                a = need(r, "force_axis", w)
                if not isinstance(a, list) or len(a) != 2:
                    raise BadInput(f"'{w}.force_axis' is not a list [ax, ay]")
                axis = [abs(number(v, f"{w}.force_axis[{k}]")) for k, v in enumerate(a)]
            rob["force_bound"] = [rob["F_max"] * axis[0], rob["F_max"] * axis[1]]
        sol["robots"].append(rob)

    pairs = need(doc, "pairs", "")
    if not isinstance(pairs, list):
        raise BadInput("'pairs' is not a list")
    sol["pairs"] = []
    for p_idx, p in enumerate(pairs):
        w = f"pairs[{p_idx}]"
        i, j = need(p, "i", w), need(p, "j", w)
        for name, v in (("i", i), ("j", j)):
            if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v < len(robots):
                raise BadInput(f"'{w}.{name}' is {json.dumps(v)}, expected a robot index "
                               f"0..{len(robots) - 1}")
        pair = {"i": i, "j": j}
        steps = PAIR_STEPS if full else ("normal_force",)
        for key, length in [(k, n_t) for k in steps] + [(k, n_t + 1) for k in
                                                        (PAIR_STATES if full else ())]:
            if has_traj:
                pair[key] = series(p, key, w, length)
            else:
                need(p, key, w)
        if full:
            pair["mode"] = str(need(p, "mode", w))
            pair["safe_distance"] = number(need(p, "safe_distance", w), f"{w}.safe_distance")
            pair["mu"] = number(need(p, "mu", w), f"{w}.mu")
        sol["pairs"].append(pair)
    sol["obstacles"] = read_obstacles(doc)
    if full:
        sol["g"] = number(need(doc, "g", ""), "g")
        sol["status_detail"] = str(doc.get("status_detail", ""))
        for key in ("certificate", "model", "timing"):
            v = need(doc, key, "")
            if not isinstance(v, dict):
                raise BadInput(f"'{key}' is not an object")
            sol[key] = v
    return sol


def read_obstacles(doc):
    """The file's obstacles (none in files written before disco had them): name, shape
    ("disk" or "wall"), radius, and a wall's ends or a disk's centre at t = 0 with its
    constant velocity or its waypoints (path); a disk's centres at the states (x, y, written
    with a solution) are kept (x, y: its track), with the step h."""
    obstacles = doc.get("obstacles", [])
    if not isinstance(obstacles, list):
        raise BadInput("'obstacles' is not a list")
    out = []
    for k, o in enumerate(obstacles):
        w = f"obstacles[{k}]"
        shape = need(o, "shape", w)
        if shape not in ("disk", "wall"):
            raise BadInput(f"'{w}.shape' is {json.dumps(shape)}, expected \"disk\" or \"wall\"")
        ob = {"name": str(need(o, "name", w)), "shape": shape,
              "radius": number(need(o, "radius", w), f"{w}.radius")}
        if shape == "disk" and o.get("path") is not None:
            path = o["path"]
            if not isinstance(path, list) or len(path) < 2:
                raise BadInput(f"'{w}.path' is not a list of at least two waypoints")
            ob["path"] = [[number(need(p, key, f"{w}.path[{i}]"), f"{w}.path[{i}].{key}")
                           for key in ("t", "x", "y")] for i, p in enumerate(path)]
        keys = ("from", "to") if shape == "wall" else ("centre",) if "path" in ob else ("centre", "velocity")
        for key in keys:
            v = need(o, key, w)
            if not isinstance(v, list) or len(v) != 2:
                raise BadInput(f"'{w}.{key}' is not a list [x, y]")
            ob[key] = [number(c, f"{w}.{key}[{a}]") for a, c in enumerate(v)]
        if shape == "disk" and o.get("x") is not None and doc.get("h"):
            xs, ys = o["x"], o.get("y")
            if not isinstance(xs, list) or not isinstance(ys, list) or len(xs) != len(ys) or len(xs) < 2:
                raise BadInput(f"'{w}.x' and '{w}.y' are not two lists of the same length")
            ob["x"] = [number(x, f"{w}.x[{i}]") for i, x in enumerate(xs)]
            ob["y"] = [number(y, f"{w}.y[{i}]") for i, y in enumerate(ys)]
            ob["h"] = number(doc["h"], "h")
        out.append(ob)
    return out


# --- geometry ---------------------------------------------------------------------------------

def obstacle_at(ob, t):
    """A disk obstacle's centre at time t: on its track (its centres at the states, straight
    between them), or from its constant velocity; a path obstacle without a track (a file
    without a solution) is drawn at its first waypoint."""
    if "x" in ob:
        return along(ob, ("x", "y"), t, ob["h"], len(ob["x"]) - 1)
    if "path" in ob:
        return tuple(ob["centre"])
    return (ob["centre"][0] + t * ob["velocity"][0], ob["centre"][1] + t * ob["velocity"][1])


def obstacle_way(ob, T_f):
    """The places a moving disk obstacle passes over [0, T_f]: its track, its waypoints (a
    path without a track), or the two ends of its straight way."""
    if "x" in ob:
        return list(zip(ob["x"], ob["y"]))
    if "path" in ob:
        return [(p[1], p[2]) for p in ob["path"]]
    return [obstacle_at(ob, 0.0), obstacle_at(ob, T_f)]


def moves(ob):
    return ob["shape"] == "disk" and ("path" in ob or any(v != 0.0 for v in ob["velocity"]))


def along(obj, keys, t, h, n_t):
    """The series obj[key] (N_t + 1 values at t_k = k h) at time t, linear between states."""
    s = min(max(t / h, 0.0), float(n_t))
    k = min(int(math.floor(s)), n_t - 1)
    f = s - k
    return tuple(obj[key][k] * (1 - f) + obj[key][k + 1] * f for key in keys)


def state_at(rob, t, h, n_t):
    """(x, y, phi) at time t, linear between the stored states."""
    return along(rob, ("x", "y", "phi"), t, h, n_t)


def contacts_at(sol, t, h, thr, poses):
    """Contact points of pairs pushing over the step ending at (or containing) time t."""
    k = int(math.ceil(t / h - 1e-9)) - 1
    if k < 0:
        return []
    k = min(k, sol["N_t"] - 1)
    pts = []
    for p in sol["pairs"]:
        if p["normal_force"][k] > thr:
            pts.append(contact_point(sol["robots"], p["i"], p["j"], poses))
    return pts


def contact_point(robots, i, j, poses):
    (xi, yi, _), (xj, yj, _) = poses[i], poses[j]
    d = math.hypot(xj - xi, yj - yi) or 1e-12
    ri, rj = robots[i]["radius"], robots[j]["radius"]
    gap = d - ri - rj
    s = (ri + gap / 2) / d
    return (xi + s * (xj - xi), yi + s * (yj - yi))


def all_contacts(sol, thr, until=None):
    """Contact points of every step with a normal force above thr (steps ending by `until`)."""
    pts = []
    h = sol["T_f"] / sol["N_t"]
    for p in sol["pairs"]:
        for k, fn in enumerate(p["normal_force"]):
            if fn > thr and (until is None or (k + 1) * h <= until * (1 + 1e-12)):
                poses = {q: tuple(sol["robots"][q][key][k + 1] for key in ("x", "y", "phi"))
                         for q in (p["i"], p["j"])}
                pts.append(contact_point(sol["robots"], p["i"], p["j"], poses))
    return pts


def driven(sol):
    """The robots of `sol`, without its objects (passive disks: no force of their own)."""
    return [r for r in sol["robots"] if not r.get("object")]


def default_contact_threshold(sol):
    """A pair is in contact above this normal force [N]: 0.1 % of the robots' mean F_max
    (objects have none)."""
    robots = driven(sol)
    return 1e-3 * sum(r["F_max"] for r in robots) / len(robots)


def bounds(sol):
    xs, ys = [], []
    for r in sol["robots"]:
        rad = r["radius"]
        px = r["x"] if "x" in r else [r["start"][0]]
        py = r["y"] if "y" in r else [r["start"][1]]
        xs += [min(px) - rad, max(px) + rad]
        ys += [min(py) - rad, max(py) + rad]
        (xl, yl), (xh, yh) = r["target"]
        for v, acc in ((xl, xs), (xh, xs), (yl, ys), (yh, ys)):
            if v is not None:
                acc += [v - rad, v + rad]
    T_f = sol["T_f"] or 0.0
    for ob in sol.get("obstacles", []):
        rad = ob["radius"]
        ends = (ob["from"], ob["to"]) if ob["shape"] == "wall" else obstacle_way(ob, T_f)
        for (x, y) in ends:
            xs += [x - rad, x + rad]
            ys += [y - rad, y + rad]
    pad = 0.05 * max(max(xs) - min(xs), max(ys) - min(ys)) + 0.1
    return min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad

