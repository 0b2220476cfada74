#!/usr/bin/env python3
"""Stress tests: `disco solve` on each scene of configs/stress/ (run by CTest as stress.NAME;
see tests/CMakeLists.txt). The expectations, computed from the scene files alone, are in
tests/stress_cases.py.

  stress_tests.py DISCO WORKDIR NAME
NAME:
  a scene    solves it (OMP_NUM_THREADS=1) into WORKDIR/NAME and checks, by its expected
             outcome: the exit status (0 solved, 3 without a solution, 2 bad input); the
             status; no NaN or Inf anywhere in solution.json; when solved, the certificate
             within configs/disco.yaml's elastic.violation_tolerance and
             complementarity_tolerance and T_f equal to the expected time (relative 1e-6; for
             a case with "starts", T_f not below it, and the best of a `disco search` with
             that many starts equal to it);
             without a solution, T_f, h and every trajectory null; for a failed solve, the
             detail naming Ipopt's status; for bad input, the message naming the file, the
             line and the key, and no solution written.
  scale      after stress.scale_m, stress.scale_mm, stress.scale_mass1000 (a CTest fixture):
             the three files are the same scene in m, in mm, and with masses x1000, and their
             solutions have the same T_f in seconds (relative 1e-6).
  search_nan `disco search` (one process) on overflow (every evaluation at its start point
             overflows) and mu_0: the overflow starts are recorded as failed with Ipopt's
             Invalid_Number_Detected, the search goes on and solves mu_0 at its expected time,
             and exits 3 (a scene without a solution, search/run_search.h).
"""
import json
import os
import shutil
import subprocess
import sys

import stress_cases as sc
from script_checks import check, finish

DISCO, WORK, NAME = sys.argv[1:4]
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def rel(a, b):
    return abs(a - b) / abs(b)


def solve(name, out):
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run([DISCO, "solve", sc.scene_path(name), "--out", out], env=ENV,
                       capture_output=True, text=True)
    sys.stderr.write(r.stderr)
    return r


def check_scene(name):
    out = os.path.join(WORK, name)
    r = solve(name, out)
    checks, _ = sc.assess(name, r.returncode, r.stderr, os.path.join(out, "solution.json"))
    for ok, what in checks:
        check(ok, what)
    starts = sc.CASES[name].get("starts")
    if starts:  # the optimum is the best of a search (one process)
        search = os.path.join(WORK, name + "_search")
        shutil.rmtree(search, ignore_errors=True)
        r = subprocess.run([DISCO, "search", sc.scene_path(name), "--starts", str(starts), "--seed", "1",
                            "--out", search], env=ENV)
        check(r.returncode == 0, f"{name}: disco search --starts {starts} exits 0 (got {r.returncode})")
        with open(os.path.join(search, "best.json")) as f:
            T = json.load(f)["scenes"][name]["T_f"]
        expected = sc.expected_T(name)
        check(T is not None and rel(T, expected) <= sc.REL_TOL,
              f"{name}: the best of {starts} starts {T} = expected {expected:.12g} (relative <= {sc.REL_TOL})")


def check_scale():
    """The triple is one scene in three unit systems; the same T_f."""
    base = sc.load_scene("scale_m")
    factors = {"scale_mm": (1000.0, 1.0), "scale_mass1000": (1.0, 1000.0)}  # (length, mass)
    for name, (L, M) in factors.items():
        s = sc.load_scene(name)
        same = s["steps"] == base["steps"] and len(s["robots"]) == len(base["robots"])
        same = same and abs(s["gravity"] - L * base["gravity"]) <= 1e-12 * L * base["gravity"]
        for a, b in zip(s["robots"], base["robots"]):
            pairs = [(a["radius"], L * b["radius"]), (a["mass"], M * b["mass"]),
                     (a["force_max"], L * M * b["force_max"]), (a["mu"], b["mu"])]
            for part in ("start", "target"):
                pairs += [(a[part][k], L * b[part][k]) for k in ("x", "y")]
            same = same and all(abs(x - y) <= 1e-12 * abs(y) for x, y in pairs)
            same = same and all(a[k] == b[k] for k in ("K", "force_dims", "force_axis", "name"))
        for key, p in s["pairs"].items():
            q = base["pairs"][key]
            same = same and p["mode"] == q["mode"] and abs(p["safe_distance"] - L * q["safe_distance"]) <= 1e-12
        check(same, f"{name} is scale_m with lengths x{L:g} and masses x{M:g} (forces x{L * M:g})")
    T = {}
    for name in sc.SCALE_GROUP:
        doc, _ = sc.load_solution(os.path.join(WORK, name, "solution.json"))
        T[name] = doc["T_f"] if doc["status"] == "solved" else None
    check(all(v is not None for v in T.values()), f"all three solved ({T})")
    if all(v is not None for v in T.values()):
        for name in sc.SCALE_GROUP[1:]:
            check(rel(T[name], T["scale_m"]) <= sc.REL_TOL,
                  f"{name}: T_f {T[name]!r} s = scale_m's {T['scale_m']!r} s "
                  f"(relative {rel(T[name], T['scale_m']):.2g} <= {sc.REL_TOL})")


def check_search_nan():
    out = os.path.join(WORK, "search_nan")
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run([DISCO, "search", sc.scene_path("overflow"), sc.scene_path("mu_0"),
                        "--starts", "2", "--seed", "1", "--out", out], env=ENV)
    check(r.returncode == 3, f"disco search exits 3: a scene has no solution (got {r.returncode})")
    with open(os.path.join(out, "runs.jsonl")) as f:
        runs = [json.loads(line) for line in f if line.strip()]
    over = [x for x in runs if x["scene"] == "overflow"]
    mu0 = [x for x in runs if x["scene"] == "mu_0"]
    check(len(over) == 2 and all(x["status"] == "failed" and "Invalid_Number_Detected" in x["detail"]
                                 for x in over),
          f"both overflow starts recorded as failed, naming Invalid_Number_Detected "
          f"({[(x['status'], x['detail']) for x in over]})")
    # (sharing the incumbent, a later start may stop dominated: certified, above start 0's best)
    check(len(mu0) == 2 and all(x["status"] in ("solved", "dominated") and x["T_f"] is not None
                                for x in mu0), "the search went on: mu_0 solved")
    with open(os.path.join(out, "best.json")) as f:
        best = json.load(f)["scenes"]
    expected = sc.expected_T("mu_0")
    T = best["mu_0"]["T_f"]
    check(T is not None and rel(T, expected) <= sc.REL_TOL, f"mu_0 best {T} = expected {expected:.12g}")
    check(best["overflow"]["T_f"] is None, "overflow has no best")


if NAME == "scale":
    check_scale()
elif NAME == "search_nan":
    check_search_nan()
else:
    try:
        check_scene(NAME)
    except sc.PremiseError as e:
        check(False, f"{NAME}: the scene fits its expectation's premise ({e})")
finish(f"stress_tests {NAME}")
