#!/usr/bin/env python3
"""Booleans of lattice solids in exact coplanar contact, against the peers.

A Menger sponge built from unit lattice cubes (level 2 or 3; every square
face between a cube and an empty cell, two triangles) and its copy shifted
by whole cells: their faces lie on one lattice, so the operands touch in
coplanar faces (the same squares, split along different diagonals where a
cube meets the other from the other side), and the results meet
themselves along edges and at corners. The exact answer is known: the
volume is the number of cubes the rule keeps, counted here on the cell
sets.

For each shift and operation it prints, per tool, the time, the volume
and its error against the cube count, and for holey whether the output is
a closed 2-manifold and how it was made (its report's method and nudges).
All tools get the same float64 arrays (manifold3d through `Mesh64`,
trueform as float64 `tf.Mesh`); holey's time is its engine's own
`seconds.total` (no file reading), and the whole process's.

    cargo build --release -p holey-cli
    python3 bench/peers/lattice_booleans.py [--holey target/release/holey] [--level 2] [--runs 3]
"""
import argparse, os, tempfile

import numpy as np

from peer_io import holey_info, holey_run, peer_booleans, write_obj


def menger_cells(level):
    n = 3 ** level

    def kept(c):
        while any(c):
            if sum(1 for x in c if x % 3 == 1) >= 2:
                return False
            c = [x // 3 for x in c]
        return True

    return [(x, y, z) for x in range(n) for y in range(n) for z in range(n) if kept([x, y, z])]


def lattice_surface(cells):
    """Vertices (float64) and triangles of the cubes' outer faces, outward."""
    cells_set = set(cells)
    index, verts, tris = {}, [], []

    def vid(p):
        if p not in index:
            index[p] = len(verts)
            verts.append(p)
        return index[p]

    for c in cells:
        for axis in range(3):
            for d in (-1, 1):
                n = list(c)
                n[axis] += d
                if tuple(n) in cells_set:
                    continue
                u, w = (axis + 1) % 3, (axis + 2) % 3
                base = list(c)
                base[axis] += 1 if d > 0 else 0
                quad = []
                for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    q = list(base)
                    q[u] += du
                    q[w] += dw
                    quad.append(tuple(q))
                if d < 0:
                    quad.reverse()
                a, b, cc, dd = (vid(q) for q in quad)
                tris += [(a, b, cc), (a, cc, dd)]
    return np.array(verts, dtype=np.float64), np.array(tris, dtype=np.int64)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--level", type=int, default=2)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    holey = os.path.abspath(args.holey)
    cells = menger_cells(args.level)
    va, fa = lattice_surface(cells)
    print(f"Menger sponge level {args.level}: {len(cells)} cubes, {len(fa)} triangles")
    ratios = []
    with tempfile.TemporaryDirectory() as d:
        pa = os.path.join(d, "a.obj")
        write_obj(pa, va, fa)
        for shift in [(1, 0, 0), (3, 0, 0), (1, 1, 0), (1, 1, 1)]:
            moved = [(x + shift[0], y + shift[1], z + shift[2]) for x, y, z in cells]
            vb, fb = lattice_surface(moved)
            pb = os.path.join(d, "b.obj")
            write_obj(pb, vb, fb)
            in_a, in_b = set(cells), set(moved)
            for op, keep in [
                ("union", lambda x, y: x or y),
                ("intersection", lambda x, y: x and y),
                ("difference", lambda x, y: x and not y),
            ]:
                want = sum(1 for c in in_a | in_b if keep(c in in_a, c in in_b))
                t_tf, v_tf, t_m3d, v_m3d = peer_booleans(op, (va, fa), (vb, fb), args.runs)
                out, rep = os.path.join(d, "out.obj"), os.path.join(d, "r.json")
                wall, engine, report, err = holey_run(holey, op, [pa, pb], out, rep, args.runs)
                if err is None:
                    info = holey_info(holey, out)
                    v_h = info.get("volume")
                    shape = "closed 2-manifold" if info.get("closed") and info.get("manifold") else "NOT a closed 2-manifold"
                    how = f'{report["method"]}, {report["perturbation_retries"]} nudges'
                    ratios.append(engine / t_tf)
                else:
                    v_h, shape, how = None, err, ""
                err_of = lambda v: "-" if v is None else f"{abs(v - want) / want:.1e}"
                print(f"{str(shift):10} {op:12} exact {want:5d} | m3d {t_m3d:.3f}s err {err_of(v_m3d)} | "
                      f"tf {t_tf:.3f}s err {err_of(v_tf)} | holey {engine if engine else float('nan'):.3f}s "
                      f"(process {wall if wall else float('nan'):.3f}s) err {err_of(v_h)} {shape} ({how})", flush=True)
    if ratios:
        print(f"median holey/trueform (engine, from arrays): {np.median(ratios):.2f} over {len(ratios)}")


if __name__ == "__main__":
    main()
