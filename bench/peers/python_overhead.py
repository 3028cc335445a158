#!/usr/bin/env python3
"""What a Python call to holey costs beyond the engine: the union of two
262,088-triangle spheres (issue 4's setting) through `holey.union`, against
the engine's own time for the same call (its report's `seconds.total`),
the CLI as a whole process on OBJ files, and manifold3d and trueform from
the same float64 arrays, measured side by side in one run.

Run it in a virtualenv where the package is installed (`pip install .`)
with the peers (`pip install manifold3d trueform`):

    cargo build --release -p holey-cli
    python bench/peers/python_overhead.py [--holey target/release/holey] [--runs 5]
"""
import argparse, json, os, subprocess, tempfile, time

import numpy as np
import manifold3d as m3d
import trueform as tf

import holey

from peer_io import best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()

    mesh = m3d.Manifold.sphere(1, 724).to_mesh64()
    # Copies: manifold3d refuses its own read-only arrays back.
    va = np.array(mesh.vert_properties, dtype=np.float64)[:, :3].copy()
    fa = np.array(mesh.tri_verts, dtype=np.int64)
    vb = va + [0.5, 0.0, 0.0]
    print(f"two spheres of {len(fa)} triangles, the second shifted by 0.5 in x")

    # holey from Python: the call, and the engine's time inside it (best of
    # runs each; the overhead is converting and copying the arrays both
    # ways, compacting the result and the report).
    calls, engines = [], []
    for _ in range(args.runs):
        t = time.perf_counter()
        V, F, report = holey.union(va, fa, vb, fa, report=True)
        calls.append(time.perf_counter() - t)
        engines.append(report["seconds"]["total"])
    call, engine = min(calls), min(engines)
    # Without the exact check that neither input crosses itself (the
    # peers make no such check).
    unchecked, _ = best(lambda: holey.union(va, fa, vb, fa, check=False), args.runs)

    # The CLI, whole process, from OBJ files written with shortest
    # round-trip decimals (so it unites the same solids).
    with tempfile.TemporaryDirectory() as d:
        a, b, out, rep = (os.path.join(d, n) for n in ("a.obj", "b.obj", "u.obj", "r.json"))
        holey.write(a, va, fa)
        holey.write(b, vb, fa)
        cli, _ = best(lambda: subprocess.run([args.holey, "union", a, b, out, "--report", rep], check=True), args.runs)
        with open(rep) as fh:
            cli_engine = json.load(fh)["seconds"]["total"]

    def manifold():
        A = m3d.Manifold(m3d.Mesh64(vert_properties=va, tri_verts=fa.astype(np.uint64)))
        B = m3d.Manifold(m3d.Mesh64(vert_properties=vb, tri_verts=fa.astype(np.uint64)))
        return (A + B).num_tri()

    t_m3d, _ = best(manifold, args.runs)
    fa32 = fa.astype(np.int32)
    t_tf, _ = best(lambda: tf.boolean_union(tf.Mesh(fa32, va), tf.Mesh(fa32, vb)), args.runs)

    print(f"holey.union (Python call)        {call:.3f} s")
    print(f"  engine inside the call         {engine:.3f} s  overhead {call - engine:.3f} s ({(call - engine) / call:.0%})")
    print(f"holey.union(check=False)         {unchecked:.3f} s  / trueform = {unchecked / t_tf:.2f}")
    print(f"holey union (CLI, whole process) {cli:.3f} s  engine {cli_engine:.3f} s")
    print(f"manifold3d from arrays           {t_m3d:.3f} s  holey.union / manifold3d = {call / t_m3d:.2f}")
    print(f"trueform from arrays             {t_tf:.3f} s  holey.union / trueform = {call / t_tf:.2f}")
    print(f"result: {len(F)} triangles, volume {holey.volume(V, F):.9f}")


if __name__ == "__main__":
    main()
