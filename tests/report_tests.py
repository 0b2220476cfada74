#!/usr/bin/python3
"""Tests of scripts/report and scripts/screenshot_report (CTest report.build, report.screenshot;
see tests/CMakeLists.txt). Run on Debian's python3 (Pillow, a dependency of matplotlib, reads
the images).

  report_tests.py DISCO SCRIPTS CONFIGS WORKDIR MODE
MODE:
  build       a real search (smoke benchmark, 2 starts per scene, plus a collision and a
              scene without a solution), then scripts/report. Checks, from best.json and runs.jsonl and not
              from the report's code: the page is offline (no script, no absolute URL, every
              linked file inside the report folder); a summary row per scene with its T_f,
              lower bound, gap, times, starts and certificate; per solved scene the snapshots,
              an animated GIF whose disks move, the plots over time (pair gaps for
              scenes with pairs, contact forces for scenes with contact pairs) and the two search plots, none of them blank; a row per start
              with its T_f and the best start marked; the scene without a solution says so,
              with its status; the raw data copied byte for byte. Then bad input: a missing
              directory and a corrupt best.json give exit 2 and name the file; a corrupt
              runs.jsonl line is skipped with a warning naming the line; a missing solution
              file gives exit 1 with the page saying so and the other scenes drawn; a
              `disco solve` output gives a one-scene report without a search section; lines of
              another seed are left out, older lines (no history, schedule or times) are
              drawn, and a resumed search's scene times are marked.
  plots       on the search of `build`: every plot's drawn data read back from the figure
              and compared with the solution file and runs.jsonl (controls, speeds, floor
              friction, contact forces, gaps; each start's new bests against time, the
              spread of final T_f).
  screenshot  scripts/screenshot_report on the page built by `build`: a PNG of the window
              size, not blank, in which the plots' colours appear (the images loaded offline).
"""
import copy
import filecmp
import html.parser
import json
import os
import shutil
import subprocess
import sys

from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from viz.search_plots import has_final_point  # noqa: E402

DISCO, SCRIPTS, CONFIGS, WORK, MODE = sys.argv[1:6]
REPORT = os.path.join(SCRIPTS, "report")
SHOT = os.path.join(SCRIPTS, "screenshot_report")
ENV = dict(os.environ, OMP_NUM_THREADS="1")
SEARCH = os.path.join(WORK, "search")
PAGE = os.path.join(SEARCH, "report", "index.html")


def run(cmd):
    return subprocess.run(cmd, env=ENV, capture_output=True, text=True)


class Page(html.parser.HTMLParser):
    """Links, images, scripts, ids and table rows (as lists of cell texts, with the row's
    class) of an HTML page."""

    def __init__(self, text):
        super().__init__()
        self.refs, self.ids, self.rows, self.scripts = [], set(), [], 0
        self.facts = {}  # (h2 id, dt text) -> dd text
        self.sections = {}  # h2 id -> text until the next h2
        self._row = self._cell = None
        self._section = None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "script":
            self.scripts += 1
        for key in ("src", "href"):
            if key in a:
                self.refs.append(a[key])
        if tag == "h2":
            self._section = a.get("id")
            self.sections[self._section] = ""
        if tag == "tr":
            self._row = {"class": a.get("class", ""), "cells": [], "section": self._section}
        if tag in ("td", "th") and self._row is not None:
            self._cell = ""
        if tag == "dt":
            self._dt = ""
        if tag == "dd":
            self._dd = ""

    _dt = _dd = None

    def handle_endtag(self, tag):
        if tag == "dt":
            self._key, self._dt = " ".join(self._dt.split()), None
        if tag == "dd":
            self.facts[(self._section, self._key)] = " ".join(self._dd.split())
            self._dd = None
        if tag in ("td", "th") and self._row is not None and self._cell is not None:
            self._row["cells"].append(" ".join(self._cell.split()))
            self._cell = None
        if tag == "tr" and self._row is not None:
            self.rows.append(self._row)
            self._row = None

    def handle_data(self, data):
        if self._dt is not None:
            self._dt += data
        if self._dd is not None:
            self._dd += data
        if self._cell is not None:
            self._cell += data
        if self._section is not None:
            self.sections[self._section] += data


def anchor(name):
    return "scene-" + "".join(c if c.isalnum() or c in "-_" else "-" for c in name)


def not_blank(path):
    """The fraction of pixels that are not near-white, and whether there are coloured ones
    (robots, pairs and guesses are drawn in colour; axes and text are grey)."""
    return not_blank_image(Image.open(path).convert("RGB"))


def not_blank_image(im):
    px = list(im.getdata())
    ink = sum(1 for p in px if min(p) < 235) / len(px)
    coloured = sum(1 for p in px if max(p) - min(p) > 80)
    return ink, coloured > 50


