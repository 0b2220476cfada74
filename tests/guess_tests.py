#!/usr/bin/env python3
"""Starts from a trajectory (run by CTest as cli.guess; see tests/CMakeLists.txt).

  guess_tests.py DISCO SCENES WORKDIR

`disco solve --guess FILE` from a solution of the same scene at other steps gives a certified
answer, starts at (1 + feasibility.guess_slack) times the file's T_f and names the file in
its provenance; a file of other robots, of moved starts, without a trajectory or not JSON is
refused (exit 2) with a message naming the file and what differs. `disco search --guess`
gives start 0 of the file's scene (and only it) the trajectory, records it in the manifest
(a resume with another file is refused) and in the best solution's provenance; a file whose
scenario is not in a search of several scenes is refused. feasibility.coarse_fraction: the
coarse solves come first in the log, never marked as a new best.
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

from script_checks import check, finish

DISCO, SCENES, WORK = sys.argv[1:4]
ENV = dict(os.environ, OMP_NUM_THREADS="1")
SWAP = os.path.join(SCENES, "two_robots_swap_avoid.yaml")
AXIS = os.path.join(SCENES, "one_robot_axis.yaml")
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)


def run(*args):
    return subprocess.run([DISCO, *args], env=ENV, capture_output=True, text=True)


def load(path):
    with open(path) as f:
        return json.load(f)


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def solve_lines(text):
    """(number, phase, bound, T_f, marked) of each solve-log line."""
    out = []
    for line in text.splitlines():
        m = re.match(r"^\s*(\d+) ([a-z][a-z ]*?)\s+([\d.]+)\s+([\d.]+)\s.*?(\*?)\s*$", line)
        if m:
            out.append((int(m.group(1)), m.group(2), float(m.group(3)), float(m.group(4)),
                        m.group(5) == "*"))
    return out


# A solution at 8 steps, the guess of everything below.
coarse_dir = os.path.join(WORK, "coarse")
r = run("solve", SWAP, "--set", "scene.steps=8", "--out", coarse_dir, "--quiet")
GUESS = os.path.join(coarse_dir, "solution.json")
check(r.returncode == 0, f"a solution of the swap at 8 steps ({r.stderr[-300:]!r})")
T8 = load(GUESS)["T_f"]

# solve --guess at 16 steps.
fine_dir = os.path.join(WORK, "fine")
r = run("solve", SWAP, "--set", "scene.steps=16", "--out", fine_dir, "--guess", GUESS)
sol = load(os.path.join(fine_dir, "solution.json"))
check(r.returncode == 0 and sol["status"] == "solved", f"solve --guess: certified ({r.stderr[-300:]!r})")
cert = sol["certificate"]
check(cert["max_violation"] <= 1e-6 and cert["max_complementarity"] <= 1e-6,
      f"... its certificate within the elastic tolerances ({cert})")
check(f"resampled to N_t = 16" in r.stderr, "the log says the guess was resampled to the scene's N_t")
m = re.search(r"first horizon ([\d.]+) s", r.stderr)
lines = solve_lines(r.stderr)
check(m is not None and lines and lines[0][1] == "feasibility"
      and abs(lines[0][2] - float(m.group(1))) < 1e-5 and float(m.group(1)) > T8,
      f"the first solve is a feasibility solve at the first horizon, above the guess's T_f "
      f"{T8:.6f} ({lines[:1]}, {m and m.group(1)})")
g = sol["provenance"]["guess"]
check(g is not None and g["file"] == GUESS and g["sha256"] == sha256(GUESS),
      f"provenance names the guess file and its SHA-256 ({g})")
plain = run("solve", SWAP, "--set", "scene.steps=16", "--out", os.path.join(WORK, "plain"),
            "--quiet")
check(load(os.path.join(WORK, "plain", "solution.json"))["provenance"]["guess"] is None,
      "without --guess, provenance.guess is null")

# Mismatches: exit 2, the file named, what differs said.
axis_dir = os.path.join(WORK, "axis")
run("solve", AXIS, "--set", "scene.steps=6", "--out", axis_dir, "--quiet")
AXIS_SOL = os.path.join(axis_dir, "solution.json")
r = run("solve", SWAP, "--guess", AXIS_SOL, "--out", os.path.join(WORK, "x1"))
check(r.returncode == 2 and f"--guess {AXIS_SOL}: its robots do not match scene "
      "'two_robots_swap_avoid': 1 there (r1), 2 in the scene" in r.stderr,
      f"a guess of other robots: exit 2, the file and both robot lists ({r.stderr.strip()[-300:]!r})")
check("model (adaptive)" not in r.stderr, "... refused before the model is built")
moved = load(GUESS)
moved["robots"][0]["x"][0] += 1.0
MOVED = os.path.join(WORK, "moved.json")
with open(MOVED, "w") as f:
    json.dump(moved, f)
r = run("solve", SWAP, "--guess", MOVED, "--out", os.path.join(WORK, "x2"))
check(r.returncode == 2 and "starts at" in r.stderr and MOVED in r.stderr,
      f"a guess whose robot starts elsewhere: exit 2 ({r.stderr.strip()[-200:]!r})")
none = load(GUESS)
none["T_f"] = None
none["status"] = "infeasible"
NONE = os.path.join(WORK, "none.json")
with open(NONE, "w") as f:
    json.dump(none, f)
r = run("solve", SWAP, "--guess", NONE, "--out", os.path.join(WORK, "x3"))
check(r.returncode == 2 and "holds no trajectory (T_f is null, status infeasible)" in r.stderr,
      f"a file without a trajectory: exit 2 ({r.stderr.strip()[-200:]!r})")
NOTJSON = os.path.join(WORK, "not.json")
with open(NOTJSON, "w") as f:
    f.write("robots: [")
r = run("solve", SWAP, "--guess", NOTJSON, "--out", os.path.join(WORK, "x4"))
check(r.returncode == 2 and f"--guess {NOTJSON}: not JSON" in r.stderr, "a file that is not JSON: exit 2")

# search --guess: start 0 of the file's scene starts from it.
sdir = os.path.join(WORK, "search")
r = run("search", SWAP, "--set", "scene.steps=16", "--starts", "2", "--guess", GUESS, "--out", sdir,
        "--quiet")
check(r.returncode == 0, f"search --guess: exit 0 ({r.stderr[-300:]!r})")
with open(os.path.join(sdir, "runs.jsonl")) as f:
    rs = {j["start"]: j for j in map(json.loads, f)}
check(rs[0]["guess"] == "given" and GUESS in rs[0]["description"]
      and rs[1]["guess"] != "given", f"start 0 starts from the file, start 1 does not "
      f"({rs[0]['description']!r}, {rs[1]['guess']!r})")
manifest = load(os.path.join(sdir, "manifest.json"))
mg = manifest["scenes"][0]["guess"]
check(mg == {"file": GUESS, "sha256": sha256(GUESS)}, f"the manifest names the guess ({mg})")
best_sol = load(os.path.join(sdir, "best", "two_robots_swap_avoid.json"))
want = GUESS if best_sol["provenance"]["start"] == 0 else None
check((best_sol["provenance"]["guess"] or {}).get("file") == want,
      f"the best solution's provenance names the guess iff start 0 gave it "
      f"({best_sol['provenance']['start']}, {best_sol['provenance']['guess']})")
PLAIN = os.path.join(WORK, "plain", "solution.json")
r = run("search", SWAP, "--set", "scene.steps=16", "--starts", "2", "--guess", PLAIN, "--out", sdir,
        "--resume")
check(r.returncode == 2 and "holds a different run" in r.stderr
      and f"--guess {GUESS} sha256" in r.stderr and f"there, {PLAIN} sha256" in r.stderr,
      f"resume with another guess file: refused, both files named ({r.stderr.strip()[-400:]!r})")
r = run("search", SWAP, "--set", "scene.steps=16", "--starts", "2", "--guess", NOTJSON, "--out", sdir,
        "--resume")
check(r.returncode == 2 and "not JSON" in r.stderr, "a bad guess file under search: exit 2")
r = run("search", SWAP, AXIS, "--starts", "1", "--guess", AXIS_SOL, "--guess", AXIS_SOL,
        "--out", os.path.join(WORK, "two"))
check(r.returncode == 2 and "scene 'one_robot_axis' already has one" in r.stderr,
      f"two guesses for one scene: refused ({r.stderr.strip()[-200:]!r})")
other = load(AXIS_SOL)
other["scenario"] = "no_such_scene"
OTHER = os.path.join(WORK, "other.json")
with open(OTHER, "w") as f:
    json.dump(other, f)
r = run("search", SWAP, AXIS, "--starts", "1", "--guess", OTHER, "--out", os.path.join(WORK, "two"))
check(r.returncode == 2 and "its scenario 'no_such_scene' is not a scene of this search "
      "(two_robots_swap_avoid, one_robot_axis)" in r.stderr,
      f"a guess for no scene of a search of two: refused ({r.stderr.strip()[-200:]!r})")

# Coarse to fine.
r = run("solve", SWAP, "--set", "scene.steps=16", "--set", "feasibility.coarse_fraction=0.5",
        "--out", os.path.join(WORK, "c2f"))
lines = solve_lines(r.stderr)
phases = [p for _, p, _, _, _ in lines]
n_coarse = sum(p.startswith("coarse ") for p in phases)
check(r.returncode == 0 and load(os.path.join(WORK, "c2f", "solution.json"))["status"] == "solved",
      f"coarse to fine: certified ({r.stderr[-300:]!r})")
check(n_coarse > 0 and all(p.startswith("coarse ") for p in phases[:n_coarse])
      and not any(p.startswith("coarse ") for p in phases[n_coarse:])
      and phases[n_coarse] == "feasibility",
      f"the coarse solves come first, then the full scene's feasibility solve ({phases})")
check(not any(marked for _, p, _, _, marked in lines if p.startswith("coarse ")),
      "no coarse solve is marked as a new best")
finish("guess_tests")
