#!/usr/bin/env python3
"""End-to-end tests of `disco search` (run by CTest; see tests/CMakeLists.txt).

  search_tests.py DISCO MPIEXEC BENCHMARK WORKDIR MODE
MODE:
  mpi2         mpirun -np 2, sharing the incumbent: every start recorded once,
               both ranks worked, best.json and best/<scene>.json consistent with
               runs.jsonl; starts knew other starts' points as their incumbent, and a
               dominated start ended above it, certified.
  mpi8         mpirun -np 8 --oversubscribe, sharing the incumbent, on the smoke scenes at 10
               steps with 12 starts each: every start recorded once, all 8 ranks worked and
               none stopped working while tasks remained, incumbent messages reached workers
               (their --verbose log line).
  determinism  --deterministic, 1 rank (no mpirun) and 2 ranks: the same set of runs (scene,
               start, status, T_f bit for bit) and the same best T_f per scene; no incumbent.
Every mode that compares runs bit for bit (determinism, resume, timelimit, interrupt,
killrandom) runs --deterministic.
  resume       a 2-rank search killed after its first finished start, then --resume:
               every start exactly once in runs.jsonl, the same best as a clean run.
  timelimit    on the simulated clock (time = Ipopt iterations), one rank, two starts per
               scene, a --time-limit halfway through the second start: the first is the clean
               run's, the second is cut (time_limit, the progress line saying so); every start
               from the second on has the time left for budget and ends by one iteration past
               the limit at most; some are never handed out; best.json says so; the same limit
               again gives the same runs; --resume without the limit ends with the runs and
               best of a clean run. Then on the machine's clock, only what holds at any speed
               (starts 0 only): a 0.1 s limit ends the run marked cut, and --resume ends with
               the clean run's runs.
  manifest     OUT/manifest.json: a non-empty OUT is refused without --resume (nothing
               touched) and replaced with --force; --resume refuses a different seed, scene
               set, scene override or setting, naming each difference; a matching --resume
               with more starts runs only the new ones and appends its invocation.
  interrupt    SIGINT to one process, and SIGTERM to both ranks under mpirun (what mpirun
               sends them on Ctrl-C), while starts run: exit 130 / the ranks' SIGTERM,
               "interrupted (...): K of N starts kept ..., L lost ...;
               continue with --resume", the starts in flight recorded as interrupted; then
               --resume ends with the runs and best of a clean run.
  killrandom   10 runs on 2 ranks, some with a time limit, each killed (SIGINT to mpirun, or
               SIGKILL to everything) at a random moment, then resumed without the limit
               (once more if the kill left nothing): each ends with exactly the runs and
               best of a clean run.
  MODE_screened  (determinism, resume, timelimit, killrandom): the same, as a screened search
               (search.screen_fraction 0.5, search.refine_count 2; search/README.md,
               "Screening"; but for resume_screened with early refines,
               search.early_refine_batch 1), every start's screen and refine compared; timelimit_screened: on
               the simulated clock, a limit cuts the same runs twice, and --resume without it
               ends with the runs and best of a clean screened run.
  refinefrom   a screened search with search.refine_from start (2 ranks): every refine ends
               with the status, T_f (bit for bit), iterations and guess of the same start in a
               search without screening, every certified screen is refined (the smoke
               benchmark's scene limit), and the best refine is the scene's best; with
               refine_from both, every refine is the better of the same start's refine from
               its screen (refine_from screen) and its full run with its minimisations run
               as search.refine_minimize_weak says (a search without screening with
               reduction.minimize_weak set so), with both runs' iterations; each run's
               runs.jsonl schedule names how its minimisations ran: a refine chosen from a
               certified screen (refine_from screen or both) search.refine_minimize_weak, every
               other run reduction.minimize_weak.
  logging      logs go to stderr and results to files (stdout stays empty): the progress
               line by default, a live status line on a terminal only, nothing with --quiet, every start's solve log and every
               Ipopt solve with --verbose (each line naming its rank); the same for
               `disco solve`; --quiet with --verbose is a usage error (exit 2).
"""
import json
import re
import os
import random
import shutil
import signal
import subprocess
import sys
import time

import yaml

from script_checks import check, failures, finish

DISCO, MPIEXEC, BENCH, WORK, MODE = sys.argv[1:6]
SCREENED = MODE.endswith("_screened")
MODE = MODE.removesuffix("_screened")
MPI = [MPIEXEC, "-np", "2", "--allow-run-as-root", "--oversubscribe"]
# The benchmark's time limit per scene (the smoke benchmark's: 300 s), if it has one.
with open(BENCH) as f:
    SCENE_LIMIT = (yaml.safe_load(f) or {}).get("time_limit")
ENV = dict(os.environ, OMP_NUM_THREADS="1")
# Screens within this relative difference rank by start (configs/disco.yaml, search.screen_tie).
with open(os.path.join(os.path.dirname(BENCH), "..", "disco.yaml")) as f:
    DEFAULTS = yaml.safe_load(f)
TIE = DEFAULTS["search"]["screen_tie"]


# Runs compared bit for bit (across ranks, with a clean run after a resume) are deterministic:
# each start alone (the default of configs/disco.yaml, forced here). mpi2 and mpi8 share the
# incumbent.
EARLY_BATCH = 1 if SCREENED and MODE != "resume" else 0
DET = ["--deterministic"] + (["--set", "search.screen_fraction=0.5", "--set", "search.refine_count=2",
                              "--set", f"search.early_refine_batch={EARLY_BATCH}"] if SCREENED else [])
SHARED = ["--set", "search.share_incumbent=true"]


