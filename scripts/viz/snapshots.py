"""Snapshots of the disks along a trajectory, like Figs. 2-3 of Peng, Anitescu & Akella
(scripts/plot_snapshots, scripts/report): the overlay (one axes, disks at N times, light to dark)
and the panels (one axes per time). The disk, target and colour helpers are shared with the
animation (viz/animation.py).
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import patheffects  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch, Polygon  # noqa: E402

from viz.solution_file import (all_contacts, bounds, contacts_at,  # noqa: E402
                               default_contact_threshold, moves, obstacle_at, obstacle_way,
                               state_at)

DPI = 100


def save_figure(fig, out):
    """Writes `fig` to the file `out` and closes it; with out None, returns the figure open
    (for tests that read what was drawn)."""
    if out is None:
        return fig
    try:
        fig.savefig(out, dpi=DPI)
    finally:
        plt.close(fig)
    return None

# --- drawing ----------------------------------------------------------------------------------

def blend(c, other, w):
    """Colour c moved a fraction w towards other (RGB tuples)."""
    return tuple((1 - w) * a + w * b for a, b in zip(c[:3], other))


WHITE, BLACK = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)


def shade(frac):
    """Lightening for a snapshot at fraction frac of the time: early light, late full colour."""
    return 0.78 * (1 - frac)


# An object (a passive disk, no force of its own) is hatched, so that it reads apart from the
# robots at any size and in grey print.
OBJECT_HATCH = "////"


def draw_disk(ax, x, y, phi, r, color, frac, z, label=None, obj=False):
    face = blend(color, WHITE, shade(frac))
    edge = blend(color, BLACK, 0.15 + 0.35 * frac)
    ax.add_patch(plt.Circle((x, y), r, facecolor=face, edgecolor=edge, lw=1.2, alpha=0.8,
                            zorder=z, hatch=OBJECT_HATCH if obj else None))
    ax.plot([x, x + r * math.cos(phi)], [y, y + r * math.sin(phi)], color=edge, lw=2.0,
            solid_capstyle="round", zorder=z + 0.001)
    if label is not None:
        # Opposite the orientation line, so the two do not collide.
        lx, ly = x - 0.45 * r * math.cos(phi), y - 0.45 * r * math.sin(phi)
        ax.text(lx, ly, label, ha="center", va="center", fontsize=9,
                color="black" if frac < 0.75 else "white", zorder=z + 0.002)


OBSTACLE_FACE, OBSTACLE_EDGE = (0.62, 0.62, 0.62), (0.25, 0.25, 0.25)


def capsule(a, b, r, n=16):
    """The outline of the points within r of the segment a-b (a wall), as a polygon."""
    ang = math.atan2(b[1] - a[1], b[0] - a[0])
    pts = []
    for (cx, cy), start in ((b, ang - math.pi / 2), (a, ang + math.pi / 2)):
        pts += [(cx + r * math.cos(start + math.pi * k / n), cy + r * math.sin(start + math.pi * k / n))
                for k in range(n + 1)]
    return pts


def draw_obstacles(ax, sol, t, frac=1.0, path=False, label=None):
    """The obstacles at time t: solid grey, walls as capsules (a line when they have no
    thickness), disks as circles; a moving disk faded by frac like the robots' snapshots,
    and with path=True its whole way over [0, T_f] dotted."""
    for ob in sol.get("obstacles", []):
        if ob["shape"] == "wall":
            if ob["radius"] > 0:
                ax.add_patch(Polygon(capsule(ob["from"], ob["to"], ob["radius"]), closed=True,
                                     facecolor=OBSTACLE_FACE, edgecolor=OBSTACLE_EDGE, lw=1.0,
                                     zorder=1.5))
            else:
                ax.plot([ob["from"][0], ob["to"][0]], [ob["from"][1], ob["to"][1]],
                        color=OBSTACLE_EDGE, lw=2.5, solid_capstyle="round", zorder=1.5)
            continue
        x, y = obstacle_at(ob, t)
        face = blend(OBSTACLE_FACE, WHITE, shade(frac)) if moves(ob) else OBSTACLE_FACE
        ax.add_patch(plt.Circle((x, y), ob["radius"], facecolor=face, edgecolor=OBSTACLE_EDGE,
                                lw=1.0, zorder=1.6))
        if label and moves(ob):  # the snapshot's number, as on the robots
            ax.text(x, y, label, ha="center", va="center", fontsize=9, zorder=1.7,
                    color="white" if frac > 0.6 else "black")
        if path and moves(ob) and sol["T_f"]:
            way = obstacle_way(ob, sol["T_f"])
            ax.plot([p[0] for p in way], [p[1] for p in way], ls=":", lw=1.2, color=OBSTACLE_EDGE,
                    zorder=1.4)


# A white edge around a target's dashes and cross: they stay visible over a disk of the same
# colour (a robot at rest on its target, or starting inside it).
HALO = [patheffects.withStroke(linewidth=3.2, foreground="white")]


def draw_target(ax, rob, color):
    """The robot's target, dashed, in a darker shade of its colour with a white halo, over the
    disks (zorder 7-9)."""
    (xl, yl), (xh, yh) = rob["target"]
    if None in (xl, yl, xh, yh):
        return False  # free in x or y: nothing sensible to draw
    r = rob["radius"]
    edge = blend(color, BLACK, 0.35)
    if xl == xh and yl == yh:
        ax.add_patch(plt.Circle((xl, yl), r, fill=False, ls="--", lw=1.4, edgecolor=edge,
                                zorder=7, path_effects=HALO))
        ax.plot([xl], [yl], marker="x", ms=7, mew=1.6, color=edge, zorder=9, path_effects=HALO)
    else:
        ax.add_patch(plt.Rectangle((xl, yl), xh - xl, yh - yl, fill=False, ls="--", lw=1.4,
                                   edgecolor=edge, zorder=7, path_effects=HALO))
    return True


# Text sizes in points (at DPI): legible when the report shows a figure at its full width.
TICK_PT, LABEL_PT, TITLE_PT, LEGEND_PT = 11, 12, 13, 11


def data_aspect(sol):
    """Height over width of the scene's drawn region (viz.solution_file.bounds)."""
    x0, x1, y0, y1 = bounds(sol)
    return (y1 - y0) / (x1 - x0)


