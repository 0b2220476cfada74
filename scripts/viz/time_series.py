"""Plots over time of one solution (scripts/report): controls, speeds, floor friction, contact
forces and pair gaps. Input: a solution read by viz.solution_file.load(path, full=True)
with a trajectory.

States (x, v, omega, gap) live at t_k = k h, k = 0..N_t, and are drawn as lines; a step's
quantities (the control F, floor friction, contact impulses / h) hold over [t_k, t_k+1) and are
drawn as stairs. Robots keep the colours of the snapshots (tab10); pairs get their own (Dark2).
Dotted vertical lines mark the snapshot times, numbered as in the snapshot figure.
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from viz.snapshots import DPI, robot_colors, save_figure  # noqa: E402
from viz.solution_file import driven  # noqa: E402

WIDTH = 1140          # pixels: the report page's text width (viz/report_page.py, main)
ROW_HEIGHT = 230      # pixels per subplot row
MAX_PAIR_LINES = 12   # pairs drawn by name; the rest are summarised in the title


def _grid(sol):
    """t_k = k h, k = 0..N_t."""
    h = sol["T_f"] / sol["N_t"]
    return [k * h for k in range(sol["N_t"] + 1)]


def _robots(sol):
    """(robot, colour) pairs, in the snapshots' colours."""
    return zip(sol["robots"], robot_colors(len(sol["robots"])))


def _same(a, b):
    """Whether two series would be drawn on top of each other: within 0.3 % of their largest
    magnitude everywhere, under a pixel of a panel ROW_HEIGHT tall."""
    scale = max([abs(v) for v in a] + [abs(v) for v in b] + [1e-300])
    return len(a) == len(b) and all(abs(u - v) <= 3e-3 * scale for u, v in zip(a, b))


def _styles(names, series):
    """Per series: (line width, line style, label suffix). A series that looks the same as an
    earlier one (_same) is drawn thinner and dashed on top of it, with "(= that one)" in its
    label, so that both stay visible instead of one hiding the other."""
    out = []
    for k, s in enumerate(series):
        twin = next((names[q] for q in range(k) if _same(series[q], s)), None)
        out.append((1.3, "-", "") if twin is None else (1.0, (0, (4, 3)), f" (= {twin})"))
    return out


def _note(ax, text):
    """A grey note in the middle of an axes with nothing (or nothing visible) to draw."""
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", color="0.4")


def _bound_lines(ax, values, both_signs=False):
    """A dashed line at each distinct positive value (within 1e-12 relative; and at its
    negative too with both_signs), drawn once and over the data, which lies on a bound
    wherever it is reached."""
    drawn = []
    for v in values:
        if v > 0 and all(abs(v - d) > 1e-12 * v for d in drawn):
            drawn.append(v)
            for y in ((-v, v) if both_signs else (v,)):
                ax.axhline(y, color="0.25", lw=0.8, ls="--", zorder=3)


def _figure(rows, title):
    fig, axes = plt.subplots(rows, 1, sharex=True, squeeze=False,
                             figsize=(WIDTH / DPI, (ROW_HEIGHT * rows + 70) / DPI), dpi=DPI,
                             layout="constrained")
    fig.suptitle(title, fontsize=12)
    return fig, [a[0] for a in axes]


def _finish(fig, axes, sol, times, out):
    """Grid, snapshot-time lines, the legend of the first axes; saves to `out` and closes
    (out None: returns the figure)."""
    _legend(axes[0])
    for ax in axes:
        ax.grid(True, lw=0.4, color="0.88")
        ax.set_axisbelow(True)
        ax.tick_params(labelsize=10)
        ax.yaxis.label.set_size(11)  # set_ylabel came first
        ax.set_xlim(0.0, sol["T_f"])
        for k, t in enumerate(times):
            ax.axvline(t, color="0.6", lw=0.7, ls=":", zorder=0.5)
    top = axes[0]
    for k, t in enumerate(times):
        top.annotate(str(k + 1), (t, 1.0), xycoords=("data", "axes fraction"),
                     xytext=(0, 2), textcoords="offset points", ha="center", va="bottom",
                     fontsize=7, color="0.4")
    axes[-1].set_xlabel("t [s]", fontsize=11)
    return save_figure(fig, out)


def _legend(ax, ncol=1):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=10, loc="upper left", bbox_to_anchor=(1.005, 1.0), frameon=False,
                  ncol=ncol, borderaxespad=0.0)


def plot_controls(sol, out, times):
    """F_x, F_y [N] per robot; dashed: each component's bound (Appendix A bounds each by F_max;
    a D_ef = 1 robot pushes f along its unit axis a with |f| <= F_max: |F_x| <= |a_x| F_max).
    A component no robot can push in (every bound 0: robots pushing along x, or along y) gets
    no panel; the title says so. Objects (no force of their own) are left out."""
    sol = dict(sol, robots=driven(sol))
    t = _grid(sol)
    comps = [(c, key) for c, key in ((0, "Fx"), (1, "Fy"))
             if any(rob["force_bound"][c] > 0 or any(rob[key]) for rob in sol["robots"])]
    comps = comps or [(0, "Fx")]
    absent = {0: "F_x", 1: "F_y"}[1 - comps[0][0]] if len(comps) == 1 else None
    fig, axes = _figure(len(comps), f"{sol['scenario']}: controls (dashed: the bounds)"
                        + (f"; {absent} ≡ 0, no robot can push that way" if absent else ""))
    names = [rob["name"] for rob in sol["robots"]]
    for ax, (c, key) in zip(axes, comps):
        styles = _styles(names, [rob[key] for rob in sol["robots"]])
        for (rob, col), (lw, ls, twin) in zip(_robots(sol), styles):
            ax.stairs(rob[key], t, color=col, lw=lw, ls=ls, label=rob["name"] + twin,
                      baseline=None, zorder=2)
        _bound_lines(ax, [rob["force_bound"][c] for rob in sol["robots"]], both_signs=True)
        ax.set_ylabel(f"F_{'xy'[c]} [N]")
    return _finish(fig, axes, sol, times, out)