def search(out, ranks, *extra):
    shutil.rmtree(out, ignore_errors=True)
    cmd = (MPI if ranks == 2 else []) + [DISCO, "search", BENCH, "--seed", "7", "--out", out, *extra]
    return subprocess.run(cmd, env=ENV).returncode


def runs(out):
    with open(os.path.join(out, "runs.jsonl")) as f:
        return [json.loads(line) for line in f if line.strip()]


def key_set(rs):
    return sorted((r["scene"], r["start"], r.get("stage", "full"), r["status"], repr(r["T_f"]))
                  for r in rs)


def best(out):
    with open(os.path.join(out, "best.json")) as f:
        return json.load(f)


def kill_all(proc, out):
    """SIGKILL to the whole run writing into `out`: mpirun's group and every rank (ranks may
    outlive mpirun)."""
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    pattern = f"search .* --out {re.escape(out)}( |$)"
    subprocess.run(["pkill", "-KILL", "-f", pattern])
    while subprocess.run(["pgrep", "-f", pattern], stdout=subprocess.DEVNULL).returncode == 0:
        time.sleep(0.05)


# The simulated clock (configs/disco.yaml `clock:`, core/util/clock.h): time is Ipopt iterations.
TICK = 0.01
SIM = ["--set", "clock.kind=iterations", "--set", f"clock.seconds_per_iteration={TICK}"]

CUT = ("time_limit", "interrupted")  # a start cut short: --resume runs it again


def latest(rs):
    """Each start's last line (a start cut short and run again has two)."""
    last = {}
    for r in rs:
        last[(r["scene"], r["start"], r.get("stage", "full"))] = r
    return list(last.values())


def below(a, b):
    """search/screening.h's screen_below: a below b by more than the relative tie."""
    return b - a > TIE * max(abs(a), abs(b))


def refine_choice(screens, count):
    """search/screening.h's refine_choice: the certified screens ranked by T_f in groups within
    the tie of their lowest, by start within a group; the best of each homotopy class first,
    then the next best."""
    ranked = sorted((r for r in screens if r["T_f"] is not None), key=lambda r: (r["T_f"], r["start"]))
    group, first = [], None
    for r in ranked:
        if first is None or below(first, r["T_f"]):
            first = r["T_f"]
        group.append(first)
    ranked = [r for _, r in sorted(zip(group, ranked), key=lambda x: (x[0], x[1]["start"]))]
    out, classes = [], set()
    for r in ranked:
        key = (r.get("class") or {}).get("key", "")
        if len(out) < count and (key == "" or key not in classes):
            classes.add(key)
            out.append(r["start"])
    out += [r["start"] for r in ranked if r["start"] not in out][:max(0, count - len(out))]
    return out


def early_refine_choice(screens, batch):
    """search/screening.h's early_refine_choice on a scene whose screens have all ended: each
    batch's best certified screen (by start, replaced only by one below it) if below every
    earlier batch's best."""
    by_start = {r["start"]: r["T_f"] for r in screens}
    out, best_before = [], None
    for first in range(0, len(by_start), batch) if batch > 0 else []:
        chosen = None
        for k in range(first, min(first + batch, len(by_start))):
            if by_start[k] is not None and (chosen is None or below(by_start[k], by_start[chosen])):
                chosen = k
        if chosen is not None:
            if best_before is None or below(by_start[chosen], best_before):
                out.append(chosen)
            best_before = by_start[chosen] if best_before is None else min(best_before, by_start[chosen])
    return out


def check_consistent(out, label, timing=False, limited=False):
    rs, b = runs(out), best(out)
    # A refine from the answer of a screen cut short is not final either: --resume runs the
    # screen again, then the refine (search/search_record.h, stale_refines_).
    screen_status, final = {}, []
    for r in rs:
        key = (r["scene"], r["start"])
        if r.get("stage") == "screen":
            screen_status[key] = r["status"]
        # So is a start run in the time left without a screen: --resume screens it, then refines.
        stale = r.get("stage") == "refine" and (screen_status.get(key) in CUT or key not in screen_status)
        if r["status"] not in CUT and not stale:
            final.append((r["scene"], r["start"], r.get("stage", "full")))
    check(len(final) == len(set(final)), f"{label}: every start ended once ({len(final)} final lines)")
    rs = latest(rs)
    check(all(r["status"] not in CUT for r in rs), f"{label}: no start left cut short")
    check(b["starts_finished"] == b["starts_total"] == len(rs), f"{label}: best.json counts all starts")
    stages = {r.get("stage", "full") for r in rs}
    check(stages == ({"screen", "refine"} if SCREENED else {"full"}), f"{label}: stages {sorted(stages)}")
    for scene, s in b["scenes"].items():
        if SCREENED:
            screens = [r for r in rs if r["scene"] == scene and r["stage"] == "screen"]
            check(all(os.path.exists(os.path.join(out, "screened", scene, f"{r['start']}.json"))
                      for r in screens if r["T_f"] is not None),
                  f"{label}: {scene}: every certified screen's answer is in screened/")
            refined = {r["start"] for r in rs if r["scene"] == scene and r["stage"] == "refine"}
            chosen = refine_choice(screens, 2) + early_refine_choice(screens, EARLY_BATCH)
            # Under the scene's own time limit the time left refines the rest of the ranking
            # and then runs the starts without a certified screen from their own guess
            # (search/README.md, "Screening"): every start, that limit being far away.
            expected = {r["start"] for r in screens} if SCENE_LIMIT else set(chosen)
            # A time limit may have made an earlier run refine others too (from fewer screens).
            check(set(chosen) <= refined and (limited or refined == expected),
                  f"{label}: {scene}: refined {sorted(refined)}, expected {sorted(expected)} (the choice {chosen})")
        # The best: of full starts and refines only (a screen's T_f is a coarser model's).
        solved = [r for r in rs if r["scene"] == scene and r["T_f"] is not None
                  and r.get("stage", "full") != "screen"]
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
        prov = sol.get("provenance", {})
        check(prov.get("mode") == "search" and prov.get("start") == m["start"] and
              prov.get("seed") == m["seed"] and len(prov.get("scene_sha256", "")) == 64,
              f"{label}: {scene} solution file's provenance names its start and seed")
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
    check(search(out, 2, *SHARED) == 0, "mpirun -np 2 disco search exits 0")
    check_consistent(out, "np2", timing=True)
    check(sorted({r["rank"] for r in runs(out)}) == [0, 1], "both ranks ran starts")
    # The shared incumbent (the default): starts handed out after a certified point, or
    # running when one was found, know their scene's best from other starts.
    check(best(out)["mode"] == "shared", "best.json says the incumbent was shared")
    told = [r for r in runs(out) if r["incumbent"] is not None]
    check(len(told) >= 1, f"{len(told)} start(s) knew an incumbent")
    for r in told:  # a point some start of the scene reached (its own included), none lower
        points = [h[1] for x in runs(out) if x["scene"] == r["scene"] for h in x["history"]]
        check(r["incumbent"] in points and r["incumbent"] >= min(points),
              f"{r['scene']} start {r['start']}: its incumbent {r['incumbent']} is a start's point")
    for r in runs(out):
        if r["status"] == "dominated":
            check(r["T_f"] is not None and r["T_f"] > r["incumbent"],
                  f"{r['scene']} start {r['start']}: dominated above its incumbent, certified")