def overlay_size(sol, width=1200):
    """(width, height) of the overlay: the axes (the figure less the legend at the right and
    the labels) as tall as the scene's region is at equal scale, between 30 % and 90 % of the
    axes width; so a scene along a line is a wide, short figure, not a strip in white."""
    axes_w = width - 340
    axes_h = min(max(data_aspect(sol) * axes_w, 0.3 * axes_w), 0.9 * axes_w)
    return width, int(round(axes_h + 130))


def title_text(sol, extra, width_px):
    tf = "T_f = –" if sol["T_f"] is None else f"T_f = {sol['T_f']:.3f} s"
    lb = "" if sol["lower_bound"] is None else f" (lower bound {sol['lower_bound']:.3f} s)"
    rest = f"{tf}{lb}, status {sol['status']}{extra}"
    one_line = f"{sol['scenario']}: {rest}"
    # About 9.5 px per character at TITLE_PT = 13 pt and 100 dpi; wrap rather than clip.
    return one_line if 9.5 * len(one_line) < width_px else f"{sol['scenario']}\n{rest}"


def robot_colors(n):
    cmap = plt.get_cmap("tab10")
    return [cmap(k % 10)[:3] for k in range(n)]


def legend_handles(sol, colors, contact_any, contact_snap):
    hs = [Patch(facecolor=blend(c, WHITE, 0.4), edgecolor=c, hatch=OBJECT_HATCH,
                label=r["name"] + " (object)") if r.get("object") else
          Line2D([], [], color=c, lw=1.5, marker="o", ms=8, mfc=blend(c, WHITE, 0.4), mec=c,
                 label=r["name"]) for r, c in zip(sol["robots"], colors)]
    if sol.get("obstacles"):
        hs.append(Patch(facecolor=OBSTACLE_FACE, edgecolor=OBSTACLE_EDGE, label="obstacle"))
    hs.append(Line2D([], [], ls="none", marker="o", ms=4, color="0.2", label="start"))
    hs.append(Line2D([], [], ls="--", marker="x", ms=7, color="0.2", label="target"))
    if contact_snap:
        hs.append(Line2D([], [], ls="none", marker="o", ms=6, mfc="red", mec="black",
                         label="contact at snapshot"))
    if contact_any:
        hs.append(Line2D([], [], ls="none", marker="+", ms=6, color="red",
                         label="contact (any step)"))
    return hs