def plot_speeds(sol, out, times):
    """|v| [m/s] and omega [rad/s] per robot."""
    t = _grid(sol)
    fig, axes = _figure(2, f"{sol['scenario']}: speeds")
    names = [rob["name"] for rob in sol["robots"]]
    speeds = [[math.hypot(a, b) for a, b in zip(rob["vx"], rob["vy"])] for rob in sol["robots"]]
    for (rob, c), v, (lw, ls, twin) in zip(_robots(sol), speeds, _styles(names, speeds)):
        axes[0].plot(t, v, color=c, lw=lw, ls=ls, label=rob["name"] + twin)
    omegas = [rob["omega"] for rob in sol["robots"]]
    for (rob, c), w, (lw, ls, _) in zip(_robots(sol), omegas, _styles(names, omegas)):
        axes[1].plot(t, w, color=c, lw=lw, ls=ls)
    axes[0].set_ylabel("|v| [m/s]")
    axes[1].set_ylabel("ω [rad/s]")
    if max(abs(w) for rob in sol["robots"] for w in rob["omega"]) < 1e-9:
        axes[1].set_ylim(-1.0, 1.0)  # roundoff only: do not blow it up to full height
        _note(axes[1], "no robot turns (|ω| < 1e-9 rad/s)")
    return _finish(fig, axes, sol, times, out)


def plot_floor_friction(sol, out, times):
    """|floor friction| [N] per robot; dashed, drawn over the data (a sliding robot's friction
    lies on it): its largest value mu M g, one line per value."""
    t = _grid(sol)
    fig, axes = _figure(1, f"{sol['scenario']}: floor friction (dashed: μ M g)")
    names = [rob["name"] for rob in sol["robots"]]
    mags = [[math.hypot(a, b) for a, b in zip(rob["friction_x"], rob["friction_y"])]
            for rob in sol["robots"]]
    for (rob, c), mag, (lw, ls, twin) in zip(_robots(sol), mags, _styles(names, mags)):
        axes[0].stairs(mag, t, color=c, lw=lw, ls=ls, label=rob["name"] + twin, baseline=None,
                       zorder=2)
    _bound_lines(axes[0], [rob["mu"] * rob["mass"] * sol["g"] for rob in sol["robots"]])
    axes[0].set_ylabel("|friction| [N]")
    return _finish(fig, axes, sol, times, out)


def _pair_label(sol, p):
    return f"{sol['robots'][p['i']]['name']}–{sol['robots'][p['j']]['name']}"


def _pair_colors(n):
    """n distinct colours: Dark2 for up to 8 pairs, else tab20 (MAX_PAIR_LINES <= 20)."""
    cmap = plt.get_cmap("Dark2" if n <= 8 else "tab20")
    return [cmap(k % cmap.N) for k in range(n)]


def contact_pairs(sol, thr):
    """The pairs whose normal force exceeds thr [N] at some step."""
    return [p for p in sol["pairs"] if max(p["normal_force"], default=0.0) > thr]


def plot_contact_forces(sol, out, times, thr):
    """Normal and tangential contact force [N] of every pair that pushes (normal > thr)."""
    t = _grid(sol)
    pushing = contact_pairs(sol, thr)
    fig, axes = _figure(2, f"{sol['scenario']}: contact forces "
                           f"({len(pushing)} of {len(sol['pairs'])} pairs push)")
    for p, c in zip(pushing[:MAX_PAIR_LINES], _pair_colors(len(pushing))):
        axes[0].stairs(p["normal_force"], t, color=c, lw=1.3, label=_pair_label(sol, p),
                       baseline=None)
        axes[1].stairs(p["tangential_force"], t, color=c, lw=1.3, baseline=None)
    if not pushing:
        _note(axes[0], "no contact force in this solution")
    axes[0].set_ylabel("normal [N]")
    axes[1].set_ylabel("tangential [N]")
    return _finish(fig, axes, sol, times, out)


def plot_gaps(sol, out, times):
    """The gap rho [m] of the pairs that come close (at most twice the mean diameter);
    dashed: each mode's safe distance (avoid pairs) and 0 (contact)."""
    t = _grid(sol)
    near = 4.0 * sum(r["radius"] for r in sol["robots"]) / len(sol["robots"])
    close = sorted((p for p in sol["pairs"] if min(p["gap"]) <= near),
                   key=lambda p: min(p["gap"]))
    shown = close[:MAX_PAIR_LINES]
    which = (f" (the {len(shown)} closest of {len(sol['pairs'])} pairs)"
             if len(shown) < len(sol["pairs"]) else "")
    fig, axes = _figure(1, f"{sol['scenario']}: pair gaps ρ{which} "
                           "(dashed: safe distance)")
    ax = axes[0]
    for p, c in zip(shown, _pair_colors(len(shown))):
        ax.plot(t, p["gap"], color=c, lw=1.3, label=f"{_pair_label(sol, p)} ({p['mode']})")
    for d in sorted({p["safe_distance"] if p["mode"] == "avoid" else 0.0 for p in shown}):
        ax.axhline(d, color="0.3", lw=0.8, ls="--")
    if shown:
        top = max(max(p["gap"]) for p in shown)
        ax.set_ylim(-0.02 * near, min(top, 2.0 * near) * 1.05)
    else:
        _note(ax, "no pair comes within two diameters")
    ax.set_ylabel("ρ [m]")
    return _finish(fig, axes, sol, times, out)
