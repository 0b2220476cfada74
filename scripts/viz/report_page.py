"""The HTML of a search report (scripts/report): one self-contained page, no script, no network.
Images and raw data are referenced by relative paths inside the report folder.

page(report) takes the plain data gathered by scripts/report:
  report = {title, source, generated, search: best.json's top level or None,
            ranks, scenes: [scene, ...], data: [(label, path), ...]}
  scene  = {name, best: best.json entry (T_f, lower_bound, ...), runs: [runs.jsonl lines],
            sol: solution (viz.solution_file.load full) or None, figures: [(title, path,
            caption)], search_figures: [...], solution_link, problems: [text], info: {...}}
"""
import html

from viz.search_plots import has_final_point, is_time, objective_label, value_of

CSS = """
:root { --fg: #1d232a; --muted: #5b6570; --line: #d9dee3; --head: #f3f5f7; --best: #fff4c2;
        --bad: #a4281e; --ok: #1f6f3a; }
* { box-sizing: border-box; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", sans-serif;
       color: var(--fg); margin: 0; background: #fff; }
main { max-width: 1200px; margin: 0 auto; padding: 24px 28px 64px; }
h1 { font-size: 26px; margin: 0 0 4px; }
h2 { font-size: 21px; margin: 40px 0 8px; padding-top: 12px; border-top: 2px solid var(--line); }
h3 { font-size: 16px; margin: 24px 0 8px; color: #2c3a47; }
p.meta, .muted { color: var(--muted); }
p.meta { margin: 0 0 16px; }
a { color: #1659a8; text-decoration: none; }
a:hover { text-decoration: underline; }
nav.toc { margin: 8px 0 0; font-size: 14px; }
nav.toc a { margin-right: 14px; white-space: nowrap; }
table { border-collapse: collapse; font-size: 13.5px; margin: 8px 0 4px; }
th, td { padding: 5px 9px; border-bottom: 1px solid var(--line); text-align: left;
         vertical-align: top; }
th { background: var(--head); font-weight: 600; vertical-align: bottom; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
td.num { white-space: nowrap; }
tr.best td { background: var(--best); }
.status-solved { color: var(--ok); font-weight: 600; }
.status-other { color: var(--bad); font-weight: 600; }
.scroll { overflow-x: auto; }
.facts { display: grid; grid-template-columns: max-content 1fr; gap: 3px 16px; margin: 8px 0 12px;
         font-size: 14px; }
.facts dt { color: var(--muted); }
.facts dd { margin: 0; }
.row { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
figure { margin: 8px 0 16px; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--line); border-radius: 3px;
             display: block; }
figcaption { font-size: 13px; color: var(--muted); margin-top: 4px; max-width: 900px; }
.row figure { flex: 1 1 480px; min-width: 0; }
.row figure.wide { flex-basis: 100%; }
.problem { background: #fdecea; border-left: 4px solid var(--bad); padding: 8px 12px;
           margin: 8px 0; }
footer { margin-top: 48px; font-size: 13px; color: var(--muted); }
"""


def esc(x):
    return html.escape(str(x), quote=True)


def fmt(v, spec, none="–"):
    return none if v is None else format(v, spec)


def anchor(name):
    return "scene-" + "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def gap_text(best):
    """(gap text, against what) of a scene: vs its lower bound, else vs its reference time
    (both on T_f: none for another objective)."""
    T = best.get("T_f")
    if T is None or not is_time(best):
        return "–", ""
    for key, what in (("lower_bound", ""), ("reference_time", " vs ref")):
        ref = best.get(key)
        if ref:
            return f"{100.0 * (T - ref) / ref:.2f} %{what}", key
    return "–", ""


def certificate_text(c):
    if not c or c.get("max_violation") is None:
        return "–"
    return f"{c['max_violation']:.1e} / {c['max_complementarity']:.1e}"


