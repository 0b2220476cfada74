#!/usr/bin/env python3
"""The command line's traps (run by CTest as cli.traps and cli.clock; see tests/CMakeLists.txt).

  cli_tests.py DISCO SCENES WORKDIR [traps | clock | ordering | rescue]

clock: on the simulated clock (`clock.kind: iterations`) a time-limited solve gives the same
point, counts and time twice, and a bad clock key is refused. ordering: on a dense contact
scene the KKT analyses keep METIS's nested dissection (kkt.ldlt.ordering), counted in
solution.json and the log, and none with the threshold out of reach. rescue: the polishes that
kkt.polish_rescue started again are counted alike in solution.json, the summary and the solve
log, and none with its solver 'same'. traps (the default):
Each check runs disco and looks at its exit status and messages: the scene file may come
after --set; an unknown command is named, with the closest one; a settings key that is a
scene key gets the 'scene.' hint, a mistyped one the closest key; --model-only checks every
option (Ipopt's too); a model above model.memory_limit is refused at once (exit 2); --version;
--help lists the exit statuses and the defaults of --starts and --out; SIGINT during
`disco solve` writes the best point so far and exits 130.
"""
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

from script_checks import check, finish

DISCO, SCENES, WORK = sys.argv[1:4]
MODE = sys.argv[4] if len(sys.argv) > 4 else "traps"
ENV = dict(os.environ, OMP_NUM_THREADS="1")
AXIS = os.path.join(SCENES, "one_robot_axis.yaml")
os.makedirs(WORK, exist_ok=True)


def run(*args):
    return subprocess.run([DISCO, *args], env=ENV, capture_output=True, text=True)


if MODE == "ordering":
    # kkt.ldlt.ordering (core/linalg/permuted_symmetric.h): on a dense contact scene (scene 5
    # of `scripts/bench_random --kind mixed --seed 1`: 4 robots in contact pairs, two contact
    # posts, 40 steps), AMD's elimination needs 1.8e8 multiply-adds, far above the threshold,
    # and nested dissection's fewer: the analyses keep it, and say so (solution.json and the
    # log); with the threshold out of reach, none does. The first Ipopt iterations only (the
    # simulated clock cuts the solve at the same iteration every time).
    scene = os.path.join(WORK, "dense_contact.yaml")
    with open(scene, "w") as f:
        f.write("""scenario: dense_contact
steps: 40
robots:
  - {name: r0, radius: 0.213, mass: 1.907, mu: 0.448, force_max: 24.596, K: 16, start: {x: -0.628, y: 0.196}, target: {x: 0.097, y: -0.000, vx: 0, vy: 0}}
  - {name: r1, radius: 0.206, mass: 2.793, mu: 0.460, force_max: 17.223, K: 8, start: {x: 1.469, y: 2.214}, target: {x: -2.010, y: 3.816, vx: 0, vy: 0}}
  - {name: r2, radius: 0.504, mass: 1.347, mu: 0.134, force_max: 2.369, K: 16, start: {x: 3.431, y: -3.518}, target: {x: 1.545, y: -0.437, vx: 0, vy: 0}}
  - {name: r3, radius: 0.212, mass: 2.236, mu: 0.104, force_max: 7.343, K: 16, start: {x: 3.546, y: 2.694}, target: {x: -1.822, y: 2.832, vx: 0, vy: 0, phi: 0.350}}
obstacles:
  - {name: ob0, disk: {x: 0.921, y: -1.731, radius: 0.293}, mode: contact}
  - {name: ob1, disk: {x: -1.863, y: 0.451, radius: 0.254}, mode: contact}
pairs: {mode: contact, mu: 0.226}
""")
    counts = {}
    for name, above in (("judged", None), ("amd_only", "1e300")):
        out = os.path.join(WORK, name)
        extra = [] if above is None else ["--set", f"kkt.ldlt.ordering.nested_dissection_above={above}"]
        r = run("solve", scene, "--threads", "1", "--set", "clock.kind=iterations", "--set",
                "clock.seconds_per_iteration=0.01", "--set", "reduction.time_limit=0.05", "--out", out,
                *extra)
        path = os.path.join(out, "solution.json")
        kkt = json.load(open(path))["timing"]["kkt"] if os.path.exists(path) else {}
        logged = re.search(r"(\d+) analyses ordered by nested dissection", r.stderr)
        counts[name] = (r.returncode, kkt.get("nested_dissection"), logged and int(logged.group(1)),
                        kkt.get("factorisations"))
    judged, amd_only = counts["judged"], counts["amd_only"]
    check(judged[0] in (0, 3) and judged[1] is not None and judged[1] >= 1 and judged[2] == judged[1],
          f"a dense contact scene: its analyses keep nested dissection, counted in solution.json and "
          f"the log (exit, solution.json, log, factorisations: {judged})")
    check(amd_only[0] in (0, 3) and amd_only[1] == 0 and amd_only[2] == 0 and amd_only[3],
          f"with nested_dissection_above out of reach: AMD only (exit, solution.json, log, "
          f"factorisations: {amd_only})")
    finish("cli_tests ordering")

