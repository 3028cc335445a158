#!/usr/bin/env python3
"""Dwell inflates on the rims of the shared open meshes: how many frames
the guard holds, and why.

For each mesh with a rim (edges one triangle uses), six rim vertices
spread along the rim each get a stroke of 40 frames of inflate at the
vertex (radius 5% of the bounding-box diagonal, the modeler's strength
for slider 1: 5% of the radius per frame), replayed in order with
`holey sculpt -v` (remeshing on). Prints the held frames per stroke and
the reasons the CLI gives. Usage:

    cargo build --release -p holey-cli
    python3 bench/sculpt/rim_dwells.py [--holey target/release/holey] [--shared ../shared]
"""
import json, os, re, subprocess, tempfile
from collections import Counter

from shared_obj import read_obj, sculpt_args, shared_meshes, used_bounds

MESHES = ["stanford-bunny.obj", "bigguyhalf.obj", "suzanne.obj", "beetle.obj"]


def dwell_strokes(v, f, strokes=6, frames=40):
    _, _, diagonal = used_bounds(v, f)
    sides = Counter()
    for a, b, c in f:
        for u, w in ((a, b), (b, c), (c, a)):
            sides[(min(u, w), max(u, w))] += 1
    rim = sorted({i for side, n in sides.items() if n == 1 for i in side})
    if not rim:
        return []
    radius = 0.05 * diagonal
    step = max(1, len(rim) // strokes)
    return [
        {"brush": "inflate", "radius": radius, "strength": 0.05 * radius, "path": [v[i]] * frames}
        for i in rim[::step][:strokes]
    ]


def main():
    args = sculpt_args().parse_args()
    total = 0
    with tempfile.TemporaryDirectory() as d:
        for name, path in shared_meshes(args.shared, MESHES):
            strokes = dwell_strokes(*read_obj(path))
            if not strokes:
                continue
            file = os.path.join(d, "strokes.json")
            with open(file, "w") as fh:
                json.dump({"strokes": strokes}, fh)
            out = subprocess.run([args.holey, "sculpt", path, file, os.path.join(d, "out.obj"), "-v"],
                                 capture_output=True, text=True, check=True).stderr
            held = [int(x) for x in re.findall(r"(\d+) guarded frame", out)]
            total += sum(held)
            print(f"{name}: held frames per stroke {held}")
            for line in out.splitlines():
                if "held frames that would have left" in line:
                    print("   ", line.strip())
    print(f"held frames in all: {total}")


if __name__ == "__main__":
    main()