def status_cell(status):
    cls = {"solved": "status-solved", "dominated": "muted", "not run": "muted"}.get(status, "status-other")
    return f'<span class="{cls}">{esc(status)}</span>'


def starts_text(b):
    """"run / solved", with the planned count when fewer ran, and the scene's time limit."""
    text = f"{b.get('starts_run', '–')} / {b.get('starts_solved', '–')}"
    if isinstance(b.get("starts"), int) and b.get("starts_run", 0) < b["starts"]:
        text += f" (of {b['starts']})"
    if b.get("time_limit_reached"):
        text += ", time limit"
    return text


def scene_time(s, key):
    """A best.json scene time; after --resume the earlier run's clock is not this one's."""
    if s["info"].get("resumed"):
        return "– (resumed)"
    return fmt(s["best"].get(key), ".1f")


def plural(n, word):
    return f"{n} {word}{'' if n == 1 else 's'}"


def disks_cell(info):
    """Robots (and objects, when the scene has any) for the summary's 'robots / pairs'."""
    objects = info.get("objects") or 0
    return f"{info.get('robots', '–')}" + (f" + {objects} obj." if objects else "")


def objective_cell(b):
    """Below T_f in the summary: the objective's value when it is not time."""
    if is_time(b) or value_of(b) is None:
        return ""
    return (f"<br><span class=muted>{esc(b['objective'])}: "
            f"{value_of(b):.6g} {esc(b.get('objective_unit', ''))}</span>")


def summary_table(scenes):
    head = ("<tr><th>scene</th><th class=num>robots / pairs</th><th class=num>N_t</th>"
            "<th class=num>T_f [s]</th><th class=num>lower bound [s]</th><th class=num>gap</th>"
            "<th class=num>first feasible [s]</th><th class=num>best found [s]</th>"
            "<th class=num>starts run / solved</th><th class=num>certificate viol. / compl.</th>"
            "<th>found by</th></tr>")
    rows = []
    uses_ref = False
    for s in scenes:
        b = s["best"]
        gap, against = gap_text(b)
        uses_ref |= against == "reference_time"
        found = (f"start {b['start']}: {esc(s['info'].get('best_guess', ''))}"
                 if b.get("start") is not None
                 else esc(b["solved_by"]) if b.get("solved_by")  # a disco solve output
                 else status_cell(s["info"].get("status", "no certified solution")))
        info = s["info"]
        rows.append(
            f'<tr><td><a href="#{anchor(s["name"])}">{esc(s["name"])}</a></td>'
            f"<td class=num>{disks_cell(info)} / {info.get('pairs', '–')}</td>"
            f"<td class=num>{info.get('N_t', '–')}</td>"
            f"<td class=num><b>{fmt(b.get('T_f'), '.6f')}</b>{objective_cell(b)}</td>"
            f"<td class=num>{fmt(b.get('lower_bound'), '.6f', 'none')}</td>"
            f"<td class=num>{esc(gap)}</td>"
            f"<td class=num>{scene_time(s, 'time_to_first_feasible_s')}</td>"
            f"<td class=num>{scene_time(s, 'time_to_best_s')}</td>"
            f"<td class=num>{starts_text(b)}</td>"
            f"<td class=num>{certificate_text(b.get('certificate'))}</td>"
            f"<td>{found}</td></tr>")
    notes = ["Times count from the hand-out of the scene's first start to the moment a rank "
             "found the point (best.json). Certificate: the largest constraint violation and "
             "the largest |min(G, H)| over complementarity pairs, in the model's units; "
             "<i>solved</i> means both are at most 1e-6."]
    if any(s["info"].get("resumed") for s in scenes):
        notes.append("“resumed”: the search was resumed (--resume), and times of starts from "
                     "an earlier run are on that run's clock, so the scene's times are not "
                     "shown; the T_f-against-time plot shows the last run's starts.")
    if uses_ref:
        notes.append("“vs ref”: no lower bound holds (robots can be pushed); the gap is "
                     "measured against the slowest robot's straight move alone "
                     "(reference_time), which is not a bound.")
    return (f'<div class="scroll"><table>{head}{"".join(rows)}</table></div>'
            + "".join(f'<p class="muted" style="font-size:13px;margin:4px 0">{n}</p>'
                      for n in notes))


