#!/usr/bin/env python3
"""Tests of scripts/plot_snapshots (run by CTest as plot.snapshots; see tests/CMakeLists.txt).

  plot_tests.py DISCO PLOT_SNAPSHOTS SCENE WORKDIR

Solves SCENE (one_robot_axis, 25 steps) with `disco solve`, then checks that plot_snapshots
- writes SOLUTION.png next to the input by default: a PNG (signature, IHDR) of the documented
  size fitted to the scene's shape: one_robot_axis moves along x only, so its region is
  far wider than tall and the overlay takes the documented least height, 1200 x (0.3 x 860
  + 130) = 1200x388, not 1200x900 of mostly white;
- draws the robot: a fair share of the pixels carry the robot's colour (tab:blue);
- sizes the panel grid as documented (--panels: 3 columns for 6 snapshots, 2 for 4) and
  honours --size;
- fails with exit 2 and a message naming the file and the key for a file without
  robots[0].phi, a truncated trajectory and a missing file, and writes no image then.
Only the standard library is used here; the PNG is decoded with zlib.
"""
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib

from script_checks import check, failures, finish

DISCO, PLOT, SCENE, WORK = sys.argv[1:5]
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def plot(*args):
    r = subprocess.run([PLOT, *args], env=ENV, capture_output=True, text=True)
    if r.returncode not in (0, 2):
        print(r.stdout, r.stderr, sep="\n")
    return r


def png_header(path):
    """(width, height, bit depth, colour type) from the IHDR chunk, or None if not a PNG."""
    if not os.path.isfile(path):
        return None
    with open(path, "rb") as f:
        head = f.read(33)
    if len(head) < 33 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">IIBB", head[16:26])


def png_pixels(path):
    """RGB(A) rows of an 8-bit, non-interlaced truecolour PNG (what matplotlib's Agg writes)."""
    with open(path, "rb") as f:
        data = f.read()
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    assert depth == 8 and ctype in (2, 6), (depth, ctype)
    bpp = 4 if ctype == 6 else 3
    idat, pos = b"", 8
    while pos < len(data):
        (n,), kind = struct.unpack(">I", data[pos:pos + 4]), data[pos + 4:pos + 8]
        if kind == b"IDAT":
            idat += data[pos + 8:pos + 8 + n]
        pos += 12 + n
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ftype, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
solve_dir = os.path.join(WORK, "solve")
r = subprocess.run([DISCO, "solve", SCENE, "--set", "scene.steps=25", "--out", solve_dir], env=ENV)
sol = os.path.join(solve_dir, "solution.json")
check(r.returncode == 0 and os.path.isfile(sol), f"disco solve wrote {sol} (exit {r.returncode})")
if failures:
    sys.exit(1)

# Default output: next to the input, the overlay (1 robot along a line), 1200x388.
r = plot(sol)
png = os.path.join(solve_dir, "solution.png")
check(r.returncode == 0, f"plot_snapshots exits 0 (got {r.returncode}: {r.stderr.strip()})")
check(os.path.isfile(png), "default output is solution.png next to the input")
hdr = png_header(png)
check(hdr is not None, "the output starts with the PNG signature and an IHDR chunk")
check(hdr is not None and hdr[:2] == (1200, 388), f"overlay is 1200x388 (got {hdr and hdr[:2]})")

# The robot is drawn: count robot-blue pixels (tab:blue is (31, 119, 180); the disks are
# shades of it, the background and decorations are white, grey or black).
small = os.path.join(WORK, "small.png")
r = plot(sol, "-o", small, "--size", "480x360")
hdr = png_header(small)
check(r.returncode == 0 and hdr is not None and hdr[:2] == (480, 360),
      f"--size 480x360 gives a 480x360 PNG (got {hdr and hdr[:2]})")
if hdr is not None:
    w, h, bpp, rows = png_pixels(small)
    blue = sum(1 for row in rows for k in range(0, len(row), bpp)
               if row[k + 2] - row[k] > 60 and row[k + 2] > row[k + 1])
    check(blue > 0.005 * w * h, f"the robot is drawn: {blue} of {w * h} pixels are robot blue")

# Panels: 3 columns for 6 snapshots, 2 columns for 4; rows 400 x 0.4 = 160 px tall for this
# flat scene, + 110: 1200x430 and 800x430.
for n, size in ((6, (1200, 430)), (4, (800, 430))):
    out = os.path.join(WORK, f"panels{n}.png")
    r = plot(sol, "--panels", "--snapshots", str(n), "-o", out)
    hdr = png_header(out)
    check(r.returncode == 0 and hdr is not None and hdr[:2] == size,
          f"--panels --snapshots {n} is {size[0]}x{size[1]} (got {hdr and hdr[:2]})")

# Bad input: exit 2, the file and the key named, no image written.
with open(sol) as f:
    doc = json.load(f)
bad_cases = []
d = json.loads(json.dumps(doc))
del d["robots"][0]["phi"]
bad_cases.append(("no_phi", d, "missing key 'robots[0].phi'"))
d = json.loads(json.dumps(doc))
d["robots"][0]["x"] = d["robots"][0]["x"][:-1]
bad_cases.append(("short_x", d, "'robots[0].x' has 25 entries, expected 26"))
# A search's best.json (the shape `disco search` writes): the message names its scenes'
# solution files, to be given instead.
best_dir = os.path.join(WORK, "search")
os.makedirs(best_dir, exist_ok=True)
bad_cases.append(("search/best", {"seed": 1, "scenes": {
    "one_robot_axis": {"T_f": doc["T_f"], "solution": "best/one_robot_axis.json"},
    "two": {"T_f": None, "solution": None}}},
    "a search's best.json, not a solution file: give one of its scenes' "
    + os.path.join(best_dir, "best", "one_robot_axis.json")))
for name, d, msg in bad_cases:
    path = os.path.join(WORK, name + ".json")
    with open(path, "w") as f:
        json.dump(d, f)
    r = plot(path)
    check(r.returncode == 2, f"{name}: exit 2 (got {r.returncode})")
    check(path in r.stderr and msg in r.stderr, f"{name}: stderr names the file and says {msg!r} "
          f"(got {r.stderr.strip()!r})")
    check(not os.path.exists(os.path.join(WORK, name + ".png")), f"{name}: no image written")
missing = os.path.join(WORK, "no_such.json")
r = plot(missing)
check(r.returncode == 2 and f"{missing}: cannot open" in r.stderr,
      f"missing file: exit 2 and '{missing}: cannot open' (got {r.returncode}, {r.stderr.strip()!r})")

finish("plot_tests")
