#!/usr/bin/python3
"""Tests of the scripts' shared helpers (scripts/common) and of the results files the benchmark
scripts write (CTest script.common, script.results; see tests/CMakeLists.txt).

  script_tests.py SCRIPTS WORKDIR common
  script_tests.py SCRIPTS WORKDIR results DISCO BENCH_KKT

common   without disco: the results file's sections (a run replaces only its own label; a
         full run drops its configuration's partial sections; a partial run never touches the
         full run's section); which options make a run partial; where find_disco() looks, in
         order (build tree, installed layout PREFIX/bin, PATH, --disco first of all); the
         argument types; bench_incumbent's measures of one search (time to the target on the
         scene's clock, the fastest start alone, wasted start time) on made-up runs.
results  with a real disco: scripts/bench_stress and scripts/bench_examples on one small scene
         each, into scratch results files: the header (command, UTC date, `disco --version`,
         nproc, memory, wall time) and the table; a second run with other options adds its own
         section and keeps the first. And common.solve on one_robot_axis: the solve log's
         iterations and NLP solves, summed, equal solution.json's timing (two records disco
         writes independently). Then bench_kkt (BENCH_KKT, tests/bench_kkt.cpp; MUMPS and both
         of disco's LDLT solvers) on a KKT matrix
         of known inertia written here, [H Jᵀ; J 0] with H positive definite, and on a truncated
         one; and scripts/bench_kkt on start 0 of A2 (a corpus it dumps with disco).
         scripts/bench_random: its generator (seeded, --kind objects), and a run of 2 scenes
         against disco itself (the files, the rows against the solution files, the summary);
         a baseline that cannot run (no settings file) stops it with the command and its error.
         scripts/bench_starts --others on a refused and a small stress scene, 2 at a time
         against disco itself: refused rows, the same iterations and T_f as one at a time and
         as the baseline (a start is deterministic), and the tables' note on wall times; a
         baseline that cannot run (no settings file) stops it with the command and its error,
         and a run whose every start is refused prints its ratios as "—".
"""
import argparse
import json
import os
import random
import re
import shutil
import stat
import struct
import subprocess
import sys
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader

import yaml  # python3-yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish  # noqa: E402

SCRIPTS, WORK, MODE = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, SCRIPTS)
from common import arguments, paths, results, tables  # noqa: E402
from common.solve import solve  # noqa: E402