SCHEDULE_KEYS = (("horizon_factor", "horizon ×{:.2f}"), ("rate", "rate {:.3f}"),
                 ("grow", "grow {:.2f}"), ("shrink", "shrink {:.2f}"),
                 ("min_rate", "min rate {:.4f}"), ("zeta", "ζ {:g}"),
                 ("minimize_weak", "weak {}"))


def schedule_text(r):
    """A start's schedule from runs.jsonl's `schedule` (what it holds of it), else its
    description."""
    sched = r.get("schedule")
    if isinstance(sched, dict) and sched:
        return esc(", ".join(f.format(sched[k]) for k, f in SCHEDULE_KEYS
                             if isinstance(sched.get(k), (int, float, str))))
    return esc(r.get("description", ""))


def guess_of(description):
    """The guess part of a start's description ("start 3: detour left, horizon x1.75, ..."
    -> "detour left"; StartSpec::describe in search/start.cpp)."""
    return description.split(": ", 1)[-1].split(", horizon")[0]


def start_table(s):
    runs = s["runs"]
    if not runs:
        return '<p class="muted">No runs.jsonl lines for this scene.</p>'
    best_T = value_of(s["best"])
    ordered = sorted(runs, key=lambda r: (not has_final_point(r), value_of(r) or 0.0,
                                          r["start"]))
    head = ("<tr><th class=num>start</th><th>guess</th><th>schedule</th><th>status</th>"
            f"<th class=num>{esc(objective_label(s['best']))}</th><th class=num>vs best</th>"
            "<th class=num>first feasible [s]</th><th class=num>best at [s]</th>"
            "<th class=num>run [s]</th><th class=num>solves / iterations</th>"
            "<th class=num>rank</th><th class=num>certificate</th></tr>")
    rows = []
    for r in ordered:
        solved = has_final_point(r)
        stage = r.get("stage", "full")  # a screen's value is a coarser model's: no "vs best"
        best = r["start"] == s["best"].get("start") and stage != "screen"
        vs = ("best" if best else f"{100.0 * (value_of(r) - best_T) / best_T:+.2f} %"
              if solved and best_T and stage != "screen" else "–")
        sched_text = schedule_text(r)
        detail = f"<br><span class=muted>{esc(r['detail'])}</span>" if r.get("detail") else ""
        guess_text = guess_of(r.get("description", ""))
        rows.append(
            f'<tr{" class=best" if best else ""}><td class=num>{r["start"]}'
            f'{"" if stage == "full" else " <span class=muted>" + esc(stage) + "</span>"}</td>'
            f"<td>{esc(guess_text or r.get('guess', ''))}</td><td>{sched_text}</td>"
            f"<td>{status_cell(r['status'])}{detail}</td>"
            f"<td class=num>{fmt(value_of(r), '.6f')}</td><td class=num>{vs}</td>"
            f"<td class=num>{fmt(r.get('time_to_first_feasible') if solved else None, '.2f')}</td>"
            f"<td class=num>{fmt(r.get('time_to_best') if solved else None, '.2f')}</td>"
            f"<td class=num>{r.get('seconds', 0.0):.2f}</td>"
            f"<td class=num>{r.get('nlp_solves', '–')} / {r.get('iterations', '–')}</td>"
            f"<td class=num>{r.get('rank', '–')}</td>"
            f"<td class=num>{certificate_text(r.get('certificate'))}</td></tr>")
    return f'<div class="scroll"><table>{head}{"".join(rows)}</table></div>'