elif MODE == "mpi8":
    out = os.path.join(WORK, "mpi8")
    shutil.rmtree(out, ignore_errors=True)
    mpi8 = [MPIEXEC, "-np", "8", "--allow-run-as-root", "--oversubscribe"]
    r = subprocess.run(mpi8 + [DISCO, "search", BENCH, "--seed", "7", "--starts", "12", "--set",
                               "scene.steps=10", "--out", out, "--verbose", *SHARED],
                       env=ENV, capture_output=True, text=True)
    check(r.returncode == 0, f"mpirun -np 8 disco search exits 0 (got {r.returncode}; {r.stderr[-300:]!r})")
    check_consistent(out, "np8")
    rs = runs(out)
    check(len(rs) == 24, f"24 starts recorded ({len(rs)})")
    check(sorted({x["rank"] for x in rs}) == list(range(8)), "all 8 ranks ran starts")
    # No rank stopped working while tasks remained: each rank's last start ended after the last
    # hand-out (approximately: a start's hand-out is its recording time less its run time).
    last_handout = max(x["finished_s"] - x["seconds"] for x in rs)
    for k in range(8):
        mine = [x for x in rs if x["rank"] == k]
        if mine:
            end = max(x["finished_s"] for x in mine)
            check(end >= last_handout - 1.0,
                  f"rank {k} worked until the last hand-out ({end:.2f} s >= {last_handout:.2f} s - 1 s)")
    told = re.findall(r"rank ([1-7]): incumbent of \S+ now [0-9.]+ \(from rank 0\)", r.stderr)
    check(len(told) >= 1, f"incumbent messages reached workers ({len(told)}, ranks {sorted(set(told))})")
    check(best(out)["mode"] == "shared", "best.json says shared")
elif MODE == "determinism":
    a, b = os.path.join(WORK, "det1"), os.path.join(WORK, "det2")
    check(search(a, 1, *DET) == 0, "1-rank search exits 0")
    check(search(b, 2, *DET) == 0, "2-rank search exits 0")
    check(best(a)["mode"] == best(b)["mode"] == "deterministic", "best.json says deterministic")
    check(all(r["incumbent"] is None and r["status"] != "dominated" for r in runs(a) + runs(b)),
          "no start knew an incumbent")
    check(key_set(runs(a)) == key_set(runs(b)), "same runs (scene, start, status, T_f) for 1 and 2 ranks")
    ba, bb = best(a)["scenes"], best(b)["scenes"]
    check({k: (v["T_f"], v.get("start")) for k, v in ba.items()} ==
          {k: (v["T_f"], v.get("start")) for k, v in bb.items()}, "same best T_f and start per scene")
