"""One `disco solve` run, as the benchmarks make it, and what it leaves: solution.json, the
solve log (one line per elastic-mode solve on stderr), wall and CPU time.
"""
import json
import os
import re
import resource
import subprocess
import time
from dataclasses import dataclass, field
from typing import Optional

# One line of the solve log (search/objective_reduction.cpp, solve_log_line):
#   "  3 reduction      8.27916    8.27916 not tight           7.0e-02   1.1e-15    6    41   0.210"
# number, phase (may hold a space), bound, T_f, how it ended (one or two words: solved, not
# tight, cap reached, max_iter, ...; ", stalled" after them for a minimisation the stall rule
# ended), compl, viol, NLP solves, iterations, seconds; then
# optionally "*" or "(Ipopt: ...)".
SOLVE_LINE = re.compile(
    r"^\s*(\d+)\s+([a-z][a-z -]*?)\s+(\S+)\s+(\S+)\s+([a-z_]+(?: [a-z_]+)?(?:, stalled)?)\s+(\S+)\s+(\S+)"
    r"\s+(\d+)\s+(\d+)\s+([\d.]+)\b")


@dataclass
class SolveLine:
    number: int
    phase: str
    ended: str
    nlp_solves: int
    iterations: int
    seconds: float


def solve_lines(text):
    """The solve-log lines in `text` (disco's stderr), in order."""
    out = []
    for line in text.splitlines():
        m = SOLVE_LINE.match(line)
        if m:
            out.append(SolveLine(int(m.group(1)), m.group(2).strip(), m.group(5), int(m.group(8)),
                                 int(m.group(9)), float(m.group(10))))
    return out


def phase_totals(lines):
    """{phase: [iterations, seconds]} summed over solve-log lines, in order of appearance."""
    phases = {}
    for s in lines:
        ph = phases.setdefault(s.phase, [0, 0.0])
        ph[0] += s.iterations
        ph[1] += s.seconds
    return phases


@dataclass
class Run:
    """What one `disco solve` left. exit is the exit code, or "timeout" when it was killed."""
    cmd: list
    exit: object
    wall: float                 # seconds, measured around the process
    cpu: float                  # user + system seconds of the process (getrusage)
    stdout: str
    stderr: str
    solution: Optional[dict]    # solution.json, or None when it wrote none
    lines: list = field(default_factory=list)   # the solve log (SolveLine)

    def refused(self):
        """disco refused the scene as bad input: exit 2 with an error naming the scene's file
        (file, line and key). Any other exit 2 (no settings file under the binary's prefix, a bad
        --set) is the run's own error, not the scene's."""
        return self.exit == 2 and self.cmd[2] in self.stderr

    def failure(self):
        """An account of a run that failed on its own: the command, its exit and the end of its
        stderr (for a script to stop with)."""
        return f"{' '.join(self.cmd)} exited {self.exit}:\n{self.stderr[-2000:]}"

    def get(self, *keys):
        """solution[k1][k2]..., or None where anything is missing."""
        v = self.solution
        for k in keys:
            if not isinstance(v, dict):
                return None
            v = v.get(k)
        return v


def solve(disco, scene, out, sets=(), threads=1, timeout=None, args=(), log=None, env=None):
    """Runs `disco solve SCENE --out OUT --threads N ARGS --set S ...` once and waits for it;
    an earlier OUT/solution.json is removed first, so that a run that writes none leaves none.
    `log` (a path): the command, its stdout and its stderr are written there. `env`: variables
    added to the environment. Runs must be sequential for `cpu` to be the run's own."""
    os.makedirs(out, exist_ok=True)
    sol_path = os.path.join(out, "solution.json")
    if os.path.exists(sol_path):
        os.remove(sol_path)
    cmd = [disco, "solve", scene, "--out", out, "--threads", str(threads), *args]
    for s in sets:
        cmd += ["--set", s]
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                           env=dict(os.environ, **env) if env else None)
        code, stdout, stderr = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        code = "timeout"
        stdout, stderr = [x.decode(errors="replace") if isinstance(x, bytes) else (x or "")
                          for x in (e.stdout, e.stderr)]
    wall = time.monotonic() - t0
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)
    if log:
        with open(log, "w") as f:
            f.write(" ".join(cmd) + "\n" + stdout + stderr)
    sol = None
    if os.path.exists(sol_path):
        with open(sol_path) as f:
            sol = json.load(f)
    return Run(cmd, code, wall, cpu, stdout, stderr, sol, solve_lines(stderr))


def disco_version(disco):
    """What `disco --version` prints (version and git commit), or why it could not be asked."""
    try:
        p = subprocess.run([disco, "--version"], capture_output=True, text=True, timeout=60)
    except OSError as e:
        return f"unknown ({disco}: {e.strerror})"
    text = (p.stdout or p.stderr).strip()
    return text if p.returncode == 0 and text else f"unknown ({disco} --version exited {p.returncode})"
