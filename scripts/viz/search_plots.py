"""Plots of a multi-start search for one scene (scripts/report), from its runs.jsonl lines and
its best.json entry:

- progress: T_f against search time for every start (for another objective, best.json
  "objective", its value J instead, here and below). A start runs from its hand-out
  (finished_s - seconds) to its end; its line steps down at every new best of its `history`
  ([seconds within the start, T_f]). The black stairs are the scene's best so far over all
  starts. Times count from the scene's first hand-out (best.json `started_s`), as best.json's
  time_to_first_feasible_s and time_to_best_s do. A start without a solution is a grey cross
  at its end, on the bottom edge. Starts of an earlier run of a resumed search (another clock)
  and lines without times are left out, and the title says how many.
- spread: the final T_f of every solved start, one column per initial-guess kind, with the
  count solved / run under each column.

Colours follow the guess kind in both plots (GUESS_ORDER); the best start is a star.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.transforms import blended_transform_factory  # noqa: E402

from viz.snapshots import DPI, save_figure  # noqa: E402

GUESS_ORDER = ["straight", "perturbed", "detour", "yield", "perturbed feasible"]
SIZE = (900, 430)


def guess_kinds(runs):
    """The guess kinds of `runs`, in GUESS_ORDER, unknown kinds last (alphabetically)."""
    kinds = {r.get("guess") or "unknown" for r in runs}
    return [k for k in GUESS_ORDER if k in kinds] + sorted(kinds - set(GUESS_ORDER))


def guess_colors(kinds):
    cmap = plt.get_cmap("tab10")
    return {k: cmap((GUESS_ORDER.index(k) if k in GUESS_ORDER else 5 + i) % 10)
            for i, k in enumerate(kinds)}


def _reference_line(ax, scene):
    if not is_time(scene):  # the bounds are on T_f, not on another objective
        return
    if scene.get("lower_bound") is not None:
        ax.axhline(scene["lower_bound"], color="0.25", lw=0.9, ls="--",
                   label=f"lower bound {scene['lower_bound']:.4f} s")
    elif scene.get("reference_time") is not None:
        ax.axhline(scene["reference_time"], color="0.25", lw=0.9, ls=":",
                   label=f"reference {scene['reference_time']:.4f} s")


# A start that ran to its own end with a certified point: solved, or dominated (stopped when
# it could not get below the best another start had found; search/reduction_phases.h).
FINAL_POINT = ("solved", "dominated")


def value_of(d):
    """The objective J of a runs.jsonl line or a best.json scene (core/model/objective.h):
    "value", which is T_f for objective time (lines of an older disco have T_f only)."""
    v = d.get("value")
    return d.get("T_f") if v is None and "value" not in d else v


def objective_label(best):
    """The axis and column label of J for a best.json scene: "T_f [s]" for objective time."""
    kind = best.get("objective", "time")
    unit = best.get("objective_unit", "s")
    return {"time": "T_f", "energy": "E", "time + energy": "T_f + w E"}.get(kind, kind) + f" [{unit}]"


def is_time(best):
    return best.get("objective", "time") == "time"


def has_final_point(run):
    return run["status"] in FINAL_POINT and value_of(run) is not None


def start_curve(run, scene_start):
    """[(search time since the scene's first hand-out, J)] of a solved start's new bests,
    and its end time. Lines written before `history` existed give their best only."""
    handed = run["finished_s"] - run["seconds"] - scene_start
    hist = run.get("history") or [[run.get("time_to_best", run["seconds"]), value_of(run)]]
    return [(handed + t, tf) for t, tf in hist], handed + run["seconds"]


def plot_progress(runs, scene, out):
    fig, ax = plt.subplots(figsize=(SIZE[0] / DPI, SIZE[1] / DPI), dpi=DPI, layout="constrained")
    scene_start = scene.get("started_s") or 0.0
    kinds = guess_kinds(runs)
    colors = guess_colors(kinds)
    events, failed = [], []
    timed = [r for r in runs if isinstance(r.get("finished_s"), (int, float))
             and isinstance(r.get("seconds"), (int, float)) and not r.get("_resumed")]
    for r in sorted(timed, key=lambda r: r["start"]):
        if not has_final_point(r):
            failed.append(r["finished_s"] - scene_start)
            continue
        pts, end = start_curve(r, scene_start)
        best = r["start"] == scene.get("start")
        xs = [p[0] for p in pts] + [end]
        ys = [p[1] for p in pts] + [pts[-1][1]]
        ax.step(xs, ys, where="post", color=colors[r.get("guess") or "unknown"],
                lw=2.2 if best else 1.0, alpha=1.0 if best else 0.75, zorder=3 if best else 2)
        ax.plot(xs[:-1], ys[:-1], ls="none", marker="o", ms=2.5,
                color=colors[r.get("guess") or "unknown"], zorder=3)
        events += pts
        if best:
            ax.plot([pts[-1][0]], [pts[-1][1]], marker="*", ms=14, mfc="gold", mec="black",
                    zorder=5)
    if events:
        events.sort()
        xs, ys, low = [], [], float("inf")
        for t, tf in events:
            if tf < low:
                low = tf
                xs.append(t)
                ys.append(tf)
        end = max(r["finished_s"] - scene_start for r in timed)
        ax.step(xs + [end], ys + [ys[-1]], where="post", color="black", lw=1.6, ls="-",
                alpha=0.55, zorder=4)
    if failed:
        tr = blended_transform_factory(ax.transData, ax.transAxes)
        ax.plot(failed, [0.02] * len(failed), ls="none", marker="x", ms=7, color="0.45",
                transform=tr, zorder=5)
    _reference_line(ax, scene)
    handles = [Line2D([], [], color=colors[k], lw=1.5, label=k) for k in kinds]
    handles.append(Line2D([], [], color="black", alpha=0.55, lw=1.6, label="best so far"))
    handles.append(Line2D([], [], ls="none", marker="*", ms=12, mfc="gold", mec="black",
                          label="best start"))
    if failed:
        handles.append(Line2D([], [], ls="none", marker="x", ms=7, color="0.45",
                              label="no solution"))
    handles += [h for h in ax.get_legend_handles_labels()[0] if h.get_label().startswith(
        ("lower", "reference"))]
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0),
              frameon=False, borderaxespad=0.0)
    ax.set_xlabel("search time since the scene's first hand-out [s]")
    ax.set_ylabel(objective_label(scene))
    left_out = len(runs) - len(timed)
    ax.set_title(f"{scene['name']}: {objective_label(scene).split(' [')[0]} of every start against time"
                 + (f" ({left_out} start(s) of an earlier run or without times left out)"
                    if left_out else ""), fontsize=11 if not left_out else 9)
    ax.set_xlim(left=0.0)
    ax.grid(True, lw=0.4, color="0.88")
    ax.tick_params(labelsize=8)
    return save_figure(fig, out)


def plot_spread(runs, scene, out):
    fig, ax = plt.subplots(figsize=(SIZE[0] / DPI, SIZE[1] / DPI), dpi=DPI, layout="constrained")
    kinds = guess_kinds(runs)
    colors = guess_colors(kinds)
    for x, k in enumerate(kinds):
        mine = sorted((r for r in runs if (r.get("guess") or "unknown") == k),
                      key=lambda r: r["start"])
        solved = [r for r in mine if has_final_point(r)]
        n = len(solved)
        for m, r in enumerate(solved):
            dx = 0.0 if n == 1 else 0.3 * (2.0 * m / (n - 1) - 1.0)  # spread evenly, no overlap
            best = r["start"] == scene.get("start")
            ax.plot([x + dx], [value_of(r)], ls="none", marker="*" if best else "o",
                    ms=14 if best else 6, mfc="gold" if best else colors[k],
                    mec="black" if best else colors[k], alpha=1.0 if best else 0.8,
                    zorder=4 if best else 3)
        ax.annotate(f"{n} / {len(mine)} solved", (x, 0.0), xycoords=("data", "axes fraction"),
                    xytext=(0, 4), textcoords="offset points", ha="center", va="bottom",
                    fontsize=8, color="0.35")
    _reference_line(ax, scene)
    ax.set_xticks(range(len(kinds)), kinds, fontsize=9)
    ax.set_xlim(-0.6, len(kinds) - 0.4)
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo - 0.08 * (hi - lo), hi)  # room for the counts
    ax.set_xlabel("initial guess")
    ax.set_ylabel("final " + objective_label(scene))
    ax.set_title(f"{scene['name']}: final {objective_label(scene).split(' [')[0]} of every start, by initial guess "
                 "(star: the best)", fontsize=11)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
                  borderaxespad=0.0)
    ax.grid(True, axis="y", lw=0.4, color="0.88")
    ax.tick_params(labelsize=8)
    return save_figure(fig, out)


def screen_runs(runs):
    """(screens, the rest): a screened search's screen lines (stage "screen", search/README.md,
    "Screening") and its full starts and refines, the only ones with a scene's result."""
    screens = [r for r in runs if r.get("stage") == "screen"]
    return screens, [r for r in runs if r.get("stage") != "screen"]


def plot_screening(runs, scene, out):
    """Screened against refined: every screened start, ranked by its screened J (hollow: at
    the screen's steps), and for the refined ones the J they reached at full N_t (filled,
    joined to their screen); then the starts run at full N_t without a certified screen (the
    time left of a limit: squares, by start); the best start is a star."""
    fig, ax = plt.subplots(figsize=(SIZE[0] / DPI, SIZE[1] / DPI), dpi=DPI, layout="constrained")
    screens, rest = screen_runs(runs)
    refined = {r["start"]: r for r in rest if r.get("stage") == "refine"}
    order = sorted((r for r in screens if has_final_point(r) or r["status"] == "time_limit"
                    and value_of(r) is not None), key=lambda r: (value_of(r), r["start"]))
    kinds = guess_kinds(screens)
    colors = guess_colors(kinds)
    for x, r in enumerate(order):
        c = colors[r.get("guess") or "unknown"]
        ax.plot([x], [value_of(r)], ls="none", marker="o", ms=7, mfc="none", mec=c, zorder=3)
        f = refined.get(r["start"])
        if f is not None and value_of(f) is not None:
            best = r["start"] == scene.get("start")
            ax.plot([x, x], [value_of(r), value_of(f)], color=c, lw=1.0, zorder=2)
            ax.plot([x], [value_of(f)], ls="none", marker="*" if best else "o",
                    ms=14 if best else 7, mfc="gold" if best else c, mec="black" if best else c,
                    zorder=4)
    # Starts without a certified screen that the time left of a limit ran from their own guess
    # (search/README.md, "Screening", step 5): after the ranked screens, by start.
    shown = {r["start"] for r in order}
    unscreened = sorted((f for k, f in refined.items() if k not in shown and value_of(f) is not None),
                        key=lambda f: f["start"])
    for x, f in enumerate(unscreened, start=len(order)):
        best = f["start"] == scene.get("start")
        ax.plot([x], [value_of(f)], ls="none", marker="*" if best else "s", ms=14 if best else 6,
                mfc="gold" if best else "0.3", mec="black" if best else "0.3", zorder=4)
    ax.set_xticks(range(len(order) + len(unscreened)), [str(r["start"]) for r in order + unscreened], fontsize=8)
    _reference_line(ax, scene)
    handles = [Line2D([], [], ls="none", marker="o", mfc="none", mec="0.3", label="screened"),
               Line2D([], [], ls="none", marker="o", color="0.3", label="refined (full N_t)"),
               Line2D([], [], ls="none", marker="*", ms=12, mfc="gold", mec="black", label="best start")]
    if unscreened:
        handles.append(Line2D([], [], ls="none", marker="s", ms=6, color="0.3",
                              label="no certified screen: run from its own guess"))
    handles += [Line2D([], [], color=colors[k], lw=1.5, label=k) for k in kinds]
    handles += [h for h in ax.get_legend_handles_labels()[0] if h.get_label().startswith(
        ("lower", "reference"))]
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0),
              frameon=False, borderaxespad=0.0)
    unsolved = len(screens) - len(order)
    ax.set_xlabel("start, by screened " + objective_label(scene).split(" [")[0]
                  + (f" ({unsolved} screen(s) without a point left out)" if unsolved else ""))
    ax.set_ylabel(objective_label(scene))
    ax.set_title(f"{scene['name']}: screened against refined", fontsize=11)
    ax.grid(True, axis="y", lw=0.4, color="0.88")
    ax.tick_params(labelsize=8)
    return save_figure(fig, out)
