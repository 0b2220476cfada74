"""Searches: the mpirun command line of `disco search`, running scripts/bench_paper (which
bench_adaptive, bench_budget and bench_formulations compare), and reading what a search
leaves in its DIR (best.json, runs.jsonl, bench_paper's paper_table.csv).
"""
import csv
import json
import os
import subprocess
import sys

from common.paths import SCRIPTS


def mpirun(ranks, disco, *args):
    """`mpirun -np RANKS disco ARGS...` as the scripts run it (root allowed, and more ranks than
    cores allowed)."""
    return ["mpirun", "-np", str(ranks), "--allow-run-as-root", "--oversubscribe", disco, *args]


def read_json(path):
    with open(path) as f:
        return json.load(f)


def read_runs(path, warn=None):
    """The lines of runs.jsonl that are JSON objects with scene, start and status. A line that
    is not is skipped, and warn(message naming its line number) is called when given (as
    `disco search --resume` does)."""
    runs = []
    with open(path, errors="replace") as f:
        for n, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                r = json.loads(line)
                if not isinstance(r, dict) or not all(k in r for k in ("scene", "start", "status")):
                    raise ValueError("missing scene, start or status")
                runs.append(r)
            except ValueError as e:
                if warn:
                    warn(f"{path}:{n}: skipped ({e})")
    return runs


def read_table(path, key="problem"):
    """A CSV file as {row[key]: row}."""
    with open(path) as f:
        return {row[key]: row for row in csv.DictReader(f)}


def number(text):
    """A CSV cell as a float, None when empty."""
    return float(text) if text not in ("", None) else None


def run_bench_paper(out, ranks, disco=None, starts=None, time_limit=None, scenes=None, sets=()):
    """Runs `scripts/bench_paper --run --no-results` into `out` (its output hidden, the command
    echoed) and returns its paper_table.csv as {problem: row}. Exits when it fails."""
    cmd = [os.path.join(SCRIPTS, "bench_paper"), "--run", "--no-results", "--out", out,
           "--ranks", str(ranks)]
    if disco:
        cmd += ["--disco", disco]
    if starts is not None:
        cmd += ["--starts", str(starts)]
    if time_limit is not None:
        cmd += ["--time-limit", f"{time_limit:g}"]
    if scenes:
        cmd += ["--scenes", ",".join(scenes)]
    for kv in sets:
        cmd += ["--set", kv]
    print("$", " ".join(cmd), flush=True)
    if subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode != 0:
        sys.exit("scripts/bench_paper failed: " + " ".join(cmd))
    return read_table(os.path.join(out, "paper_table.csv"))