elif MODE == "refinefrom":
    # search.refine_from start: a refine is the start's own run at full N_t, so each refine of
    # a screened search ends exactly where the same start ends in a search without screening.
    a, b = os.path.join(WORK, "full"), os.path.join(WORK, "refine_from_start")
    check(search(a, 2, "--deterministic") == 0, "2-rank search without screening exits 0")
    check(search(b, 2, *DET, "--set", "search.screen_fraction=0.5", "--set", "search.refine_count=2",
                 "--set", "search.early_refine_batch=1", "--set", "search.refine_from=start") == 0,
          "2-rank screened search with refines from the start exits 0")
    full = {(r["scene"], r["start"]): r for r in runs(a)}
    rb = runs(b)
    refines = [r for r in rb if r["stage"] == "refine"]
    check(len(refines) > 0, f"refines ran ({len(refines)})")
    for r in refines:
        f = full[(r["scene"], r["start"])]
        check((r["status"], repr(r["T_f"]), r["iterations"], r["guess"]) ==
              (f["status"], repr(f["T_f"]), f["iterations"], f["guess"]),
              f"{r['scene']} refine {r['start']}: {r['status']} T_f {r['T_f']!r} in {r['iterations']} "
              f"iterations, its full start's {f['status']} {f['T_f']!r} in {f['iterations']}")
    # The smoke benchmark's scene limit leaves time to refine every certified screen and to run
    # every other start from its own guess (the fill).
    screened_keys = {(r["scene"], r["start"]) for r in rb if r["stage"] == "screen"}
    check(screened_keys == {(r["scene"], r["start"]) for r in refines}, "every start refined or run in the time left")
    for scene, sb in best(b)["scenes"].items():
        points = [r["T_f"] for r in refines if r["scene"] == scene and r["T_f"] is not None]
        check(sb["T_f"] == (min(points) if points else None), f"{scene}: the best refine is the best")
    # search.refine_from both: each refine is its refine from the screen (as a search with
    # refine_from screen makes it) and then its start's full run, the better one kept.
    s, o = os.path.join(WORK, "refine_from_screen"), os.path.join(WORK, "refine_from_both")
    screened_sets = ["--set", "search.screen_fraction=0.5", "--set", "search.refine_count=2",
                     "--set", "search.early_refine_batch=1"]
    check(search(s, 2, *DET, *screened_sets, "--set", "search.refine_from=screen") == 0,
          "2-rank screened search with refines from the screen exits 0")
    check(search(o, 2, *DET, *screened_sets, "--set", "search.refine_from=both") == 0,
          "2-rank screened search with refines from both exits 0")
    from_screen = {(r["scene"], r["start"]): r for r in runs(s) if r["stage"] == "refine"}
    # A refine chosen from its certified screen minimises as search.refine_minimize_weak says
    # (both of its runs); screens and every other run as reduction.minimize_weak says.
    own_weak, refine_weak = DEFAULTS["reduction"]["minimize_weak"], DEFAULTS["search"]["refine_minimize_weak"]

    def uncertified_screens(out):
        return {(r["scene"], r["start"]) for r in runs(out) if r["stage"] == "screen" and r["T_f"] is None}

    def check_minimize_weak(out, name):
        uncertified_here = uncertified_screens(out)
        for r in runs(out):
            refined_screen = r["stage"] == "refine" and (r["scene"], r["start"]) not in uncertified_here
            want = refine_weak if refined_screen else own_weak
            check(r["schedule"]["minimize_weak"] == want,
                  f"{name}: {r['scene']} {r['stage']} {r['start']}: minimize_weak "
                  f"{r['schedule']['minimize_weak']}, want {want}")
    check_minimize_weak(s, "screen")
    check(any(r["schedule"]["minimize_weak"] == refine_weak for r in from_screen.values()),
          "a refine from its screen ran")
    both = [r for r in runs(o) if r["stage"] == "refine"]
    check(sorted((r["scene"], r["start"]) for r in both) == sorted(from_screen),
          "the same refines as from the screen")
    uncertified = uncertified_screens(o)
    check_minimize_weak(o, "both")
    # A refine's run from its start's own guess minimises as search.refine_minimize_weak says:
    # the full run of a search without screening with reduction.minimize_weak set so.
    if refine_weak == own_weak:
        full_refine_weak = full
    else:
        w = os.path.join(WORK, "full_refine_weak")
        check(search(w, 2, "--deterministic", "--set", f"reduction.minimize_weak={refine_weak}") == 0,
              f"2-rank search without screening, reduction.minimize_weak {refine_weak}, exits 0")
        full_refine_weak = {(r["scene"], r["start"]): r for r in runs(w)}
    for r in both:
        x, f = from_screen[(r["scene"], r["start"])], full_refine_weak[(r["scene"], r["start"])]
        if (r["scene"], r["start"]) in uncertified:  # the time left runs it from its own guess only
            f = full[(r["scene"], r["start"])]  # as a search without screening runs it
            check((r["status"], repr(r["T_f"]), r["iterations"]) == (f["status"], repr(f["T_f"]), f["iterations"]),
                  f"{r['scene']} start {r['start']} without a certified screen: its full start's run")
            continue
        kept = f if f["T_f"] is not None and (x["T_f"] is None or f["T_f"] < x["T_f"]) else x
        check((r["status"], repr(r["T_f"]), r["iterations"]) ==
              (kept["status"], repr(kept["T_f"]), x["iterations"] + f["iterations"]),
              f"{r['scene']} refine {r['start']} from both: T_f {r['T_f']!r} in {r['iterations']} iterations; "
              f"from the screen {x['T_f']!r} in {x['iterations']}, from the start {f['T_f']!r} in {f['iterations']}")
elif MODE == "resume":
    clean, out = os.path.join(WORK, "clean"), os.path.join(WORK, "resume")
    check(search(clean, 2, *DET) == 0, "clean 2-rank search exits 0")
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.Popen(MPI + [DISCO, "search", BENCH, "--seed", "7", "--out", out, *DET],
                            env=ENV, start_new_session=True)
    path = os.path.join(out, "runs.jsonl")
    deadline = time.time() + 120
    while time.time() < deadline and not (os.path.exists(path) and os.path.getsize(path) > 0):
        time.sleep(0.05)
    kill_all(proc, out)
    before = len(runs(out))
    check(0 < before < best(clean)["starts_total"], f"killed after {before} finished start(s)")
    resumed = subprocess.run(MPI + [DISCO, "search", BENCH, "--seed", "7", "--out", out, "--resume", *DET],
                             env=ENV)
    check(resumed.returncode == 0, "--resume exits 0")
    check_consistent(out, "resumed")
    check({k: v["T_f"] for k, v in best(out)["scenes"].items()} ==
          {k: v["T_f"] for k, v in best(clean)["scenes"].items()}, "resumed best equals the clean run's")
