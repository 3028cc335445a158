#!/usr/bin/env python3
"""The fuzz strokes of `fuzz_strokes.py`, replayed by one or more builds,
with each output judged by its welded surface: every exact position one
point, as a soup or an unwelded seam is meant. A run counts as damaged
when the output has more boundary loops or more non-manifold curves
(pieces of edges with more than two triangles, joined through shared
points) than the input, welded that way. An independent check of the
CLI's own audit, which joins a rim's copies in the same spirit, and the
way to compare builds from before it did. Usage:

    python3 bench/sculpt/welded_damage.py --holey OLD,NEW [--seeds 10] [--first-seed 910] [--frames-of 8]
"""
import os, subprocess, tempfile
from collections import Counter

from fuzz_strokes import fuzz_args, stroke_files
from shared_obj import read_obj


def welded_loops_and_fins(path):
    """Boundary loops and non-manifold curves of the OBJ at `path` with
    its exact positions welded."""
    v, f = read_obj(path)
    ids = {}
    point = [ids.setdefault(tuple(p), len(ids)) for p in v]
    sides = Counter()
    for t in f:
        c = [point[i] for i in t]
        for k in range(3):
            a, b = c[k], c[(k + 1) % 3]
            if a != b:
                sides[(min(a, b), max(a, b))] += 1

    def pieces(edges):
        parent = {}

        def find(x):
            while parent.setdefault(x, x) != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        for a, b in edges:
            parent[find(a)] = find(b)
        return len({find(x) for x in parent})

    return (pieces([e for e, n in sides.items() if n == 1]),
            pieces([e for e, n in sides.items() if n > 2]))


def main():
    args = fuzz_args(first_seed=910).parse_args()
    builds = args.holey.split(",")
    damaged = Counter()
    runs = 0
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "out.obj")
        for name, path, seed, file in stroke_files(args, d):
            base = welded_loops_and_fins(path)
            runs += 1
            row = []
            for b in builds:
                if subprocess.run([b, "sculpt", path, file, out], capture_output=True).returncode:
                    row.append("refused")
                    continue
                loops, fins = welded_loops_and_fins(out)
                if loops > base[0] or fins > base[1]:
                    damaged[b] += 1
                row.append(f"loops {loops - base[0]:+d}, curves {fins - base[1]:+d}")
            print(f"{name} seed {seed}: " + " | ".join(row))
    for b in builds:
        print(f"{b}: {damaged[b]} of {runs} outputs with more welded boundary loops or non-manifold curves")


if __name__ == "__main__":
    main()