if MODE == "rescue":
    # kkt.polish_rescue (core/ipopt/ipopt_solver.h): with `after` 1 every polish that Ipopt has
    # not ended at its first iterate is started again by the pivoting LDLT; the count is the
    # same in solution.json, the summary's KKT line and the --verbose solve log ("rescued").
    # With the solver 'same' there is no rescue.
    counts = {}
    for name, rescue in (("rescued", "pivoted"), ("same", "same")):
        out = os.path.join(WORK, name)
        r = run("solve", AXIS, "--set", "scene.steps=20", "--set", "kkt.polish_rescue.after=1",
                "--set", f"kkt.polish_rescue.solver={rescue}", "--out", out, "-v")
        path = os.path.join(out, "solution.json")
        doc = json.load(open(path)) if os.path.exists(path) else {}
        summary = re.search(r"(\d+) polish solves started again by kkt.polish_rescue", r.stderr)
        counts[name] = (r.returncode, doc.get("status"), doc.get("timing", {}).get("kkt", {}).get("polish_rescues"),
                        summary and int(summary.group(1)), r.stderr.count("rescued (kkt.polish_rescue)"),
                        r.stderr.count("ipopt polish"))
    rescued, same = counts["rescued"], counts["same"]
    check(rescued[0] == 0 and rescued[1] == "solved" and rescued[2] is not None and rescued[2] >= 1
          and rescued[2] == rescued[3] == rescued[4] and rescued[4] <= rescued[5],
          f"after 1: polishes rescued, counted alike in solution.json, the summary and the log "
          f"(exit, status, solution.json, summary, log, polishes: {rescued})")
    check(same[0] == 0 and same[1] == "solved" and same[2] == 0 and same[3] == 0 and same[4] == 0
          and same[5] >= 1,
          f"solver same: no rescue (exit, status, solution.json, summary, log, polishes: {same})")
    finish("cli_tests rescue")

if MODE == "clock":
    # The simulated clock (`clock.kind: iterations`, core/util/clock.h): a time-limited solve
    # cuts at the same Ipopt iteration every time, so two runs give the same point, counts and
    # time; a bad clock setting is refused at once, naming the key.
    clocked = []
    for k in range(2):
        out = os.path.join(WORK, f"clock{k}")
        r = run("solve", AXIS, "--set", "scene.steps=20", "--set", "clock.kind=iterations", "--set",
                "clock.seconds_per_iteration=0.01", "--set", "reduction.time_limit=0.4", "--out", out)
        doc = json.load(open(os.path.join(out, "solution.json"))) if r.returncode == 0 else {}
        clocked.append((repr(doc.get("T_f")), doc.get("timing"), r.stderr.count("time limit")))
    check(clocked[0] == clocked[1] and clocked[0][2] > 0 and clocked[0][1]["wall_s"] <= 0.4 + 0.01 + 1e-9,
          f"solve on the simulated clock, reduction.time_limit=0.4: cut, the same point, counts "
          f"and time twice ({clocked})")
    r = run("solve", AXIS, "--model-only", "--set", "clock.kind=cpu")
    check(r.returncode == 2 and "key 'clock.kind': must be 'wall' or 'iterations', got 'cpu'" in r.stderr,
          f"a bad clock.kind is refused naming the key ({r.stderr.strip()[-200:]!r})")
    finish("cli_tests clock")

r = run("solve", "--set", "scene.steps=10", AXIS, "--model-only")
check(r.returncode == 0 and "N_t = 10" in r.stderr,
      f"solve --set KEY=VALUE SCENE: the scene file after --set is the scene ({r.stderr[-200:]!r})")
r = run("solve", "--set", "scene.steps=10", "--set", "elastic.zeta=20", AXIS, "--model-only")
check(r.returncode == 0 and "N_t = 10" in r.stderr, "two --set, then the scene file")
r = run("search", "--set", "scene.steps=10", AXIS, os.path.join(SCENES, "one_robot_diagonal.yaml"),
        "--starts", "1", "--out", os.path.join(WORK, "search_order"), "--force")
check(r.returncode == 0 and "2 scene(s)" in r.stderr, "search --set KEY=VALUE CONFIG CONFIG: both configs")

r = run("sovle", AXIS)
check(r.returncode == 2 and "unknown command 'sovle' (did you mean 'solve'?)" in r.stderr,
      f"an unknown command is named, with the closest one ({r.stderr.strip()!r})")
r = run("serach", AXIS)
check(r.returncode == 2 and "did you mean 'search'?" in r.stderr, "serach: did you mean 'search'?")

r = run("solve", AXIS, "--set", "steps=10", "--model-only")
check(r.returncode == 2 and "key 'steps'" in r.stderr and "scene.steps" in r.stderr,
      f"--set steps=10: the hint that scene keys take 'scene.' ({r.stderr.strip()!r})")