def class_table(s):
    """The homotopy classes the scene's starts ended in (runs.jsonl "class", search/homotopy.h):
    per class, its best T_f, how many starts ended in it and how many guesses were of it;
    best class first. "" when no line has a class (runs of an older disco). Screens (their
    values a coarser model's) are left out."""
    runs = [r for r in s["runs"] if r.get("stage") != "screen"]
    ended, guessed = {}, {}
    for r in runs:
        g = r.get("guess_class")
        if isinstance(g, dict):
            guessed[g.get("key", "")] = guessed.get(g.get("key", ""), 0) + 1
        c = r.get("class")
        if isinstance(c, dict) and has_final_point(r):
            e = ended.setdefault(c.get("key", ""), {"n": 0, "best": None, "start": None})
            e["n"] += 1
            if e["best"] is None or value_of(r) < e["best"]:
                e["best"], e["start"] = value_of(r), r["start"]
    if not ended:
        return ""
    best_T = value_of(s["best"])
    head = ("<tr><th>class (pair: turn of j around i, who passes first, touch)</th>"
            f"<th class=num>best {esc(objective_label(s['best']))}</th><th class=num>vs best</th><th class=num>best start</th>"
            "<th class=num>starts ended in it</th><th class=num>guesses of it</th></tr>")
    rows = []
    for key, e in sorted(ended.items(), key=lambda kv: kv[1]["best"]):
        vs = f"{100.0 * (e['best'] - best_T) / best_T:+.2f} %" if best_T else "–"
        rows.append(f"<tr><td>{esc(key or '(no pair within reach)')}</td>"
                    f"<td class=num>{e['best']:.6f}</td><td class=num>{vs}</td>"
                    f"<td class=num>{e['start']}</td><td class=num>{e['n']}</td>"
                    f"<td class=num>{guessed.get(key, 0)}</td></tr>")
    note = (f'<p class="muted">{len(ended)} classes reached by {sum(e["n"] for e in ended.values())} '
            f"starts; {sum(guessed.values())} guesses, of which "
            f"{sum(n for k, n in guessed.items() if k not in ended)} in classes no start ended "
            f"in (guesses whose paths run through each other decide no class).</p>")
    return f'<div class="scroll"><table>{head}{"".join(rows)}</table></div>{note}'


def figure(title, path, caption, wide=False):
    cls = ' class="wide"' if wide else ""
    return (f'<figure{cls}><img src="{esc(path)}" alt="{esc(title)}" loading="lazy">'
            f"<figcaption><b>{esc(title)}.</b> {caption}</figcaption></figure>")


def scene_section(s):
    b, info = s["best"], s["info"]
    out = [f'<h2 id="{anchor(s["name"])}">{esc(s["name"])}</h2>']
    for p in s["problems"]:
        out.append(f'<div class="problem">{esc(p)}</div>')
    facts = [("status", status_cell(info.get("status", "–"))
              + (f" <span class=muted>({esc(info['status_detail'])})</span>"
                 if info.get("status_detail") else ""))]
    if b.get("T_f") is not None:
        gap, _ = gap_text(b)
        facts.append(("T_f", f"<b>{b['T_f']:.6f} s</b>, gap {esc(gap)}" if is_time(b)
                      else f"{b['T_f']:.6f} s"))
        if not is_time(b) and value_of(b) is not None:
            facts.append(("objective", f"<b>{esc(b['objective'])} = {value_of(b):.6g} "
                                       f"{esc(b.get('objective_unit', ''))}</b>"))
    if info.get("best_description"):
        facts.append(("found by", esc(info["best_description"])
                      + (f", {b['time_to_best_s']:.1f} s into the scene"
                         if b.get("time_to_best_s") is not None and not info.get("resumed")
                         else "")))
    if info.get("solve_timing"):
        facts.append(("solve", esc(info["solve_timing"])))
    if info.get("model"):
        m = info["model"]
        facts.append(("model", f"{m.get('variables')} variables, {m.get('constraints')} "
                               f"constraints, {m.get('complementarity_pairs')} "
                               "complementarity pairs"))
    if info.get("robots") is not None:
        objects = info.get("objects") or 0
        disks = plural(info["robots"], "robot") + (", " + plural(objects, "object") if objects else "")
        obstacles = info.get("obstacles") or 0
        facts.append(("scene", f"{disks}, {plural(info['pairs'], 'pair')} "
                               f"({esc(info.get('pair_modes', ''))})"
                               + (f", {plural(obstacles, 'obstacle')}" if obstacles else "")
                               + f", N_t = {info['N_t']}"))
    links = [f'<a href="{esc(p)}">{esc(label)}</a>' for label, p in s["links"]]
    if links:
        facts.append(("raw data", " · ".join(links)))
    out.append('<dl class="facts">' + "".join(f"<dt>{k}</dt><dd>{v}</dd>" for k, v in facts)
               + "</dl>")
    if s["motion"]:
        out.append("<h3>Motion</h3>")
        out.append('<div class="row">' + "".join(figure(*f) for f in s["motion"]) + "</div>")
    if s["figures"]:
        out.append("<h3>Over time</h3>")
        out.extend(figure(*f) for f in s["figures"])
    if s["runs"] or s["search_figures"]:
        out.append("<h3>The search</h3>")
        out.extend(figure(*f) for f in s["search_figures"])
        classes = class_table(s)
        if classes:
            out.append("<h4>Homotopy classes</h4>")
            out.append(classes)
        out.append(start_table(s))
    return "\n".join(out)


