#!/usr/bin/env python3
"""End-to-end tests of `disco search` (run by CTest; see tests/CMakeLists.txt).

  search_tests.py DISCO MPIEXEC BENCHMARK WORKDIR MODE
MODE:
  mpi2         mpirun -np 2: every start recorded once, both ranks worked, best.json
               and best/<scene>.json consistent with runs.jsonl.
  determinism  1 rank (no mpirun) and 2 ranks: the same set of runs (scene, start,
               status, T_f bit for bit) and the same best T_f per scene.
  resume       a 2-rank search killed after its first finished start, then --resume:
               every start exactly once in runs.jsonl, the same best as a clean run.
  timelimit    --time-limit 3 on one rank: hands out no start after 3 s, ends soon after
               (starts in flight get only the time left), says so in best.json, and
               keeps the best of what finished.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

from script_checks import check, failures, finish

DISCO, MPIEXEC, BENCH, WORK, MODE = sys.argv[1:6]
MPI = [MPIEXEC, "-np", "2", "--allow-run-as-root", "--oversubscribe"]
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def search(out, ranks, *extra):
    shutil.rmtree(out, ignore_errors=True)
    cmd = (MPI if ranks == 2 else []) + [DISCO, "search", BENCH, "--seed", "7", "--out", out, *extra]
    return subprocess.run(cmd, env=ENV).returncode


def runs(out):
    with open(os.path.join(out, "runs.jsonl")) as f:
        return [json.loads(line) for line in f if line.strip()]


def key_set(rs):
    return sorted((r["scene"], r["start"], r["status"], repr(r["T_f"])) for r in rs)


def best(out):
    with open(os.path.join(out, "best.json")) as f:
        return json.load(f)


def check_consistent(out, label, timing=False):
    rs, b = runs(out), best(out)
    pairs = [(r["scene"], r["start"]) for r in rs]
    check(len(pairs) == len(set(pairs)), f"{label}: every start recorded once ({len(pairs)} lines)")
    check(b["starts_finished"] == b["starts_total"] == len(rs), f"{label}: best.json counts all starts")
    for scene, s in b["scenes"].items():
        solved = [r for r in rs if r["scene"] == scene and r["status"] == "solved"]
        if not solved:
            check(s["T_f"] is None, f"{label}: {scene} has no best")
            continue
        m = min(solved, key=lambda r: (r["T_f"], r["start"]))
        check(s["T_f"] == m["T_f"] and s["start"] == m["start"],
              f"{label}: {scene} best is start {m['start']} T_f {m['T_f']}")
        with open(os.path.join(out, s["solution"])) as f:
            sol = json.load(f)
        check(sol["T_f"] == m["T_f"] and sol["status"] == "solved",
              f"{label}: {scene} solution file matches its best")
        check(sol["certificate"]["max_violation"] <= 1e-6 and sol["certificate"]["max_complementarity"] <= 1e-6,
              f"{label}: {scene} best is certified")
        # Scene times (of one uninterrupted search): when a rank found the points,
        # so the first feasible point comes before any start of the scene
        # finished, and before the best.
        if not timing:
            continue
        ff, tb = s["time_to_first_feasible_s"], s["time_to_best_s"]
        first_done = min(r["finished_s"] for r in solved) - s["started_s"]
        check(0 <= ff <= tb <= s["wall_s"] + 1e-3 and ff < first_done,
              f"{label}: {scene} first feasible {ff:.2f} s <= best {tb:.2f} s <= wall "
              f"{s['wall_s']:.2f} s, and before the first start finished ({first_done:.2f} s)")


if MODE == "mpi2":
    out = os.path.join(WORK, "mpi2")
    check(search(out, 2) == 0, "mpirun -np 2 disco search exits 0")
    check_consistent(out, "np2", timing=True)
    check(sorted({r["rank"] for r in runs(out)}) == [0, 1], "both ranks ran starts")
elif MODE == "determinism":
    a, b = os.path.join(WORK, "det1"), os.path.join(WORK, "det2")
    check(search(a, 1) == 0, "1-rank search exits 0")
    check(search(b, 2) == 0, "2-rank search exits 0")
    check(key_set(runs(a)) == key_set(runs(b)), "same runs (scene, start, status, T_f) for 1 and 2 ranks")
    ba, bb = best(a)["scenes"], best(b)["scenes"]
    check({k: (v["T_f"], v.get("start")) for k, v in ba.items()} ==
          {k: (v["T_f"], v.get("start")) for k, v in bb.items()}, "same best T_f and start per scene")
elif MODE == "resume":
    clean, out = os.path.join(WORK, "clean"), os.path.join(WORK, "resume")
    check(search(clean, 2) == 0, "clean 2-rank search exits 0")
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.Popen(MPI + [DISCO, "search", BENCH, "--seed", "7", "--out", out],
                            env=ENV, start_new_session=True)
    path = os.path.join(out, "runs.jsonl")
    deadline = time.time() + 120
    while time.time() < deadline and not (os.path.exists(path) and os.path.getsize(path) > 0):
        time.sleep(0.05)
    # Kill the whole run: mpirun's group and every rank (ranks may outlive mpirun).
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    pattern = f"search {BENCH} --seed 7 --out {out}"
    subprocess.run(["pkill", "-KILL", "-f", pattern])
    while subprocess.run(["pgrep", "-f", pattern], stdout=subprocess.DEVNULL).returncode == 0:
        time.sleep(0.05)
    before = len(runs(out))
    check(0 < before < best(clean)["starts_total"], f"killed after {before} finished start(s)")
    resumed = subprocess.run(MPI + [DISCO, "search", BENCH, "--seed", "7", "--out", out, "--resume"],
                             env=ENV)
    check(resumed.returncode == 0, "--resume exits 0")
    check_consistent(out, "resumed")
    check({k: v["T_f"] for k, v in best(out)["scenes"].items()} ==
          {k: v["T_f"] for k, v in best(clean)["scenes"].items()}, "resumed best equals the clean run's")
elif MODE == "timelimit":
    out = os.path.join(WORK, "timelimit")
    t0 = time.time()
    code = search(out, 1, "--time-limit", "3")
    wall = time.time() - t0
    b = best(out)
    check(code in (0, 3), f"time-limited search exits 0 or 3 (got {code})")
    check(wall < 3 + 10, f"ends soon after the limit ({wall:.1f} s)")
    check(b["time_limit_reached"] is True, "best.json says the time limit was reached")
    check(0 < b["starts_finished"] < b["starts_total"], f"{b['starts_finished']} of {b['starts_total']} starts ran")
    rs = runs(out)
    check(len(rs) == b["starts_finished"], "runs.jsonl holds every finished start")
    for scene, sb in b["scenes"].items():
        solved = [r["T_f"] for r in rs if r["scene"] == scene and r["status"] == "solved"]
        check(sb["T_f"] == (min(solved) if solved else None), f"{scene}: best of what finished")
else:
    sys.exit(f"unknown mode {MODE}")

finish(f"search_tests {MODE}")