r = run("solve", AXIS, "--set", "zeta_max=1e8", "--model-only")
check(r.returncode == 2 and "did you mean 'elastic.zeta_max'?" in r.stderr,
      f"--set zeta_max=...: did you mean 'elastic.zeta_max'? ({r.stderr.strip()!r})")
r = run("solve", AXIS, "--set", "elastic.zeta_mx=1e8", "--model-only")
check(r.returncode == 2 and "did you mean 'elastic.zeta_max'" in r.stderr, "a typo in a settings key")

r = run("solve", AXIS, "--model-only", "--set", "ipopt.tolerance=1e-6")
check(r.returncode == 2 and "ipopt.tolerance" in r.stderr and "Ipopt has no such option" in r.stderr,
      f"--model-only checks Ipopt's options ({r.stderr.strip()[-200:]!r})")
r = run("solve", AXIS, "--model-only", "--set", "elastic.zeta_max=-1")
check(r.returncode == 2 and "elastic.zeta_max" in r.stderr, "--model-only checks the elastic settings")

# A size a user can mistype is refused before anything is built (exit 2, at once).
for command in ("solve", "search"):
    t0 = time.monotonic()
    r = run(command, AXIS, "--set", "scene.steps=200000", "--set", "model.memory_limit=8",
            "--out", os.path.join(WORK, "too_big"), "--force" if command == "search" else "--quiet")
    seconds = time.monotonic() - t0
    check(r.returncode == 2 and "--set: key 'steps': the model would need about" in r.stderr and
          "above model.memory_limit = 8.0 GiB (--set)" in r.stderr and seconds < 20,
          f"{command}: 200000 steps refused in {seconds:.1f} s, exit {r.returncode} ({r.stderr.strip()[-300:]!r})")

r = run("--version")
check(r.returncode == 0 and re.fullmatch(r"\d+\.\d+\.\d+ \(git [0-9a-f]+(-dirty)?\)\n|\d+\.\d+\.\d+ \(git unknown\)\n",
                                         r.stdout) is not None,
      f"--version prints the version and the commit ({r.stdout!r})")

r = run("--help")
check(r.returncode == 0 and "Exit status: 0" in r.stdout and "130" in r.stdout and "3 finished" in r.stdout,
      "--help lists the exit statuses")
r = run("search", "--help")
check(r.returncode == 0 and re.search(r"--starts \S+=the benchmark file's", r.stdout) and
      "--out TEXT=runs/search" in r.stdout and "--force" in r.stdout and "Exit status" in r.stdout,
      f"search --help gives the defaults of --starts and --out ({r.stdout[:0]})")
r = run("solve", "--help")
check(r.returncode == 0 and "--out TEXT=out/SCENARIO" in r.stdout, "solve --help gives --out's default")

# solution.json says where it came from.
out = os.path.join(WORK, "provenance")
r = run("solve", "--set", "scene.steps=10", AXIS, "--out", out, "--seed", "3", "--start", "1")
doc = json.load(open(os.path.join(out, "solution.json")))
p = doc.get("provenance", {})
version = run("--version").stdout.strip()
check(r.returncode == 0 and p.get("mode") == "solve" and p.get("scene_file") == AXIS and
      p.get("scene_sha256") == hashlib.sha256(open(AXIS, "rb").read()).hexdigest() and
      p.get("scene_overrides") == ["steps=10"] and p.get("overrides") == ["scene.steps=10"] and
      p.get("seed") == 3 and p.get("start") == 1 and p.get("version") == version and
      len(p.get("settings_sha256", "")) == 64,
      f"solve: solution.json's provenance names the inputs ({p})")
check(len(doc.get("time") or []) == 11 and doc["time"][-1] == doc["T_f"], "solve: the time array")

# SIGINT during a solve: the best point so far is written, and the exit status says so.
out = os.path.join(WORK, "interrupted_solve")
shutil.rmtree(out, ignore_errors=True)
# The signal goes when the verbose log says the first phase has ended (not after a fixed sleep,
# whose verdict would depend on the machine's speed): seven more phases are still to come.
proc = subprocess.Popen([DISCO, "solve", os.path.join(SCENES, "three_robots_contact.yaml"), "--out", out,
                         "--verbose"], env=ENV, stderr=subprocess.PIPE, text=True)
seen = []
for line in proc.stderr:
    seen.append(line)
    if re.match(r"\s+1 feasibility\s", line):
        proc.send_signal(signal.SIGINT)
        break
_, err = proc.communicate(timeout=60)
err = "".join(seen) + err
check(proc.returncode == 130 and "interrupted: the solve stopped early;" in err,
      f"solve: SIGINT exits 130 and says so ({proc.returncode}, {err.strip()[-200:]!r})")
check(os.path.isfile(os.path.join(out, "solution.json")), "solve: SIGINT still writes solution.json")

finish("cli_tests")
