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
  logging      logs go to stderr and results to files (stdout stays empty): the progress
               line by default, a live status line on a terminal only, nothing with --quiet, every start's solve log and every
               Ipopt solve with --verbose (each line naming its rank); the same for
               `disco solve`; --quiet with --verbose is a usage error (exit 2).
"""
import json
import re
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
elif MODE == "logging":
    def run(cmd, out):
        shutil.rmtree(out, ignore_errors=True)
        return subprocess.run(cmd, env=ENV, capture_output=True, text=True)

    def searched(out, *extra):
        return run(MPI + [DISCO, "search", BENCH, "--starts", "1", "--out", out, *extra], out)

    out = os.path.join(WORK, "default")
    r = searched(out)
    check(r.returncode == 0 and r.stdout == "", f"default: exit 0, stdout empty ({r.stdout[:80]!r})")
    lines = r.stderr.splitlines()
    progress = [l for l in lines if l.startswith("[")]
    check(len(progress) == 2 and all(" | best " in l and " ETA " in l for l in progress),
          f"default: one progress line per start with best and ETA ({progress})")
    check(progress[-1].startswith("[2/2]"), "default: the last line counts 2 of 2")
    check(not any("ipopt" in l for l in lines), "default: no Ipopt lines")
    check("\r" not in r.stderr and "\x1b[" not in r.stderr,
          "default, not on a terminal: no live line, no control characters")
    check(best(out)["starts_finished"] == 2, "default: results in best.json")

    out = os.path.join(WORK, "quiet")
    r = searched(out, "--quiet")
    check(r.returncode == 0 and r.stdout == "" and r.stderr == "",
          f"--quiet: exit 0, nothing on stdout or stderr ({r.stderr[:200]!r})")
    check(len(runs(out)) == 2 and best(out)["starts_finished"] == 2, "--quiet: results written")

    out = os.path.join(WORK, "verbose")
    r = searched(out, "--verbose")
    lines = r.stderr.splitlines()
    check(r.returncode == 0 and r.stdout == "", "--verbose: exit 0, stdout empty")
    check(all(l.startswith(("[rank 0] ", "[rank 1] ")) for l in lines),
          "--verbose: every line names its rank")
    for scene in best(out)["scenes"]:
        check(any(f"{scene} start 0:   1 feasibility" in l for l in lines),
              f"--verbose: {scene}'s solve log")
    check(sum("ipopt elastic" in l for l in lines) >= 2, "--verbose: the Ipopt solves")
    check(sum("ipopt" in l and "[rank 1]" in l for l in lines) >= 1, "--verbose: from rank 1 too")

    # On a terminal (a pseudo-terminal from script(1)): the live line, erased before each
    # log line and drawn again below it, cut to the terminal's width.
    out = os.path.join(WORK, "terminal")
    shutil.rmtree(out, ignore_errors=True)
    swap = os.path.join(os.path.dirname(BENCH), "../scenarios/two_robots_swap_avoid.yaml")
    cmd = f"{DISCO} search {swap} --set scene.steps=15 --starts 3 --out {out}"
    r = subprocess.run(["script", "-qec", cmd, "/dev/null"], env=ENV, capture_output=True)
    tty = r.stdout.decode(errors="replace")  # as bytes: "\r" kept
    # After each erase ("\r\x1b[K"): log lines ("...\r\n"), then the status drawn anew.
    status = [seg.split("\r\n")[-1] for seg in tty.split("\r\x1b[K")]
    status = [x for x in status if x.startswith("[") and " ETA " in x]
    check(r.returncode == 0 and "[3/3] two_robots_swap_avoid start" in tty,
          f"on a terminal: exit 0, the progress lines ({r.returncode})")
    # Which counts a tick catches depends on timing: any after the first start finished.
    check(any(re.match(r"\[[123]/3\] elapsed \d\d:\d\d:\d\d ETA \d\d:\d\d:\d\d \| best "
                       r"two_robots_swap_avoid \d+\.\d{6}", x) for x in status) and
          any(" | running: " in x for x in status),
          f"on a terminal: the live line ({status[:2]})")
    check(status and all(len(x) < 80 for x in status),
          "on a terminal: the live line fits its width (80 columns)")
    check(best(out)["starts_finished"] == 3, "on a terminal: results written")

    sol = os.path.join(WORK, "solve")
    solve = [DISCO, "solve", os.path.join(os.path.dirname(BENCH), "../scenarios/one_robot_axis.yaml"),
             "--set", "scene.steps=20", "--out", sol]
    r = run(solve + ["--quiet"], sol)
    check(r.returncode == 0 and r.stdout == "" and r.stderr == "", "solve --quiet: exit 0, silent")
    check(os.path.isfile(os.path.join(sol, "solution.json")), "solve --quiet: solution.json written")
    r = run(solve, sol)
    check(r.returncode == 0 and r.stdout == "" and "  1 feasibility" in r.stderr and
          "ipopt" not in r.stderr, "solve: stdout empty, the solve log on stderr")
    r = run(solve + ["--verbose"], sol)
    check(r.returncode == 0 and r.stdout == "" and "ipopt polish" in r.stderr,
          "solve --verbose: the Ipopt solves too")
    r = run(solve + ["--quiet", "--verbose"], sol)
    check(r.returncode == 2 and "excludes" in r.stderr, "--quiet with --verbose: exit 2")
else:
    sys.exit(f"unknown mode {MODE}")

finish(f"search_tests {MODE}")
