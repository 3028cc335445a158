#!/usr/bin/env python3
"""Per-frame sculpting times on real meshes (issue 15).

Writes the stroke files the sculpting scenarios use (the same paths as
crates/sculpt/tests/real_meshes.rs: points of the surface nearest to
fractions of its bounding box, radius a share of its diagonal, inflate
strength 5% of the radius per frame at slider 1) and replays each with
the frame_trace example, which times every frame and sums up the frames
that only moved the surface apart from those where the engine cut it.

    cargo build --release -p holey-sculpt --example frame_trace
    cargo build --release -p holey-cli
    python3 bench/sculpt/frames.py [--shared ../shared] [--out /tmp/holey-frames] [--only bunny]

`--only bunny1m` replays a recorded haunch stroke on the bunny split to
1.1M triangles (made once in --out by midpoint_split.py).

Needs numpy. The shared meshes are read, never copied.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))
from peer_io import read_obj  # noqa: E402  (one OBJ reader for the bench scripts)


class Surface:
    def __init__(self, path):
        self.v, f = read_obj(path)
        self.used = np.unique(f)
        self.lo = self.v[self.used].min(0)
        self.hi = self.v[self.used].max(0)
        self.diagonal = float(np.linalg.norm(self.hi - self.lo))

    def at(self, fraction):
        """The vertex nearest to a point given as fractions of the box."""
        p = self.lo + np.array(fraction) * (self.hi - self.lo)
        j = self.used[np.argmin(np.linalg.norm(self.v[self.used] - p, axis=1))]
        return self.v[j].tolist()

    def walk(self, a, b, n):
        return [self.at(np.array(a) + (np.array(b) - np.array(a)) * i / (n - 1)) for i in range(n)]


def bunny_strokes(bunny):
    r = 0.05 * bunny.diagonal
    k = 0.05 * r
    across = bunny.walk([0.55, 0.35, 1.0], [0.75, 0.45, 1.0], 40)
    haunch = {"strokes": [
        {"brush": "inflate", "radius": r, "strength": k, "path": across},
        {"brush": "inflate", "radius": r, "strength": -k, "path": across[::-1]},
    ]}
    r8 = 0.08 * bunny.diagonal
    spot = bunny.at([0.6, 0.4, 1.0])
    dwell = {"strokes": [
        {"brush": "inflate", "radius": r8, "strength": 0.05 * r8, "path": [spot] * 30},
        {"brush": "smooth", "radius": r8, "strength": 0.5, "path": [spot] * 10},
    ]}
    # The haunch stroke mirrored across z = 0 onto the other flank (issue
    # 19: a frame with symmetry should cost at most 1.5x one without).
    mirrored = {"strokes": [dict(st, symmetry="z") for st in haunch["strokes"]]}
    # The ear pulled into the head with the snake hook (issue 15, item 3),
    # the path of crates/sculpt/tests/real_meshes.rs.
    used = bunny.v[bunny.used]
    tip = used[np.argmax(used[:, 1])]
    near = used[(np.abs(used[:, 0] + 0.065) < 0.002) & (np.abs(used[:, 2] - 0.02) < 0.002)]
    crown = near[np.argmax(near[:, 1])]
    corners = [tip, np.array([-0.04, tip[1] + 0.013, 0.02]),
               crown + np.array([0.0, 0.025, 0.005]), crown - np.array([0.0, 0.02, 0.0])]
    hook_path = [list(a + (b - a) * i / 10) for a, b in zip(corners, corners[1:]) for i in range(10)]
    hook_path.append(list(corners[-1]))
    hook = {"strokes": [{"brush": "snake_hook", "radius": 0.012, "path": [list(map(float, p)) for p in hook_path]}]}
    return {"bunny-haunch": haunch, "bunny-haunch-mirrored-z": mirrored,
            "bunny-dwell": dwell, "bunny-ear-snake-hook": hook}


def sphere_strokes():
    # @sphere:8: the unit sphere, 1,310,720 triangles; a brush touching
    # about 2,000 triangles and one of 5% of the bounding-box diagonal.
    share = 2000 / 1310720
    small = math.acos(1 - 2 * share)
    big = 0.05 * 2 * math.sqrt(3)
    path = [[math.sin(0.01 * i), 0.0, math.cos(0.01 * i)] for i in range(10)]
    return {
        "sphere8-2k-brush": {"strokes": [{"brush": "inflate", "radius": small, "strength": 0.002, "path": path}]},
        "sphere8-5pct-brush": {"strokes": [{"brush": "inflate", "radius": big, "strength": 0.025 * big, "path": path}]},
    }


def replay(trace, mesh, strokes, extra):
    out = subprocess.run([trace, mesh, strokes, "--no-audit", *extra], check=True,
                         capture_output=True, text=True).stdout
    return out.strip().splitlines()[-1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    ap.add_argument("--out", default="/tmp/holey-frames")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--only", default="", help="run only the jobs whose name contains this")
    args = ap.parse_args()
    trace = os.path.join(ROOT, "target", "release", "examples", "frame_trace")
    holey = os.path.join(ROOT, "target", "release", "holey")
    os.makedirs(args.out, exist_ok=True)
    bunny_path = os.path.join(args.shared, "data", "meshes", "stanford-bunny.obj")
    jobs = []
    if os.path.exists(bunny_path):
        for name, s in bunny_strokes(Surface(bunny_path)).items():
            jobs.append((name, bunny_path, s))
    else:
        print(f"SKIP bunny: {bunny_path} absent", file=sys.stderr)
    # The bunny split twice at its edge midpoints (1,111,216 triangles, the
    # same surface) with a haunch stroke the modeler recorded: frames that
    # change topology at a million triangles (issue 15 asks for 100 ms).
    million = "bunny1m-haunch-browser-1"
    if os.path.exists(bunny_path) and args.only in million:
        big = os.path.join(args.out, "bunny1m.obj")
        if not os.path.exists(big):
            subprocess.run([sys.executable, os.path.join(HERE, "midpoint_split.py"), bunny_path, big, "2"],
                           check=True)
        with open(os.path.join(HERE, "recorded", "bunny_haunch_browser_1.json")) as f:
            jobs.append((million, big, json.load(f)))
    sphere = os.path.join(args.out, "sphere8.obj")
    if ("sphere" in args.only or not args.only) and not os.path.exists(sphere):
        subprocess.run([holey, "convert", "@sphere:8", sphere], check=True)
    if "sphere" in args.only or not args.only:
        for name, s in sphere_strokes().items():
            jobs.append((name, sphere, s))
    for name, mesh, s in jobs:
        if args.only not in name:
            continue
        path = os.path.join(args.out, name + ".json")
        with open(path, "w") as f:
            json.dump(s, f)
        for extra in ([], ["--no-remesh"]):
            for run in range(args.runs):
                print(f"{name} {' '.join(extra) or '(remeshing)'} run {run}: {replay(trace, mesh, path, extra)}")


if __name__ == "__main__":
    main()
