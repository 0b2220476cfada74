"""An animated GIF of a solution's motion (scripts/report), drawn like the snapshots: each
robot's disk with its orientation line, the path travelled so far over the whole path (faint),
start dots and targets, red dots at pairs in contact, and the time.

Frames are evenly spaced over [0, T_f] and played at about `fps` (frame_plan); the GIF plays in
real time (to 1 %) unless that needs more than `max_frames` frames, in which case it plays
faster and says by how much.
The static part (axes, paths, targets) is drawn once; each frame restores it and draws only
the moving artists (matplotlib's blitting), then Pillow (python3-pil, a dependency of Debian's
python3-matplotlib) writes the GIF.
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

from viz.snapshots import (BLACK, DPI, OBJECT_HATCH, OBSTACLE_EDGE, OBSTACLE_FACE,  # noqa: E402
                           WHITE, blend, draw_obstacles, draw_target, finish_axes, robot_colors)
from viz.solution_file import (contacts_at, default_contact_threshold, moves,  # noqa: E402
                               obstacle_at, state_at)


def frame_plan(T_f, fps, max_frames):
    """(frames, delay in 1/100 s, speed-up). GIF stores each frame's delay in whole hundredths
    of a second (and browsers slow delays under 2/100 s down to 1/10 s), so the delay is
    round(100 / fps), at least 2. The frames, evenly spaced over [0, T_f], are as many as fill
    T_f at that delay (nearest count), at most max_frames (then faster than real time)."""
    delay = max(2, round(100.0 / fps))
    frames = max(2, min(max_frames, round(T_f * 100.0 / delay) + 1))
    return frames, delay, T_f / ((frames - 1) * delay / 100.0)


def speed_text(speed):
    """How the GIF plays: "real time" within 1 %, else the factor."""
    return "real time" if abs(speed - 1.0) <= 0.01 else f"{speed:.2f}× real time"


def write_gif(sol, out, fps=20, max_frames=160, size=(720, 540)):
    """Writes the animation of `sol` (with a trajectory) to `out`; returns (frames, speed-up)."""
    frames, delay, speed = frame_plan(sol["T_f"], fps, max_frames)
    n_t, T_f = sol["N_t"], sol["T_f"]
    h = T_f / n_t
    thr = default_contact_threshold(sol)
    fig, ax = plt.subplots(figsize=(size[0] / DPI, size[1] / DPI), dpi=DPI, layout="constrained")
    colors = robot_colors(len(sol["robots"]))
    disks, heads, trails = [], [], []
    for rob, c in zip(sol["robots"], colors):
        ax.plot(rob["x"], rob["y"], color=c, lw=0.8, alpha=0.25, zorder=1)
        ax.plot([rob["start"][0]], [rob["start"][1]], marker="o", ms=3,
                color=blend(c, BLACK, 0.3), zorder=9)
        draw_target(ax, rob, c)
        trails.append(ax.plot([], [], color=c, lw=1.4, zorder=1.8)[0])
        disk = plt.Circle((0, 0), rob["radius"], facecolor=blend(c, WHITE, 0.35),
                          edgecolor=blend(c, BLACK, 0.35), lw=1.2, alpha=0.9, zorder=3,
                          hatch=OBJECT_HATCH if rob.get("object") else None)
        ax.add_patch(disk)
        disks.append(disk)
        heads.append(ax.plot([], [], color=blend(c, BLACK, 0.35), lw=2.0,
                             solid_capstyle="round", zorder=3.1)[0])
    contacts = ax.plot([], [], ls="none", marker="o", ms=6, mfc="red", mec="black", zorder=10)[0]
    still = [ob for ob in sol.get("obstacles", []) if not moves(ob)]
    draw_obstacles(ax, dict(sol, obstacles=still), 0.0)
    runners = [ob for ob in sol.get("obstacles", []) if moves(ob)]
    runner_disks = []
    for ob in runners:
        runner_disks.append(plt.Circle(obstacle_at(ob, 0.0), ob["radius"], facecolor=OBSTACLE_FACE,
                                       edgecolor=OBSTACLE_EDGE, lw=1.0, zorder=1.6))
        ax.add_patch(runner_disks[-1])
    finish_axes(ax, sol)
    ax.set_xlabel("x [m]", fontsize=9)
    ax.set_ylabel("y [m]", fontsize=9)
    playback = speed_text(speed)
    title = ax.set_title(f"{sol['scenario']}: t = {T_f:5.2f} s of {T_f:.2f} s ({playback})",
                         fontsize=10)

    def draw(f):
        t = T_f * f / (frames - 1)
        poses = [state_at(r, t, h, n_t) for r in sol["robots"]]
        upto = min(n_t, int(math.floor(t / h + 1e-9)))
        for rob, (x, y, phi), disk, head, trail in zip(sol["robots"], poses, disks, heads, trails):
            disk.center = (x, y)
            r = rob["radius"]
            head.set_data([x, x + r * math.cos(phi)], [y, y + r * math.sin(phi)])
            trail.set_data(rob["x"][:upto + 1] + [x], rob["y"][:upto + 1] + [y])
        for ob, disk in zip(runners, runner_disks):
            disk.center = obstacle_at(ob, t)
        pts = contacts_at(sol, t, h, thr, poses)
        contacts.set_data([p[0] for p in pts], [p[1] for p in pts])
        title.set_text(f"{sol['scenario']}: t = {t:5.2f} s of {T_f:.2f} s ({playback})")

    moving = runner_disks + trails + disks + heads + [contacts, title]  # in z-order
    try:
        for a in moving:
            a.set_animated(True)
        fig.canvas.draw()  # the static part, laid out once
        background = fig.canvas.copy_from_bbox(fig.bbox)
        images = []
        for f in range(frames):
            draw(f)
            fig.canvas.restore_region(background)
            for a in moving:
                ax.draw_artist(a)
            rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
            images.append(Image.fromarray(np.ascontiguousarray(rgb)))
        # One palette for all frames, no dithering: unchanged pixels keep their index, so each
        # GIF frame stores only what moved. The palette comes from a sample of the frames
        # (the last shows every trail) and the contact dots' red.
        sample = images[::max(1, frames // 6)] + [images[-1]]
        w, hgt = images[0].size
        strip = Image.new("RGB", (w, hgt * len(sample) + 8), (255, 0, 0))
        for k, im in enumerate(sample):
            strip.paste(im, (0, k * hgt))
        palette = strip.quantize(colors=128, method=Image.Quantize.MEDIANCUT)
        frames_p = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
        frames_p[0].save(out, format="GIF", save_all=True, append_images=frames_p[1:],
                         duration=10 * delay, loop=0, optimize=False)
    finally:
        plt.close(fig)
    return frames, speed