def overlay(sol, times, thr, size, title_extra):
    fig, ax = plt.subplots(figsize=(size[0] / DPI, size[1] / DPI), dpi=DPI,
                           layout="constrained")
    colors = robot_colors(len(sol["robots"]))
    has_traj = sol["T_f"] is not None
    n = len(times)
    any_snap_contact = False
    for ri, (rob, c) in enumerate(zip(sol["robots"], colors)):
        x0, y0, _ = rob["start"]
        if has_traj:
            ax.plot(rob["x"], rob["y"], color=c, lw=1.0, zorder=1.8)  # seen through the disks
        ax.plot([x0], [y0], marker="o", ms=4, color=blend(c, BLACK, 0.3), zorder=9)
        draw_target(ax, rob, c)
    fixed = [ob for ob in sol.get("obstacles", []) if not moves(ob)]
    draw_obstacles(ax, dict(sol, obstacles=fixed), 0.0)
    if has_traj:
        h = sol["T_f"] / sol["N_t"]
        for k, t in enumerate(times):
            frac = k / (n - 1) if n > 1 else 1.0
            draw_obstacles(ax, dict(sol, obstacles=[ob for ob in sol.get("obstacles", []) if moves(ob)]),
                           t, frac, path=k == 0, label=str(k + 1))
            poses = [state_at(r, t, h, sol["N_t"]) for r in sol["robots"]]
            for rob, c, (x, y, phi) in zip(sol["robots"], colors, poses):
                draw_disk(ax, x, y, phi, rob["radius"], c, frac, 2 + 0.01 * k, str(k + 1),
                          obj=rob.get("object", False))
            for (cx, cy) in contacts_at(sol, t, h, thr, poses):
                any_snap_contact = True
                ax.plot([cx], [cy], ls="none", marker="o", ms=6, mfc="red", mec="black",
                        zorder=10)
        anyc = all_contacts(sol, thr)
        if anyc:
            ax.plot([p[0] for p in anyc], [p[1] for p in anyc], ls="none", marker="+", ms=6,
                    color="red", zorder=9.5)
    else:
        anyc = []
        for rob, c in zip(sol["robots"], colors):
            x0, y0, phi0 = rob["start"]
            draw_disk(ax, x0, y0, phi0, rob["radius"], c, 0.5, 2, obj=rob.get("object", False))
    handles = legend_handles(sol, colors, bool(anyc), any_snap_contact)
    if has_traj:
        grey = (0.35, 0.35, 0.35)
        for k, t in enumerate(times):
            frac = k / (n - 1) if n > 1 else 1.0
            handles.append(Line2D([], [], ls="none", marker="o", ms=10,
                                  mfc=blend(grey, WHITE, shade(frac)),
                                  mec=blend(grey, BLACK, 0.15 + 0.35 * frac),
                                  label=f"{k + 1}:  t = {t:.2f} s"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=LEGEND_PT,
              frameon=False, borderaxespad=0.0)
    finish_axes(ax, sol)
    ax.set_xlabel("x [m]", fontsize=LABEL_PT)
    ax.set_ylabel("y [m]", fontsize=LABEL_PT)
    ax.set_title(title_text(sol, title_extra, 0.75 * size[0]), fontsize=TITLE_PT)
    return fig


def finish_axes(ax, sol):
    x0, x1, y0, y1 = bounds(sol)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, lw=0.4, color="0.85", zorder=0)
    ax.set_axisbelow(True)
    ax.tick_params(labelsize=TICK_PT)


def panel_grid(n):
    cols = 1 if n == 1 else (2 if n <= 4 else 3)
    return cols, math.ceil(n / cols)