def page(report):
    search = report.get("search")
    meta = [f"Source: <code>{esc(report['source'])}</code>", f"generated {esc(report['generated'])}"]
    if search:
        meta.append(f"seed {search.get('seed')}, {search.get('starts_finished')} of "
                    f"{search.get('starts_total')} starts finished on {report['ranks']} rank(s) "
                    f"in {search.get('elapsed_s', 0.0):.1f} s")
        if search.get("mode"):  # written since the shared incumbent (search/README.md)
            meta.append({"shared": "starts shared the incumbent",
                         "deterministic": "deterministic (each start alone)"}.get(
                             search["mode"], esc(search["mode"])))
        if search.get("time_limit_reached"):
            meta.append("<b>the time limit stopped the search</b>")
    toc = " ".join(f'<a href="#{anchor(s["name"])}">{esc(s["name"])}</a>'
                   for s in report["scenes"])
    data = " · ".join(f'<a href="{esc(p)}">{esc(label)}</a>' for label, p in report["data"])
    body = [f"<h1>{esc(report['title'])}</h1>",
            f'<p class="meta">{" · ".join(meta)}</p>',
            "<h2 id=summary>Summary</h2>", summary_table(report["scenes"]),
            f'<nav class="toc">Scenes: {toc}</nav>',
            f'<p class="muted" style="font-size:14px">Raw data: {data}</p>']
    for s in report["scenes"]:
        try:
            body.append(scene_section(s))
        except Exception as e:  # one scene's odd data must not cost the page
            body.append(f'<h2 id="{anchor(s["name"])}">{esc(s["name"])}</h2>'
                        f'<div class="problem">this section could not be written: '
                        f"{esc(type(e).__name__)}: {esc(e)}</div>")
            report["problems"].append(f"{s['name']}: section: {type(e).__name__}: {e}")
    body.append("<footer>Made by disco's scripts/report from the raw data linked above "
                "(copied to data/). Model: Peng, Anitescu &amp; "
                "Akella, <i>Optimal Control of Multiple Robot Systems with Friction using "
                "MPCC</i>, Appendix A.</footer>")
    return ("<!DOCTYPE html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n"
            '<meta name=viewport content="width=device-width, initial-scale=1">\n'
            f"<title>{esc(report['title'])}</title>\n<style>{CSS}</style>\n</head>\n<body>\n"
            "<main>\n" + "\n".join(body) + "\n</main>\n</body>\n</html>\n")