elif MODE == "timelimit" and SCREENED:
    # On the simulated clock, one rank (as below): a limit inside the refines. Screens are
    # handed out, and end, by half of it (search.screen_share 0.5); the same limit twice gives
    # the same runs; --resume without it runs what is left and keeps every line of a clean run.
    clean, out = os.path.join(WORK, "clean"), os.path.join(WORK, "timelimit")
    RUN = ["--starts", "3", *DET, *SIM]
    check(search(clean, 1, *RUN) == 0, "clean 1-rank screened search exits 0")
    order = runs(clean)
    end = max(x["finished_s"] for x in order)
    limit = (int(0.8 * end / TICK) + 0.5) * TICK
    share_end = 0.5 * limit

    def limited(path):
        shutil.rmtree(path, ignore_errors=True)
        return subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", path, "--time-limit",
                               repr(limit), *RUN], env=ENV, capture_output=True, text=True)
    r = limited(out)
    rs, b = runs(out), best(out)
    check(r.returncode in (0, 3), f"time-limited screened search exits 0 or 3 (got {r.returncode})")
    for x in rs:
        if x["stage"] == "screen":
            check(x["finished_s"] - x["seconds"] < share_end and x["finished_s"] <= share_end + TICK + 1e-9,
                  f"{x['scene']} screen {x['start']}: handed out before and ended by the screening "
                  f"share's end ({x['finished_s']:.2f} s, {share_end:.3f})")
    check(any(x["stage"] == "refine" for x in rs), "refines ran after the screens")
    for scene, sb in b["scenes"].items():
        points = [x["T_f"] for x in rs if x["scene"] == scene and x["T_f"] is not None and x["stage"] == "refine"]
        check(sb["T_f"] == (min(points) if points else None), f"{scene}: the best refine is the best")
    again = limited(out + "_again")
    check([(x["scene"], x["start"], x["stage"], x["status"], repr(x["T_f"]), x["seconds"]) for x in runs(out + "_again")] ==
          [(x["scene"], x["start"], x["stage"], x["status"], repr(x["T_f"]), x["seconds"]) for x in rs],
          "the same limit again: the same runs")
    code = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", out, "--resume", *RUN],
                          env=ENV).returncode
    check(code == 0, "--resume without the limit exits 0")
    check_consistent(out, "resumed", limited=True)
    resumed = latest(runs(out))
    check(set(key_set(runs(clean))) <= set(key_set(resumed)),
          "resumed: every run of the clean run, bit for bit (and the refines the limit chose)")
    for scene, v in best(out)["scenes"].items():
        c = best(clean)["scenes"][scene]["T_f"]
        check(v["T_f"] is not None and (c is None or v["T_f"] <= c), f"resumed: {scene}'s best at most the clean run's")
    # A screening share that ends after the first screen: its early refine, then the time left
    # runs the starts left unscreened at full N_t from their own guess (search/README.md,
    # "Screening", step 5); none of those runs is final, and --resume without the limit screens
    # and refines them, keeping every run of the clean run.
    tight = os.path.join(WORK, "tight_share")
    first = min((x for x in order if x["stage"] == "screen"), key=lambda x: x["finished_s"])
    tight_limit = 2 * end
    share = (first["finished_s"] + TICK / 2) / tight_limit
    shutil.rmtree(tight, ignore_errors=True)
    r = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", tight, "--time-limit", repr(tight_limit),
                        *RUN, "--set", f"search.screen_share={share!r}"], env=ENV, capture_output=True, text=True)
    check(r.returncode in (0, 3), f"screened search with a tight share exits 0 or 3 (got {r.returncode})")
    rs = runs(tight)
    screened_keys = {(x["scene"], x["start"]) for x in rs if x["stage"] == "screen"}
    unscreened = [x for x in rs if x["stage"] == "refine" and (x["scene"], x["start"]) not in screened_keys]
    check(all(x["finished_s"] - x["seconds"] < share * tight_limit for x in rs if x["stage"] == "screen") and
          0 < len(screened_keys) < len(order_keys := {(x["scene"], x["start"]) for x in order}),
          f"screens handed out before the share's end only: {sorted(screened_keys)} of {len(order_keys)} starts")
    check(len(unscreened) >= 2 and all(x["guess"] != "given" for x in unscreened),
          f"the time left ran {len(unscreened)} unscreened start(s) from their own guess")
    check("from its own guess (not screened)" in r.stderr + r.stdout, "the log says so")
    b = best(tight)
    check(b["starts_finished"] < b["starts_total"], "runs without their screen are not final")
    code = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", tight, "--resume", *RUN,
                           "--set", f"search.screen_share={share!r}"], env=ENV).returncode
    check(code == 0, "--resume of the tight share without the limit exits 0")
    check_consistent(tight, "tight share resumed", limited=True)
    check(set(key_set(runs(clean))) <= set(key_set(latest(runs(tight)))),
          "tight share resumed: every run of the clean run, bit for bit")