def build():
    shutil.rmtree(SEARCH, ignore_errors=True)
    scenes = [os.path.join(CONFIGS, "benchmarks", "smoke.yaml"),
              os.path.join(CONFIGS, "stress", "forced_contact.yaml"),
              os.path.join(CONFIGS, "stress", "spin_short.yaml")]
    r = run([DISCO, "search", *scenes, "--starts", "2", "--seed", "1", "--out", SEARCH, "--quiet"])
    check(r.returncode == 3, f"the search exits 3: one scene has no solution (got {r.returncode})")
    r = run([REPORT, SEARCH])
    check(r.returncode == 0, f"report exits 0 (got {r.returncode}: {r.stderr[-300:]})")
    check(r.stdout == "" and "wrote " in r.stderr, "report: progress on stderr, stdout empty")
    check(os.path.isfile(PAGE), "index.html written")
    out = os.path.dirname(PAGE)
    with open(PAGE) as f:
        page = Page(f.read())
    with open(os.path.join(SEARCH, "best.json")) as f:
        best = json.load(f)
    with open(os.path.join(SEARCH, "runs.jsonl")) as f:
        runs = [json.loads(line) for line in f if line.strip()]

    # Offline: nothing to fetch, nothing to run, every link inside the folder.
    check(page.scripts == 0, "no <script>")
    outside = [u for u in page.refs if "://" in u or u.startswith(("//", "/", "..", "data:"))]
    check(not outside, f"no absolute or outside links ({outside[:3]})")
    missing = [u for u in page.refs if not u.startswith("#")
               and not os.path.isfile(os.path.join(out, u))]
    check(not missing, f"every linked file exists ({missing[:3]})")
    internal = [u[1:] for u in page.refs if u.startswith("#")]
    check(all(i in page.ids for i in internal), "every in-page link has its target")
    for name in ("best.json", "runs.jsonl"):
        check(filecmp.cmp(os.path.join(SEARCH, name), os.path.join(out, "data", name), False),
              f"data/{name} is a byte copy")

    # The summary: a row per scene, its numbers from best.json.
    summary = {row["cells"][0]: row["cells"] for row in page.rows if row["cells"]
               and row["cells"][0] in best["scenes"]}
    check(sorted(summary) == sorted(best["scenes"]), f"a summary row per scene ({sorted(summary)})")
    for name, s in best["scenes"].items():
        cells = " | ".join(summary.get(name, []))
        want = [f"{s['starts_run']} / {s['starts_solved']}"]
        if s["T_f"] is not None:
            # The gap is to the lower bound, or (robots that can be pushed have none) to
            # the reference time, marked so.
            lb, ref = s["lower_bound"], s["reference_time"]
            want += ([f"{lb:.6f}", f"{100 * (s['T_f'] - lb) / lb:.2f} %"] if lb is not None
                     else ["none", f"{100 * (s['T_f'] - ref) / ref:.2f} % vs ref"])
            want += [f"{s['T_f']:.6f}",
                     f"{s['time_to_first_feasible_s']:.1f}", f"{s['time_to_best_s']:.1f}",
                     f"{s['certificate']['max_violation']:.1e} / "
                     f"{s['certificate']['max_complementarity']:.1e}",
                     f"start {s['start']}:"]
        else:
            want += ["no certified solution"]
        absent = [w for w in want if w not in cells]
        check(not absent, f"{name}: summary row holds {want} (missing {absent}; row: {cells})")

    # Per scene: its section, figures and start table.
    for name, s in best["scenes"].items():
        sec = anchor(name)
        check(sec in page.ids, f"{name}: has a section")
        text = page.sections.get(sec, "")
        mine = [r for r in runs if r["scene"] == name]
        if s["T_f"] is None:
            status = page.facts.get((sec, "status"), "")
            check("no certified solution" in status and all(r["status"] in status for r in mine),
                  f"{name}: its status says there is no certified solution, and why ({status})")
            check(not os.path.exists(os.path.join(out, "img", f"{name}_motion.gif")),
                  f"{name}: no animation without a trajectory")
        else:
            with open(os.path.join(SEARCH, s["solution"])) as f:
                sol = json.load(f)
            kinds = ["snapshots.png", "controls.png", "speeds.png", "floor_friction.png",
                     "progress.png", "spread.png"]
            # Pair gaps for scenes with pairs; contact forces for contact pairs (in
            # forced_contact the collision pushes, so the plot has coloured lines).
            contact = any(p["mode"] == "contact" for p in sol["pairs"])
            kinds += ["gaps.png"] * bool(sol["pairs"]) + ["contact_forces.png"] * contact
            for k, want in (("gaps.png", bool(sol["pairs"])), ("contact_forces.png", contact)):
                check(os.path.exists(os.path.join(out, "img", f"{name}_{k}")) == want,
                      f"{name}: {k} {'drawn' if want else 'left out'}")
            for k in kinds:
                rel = f"img/{name}_{k}"
                path = os.path.join(out, rel)
                ok = rel in page.refs and os.path.isfile(path)
                ink, blue = not_blank(path) if ok else (0, False)
                check(ok and ink > 0.01 and blue,
                      f"{name}: {k} shown, drawn ({100 * ink:.1f} % ink), in colour")
            gif = os.path.join(out, "img", f"{name}_motion.gif")
            check(f"img/{name}_motion.gif" in page.refs and os.path.isfile(gif),
                  f"{name}: animation shown")
            if os.path.isfile(gif):
                im = Image.open(gif)
                frames = im.n_frames
                below_title = (0, 40, 720, 540)  # the title's time changes anyway
                first = im.convert("RGB").crop(below_title).tobytes()
                im.seek(frames // 2)
                middle = im.convert("RGB").crop(below_title).tobytes()
                check(im.format == "GIF" and frames >= 20 and first != middle and im.size == (720, 540),
                      f"{name}: GIF 720x540 with {frames} frames, the disks move")
                check(im.info.get("loop") == 0, f"{name}: the GIF loops")
                # Real time: frame delays (whole 1/100 s) times the frames span T_f to 1 %.
                span = (frames - 1) * im.info["duration"] / 1000.0
                check(im.info["duration"] % 10 == 0 and abs(span / sol["T_f"] - 1.0) <= 0.01,
                      f"{name}: plays in real time ({frames - 1} x {im.info['duration']} ms = "
                      f"{span:.3f} s for T_f {sol['T_f']:.3f} s)")
            check(filecmp.cmp(os.path.join(SEARCH, s["solution"]),
                              os.path.join(out, "data", "best", f"{name}.json"), False),
                  f"{name}: its solution file copied byte for byte")
        # A row per start: start index first, T_f in it; the best one marked.
        starts = {}
        for row in page.rows:
            cells = row["cells"]
            if row["section"] == sec and len(cells) >= 12 and cells[0].isdigit():
                starts.setdefault(cells[0], []).append(row)
        for r in mine:
            t = f"{r['T_f']:.6f}" if r["T_f"] is not None else "–"
            found = [row for row in starts.get(str(r["start"]), [])
                     if t in row["cells"] and r["status"] in " ".join(row["cells"])]
            check(len(found) >= 1, f"{name} start {r['start']}: a table row with T_f {t}")
            if s["T_f"] is not None and r["start"] == s["start"]:
                check(any(row["class"] == "best" for row in found), f"{name}: best start marked")
        marked = [row for rows in starts.values() for row in rows if row["class"] == "best"]
        check(len(marked) == (s["T_f"] is not None), f"{name}: one best row ({len(marked)})")
        # The homotopy classes: a row per class the scene's certified starts ended in, with
        # its best T_f and how many starts ended in it, from runs.jsonl's "class".
        ended = {}
        for r in mine:
            if r.get("class") and has_final_point(r):
                e = ended.setdefault(r["class"]["key"] or "(no pair within reach)", [None, 0])
                e[0] = r["T_f"] if e[0] is None else min(e[0], r["T_f"])
                e[1] += 1
        class_rows = {row["cells"][0]: row["cells"] for row in page.rows
                      if row["section"] == sec and len(row["cells"]) == 6}
        for key, (T, n) in ended.items():
            cells = class_rows.get(key, [])
            check(len(cells) == 6 and cells[1] == f"{T:.6f}" and cells[4] == str(n),
                  f"{name}: class '{key}': best {T:.6f}, {n} starts ({cells})")

    # Bad input.
    r = run([REPORT, os.path.join(WORK, "no_such_dir")])
    check(r.returncode == 2 and "no_such_dir" in r.stderr, "a missing directory: exit 2, named")
    bad = os.path.join(WORK, "bad")
    shutil.rmtree(bad, ignore_errors=True)
    shutil.copytree(SEARCH, bad, ignore=shutil.ignore_patterns("report"))
    with open(os.path.join(bad, "best.json"), "w") as f:
        f.write('{"scenes": ')
    r = run([REPORT, bad])
    check(r.returncode == 2 and "best.json" in r.stderr and "not valid JSON" in r.stderr
          and not os.path.exists(os.path.join(bad, "report", "index.html")),
          f"a corrupt best.json: exit 2, named, no page ({r.stderr.strip()[:160]})")
    shutil.copyfile(os.path.join(SEARCH, "best.json"), os.path.join(bad, "best.json"))
    with open(os.path.join(bad, "runs.jsonl"), "a") as f:
        f.write("{not json\n")
    lines = sum(1 for _ in open(os.path.join(bad, "runs.jsonl")))
    solved = next(n for n, s in best["scenes"].items() if s["T_f"] is not None)
    os.remove(os.path.join(bad, best["scenes"][solved]["solution"]))
    r = run([REPORT, bad])
    check(f"runs.jsonl:{lines}: skipped" in r.stderr, "a corrupt runs.jsonl line: skipped, named")
    check(r.returncode == 1, f"a missing solution file: exit 1 (got {r.returncode})")
    with open(os.path.join(bad, "report", "index.html")) as f:
        text = f.read()
    check(f"{solved}.json: missing" in text, "the page names the missing solution file")
    others = [n for n, s in best["scenes"].items() if s["T_f"] is not None and n != solved]
    check(all(os.path.isfile(os.path.join(bad, "report", "img", f"{n}_snapshots.png"))
              for n in others) and others, "the other scenes are drawn")

    # Lines of another seed (a --resume with another --seed appends them; the search ignores
    # them) and lines written before history, guess, schedule and the times existed.
    mixed = os.path.join(WORK, "mixed")
    shutil.rmtree(mixed, ignore_errors=True)
    shutil.copytree(SEARCH, mixed, ignore=shutil.ignore_patterns("report"))
    with open(os.path.join(mixed, "runs.jsonl"), "w") as f:
        for k, r in enumerate(runs):
            r = dict(r)
            if k % 2:
                for key in ("history", "guess", "schedule", "finished_s", "seconds"):
                    r.pop(key, None)
            elif k < len(runs) // 2:
                r["finished_s"] += 1000.0  # an earlier run's clock: the next line "resumes"
            f.write(json.dumps(r) + "\n")
        f.write(json.dumps(dict(runs[0], seed=99, T_f=0.5, start=0)) + "\n")
    r = run([REPORT, mixed])
    check(r.returncode == 0, f"older lines and another seed's: exit 0 ({r.stderr.strip()[-200:]})")
    check("1 line(s) of another seed" in r.stderr, "another seed's line: left out, with a warning")
    with open(os.path.join(mixed, "report", "index.html")) as f:
        p = Page(f.read())
    best_rows = [row for row in p.rows if row["class"] == "best"]
    check(len(best_rows) == sum(s["T_f"] is not None for s in best["scenes"].values()) and
          not any("0.500000" in row["cells"] for row in p.rows),
          "one best row per solved scene; the other seed's T_f nowhere")
    resumed = [row["cells"][0] for row in p.rows if row["section"] == "summary"
               and "– (resumed)" in row["cells"]]
    check(bool(resumed), f"a resumed search: scene times shown as resumed ({resumed})")

    # A `disco solve` output.
    one = os.path.join(WORK, "solve")
    r = run([DISCO, "solve", os.path.join(CONFIGS, "scenarios", "one_robot_axis.yaml"),
             "--set", "scene.steps=20", "--out", one, "--quiet"])
    check(r.returncode == 0, "disco solve of one_robot_axis exits 0")
    r = run([REPORT, one, "--no-animation"])
    with open(os.path.join(one, "report", "index.html")) as f:
        p = Page(f.read())
    check(r.returncode == 0 and anchor("one_robot_axis") in p.ids and
          "img/one_robot_axis_controls.png" in p.refs and
          not any("progress" in u or u.endswith(".gif") for u in p.refs) and
          "NLP solves" in p.facts.get((anchor("one_robot_axis"), "solve"), ""),
          "a solve output: one scene, its plots and solve time, no search plots, "
          "--no-animation honoured")
    # Its title names the scene (not the folder), its raw data links the solution file (copied
    # byte for byte), and "found by" says how it was solved, not its status.
    with open(os.path.join(one, "solution.json"), "rb") as f, \
            open(os.path.join(one, "report", "data", "solution.json"), "rb") as g:
        copied = f.read() == g.read()
    summary = [row["cells"] for row in p.rows if row["section"] == "summary" and row["cells"]
               and row["cells"][0] == "one_robot_axis"]
    check("<title>disco solve: one_robot_axis</title>" in open(os.path.join(one, "report", "index.html")).read()
          and "data/solution.json" in p.refs and copied
          and summary and summary[0][-1] == "disco solve, start 0"
          and p.facts.get((anchor("one_robot_axis"), "found by")) == "disco solve, start 0",
          f"a solve output: titled by its scene, its solution.json under raw data, found by "
          f"'disco solve, start 0' ({summary[0][-1] if summary else 'no summary row'})")

    # The scene line counts obstacles where there are some.
    sentry = os.path.join(WORK, "solve_sentry")
    r = run([DISCO, "solve", os.path.join(CONFIGS, "scenarios", "moving_path.yaml"),
             "--set", "scene.steps=10", "--out", sentry, "--quiet"])
    r2 = run([REPORT, sentry, "--no-animation"])
    with open(os.path.join(sentry, "report", "index.html")) as f:
        scene_line = Page(f.read()).facts.get((anchor("moving_path"), "scene"))
    plain_line = p.facts.get((anchor("one_robot_axis"), "scene"))
    check(r.returncode == 0 and r2.returncode == 0
          and scene_line == "1 robot, 0 pairs (none), 1 obstacle, N_t = 10"
          and plain_line == "1 robot, 0 pairs (none), N_t = 20",
          f"the scene line: '1 obstacle' in a scene with one ({scene_line!r}), none without ({plain_line!r})")

    # Another objective (core/model/objective.h): the page names it and its value from the
    # solution file, and measures no gap of it against the lower bound on T_f.
    energy = os.path.join(WORK, "solve_energy")
    r = run([DISCO, "solve", os.path.join(CONFIGS, "scenarios", "one_robot_axis_energy.yaml"),
             "--set", "scene.steps=20", "--out", energy, "--quiet"])
    check(r.returncode == 0, "disco solve of one_robot_axis_energy exits 0")
    with open(os.path.join(energy, "solution.json")) as f:
        objective = json.load(f)["objective"]
    r = run([REPORT, energy, "--no-animation"])
    with open(os.path.join(energy, "report", "index.html")) as f:
        p = Page(f.read())
    fact = p.facts.get((anchor("one_robot_axis_energy"), "objective"), "")
    row = [row["cells"] for row in p.rows if row["section"] == "summary" and row["cells"]
           and row["cells"][0] == "one_robot_axis_energy"]
    check(r.returncode == 0 and objective["kind"] == "energy" and objective["unit"] == "N^2 s"
          and fact == f"energy = {objective['value']:.6g} N^2 s"
          and row and "energy: " in row[0][3] and row[0][5] == "–",
          f"an energy solve: the objective and its value shown ({fact!r}), no gap "
          f"({row[0] if row else 'no summary row'})")


def screenshot():
    png = os.path.join(WORK, "screenshot.png")
    r = run([SHOT, PAGE, "-o", png, "--width", "1280", "--height", "2400"])
    check(r.returncode == 0 and os.path.isfile(png), f"screenshot exits 0 ({r.stderr.strip()[-300:]})")
    if os.path.isfile(png):
        im = Image.open(png)
        check(im.size == (1280, 2400), f"the window's size ({im.size})")
        ink, _ = not_blank(png)
        check(ink > 0.02, f"not blank ({100 * ink:.1f} % ink)")
        # Robot 1's orange (matplotlib's tab10) is in the plots only, not in the page's CSS.
        orange = sum(1 for p in im.convert("RGB").getdata()
                     if abs(p[0] - 255) + abs(p[1] - 127) + abs(p[2] - 14) < 40)
        check(orange > 500, f"the plots appear: the images loaded offline ({orange} orange pixels)")
        top = im.convert("RGB").crop((0, 0, 1280, 120))
        check(not_blank_image(top)[0] > 0.005, "the title is rendered at the top")
    # The whole page: taller than the window above, its bottom (the footer) drawn, and no
    # measuring copy left beside the page.
    full = os.path.join(WORK, "screenshot_full.png")
    r = run([SHOT, PAGE, "-o", full, "--width", "1280", "--full-page"])
    check(r.returncode == 0 and os.path.isfile(full), f"--full-page exits 0 ({r.stderr.strip()[-300:]})")
    if os.path.isfile(full):
        w, h = Image.open(full).size
        bottom = Image.open(full).convert("RGB").crop((0, h - 200, w, h))
        check(w == 1280 and 2400 < h <= 20000 and not_blank_image(bottom)[0] > 0.001,
              f"--full-page: the whole page, {w}x{h}, its end drawn")
    leftovers = [f for f in os.listdir(os.path.dirname(PAGE)) if ".measure-" in f]
    check(not leftovers, f"--full-page leaves no measuring copy ({leftovers})")
    r = run([SHOT, os.path.join(WORK, "no_such_page.html")])
    check(r.returncode == 2 and "no such file" in r.stderr, "a missing page: exit 2")


def plots():
    """What the plots draw is the data: read back from the figures (the viz functions return
    them open when given no file) and compared with the solution file and runs.jsonl."""
    import math
    import numpy as np
    from matplotlib.patches import StepPatch
    sys.path.insert(0, SCRIPTS)
    from viz import search_plots, time_series
    from viz.solution_file import load

    def refusal(path, doc):
        """What load says of `doc` written to `path` ("" if it loads)."""
        with open(path, "w") as f:
            json.dump(doc, f)
        try:
            load(path, full=True)
            return ""
        except Exception as e:  # BadInput
            return str(e)

    with open(os.path.join(SEARCH, "best.json")) as f:
        best = json.load(f)
    with open(os.path.join(SEARCH, "runs.jsonl")) as f:
        runs = [json.loads(line) for line in f if line.strip()]
    name = "forced_contact"  # 2 robots, a contact pair, a collision
    entry = best["scenes"][name]
    path = os.path.join(SEARCH, entry["solution"])
    with open(path) as f:
        raw = json.load(f)
    sol = load(path, full=True)
    n, T = raw["N_t"], raw["T_f"]
    grid = [k * T / n for k in range(n + 1)]

    def stairs(ax):
        return [p.get_data() for p in ax.patches if isinstance(p, StepPatch)]

    def hlines(ax):
        return sorted({round(l.get_ydata()[0], 12) for l in ax.lines
                       if l.get_linestyle() == "--" and len(set(l.get_ydata())) == 1})

    def same(a, b):
        return len(a) == len(b) and np.allclose(a, b, rtol=0, atol=1e-12)

    def bound(r, k):  # F_max per component; |a_k| F_max along a D_ef 1 robot's force axis a
        return r["F_max"] * (abs(r["force_axis"][k]) if r["force_dims"] == 1 else 1.0)

    # A panel per component some robot can push in: in forced_contact every robot pushes along
    # a = (1, 0), so F_y's bound is 0 for all and F_y gets no panel, only a word in the title.
    comps = [k for k in (0, 1) if any(bound(r, k) > 0 for r in raw["robots"])]
    fig = time_series.plot_controls(sol, None, [])
    data_axes = [ax for ax in fig.axes if stairs(ax)]
    check(comps == [0] and len(data_axes) == 1 and "F_y ≡ 0" in fig._suptitle.get_text(),
          f"controls: no F_y panel when no robot can push in y ({len(data_axes)} panels)")
    for ax, k in zip(data_axes, comps):
        key = "Fx" if k == 0 else "Fy"
        got = stairs(ax)
        check(len(got) == len(raw["robots"]) and
              all(same(g.values, r[key]) and same(g.edges, grid) for g, r in zip(got, raw["robots"])),
              f"controls: {key} of every robot over the step grid")
        want = sorted({round(sg * bound(r, k), 12) for r in raw["robots"] for sg in (-1, 1)})
        check(hlines(ax) == want, f"controls: component {k} dashed at its bounds {want}")
    # Turned to push along y too (a = (0.6, 0.8)), the F_y panel is back with its bounds.
    diag = copy.deepcopy(sol)
    for r in diag["robots"]:
        r["force_bound"] = [0.6 * r["F_max"], 0.8 * r["F_max"]]
    fig = time_series.plot_controls(diag, None, [])
    data_axes = [ax for ax in fig.axes if stairs(ax)]
    check(len(data_axes) == 2 and hlines(data_axes[1]) == sorted(
              {round(sg * 0.8 * r["F_max"], 12) for r in raw["robots"] for sg in (-1, 1)}),
          "controls: with a y component, two panels, F_y dashed at its bounds")
    # Equal curves do not hide each other: the second robot, given the first one's data, is
    # drawn dashed and thinner over it, and its label says whose it equals.
    twin = copy.deepcopy(sol)
    a, b = twin["robots"][0], twin["robots"][1]
    for key in ("vx", "vy", "omega", "friction_x", "friction_y"):
        b[key] = list(a[key])
    fig = time_series.plot_speeds(twin, None, [])
    lines = [l for l in fig.axes[0].lines if len(l.get_xdata()) == n + 1]
    check(len(lines) == 2 and lines[0].get_linestyle() == "-" and lines[1].get_linestyle() != "-"
          and lines[1].get_linewidth() < lines[0].get_linewidth()
          and lines[1].get_label() == f"{b['name']} (= {a['name']})",
          f"speeds: an equal curve is dashed over the first ({[l.get_label() for l in lines]})")
    fig = time_series.plot_floor_friction(twin, None, [])
    got = [p for p in fig.axes[0].patches if isinstance(p, StepPatch)]
    dashed = [l for l in fig.axes[0].lines if l.get_linestyle() == "--"]
    check(len(got) == 2 and got[1].get_linestyle() != "solid" and got[1].get_label().endswith(f"(= {a['name']})")
          and dashed and all(l.get_zorder() > max(p.get_zorder() for p in got) for l in dashed),
          "floor friction: an equal curve dashed; the μ M g line drawn over the data")

    # Objects: the second disk made a passive object (kind object, no force) is hatched in the
    # snapshots and the animation, the robots are not, and the controls leave it out.
    from viz import snapshots
    from matplotlib.patches import Circle
    obj_doc = copy.deepcopy(raw)
    o = obj_doc["robots"][1]
    # (radius 0.4, where the robots have 0.5: the drawn disks tell by their radius whose they are)
    o.update(kind="object", F_max=0.0, force_dims=0, Fx=[0.0] * n, Fy=[0.0] * n, radius=0.4)
    o.pop("force_axis", None)
    obj_path = os.path.join(WORK, "object_solution.json")
    with open(obj_path, "w") as f:
        json.dump(obj_doc, f)
    osol = load(obj_path, full=True)
    check([r["object"] for r in osol["robots"]] == [False, True], "load: kind object read")
    fig = snapshots.overlay(osol, snapshots.snapshot_times(osol), 0.01, (1200, 600), "")
    disks = [p for p in fig.axes[0].patches if isinstance(p, Circle) and p.get_fill()]
    radius = {round(r["radius"], 12): r.get("object", False) for r in osol["robots"]}
    hatched = [p for p in disks if p.get_hatch()]
    check(len(set(radius)) == 2 and hatched and len(hatched) < len(disks) and
          all(bool(p.get_hatch()) == radius[round(p.get_radius(), 12)] for p in disks),
          f"snapshots: the object's disks hatched, the robot's not ({len(hatched)} of {len(disks)})")
    legend = [t.get_text() for lg in fig.legends + [ax.get_legend() for ax in fig.axes if ax.get_legend()]
              for t in lg.get_texts()]
    check(f"{o['name']} (object)" in legend, f"snapshots: the legend names the object ({legend[:3]})")
    fig = time_series.plot_controls(osol, None, [])
    got = [g for ax in fig.axes for g in stairs(ax)]
    check(len(got) == 1 and same(got[0].values, raw["robots"][0]["Fx"]),
          f"controls: the object has no curve ({len(got)} curves)")
    bad = copy.deepcopy(obj_doc)
    bad["robots"][1]["force_dims"] = 2
    refused = refusal(obj_path, bad)
    check("'robots[1].force_dims' is 2, expected 0" in refused,
          f"load: an object with force_dims 2 is refused ({refused!r})")

    # Obstacles: a thick wall is a grey capsule, a moving post is drawn where it is at each
    # snapshot's time, the legend names them, and the drawn region holds the wall's ends.
    from matplotlib.patches import Polygon
    obs_doc = copy.deepcopy(raw)
    far = 40.0  # beyond every robot: only the wall can stretch the region this far
    obs_doc["obstacles"] = [
        {"name": "w", "shape": "wall", "radius": 0.1, "from": [far, 0.0], "to": [far, 2.0]},
        {"name": "p", "shape": "disk", "radius": 0.3, "centre": [0.0, -3.0], "velocity": [0.0, 1.0]}]
    obs_path = os.path.join(WORK, "obstacle_solution.json")
    with open(obs_path, "w") as f:
        json.dump(obs_doc, f)
    bsol = load(obs_path, full=True)
    times = snapshots.snapshot_times(bsol)
    fig = snapshots.overlay(bsol, times, 0.01, (1200, 600), "")
    ax = fig.axes[0]
    walls = [p for p in ax.patches if isinstance(p, Polygon) and p.get_facecolor()[:3] == snapshots.OBSTACLE_FACE]
    xs = [v[0] for p in walls for v in p.get_xy()]
    check(len(walls) == 1 and abs(min(xs) - (far - 0.1)) < 1e-9 and abs(max(xs) - (far + 0.1)) < 1e-9,
          f"snapshots: the wall is one capsule {far} +- 0.1 wide ({len(walls)} drawn)")
    posts = sorted(round(p.center[1], 9) for p in ax.patches if isinstance(p, Circle) and abs(p.get_radius() - 0.3) < 1e-12)
    check(posts == sorted(round(-3.0 + t, 9) for t in times),
          f"snapshots: the moving post at each snapshot's time ({posts})")
    check(ax.get_xlim()[1] >= far + 0.1, f"snapshots: the region holds the wall ({ax.get_xlim()})")
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    check("obstacle" in legend, f"snapshots: the legend names obstacles ({legend})")
    # A sentry on waypoints: drawn on its track (its centres at the states, written by disco),
    # straight between states, and the drawn region holds the whole track.
    h, n_t = raw["h"], raw["N_t"]
    track_x = [far + 2.0 + 0.5 * k for k in range(n_t + 1)]
    path_doc = copy.deepcopy(obs_doc)
    path_doc["obstacles"].append(
        {"name": "s", "shape": "disk", "radius": 0.2, "centre": [track_x[0], 2.0],
         "path": [{"t": 0.0, "x": track_x[0], "y": 2.0}, {"t": h * n_t, "x": track_x[-1], "y": 2.0}],
         "x": track_x, "y": [2.0] * (n_t + 1)})
    with open(obs_path, "w") as f:
        json.dump(path_doc, f)
    psol = load(obs_path, full=True)
    fig = snapshots.overlay(psol, times, 0.01, (1200, 600), "")
    ax = fig.axes[0]
    sentries = sorted(round(p.center[0], 9) for p in ax.patches
                      if isinstance(p, Circle) and abs(p.get_radius() - 0.2) < 1e-12)
    check(sentries == sorted(round(far + 2.0 + 0.5 * t / h, 9) for t in times),
          f"snapshots: the sentry on its track at each snapshot's time ({sentries})")
    check(ax.get_xlim()[1] >= track_x[-1] + 0.2, f"snapshots: the region holds the track ({ax.get_xlim()})")
    del path_doc["obstacles"][2]["path"]
    refused = refusal(obs_path, path_doc)
    check("missing key 'obstacles[2].velocity'" in refused,
          f"load: a disk with neither velocity nor path is refused ({refused!r})")

    obs_doc["obstacles"][0]["shape"] = "box"
    refused = refusal(obs_path, obs_doc)
    check("'obstacles[0].shape' is \"box\"" in refused, f"load: an unknown shape is refused ({refused!r})")

    fig = time_series.plot_speeds(sol, None, [])
    lines = [l for l in fig.axes[0].lines if len(l.get_xdata()) == n + 1]
    check(len(lines) == len(raw["robots"]) and all(
        same(l.get_ydata(), [math.hypot(a, b) for a, b in zip(r["vx"], r["vy"])])
        for l, r in zip(lines, raw["robots"])), "speeds: |v| of every robot at the states")

    fig = time_series.plot_floor_friction(sol, None, [])
    got = stairs(fig.axes[0])
    check(all(same(g.values, [math.hypot(a, b) for a, b in zip(r["friction_x"], r["friction_y"])])
              for g, r in zip(got, raw["robots"])) and len(got) == len(raw["robots"]),
          "floor friction: |friction| of every robot per step")
    mug = sorted(round(r["mu"] * r["mass"] * raw["g"], 12) for r in raw["robots"])
    check(hlines(fig.axes[0]) == sorted(set(mug)), f"floor friction: dashed at mu M g {mug}")

    fig = time_series.plot_contact_forces(sol, None, [], 1e-3)
    pushing = [p for p in raw["pairs"] if max(p["normal_force"]) > 1e-3]
    n_got, t_got = stairs(fig.axes[0]), stairs(fig.axes[1])
    check(pushing and len(n_got) == len(pushing) and
          all(same(g.values, p["normal_force"]) for g, p in zip(n_got, pushing)) and
          all(same(g.values, p["tangential_force"]) for g, p in zip(t_got, pushing)),
          f"contact forces: normal and tangential of the {len(pushing)} pushing pair(s)")

    fig = time_series.plot_gaps(sol, None, [])
    lines = [l for l in fig.axes[0].lines if len(l.get_xdata()) == n + 1]
    check(len(lines) == len(raw["pairs"]) and all(
        same(l.get_ydata(), p["gap"]) for l, p in zip(lines, raw["pairs"])),
        "gaps: rho of the pair at the states")

    # The search plots, for the swap (several starts, several new bests).
    name = "two_robots_swap_avoid"
    scene = dict(best["scenes"][name], name=name)
    mine = [r for r in runs if r["scene"] == name]
    fig = search_plots.plot_progress(mine, scene, None)
    ax = fig.axes[0]
    steps = [l for l in ax.lines if l.get_drawstyle() == "steps-post"]
    for r in sorted(mine, key=lambda r: r["start"]):
        handed = r["finished_s"] - r["seconds"] - scene["started_s"]
        xs = [handed + t for t, _ in r["history"]] + [handed + r["seconds"]]
        ys = [tf for _, tf in r["history"]] + [r["history"][-1][1]]
        check(any(same(l.get_xdata(), xs) and same(l.get_ydata(), ys) for l in steps),
              f"progress: start {r['start']}'s new bests at search time since the hand-out")
    env = [l for l in steps if l.get_color() == "black"]
    check(len(env) == 1 and np.isclose(min(env[0].get_ydata()), scene["T_f"], rtol=0, atol=1e-12),
          "progress: the best-so-far line ends at the scene's best T_f")
    fig = search_plots.plot_spread(mine, scene, None)
    pts = sorted(float(l.get_ydata()[0]) for l in fig.axes[0].lines
                 if len(l.get_ydata()) == 1 and l.get_linestyle() == "None")
    check(same(pts, sorted(r["T_f"] for r in mine if r["status"] in ("solved", "dominated"))),
          "spread: one point per solved start at its final T_f")
    stars = [l for l in fig.axes[0].lines if l.get_marker() == "*"]
    check(len(stars) == 1 and stars[0].get_ydata()[0] == scene["T_f"], "spread: the best is the star")

    # The screening plot, on made-up lines of a screened search under a limit: screens ranked by
    # T_f (hollow), refines joined to their screen, and the starts without a certified screen
    # that the time left ran from their own guess (2: its screen found nothing; 3: never
    # screened) after them, by start, as squares; the best (start 3) a star.
    def made_up(start, stage, T_f, status="solved"):
        return {"scene": "s", "start": start, "stage": stage, "status": status, "T_f": T_f,
                "value": T_f, "guess": "straight", "seed": 1}
    made = [made_up(0, "screen", 3.0), made_up(1, "screen", 2.0), made_up(2, "screen", None, "infeasible"),
            made_up(1, "refine", 2.5), made_up(0, "refine", 2.8), made_up(3, "refine", 2.3),
            made_up(2, "refine", 2.4)]
    fig = search_plots.plot_screening(made, {"name": "s", "start": 3, "T_f": 2.3, "value": 2.3}, None)
    ax = fig.axes[0]
    points = sorted((float(l.get_xdata()[0]), float(l.get_ydata()[0]), l.get_marker(), l.get_markerfacecolor() == "none")
                    for l in ax.lines if len(l.get_xdata()) == 1 and l.get_linestyle() == "None")
    check(points == [(0.0, 2.0, "o", True), (0.0, 2.5, "o", False), (1.0, 2.8, "o", False), (1.0, 3.0, "o", True),
                     (2.0, 2.4, "s", False), (3.0, 2.3, "*", False)],
          f"screening: screens by T_f, refines over them, starts without a certified screen after them ({points})")
    check([t.get_text() for t in ax.get_xticklabels()] == ["1", "0", "2", "3"], "screening: the ticks name the starts")


if MODE == "build":
    build()
elif MODE == "plots":
    plots()
elif MODE == "screenshot":
    screenshot()
else:
    sys.exit(f"unknown mode {MODE}")
finish(f"report_tests {MODE}")