def panels(sol, times, thr, size, title_extra):
    cols, rows = panel_grid(len(times))
    fig = plt.figure(figsize=(size[0] / DPI, size[1] / DPI), dpi=DPI, layout="constrained")
    # A last, short row holds the legend (matplotlib 3.6 has no "outside" legend placement).
    grid = fig.add_gridspec(rows + 1, cols, height_ratios=[1.0] * rows + [0.2])
    axes = [[fig.add_subplot(grid[r, c]) for c in range(cols)] for r in range(rows)]
    legend_ax = fig.add_subplot(grid[rows, :])
    legend_ax.set_axis_off()
    colors = robot_colors(len(sol["robots"]))
    h = sol["T_f"] / sol["N_t"]
    any_snap_contact = any_contact = False
    for k, t in enumerate(times):
        ax = axes[k // cols][k % cols]
        past = all_contacts(sol, thr, until=t)
        if past:
            any_contact = True
            ax.plot([p[0] for p in past], [p[1] for p in past], ls="none", marker="+", ms=6,
                    color="red", zorder=9.5)
        poses = [state_at(r, t, h, sol["N_t"]) for r in sol["robots"]]
        upto = min(sol["N_t"], int(math.floor(t / h + 1e-9)))
        draw_obstacles(ax, sol, t, path=True)
        for rob, c, (x, y, phi) in zip(sol["robots"], colors, poses):
            ax.plot(rob["x"], rob["y"], color=c, lw=0.8, alpha=0.3, zorder=1)
            ax.plot(rob["x"][:upto + 1] + [x], rob["y"][:upto + 1] + [y], color=c, lw=1.2,
                    zorder=1.8)
            ax.plot([rob["start"][0]], [rob["start"][1]], marker="o", ms=3,
                    color=blend(c, BLACK, 0.3), zorder=9)
            draw_target(ax, rob, c)
            draw_disk(ax, x, y, phi, rob["radius"], c, 0.55, 3, obj=rob.get("object", False))
        for (cx, cy) in contacts_at(sol, t, h, thr, poses):
            any_snap_contact = True
            ax.plot([cx], [cy], ls="none", marker="o", ms=6, mfc="red", mec="black", zorder=10)
        finish_axes(ax, sol)
        ax.set_title(f"t = {t:.2f} s", fontsize=LABEL_PT)
    for k in range(len(times), rows * cols):
        axes[k // cols][k % cols].set_axis_off()
    handles = legend_handles(sol, colors, any_contact, any_snap_contact)
    legend_ax.legend(handles=handles, loc="center", ncol=min(len(handles), 6), fontsize=LEGEND_PT,
                     frameon=False)
    fig.suptitle(title_text(sol, title_extra, size[0]), fontsize=TITLE_PT)
    return fig



def snapshot_times(sol, n=6, times=None):
    """The snapshot times: `times` clipped to [0, T_f] and sorted, else n evenly spaced."""
    if sol["T_f"] is None:
        return []
    if times:
        return sorted(min(max(t, 0.0), sol["T_f"]) for t in times)
    return [sol["T_f"] * k / (n - 1) if n > 1 else sol["T_f"] for k in range(n)]


def draw_snapshots(sol, out, times, use_panels=None, size=None, thr=None):
    """Draws `sol` at `times` into the PNG `out`. use_panels None: panels for 4 or more
    robots. Without a trajectory, the starts and targets in one axes. size None: 1200 px wide
    (400 per panel column), as tall as the scene's region needs (overlay_size). Returns
    (size, panels)."""
    has_traj = sol["T_f"] is not None
    if use_panels is None:
        use_panels = len(sol["robots"]) >= 4
    use_panels = use_panels and has_traj
    extra = "" if has_traj else " (no trajectory: starts and targets only)"
    thr = default_contact_threshold(sol) if thr is None else thr
    if use_panels:
        cols, rows = panel_grid(len(times))
        # Panels as tall as the region at equal scale (between 40 % and 100 % of their width).
        panel_h = int(round(400 * min(max(data_aspect(sol), 0.4), 1.0)))
        size = size or (400 * cols, panel_h * rows + 110)
        fig = panels(sol, times, thr, size, extra)
    else:
        size = size or overlay_size(sol)
        fig = overlay(sol, times, thr, size, extra)
    save_figure(fig, out)
    return size, use_panels