elif MODE == "timelimit":
    # On the simulated clock (configs/disco.yaml `clock:`, core/util/clock.h), one rank: the
    # search's time is its Ipopt iterations, so where a limit falls is a fact of the runs, the
    # same on any machine at any load. A clean run gives each start's span on that clock (on
    # one rank, starts run one after another in hand-out order, the order of runs.jsonl); the
    # limit is put halfway through start K (the second), between two iteration reports.
    clean, out = os.path.join(WORK, "clean"), os.path.join(WORK, "timelimit")
    # Two starts per scene: enough to cut one in flight with one before it and others after it.
    RUN = ["--starts", "2", *DET, *SIM]
    check(search(clean, 1, *RUN) == 0, "clean 1-rank search exits 0")
    order = runs(clean)
    K = 1
    check(len(order) > K + 1 and order[K]["seconds"] >= 4 * TICK, f"start {K} is long enough to cut inside")
    handed = order[K - 1]["finished_s"]  # start K's hand-out, on the clock
    limit = handed + (int(order[K]["seconds"] / TICK / 2) + 0.5) * TICK
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", out, "--time-limit", repr(limit),
                        *RUN], env=ENV, capture_output=True, text=True)
    b, rs = best(out), runs(out)
    check(r.returncode in (0, 3), f"time-limited search exits 0 or 3 (got {r.returncode})")
    check(b["time_limit_reached"] is True, "best.json says the time limit was reached")
    cut = [x for x in rs if x["status"] == "time_limit"]
    check(K < len(rs) <= len(order) and b["starts_finished"] == len(rs) - len(cut) < len(order),
          f"the starts before the limit ended, later ones ended, were cut or were never handed out "
          f"({len(rs)} lines, {len(cut)} cut, {b['starts_finished']} finished of {b['starts_total']})")
    check(key_set(rs[:K]) == key_set(order[:K]) and [x["seconds"] for x in rs[:K]] == [x["seconds"] for x in order[:K]],
          "the starts before the limit: the clean run's, bit for bit")
    check(len(rs) > K and (rs[K]["scene"], rs[K]["start"]) == (order[K]["scene"], order[K]["start"]),
          f"start {K} is the one in flight at the limit")
    check(len(rs) > K and rs[K]["status"] == "time_limit", f"start {K} is cut")
    # Each start from K on has for budget the time left at its hand-out (the end of the start
    # before it: a cut start may end before the limit, keeping time back for its salvage), set
    # by the search, and ends by one report past the limit at most; one the limit cut says so.
    for k in range(K, len(rs)):
        x, handout = rs[k], rs[k - 1]["finished_s"]
        check(x["budget"]["set_by"] == "search" and abs(x["budget"]["seconds"] - (limit - handout)) < 1e-6,
              f"{x['scene']} start {x['start']}: its budget is the time left ({x['budget']})")
        check(handout + x["seconds"] <= limit + TICK + 1e-9,
              f"{x['scene']} start {x['start']}: ended by one iteration report past the limit at most "
              f"({handout:.2f} + {x['seconds']:.2f} s, limit {limit:.3f})")
        if x["status"] == "time_limit":
            words = f"{x['scene']} start {x['start']} (rank 0): time limit (search, "
            check(words in r.stderr, f"its progress line says so ({words}...)")
    for scene, sb in b["scenes"].items():
        points = [x["T_f"] for x in rs if x["scene"] == scene and x["T_f"] is not None]
        check(sb["T_f"] == (min(points) if points else None), f"{scene}: best of what ran, cut starts too")
    check("--resume runs them again" in r.stderr, "the last lines say how to finish the cut starts")
    again = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", out + "_again", "--force",
                            "--time-limit", repr(limit), *RUN], env=ENV, capture_output=True, text=True)
    check([(x["scene"], x["start"], x["status"], repr(x["T_f"]), x["seconds"]) for x in runs(out + "_again")] ==
          [(x["scene"], x["start"], x["status"], repr(x["T_f"]), x["seconds"]) for x in rs],
          "the same limit again: the same runs, the cut start's point and time included")
    code = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", out, "--resume", *RUN],
                          env=ENV).returncode
    check(code == 0, "--resume without the limit exits 0")
    check_consistent(out, "resumed")
    check(key_set(latest(runs(out))) == key_set(runs(clean)), "resumed: the runs of the clean run, bit for bit")
    check({k: (v["T_f"], v.get("start")) for k, v in best(out)["scenes"].items()} ==
          {k: (v["T_f"], v.get("start")) for k, v in best(clean)["scenes"].items()},
          "resumed: the best of the clean run")

    # Under the machine's clock, only what holds at any speed, on each scene's start 0 (the
    # clean run's own starts 0: a start is the same whatever --starts says): a limit far below
    # the search's length (0.1 s; those starts run 0.4 s with disco's KKT solver, seconds
    # before it) ends the run, marked cut, and
    # --resume without the limit ends with the clean run's runs (the clock does not change a
    # start's path when no limit falls in it).
    wall = os.path.join(WORK, "timelimit_wall")
    shutil.rmtree(wall, ignore_errors=True)
    one = ["--starts", "1", *DET]
    r = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", wall, "--time-limit", "0.1", *one],
                       env=ENV, capture_output=True, text=True)
    check(r.returncode in (0, 3), f"wall clock: the time-limited search exits 0 or 3 (got {r.returncode})")
    check(best(wall)["time_limit_reached"] is True, "wall clock: best.json says the time limit was reached")
    code = subprocess.run([DISCO, "search", BENCH, "--seed", "7", "--out", wall, "--resume", *one],
                          env=ENV).returncode
    check(code == 0, "wall clock: --resume without the limit exits 0")
    check_consistent(wall, "wall clock, resumed")
    check(key_set(latest(runs(wall))) == key_set([x for x in runs(clean) if x["start"] == 0]),
          "wall clock, resumed: the clean run's starts 0, bit for bit")
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
    # starts of seconds (80 steps; 30 took a fraction of one with disco's KKT solver): ticks in each
    cmd = f"{DISCO} search {swap} --set scene.steps=80 --starts 3 --out {out}"
    r = subprocess.run(["script", "-qec", cmd, "/dev/null"], env=ENV, capture_output=True)
    tty = r.stdout.decode(errors="replace")  # as bytes: "\r" kept
    # After each erase ("\r\x1b[K"): log lines ("...\r\n"), then the status drawn anew.
    status = [seg.split("\r\n")[-1] for seg in tty.split("\r\x1b[K")]
    status = [x for x in status if x.startswith("[") and " ETA " in x]
    check(r.returncode == 0 and "[3/3] two_robots_swap_avoid start" in tty,
          f"on a terminal: exit 0, the progress lines ({r.returncode})")
    # Which counts a tick catches depends on timing: any after the first start finished. The
    # running part ends the line and is cut at the width (79 columns): once a best is shown it
    # is cut inside "running: ", so a line shows it whole or cut there, whichever ticks came.
    def shows_running(x):
        return " | running: " in x or (len(x) == 79 and " | " in x and
                                        "running: ".startswith(x.rsplit(" | ", 1)[-1]))
    check(any(re.match(r"\[[123]/3\] elapsed \d\d:\d\d:\d\d ETA \d\d:\d\d:\d\d \| best "
                       r"two_robots_swap_avoid \d+\.\d{6}", x) for x in status) and
          any(shows_running(x) for x in status),
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
elif MODE == "manifest":
    out = os.path.join(WORK, "manifest")
    swap = os.path.join(os.path.dirname(BENCH), "../scenarios/two_robots_swap_avoid.yaml")
    axis = os.path.join(os.path.dirname(BENCH), "../scenarios/one_robot_axis.yaml")

    def run(*extra, scenes=(axis,)):
        return subprocess.run([DISCO, "search", *scenes, "--seed", "7", "--out", out, *extra],
                              env=ENV, capture_output=True, text=True)

    shutil.rmtree(out, ignore_errors=True)
    r = run("--starts", "2", "--set", "scene.steps=20")
    check(r.returncode == 0, f"a search exits 0 ({r.stderr[-200:]!r})")
    m = json.load(open(os.path.join(out, "manifest.json")))
    sc = m["scenes"][0]
    check(m["seed"] == 7 and sc["name"] == "one_robot_axis" and sc["overrides"] == ["steps=20"] and
          len(sc["sha256"]) == 64 and m["settings"]["values"]["elastic.zeta"] is not None and
          re.match(r"\d+\.\d+\.\d+ \(git ", m["version"]) and m["mode"] == "search",
          "manifest.json: seed, scene, overrides, file hash, settings values, version, mode")
    with open(os.path.join(out, "runs.jsonl")) as f:
        before = f.read()

    r = run("--starts", "2", "--set", "scene.steps=20")
    check(r.returncode == 2 and "is not empty" in r.stderr and "--resume" in r.stderr and
          "--force" in r.stderr, f"a non-empty --out is refused without --resume ({r.stderr[-300:]!r})")
    check(open(os.path.join(out, "runs.jsonl")).read() == before, "the refused run touched nothing")

    for extra, scenes, words in [
            (["--set", "scene.steps=12"], (axis,), "scene 'one_robot_axis': overrides [steps=20] there, [steps=12] here"),
            (["--set", "scene.steps=20", "--set", "elastic.zeta=20"], (axis,), "setting elastic.zeta: 10.0 there, 20 here"),
            (["--set", "scene.steps=20", "--seed", "8"], (axis,), "seed: 7 there, 8 here"),
            (["--set", "scene.steps=20"], (axis, swap), "scene 'two_robots_swap_avoid': in this run, not in the earlier one")]:
        seed = [] if "--seed" in extra else ["--seed", "7"]
        r = subprocess.run([DISCO, "search", *scenes, *seed, "--out", out, "--resume", *extra],
                           env=ENV, capture_output=True, text=True)
        check(r.returncode == 2 and "holds a different run" in r.stderr and words in r.stderr,
              f"--resume refuses a mismatch naming it: {words} ({r.stderr[-300:]!r})")
    check(open(os.path.join(out, "runs.jsonl")).read() == before, "the refused resumes touched nothing")

    r = run("--starts", "3", "--set", "scene.steps=20", "--resume")
    rs = runs(out)
    check(r.returncode == 0 and [x["start"] for x in rs] == [0, 1, 2] and
          "resume: 2 start(s) already in" in r.stderr,
          f"a matching --resume with one more start runs only start 2 ({[x['start'] for x in rs]})")
    inv = json.load(open(os.path.join(out, "manifest.json")))["invocations"]
    check([i["resume"] for i in inv] == [False, True] and inv[1]["starts"] == 3,
          "the manifest lists both invocations")
    check("does not hold it" not in r.stderr, "--resume finds the best in best/SCENE.json")

    # Another objective: best/SCENE.json holds the best's J under objective.value, not in T_f.
    energy = os.path.join(os.path.dirname(BENCH), "../scenarios/one_robot_axis_energy.yaml")
    energy_out = os.path.join(WORK, "manifest_energy")
    shutil.rmtree(energy_out, ignore_errors=True)
    for extra in ([], ["--resume"]):
        r = subprocess.run([DISCO, "search", energy, "--seed", "7", "--starts", "1", "--set",
                            "scene.steps=20", "--out", energy_out, *extra],
                           env=ENV, capture_output=True, text=True)
    check(r.returncode == 0 and "resume: 1 start(s) already in" in r.stderr and
          "does not hold it" not in r.stderr,
          f"--resume of an energy search finds its best in best/SCENE.json ({r.stderr[-300:]!r})")

    r = run("--starts", "1", "--set", "scene.steps=20", "--force", scenes=(swap,))
    check(r.returncode == 0 and [x["scene"] for x in runs(out)] == ["two_robots_swap_avoid"] and
          list(best(out)["scenes"]) == ["two_robots_swap_avoid"] and
          not os.path.exists(os.path.join(out, "best", "one_robot_axis.json")),
          "--force replaces the run: runs, best and best/ hold only the new one")
    r = run("--resume", "--force")
    check(r.returncode == 2 and "excludes" in r.stderr, "--resume with --force is a usage error")

    os.remove(os.path.join(out, "manifest.json"))
    r = run("--starts", "1", "--set", "scene.steps=20", "--resume", scenes=(swap,))
    check(r.returncode == 2 and "manifest.json is missing" in r.stderr,
          f"--resume refuses runs without a manifest ({r.stderr[-200:]!r})")
elif MODE in ("interrupt", "killrandom"):
    swap = os.path.join(os.path.dirname(BENCH), "../scenarios/two_robots_swap_avoid.yaml")
    # interrupt: two starts of ~10 s each here (200 steps), the signal sent after the first of
    # their eight or so phases, so both ranks are inside one at the signal; killrandom: the
    # smoke benchmark.
    config = [swap, "--set", "scene.steps=200", "--starts", "2"] if MODE == "interrupt" else [BENCH]

    def command(out, *extra):
        return [DISCO, "search", *config, "--seed", "7", "--out", out, *DET, *extra]

    def same_as_clean(out, clean, label, limited=False):
        check_consistent(out, label, limited=limited)
        if SCREENED and limited:  # refines chosen from the screens the limit let run stay too
            check(set(key_set(runs(clean))) <= set(key_set(latest(runs(out)))),
                  f"{label}: every run of the clean run, bit for bit")
            check(all(v["T_f"] <= best(clean)["scenes"][k]["T_f"] for k, v in best(out)["scenes"].items()),
                  f"{label}: a best at most the clean run's")
            return
        check(key_set(latest(runs(out))) == key_set(runs(clean)),
              f"{label}: the runs of the clean run, bit for bit")
        check({k: (v["T_f"], v.get("start")) for k, v in best(out)["scenes"].items()} ==
              {k: (v["T_f"], v.get("start")) for k, v in best(clean)["scenes"].items()},
              f"{label}: the best of the clean run")

    clean = os.path.join(WORK, "clean")
    shutil.rmtree(clean, ignore_errors=True)
    check(subprocess.run(MPI + command(clean), env=ENV).returncode == 0, "clean 2-rank search exits 0")

    if MODE == "interrupt":
        # On Ctrl-C mpirun sends its ranks SIGTERM and, odls_base_sigkill_timeout (1) seconds
        # later, SIGKILL (search/README.md, "Ctrl-C"): whether a rank has recorded its start by
        # then depends on the machine's speed (0.11 s here in Release, ~1.6 s under the
        # sanitizers). So the test sends the ranks that SIGTERM itself.
        for ranks in (1, 2):
            out = os.path.join(WORK, f"interrupt{ranks}")
            shutil.rmtree(out, ignore_errors=True)
            proc = subprocess.Popen((MPI if ranks == 2 else []) + command(out, "--verbose"), env=ENV,
                                    stderr=subprocess.PIPE, text=True, start_new_session=True)
            # The signal goes once the verbose log shows every rank past the first phase of its
            # start (not after a fixed sleep, whose verdict would depend on the machine's speed).
            seen, begun = [], set()
            for line in proc.stderr:
                seen.append(line)
                started = re.search(r"start (\d+):\s+1 feasibility\s", line)
                begun |= {started.group(1)} if started else set()
                if len(begun) == ranks:
                    if ranks == 1:
                        proc.send_signal(signal.SIGINT)
                    else:  # mpirun's children are the ranks
                        with open(f"/proc/{proc.pid}/task/{proc.pid}/children") as f:
                            for pid in f.read().split():
                                os.kill(int(pid), signal.SIGTERM)
                    break
            _, err = proc.communicate(timeout=60)
            err = "".join(seen) + err
            name = "SIGINT" if ranks == 1 else "SIGTERM"
            match = re.search(r"interrupted \((SIG\w+)\): (\d+) of (\d+) starts kept in (\S+), (\d+) lost "
                              r"\(cut short; their best so far is in best.json\); continue with --resume", err)
            check(match is not None and match.group(1) == name and match.group(4) == out + "/runs.jsonl",
                  f"{ranks} rank(s): says what it kept ({err[-300:]!r})")
            if ranks == 1:
                check(proc.returncode == 130, f"1 rank: exit 130 after SIGINT (got {proc.returncode})")
            rs = runs(out)
            lost = [x for x in rs if x["status"] == "interrupted"]
            check(match is not None and int(match.group(5)) == len(lost) == ranks and
                  int(match.group(2)) == len(rs) - len(lost),
                  f"{ranks} rank(s): the starts in flight are recorded as interrupted ({len(lost)})")
            check(best(out)["interrupted"] is True, f"{ranks} rank(s): best.json says interrupted")
            code = subprocess.run((MPI if ranks == 2 else []) + command(out, "--resume"), env=ENV).returncode
            check(code == 0, f"{ranks} rank(s): --resume exits 0")
            same_as_clean(out, clean, f"{ranks} rank(s), resumed")
    else:
        rng = random.Random(20261124)
        for k in range(10):
            out = os.path.join(WORK, f"kill{k}")
            shutil.rmtree(out, ignore_errors=True)
            limit = ["--time-limit", str(rng.choice([1, 2, 3]))] if k % 3 == 1 else []
            how = "SIGINT" if k % 2 == 0 else "SIGKILL"
            at = rng.uniform(0.3, 4.0)
            proc = subprocess.Popen(MPI + command(out, *limit), env=ENV, stderr=subprocess.DEVNULL,
                                    start_new_session=True)
            try:
                proc.wait(timeout=at)
            except subprocess.TimeoutExpired:
                if how == "SIGINT":
                    proc.send_signal(signal.SIGINT)
                    proc.wait(timeout=60)
                else:
                    kill_all(proc, out)
            label = f"run {k} ({how} at {at:.1f} s{', ' + ' '.join(limit) if limit else ''})"
            r = subprocess.run(MPI + command(out, "--resume"), env=ENV, capture_output=True, text=True)
            check(r.returncode == 0, f"{label}: --resume exits 0 ({r.stderr[-200:]!r})")
            same_as_clean(out, clean, label, limited=bool(limit))
else:
    sys.exit(f"unknown mode {MODE}")

finish(f"search_tests {MODE}")