def load_script(name):
    """scripts/NAME (a Python script without the .py) as a module."""
    loader = SourceFileLoader(name, os.path.join(SCRIPTS, name))
    module = module_from_spec(spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    return module


def sections(path):
    with open(path) as f:
        return [label for label, _ in results.split_sections(f.read())]


def section_text(path, label):
    with open(path) as f:
        return dict(results.split_sections(f.read()))[label]


def fake_run(argv, body):
    """Results of a script 'bench_fake' with --scenes (partial) and --set (configuration),
    run as `argv`, writing `body`."""
    ap = argparse.ArgumentParser(description="A fake benchmark.\n\nMore text.")
    ap.add_argument("--scenes", type=arguments.comma_list(), default="a,b")
    ap.add_argument("--set", action="append", default=[])
    results.add_options(ap)
    saved = sys.argv
    sys.argv = [os.path.join(SCRIPTS, "bench_fake")] + argv
    try:
        args = ap.parse_args(argv)
        res = results.Results(ap, args, config=args.set, partial=["scenes"])
        return res.label, res.write(body)
    finally:
        sys.argv = saved


def test_common():
    path = os.path.join(WORK, "fake.md")
    label, written = fake_run(["--results", path], "full run 1")
    check(label == "default" and written == path, f"a full run without --set is 'default' ({label})")
    label, _ = fake_run(["--results", path, "--scenes", "a"], "partial run")
    check(label == "default (partial: --scenes a)", f"a partial run gets its own label ({label})")
    check(sections(path) == ["default", "default (partial: --scenes a)"],
          f"the partial run keeps the full run's section ({sections(path)})")
    check("full run 1" in section_text(path, "default"), "the full run's body is untouched")
    label, _ = fake_run(["--results", path, "--set", "x.y=1"], "configured run")
    check(label == "x.y=1", f"the --set list is the label ({label})")
    label, _ = fake_run(["--results", path, "--set", "x.y=1", "--scenes", "b"], "configured partial")
    check(sections(path) == ["default", "default (partial: --scenes a)", "x.y=1",
                             "x.y=1 (partial: --scenes b)"], f"four sections ({sections(path)})")
    fake_run(["--results", path], "full run 2")
    check(sections(path) == ["default", "x.y=1", "x.y=1 (partial: --scenes b)"],
          f"a full run replaces its section in place and drops its own partial ones only "
          f"({sections(path)})")
    text = section_text(path, "default")
    check("full run 2" in text and "full run 1" not in text, "the full run's section is the new run's")
    fake_run(["--results", path, "--label", "mine", "--scenes", "a"], "labelled")
    check(sections(path)[-1] == "mine", "--label names the section, even for fewer scenes")
    fake_run(["--results", path, "--no-results", "--scenes", "a"], "nothing")
    check("nothing" not in open(path).read(), "--no-results writes nothing")
    with open(path) as f:
        top = f.read().splitlines()[:5]
    check(top[0] == "# Results: scripts/bench_fake" and top[2] == "A fake benchmark.",
          f"the file starts with its title and the script's one-line description ({top[:3]})")
    head = section_text(path, "x.y=1")
    check(re.search(r"^- Command: `scripts/bench_fake --results \S+ --set x.y=1`$", head, re.M) is not None,
          "the header holds the command line as run")
    check(re.search(r"^- Date: \d{4}-\d\d-\d\d \d\d:\d\d UTC$", head, re.M) is not None, "a UTC date")
    check(re.search(r"^- Machine: \d+ CPUs \(nproc\).*GiB memory", head, re.M) is not None,
          "nproc and memory")
    check(re.search(r"^- Wall time: \d+ s$", head, re.M) is not None, "the wall time")

    # find_disco: build tree, then PREFIX/bin/disco (ROOT = PREFIX/share/disco), then PATH.
    prefix = os.path.join(WORK, "prefix")
    root = os.path.join(prefix, "share", "disco")
    tools = os.path.join(WORK, "path_bin")
    for d in (root, os.path.join(prefix, "bin"), os.path.join(root, "build", "mpi"), tools):
        os.makedirs(d, exist_ok=True)

    def executable(p):
        with open(p, "w") as f:
            f.write("#!/bin/sh\n")
        os.chmod(p, os.stat(p).st_mode | stat.S_IXUSR)
        return p
    os.environ["PATH"] = tools + os.pathsep + os.environ.get("PATH", "")
    on_path = executable(os.path.join(tools, "disco"))
    check(paths.find_disco(root=root) == on_path, "no build tree, not installed: disco on PATH")
    installed = executable(os.path.join(prefix, "bin", "disco"))
    check(os.path.samefile(paths.find_disco(root=root), installed),
          "an installed layout: PREFIX/bin/disco before PATH")
    built = executable(os.path.join(root, "build", "mpi", "disco"))
    check(paths.find_disco(root=root) == built, "the build tree first")
    check(paths.find_disco(on_path, root=root) == on_path, "--disco before everything")
    try:
        paths.find_disco(os.path.join(WORK, "no_such_disco"), root=root)
        check(False, "--disco naming no file exits")
    except SystemExit as e:
        check("not an executable file" in str(e), f"--disco naming no file exits: {e}")

    # The sign test against sums done by hand: 5 : 0 is 2 / 2^5; 6 : 2 is 2 (1 + 8 + 28) / 2^8.
    for worse, better, p in ((5, 0, 0.0625), (0, 5, 0.0625), (6, 2, 74 / 256), (3, 3, 1.0),
                             (0, 0, 1.0), (1, 0, 1.0)):
        check(abs(tables.sign_test(worse, better) - p) < 1e-12,
              f"sign test {worse} : {better} is {p} ({tables.sign_test(worse, better)})")
    for parse, text, ok in ((arguments.comma_list(int), "25,50", [25, 50]),
                            (arguments.int_at_least(2), "2", 2),
                            (arguments.int_in_range(100, 200, "a size"), "150", 150)):
        check(parse(text) == ok, f"{text} parses to {ok}")
    for parse, text, msg in ((arguments.comma_list(int), "a,b", "not a comma-separated list"),
                             (arguments.int_at_least(2), "1", "not an integer >= 2"),
                             (arguments.int_in_range(100, 200, "a size"), "99", "not a size, 100..200")):
        try:
            parse(text)
            check(False, f"'{text}' is refused")
        except argparse.ArgumentTypeError as e:
            check(msg in str(e), f"'{text}' is refused: {e}")


def test_incumbent_measures():
    """bench_incumbent's measure() on two made-up starts. Start a was handed out at 0 s and ran
    10 s, reaching T_f 10.0 at 4 s and 9.0 at 9 s; start b was handed out at 5 s and ran 3 s,
    reaching 9.05 at 2 s. For the target 9.1: a reaches it at 0 + 9 = 9 s, b at 5 + 2 = 7 s, so
    the scene's time is 7 s and the fastest start alone took 2 s (b's own clock). With the
    scene's lowest 9.0 both end within 1 % (below 9.09), so nothing is wasted; with the lowest
    8.95 (1 % above: 9.0395) b is above and a is not: 3 of 13 s. The last start (a) ended 10 s
    after the scene's first hand-out."""
    bench = load_script("bench_incumbent")
    runs = [{"status": "solved", "T_f": 9.0, "seconds": 10.0, "finished_s": 110.0,
             "history": [[4.0, 10.0], [9.0, 9.0]]},
            {"status": "dominated", "T_f": 9.05, "seconds": 3.0, "finished_s": 108.0,
             "history": [[2.0, 9.05]]}]
    best = {"scenes": {"s": {"started_s": 100.0, "T_f": 9.0}}}
    reached, alone, T_best, n, dominated, wasted, ended = bench.measure(runs, best, 9.1, 9.0)
    check((reached, alone, T_best, n, dominated, wasted, ended) == (7.0, 2.0, 9.0, 2, 1, 0.0, 10.0),
          f"measure: time 7, alone 2, best 9.0, 2 starts, 1 dominated, none wasted, the last ended at 10 s "
          f"({reached}, {alone}, {T_best}, {n}, {dominated}, {wasted}, {ended})")
    check(abs(bench.measure(runs, best, 9.1, 8.95)[5] - 3.0 / 13.0) < 1e-12,
          "measure: a start ending more than 1 % above the scene's lowest wastes its time")
    reached, alone = bench.measure(runs, best, 8.5, 9.0)[:2]
    check(reached is None and alone is None, f"measure: a target no start reached ({reached}, {alone})")


def run_script(name, *args):
    r = subprocess.run([os.path.join(SCRIPTS, name), *args], capture_output=True, text=True)
    return r


def test_results(disco):
    version = subprocess.run([disco, "--version"], capture_output=True, text=True).stdout.strip()
    check(bool(version), f"disco --version prints '{version}'")
    stress = os.path.join(WORK, "bench_stress.md")
    r = run_script("bench_stress", "--disco", disco, "--scenes", "mu_0", "--out", os.path.join(WORK, "stress"),
                   "--results", stress)
    check(r.returncode == 0, f"bench_stress --scenes mu_0 exits 0 ({r.returncode})" + (r.stderr if r.returncode else ""))
    check(sections(stress) == ["default (partial: --scenes mu_0)"], f"one partial section ({sections(stress)})")
    text = section_text(stress, "default (partial: --scenes mu_0)")
    # The path relative to the tree when inside it: results files, installed with the scripts,
    # name no machine's checkout (install.tree).
    root = os.path.dirname(os.path.abspath(SCRIPTS))
    where = os.path.abspath(disco)
    where = os.path.relpath(where, root) if where.startswith(root + os.sep) else disco
    check(f"- disco: `{version}` ({where})" in text, f"the header names disco's version and path ({where})")
    check(f"- Command: `scripts/bench_stress --disco {disco} --scenes mu_0 --out " in text,
          "the header holds the command line")
    row = re.search(r"^\| mu_0 \| solved \| ([\d.]+) \| ([\d.]+) \|.*\| yes \|$", text, re.M)
    check(row is not None, "the table's row of mu_0: solved, OK")
    if row:
        check(abs(float(row.group(1)) - float(row.group(2))) <= 1e-6 * float(row.group(2)),
              "its T_f equals the expectation computed from the scene file")
    check("1 of 1 OK" in text, "the conclusion counts the OK rows")
    r = run_script("bench_stress", "--disco", disco, "--scenes", "K_3", "--out", os.path.join(WORK, "stress"),
                   "--results", stress)
    check(sections(stress) == ["default (partial: --scenes mu_0)", "default (partial: --scenes K_3)"],
          f"another partial run adds its own section ({sections(stress)})")

    examples = os.path.join(WORK, "bench_examples.md")
    r = run_script("bench_examples", "--disco", disco, "--scenes", "one_robot_axis", "--out",
                   os.path.join(WORK, "examples"), "--results", examples, "--label", "smoke")
    check(r.returncode == 0, f"bench_examples --scenes one_robot_axis exits 0 ({r.returncode})"
          + (r.stderr if r.returncode else ""))
    check(sections(examples) == ["smoke"], f"--label names the section ({sections(examples)})")
    sol = os.path.join(WORK, "examples", "runs", "one_robot_axis", "solution.json")
    with open(sol) as f:
        doc = json.load(f)
    m = doc["model"]
    want = (f"| one_robot_axis | {m['variables']} / {m['constraints']} / {m['complementarity_pairs']} "
            f"| solved | {doc['T_f']:.6f} | {doc['lower_bound']:.6f} "
            f"| {doc['timing']['nlp_solves']} / {doc['timing']['iterations']} |")
    check(want in section_text(examples, "smoke"), f"the row is the solution file's: {want}")

    run = solve(disco, os.path.join(os.path.dirname(SCRIPTS), "configs", "scenarios", "one_robot_axis.yaml"),
                os.path.join(WORK, "solve"), ["scene.steps=30"])
    timing = run.solution["timing"]
    check(run.exit == 0 and run.lines, f"common.solve: exit 0 and {len(run.lines)} solve-log lines")
    check(sum(s.iterations for s in run.lines) == timing["iterations"],
          f"solve-log iterations sum to timing.iterations ({timing['iterations']})")
    check(sum(s.nlp_solves for s in run.lines) == timing["nlp_solves"],
          f"solve-log NLP solves sum to timing.nlp_solves ({timing['nlp_solves']})")
    check(run.lines[0].phase == "feasibility", f"the first solve is the feasibility phase ({run.lines[0].phase})")


def read_csv_rows(path):
    import csv
    with open(path) as f:
        return list(csv.DictReader(f))


def lost_disco(disco):
    """A copy of disco outside its tree: it finds no settings file under its prefix and exits 2,
    as it does for a scene it refuses."""
    lost = os.path.join(WORK, "lost", "bin")
    os.makedirs(lost, exist_ok=True)
    return shutil.copy(disco, os.path.join(lost, "disco"))


def test_bench_starts(disco):
    """scripts/bench_starts --others --jobs: the other scenes' set, refused scenes, and answers
    that do not depend on how many run at a time."""
    from common.scenes import other_scenes
    root = os.path.dirname(os.path.abspath(SCRIPTS))
    others = other_scenes(root)
    check({"stress/K_3", "stress/too_weak", "doorway", "A1", "A2"} <= set(others)
          and all(os.path.isfile(os.path.join(root, p)) for p in others.values()),
          f"other_scenes: every scene of configs/scenarios and configs/stress, A1, A2 ({len(others)})")
    common = ["--disco", disco, "--others", "--scenes", "stress/too_weak,stress/K_3", "--starts", "0,1"]
    two = os.path.join(WORK, "starts2")
    r = run_script("bench_starts", *common, "--jobs", "2", "--baseline", disco, "--out", two,
                   "--no-results")
    check(r.returncode == 0, f"bench_starts --others --jobs 2 exits 0 ({r.returncode})"
          + (r.stderr[-2000:] if r.returncode else ""))
    one = os.path.join(WORK, "starts1")
    r1 = run_script("bench_starts", *common, "--out", one, "--no-results")
    check(r1.returncode == 0, f"bench_starts --others --jobs 1 exits 0 ({r1.returncode})")
    if r.returncode or r1.returncode:
        return
    rows2, rows1 = read_csv_rows(os.path.join(two, "starts.csv")), read_csv_rows(os.path.join(one, "starts.csv"))
    refused = [x for x in rows2 if x["scene"] == "stress/too_weak"]
    check(len(refused) == 4 and all(x["status"] == "refused" for x in refused),
          "a scene disco refuses (exit 2) gives refused rows, both binaries, both starts")
    key = lambda x: (x["scene"], x["start"])  # noqa: E731
    new2 = {key(x): (x["iterations"], x["T_f"]) for x in rows2 if x["binary"] == "new"}
    base2 = {key(x): (x["iterations"], x["T_f"]) for x in rows2 if x["binary"] == "base"}
    new1 = {key(x): (x["iterations"], x["T_f"]) for x in rows1}
    k3 = [k for k in new1 if k[0] == "stress/K_3"]
    check(len(k3) == 2 and all(new1[k][1] for k in k3), f"K_3's two starts solved ({[new1[k] for k in k3]})")
    check(new2 == new1 == base2, "the same iterations and T_f 2 at a time, 1 at a time and as the baseline")
    text = open(os.path.join(two, "starts.md")).read()
    check("2 processes at a time (wall times not comparable with one at a time)" in text
          and "not a speed measurement" in text, "with --jobs 2 the tables say the wall is not comparable")
    check("Starts worse than the baseline by more than 1e-3 relative: 0 of 4" in text,
          "against itself, no start worse")
    # A baseline that cannot run (a copy of disco outside its tree: no settings file under its
    # prefix, exit 2 like a refused scene) stops the run, naming the command and its error;
    # its starts are not taken for refused scenes.
    copy = lost_disco(disco)
    r = run_script("bench_starts", "--disco", disco, "--others", "--scenes", "stress/too_weak",
                   "--starts", "0", "--baseline", copy, "--out", os.path.join(WORK, "starts_lost"),
                   "--no-results")
    check(r.returncode == 1 and copy in r.stderr and "no settings file" in r.stderr
          and "Traceback" not in r.stderr,
          f"a baseline without settings stops bench_starts with its command and error ({r.returncode}: "
          f"{r.stderr[-600:]})")
    # Every start refused on both sides: the ratios are "—", not a division by zero.
    r = run_script("bench_starts", "--disco", disco, "--others", "--scenes", "stress/too_weak",
                   "--starts", "0", "--baseline", disco, "--out", os.path.join(WORK, "starts_refused"),
                   "--no-results")
    check(r.returncode == 0 and "iterations —" in r.stdout,
          f"every start refused: the ratios are '—' ({r.returncode}: {r.stderr[-600:]})")


def test_random(disco):
    """scripts/bench_random: the generator is a function of its seed (the same text twice), a
    --kind objects scene has one object and a target for every robot, and a run against a
    baseline (disco itself) writes the scenes it drew, a row per scene for both binaries that
    is the solution file's, and the summary; the same binary gives the same T_f twice."""
    bench = load_script("bench_random")
    a = bench.scene_text("s", "mixed", random.Random(7))
    b = bench.scene_text("s", "mixed", random.Random(7))
    check(a is not None and a == b, "bench_random: the same seed draws the same scene")
    for k in range(6):
        drawn = bench.scene_text("o", "objects", random.Random(k))
        if drawn is None:
            continue
        doc = yaml.safe_load(drawn[0])
        check(len(doc.get("objects", [])) == 1 and all("x" in r["target"] for r in doc["robots"]),
              f"bench_random --kind objects (seed {k}): one object, every robot with a target")
    out, md = os.path.join(WORK, "random"), os.path.join(WORK, "bench_random.md")
    r = run_script("bench_random", "--disco", disco, "--baseline", disco, "--count", "2", "--seed", "3",
                   "--time-limit", "5", "--out", out, "--results", md)
    check(r.returncode == 0, f"bench_random exits 0 ({r.returncode})" + (r.stderr if r.returncode else ""))
    # A baseline that cannot run stops it at its first scene, naming the command and its error
    # (its rows are not "refused").
    lost = lost_disco(disco)
    r = run_script("bench_random", "--disco", disco, "--baseline", lost, "--count", "1", "--seed", "3",
                   "--time-limit", "5", "--out", os.path.join(WORK, "random_lost"), "--no-results")
    check(r.returncode == 1 and lost in r.stderr and "no settings file" in r.stderr
          and "Traceback" not in r.stderr,
          f"bench_random: a baseline without settings stops it ({r.returncode}: {r.stderr[-600:]})")
    label = "default (partial: --count 2 --seed 3 --time-limit 5)"
    check(sections(md) == [label], f"a partial section ({sections(md)})")
    text = section_text(md, label) if label in sections(md) else ""
    for k in range(2):
        name = f"random_mixed_3_{k}"
        scene = os.path.join(out, "scenes", name + ".yaml")
        if not os.path.isfile(scene):
            check(False, f"bench_random wrote {scene}")
            continue
        with open(scene) as f:
            check(f.read() == bench.scene_text(name, "mixed", random.Random(3 * 100000 + k))[0],
                  f"{name}: the file is the generator's text")
        row = re.search(rf"^\| {name} \| \d+ / \d+ / \d+ \| (avoid|contact) \| (.*) \|$", text, re.M)
        check(row is not None, f"{name}: a row")
        if not row:
            continue
        cells = [c.strip() for c in row.group(2).split("|")]
        for role, at in (("new", 0), ("base", 4)):
            path = os.path.join(out, "runs", role, name, "solution.json")
            sol = json.load(open(path)) if os.path.isfile(path) else {}
            if sol.get("status") == "solved":
                check(cells[at] in ("solved", "cut, T_f") and cells[at + 1] == f"{sol['T_f']:.6f}"
                      and cells[at + 2] == str(sol["timing"]["iterations"]),
                      f"{name} {role}: the row is the solution file's ({cells[at:at + 3]})")
            else:
                check(cells[at + 1] == "", f"{name} {role}: no T_f without a certified point ({cells[at + 1]})")
    check(re.search(r"new: a certified point on \d+ of \d+ \(\d+ loops finished\)", text) is not None
          and re.search(r"base: a certified point on \d+ of \d+", text) is not None,
          "the summary counts each binary's certified scenes")
    if "cut," not in text:  # disco is deterministic; a time limit's cut is not
        check(re.search(r"where both certified \(\d+\): new lower by more than 0.001 on 0, higher on 0", text)
              is not None, "the same binary twice: no scene lower or higher")


def write_kkt(path, nx, m, seed):
    """A KKT file (core/ipopt/kkt_solver.h) of [H Jᵀ; J 0]: H (nx × nx) tridiagonal and diagonally
    dominant, J (m × nx, m <= nx) with a nonzero J(r, r) and two more entries per row, one triangle,
    one entry repeated (to be summed). Its inertia: nx positive, m negative eigenvalues."""
    rnd = random.Random(seed)
    triplets = []
    for i in range(1, nx + 1):
        triplets.append((i, i, 4.0 + rnd.random()))
        if i < nx:
            triplets.append((i + 1, i, -1.0))
    for r in range(1, m + 1):
        triplets += [(nx + r, r, 1.0 + rnd.random()), (nx + r, rnd.randint(1, nx), rnd.uniform(-1, 1)),
                     (nx + r, rnd.randint(1, nx), rnd.uniform(-1, 1))]
    triplets.append((nx + 1, 1, 0.5))
    ia, ja, va = zip(*triplets)
    n, nnz = nx + m, len(ia)
    with open(path, "wb") as f:
        f.write(b"DISCOKKT" + struct.pack("<6i", 1, n, nnz, nx, 1, m))
        f.write(struct.pack(f"<{nnz}i", *ia) + struct.pack(f"<{nnz}i", *ja) + struct.pack(f"<{nnz}d", *va))
        f.write(struct.pack(f"<{n}d", *[rnd.uniform(-1, 1) for _ in range(n)]))


def test_bench_kkt(bench):
    kkt = os.path.join(WORK, "kkt")
    os.makedirs(kkt)
    good, cut = os.path.join(kkt, "good.kkt"), os.path.join(kkt, "cut.kkt")
    write_kkt(good, 300, 120, 1)
    with open(good, "rb") as f, open(cut, "wb") as g:
        g.write(f.read()[:200])
    r = subprocess.run([bench, good, "--repeat", "2"], capture_output=True, text=True)
    lines = [json.loads(line) for line in r.stdout.splitlines()]
    check(r.returncode == 0 and len(lines) == 2 and "residual_tolerance" in lines[0]["ldlt"],
          f"bench_kkt: a header line and one row ({r.returncode})" + (r.stderr if r.returncode else ""))
    if len(lines) == 2:
        row = lines[1]
        check((row["n"], row["dual_from"], row["expected_negative"]) == (420, 300, 120),
              f"bench_kkt reads the file's sizes ({row['n']}, {row['dual_from']}, {row['expected_negative']})")
        for name in ("mumps", "ldlt", "pivoted"):
            s = row[name]
            check(s.get("negative") == 120 and (s.get("backward_error") or 1) < 1e-12 and s["factor_ms"] > 0
                  and s["solve_ms"] > 0, f"bench_kkt {name}: 120 negative eigenvalues, backward error "
                  f"{s.get('backward_error')}, times {s.get('factor_ms')} / {s.get('solve_ms')} ms")
    r = subprocess.run([bench, cut], capture_output=True, text=True)
    check(r.returncode == 2 and f"{cut}: truncated KKT file" in r.stderr,
          f"bench_kkt: a truncated file exits 2 naming it ({r.returncode}, {r.stderr.strip()})")

    out = os.path.join(WORK, "bench_kkt.md")
    r = run_script("bench_kkt", "--disco", DISCO, "--bench", bench, "--corpus", os.path.join(WORK, "corpus"),
                   "--scenes", "A2", "--starts", "0", "--repeat", "1", "--results", out)
    check(r.returncode == 0, f"scripts/bench_kkt --scenes A2 --starts 0 exits 0 ({r.returncode})"
          + (r.stderr[-2000:] if r.returncode else ""))
    folder = os.path.join(WORK, "corpus", "A2_s0")
    dumped = [f for f in os.listdir(folder) if f.endswith(".kkt")] if os.path.isdir(folder) else []
    check(len(dumped) >= 5 and os.path.isfile(os.path.join(folder, "source.json")),
          f"the corpus: {len(dumped)} matrices and source.json in A2_s0")
    label = "default (partial: --scenes A2 --starts 0 --repeat 1)"
    text = section_text(out, label) if os.path.isfile(out) and label in sections(out) else ""
    check(re.search(rf"^\| A2 \| {len(dumped)} \| \d+–\d+ \|", text, re.M) is not None,
          f"the section '{label}' has A2's row with its {len(dumped)} matrices")
    check(re.search(rf"^\| A2 \| {len(dumped)} \| [\d.]+ / [\d.]+ / [\d.]+ \|", text, re.M) is not None,
          f"the section '{label}' has the pivoting LDLT's row for A2")


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
if MODE == "common":
    test_common()
    test_incumbent_measures()
elif MODE == "results":
    DISCO = sys.argv[4]
    test_results(DISCO)
    test_bench_starts(DISCO)
    test_random(DISCO)
    test_bench_kkt(sys.argv[5])
else:
    sys.exit(f"unknown mode {MODE}")
finish(f"script.{MODE}")
