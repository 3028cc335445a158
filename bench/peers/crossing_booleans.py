"""Booleans of solids that cross themselves or overlap: holey's
winding-number arrangement against manifold3d and trueform, side by side
in one run, on ../shared/data/meshes/self_intersectA|B.obj and
../shared/data/corpus/Offset1|2.obj. Volumes are summed about the first
vertex; the exact answer is libigl's mesh_boolean
(bench/peers/winding_reference.py, recorded in BENCHMARKS.md).

Peers are timed in process from float64 arrays (manifold3d through Mesh64,
trueform through float64 arrays, fresh objects each run); holey's figure
is the engine's `seconds.total` from `--report`, and the whole process is
timed too.

    cargo build --release -p holey-cli
    python3 bench/peers/crossing_booleans.py [--holey target/release/holey] [--runs 3]
"""
import json, os, subprocess, tempfile, time

import numpy as np
import manifold3d as m3d
import trueform as tf

from peer_io import bench_args, best, read_obj, volume


def main():
    args = bench_args().parse_args()
    holey = os.path.abspath(args.holey)
    pairs = [
        ("self_intersectA", "self_intersectB", "meshes"),
        ("Offset1", "Offset2", "corpus"),
    ]
    ops = [
        ("union", "+", tf.boolean_union, lambda a, b: a + b),
        ("intersection", "&", tf.boolean_intersection, lambda a, b: a ^ b),
        ("difference", "-", tf.boolean_difference, lambda a, b: a - b),
    ]
    with tempfile.TemporaryDirectory() as d:
        for na, nb, folder in pairs:
            pa = os.path.join(args.shared, folder, na + ".obj")
            pb = os.path.join(args.shared, folder, nb + ".obj")
            va, fa = read_obj(pa)
            vb, fb = read_obj(pb)
            for op, sym, tf_op, m3d_op in ops:
                def m3d_run():
                    a = m3d.Manifold(m3d.Mesh64(vert_properties=va, tri_verts=fa.astype(np.uint64)))
                    b = m3d.Manifold(m3d.Mesh64(vert_properties=vb, tri_verts=fb.astype(np.uint64)))
                    return m3d_op(a, b).volume()
                t_m3d, v_m3d = best(m3d_run, args.runs)
                t_tf, r_tf = best(lambda: tf_op(tf.Mesh(fa.astype(np.int32), va), tf.Mesh(fb.astype(np.int32), vb)), args.runs)
                f_tf, p_tf = r_tf[0]
                v_tf = volume(np.asarray(p_tf, dtype=np.float64), np.asarray(f_tf))
                out, rep = os.path.join(d, "out.obj"), os.path.join(d, "r.json")
                engine, wall = None, None
                for _ in range(args.runs):
                    t = time.perf_counter()
                    p = subprocess.run([holey, op, pa, pb, out, "--report", rep], capture_output=True, text=True)
                    dt = time.perf_counter() - t
                    if p.returncode != 0:
                        raise SystemExit(p.stderr)
                    r = json.load(open(rep))
                    engine = min(engine or 1e9, r["seconds"]["total"])
                    wall = min(wall or 1e9, dt)
                vh, fh = read_obj(out)
                print(f"{na} {sym} {nb}: m3d {t_m3d:.3f}s vol {v_m3d!r} | tf {t_tf:.3f}s vol {v_tf!r} | "
                      f"holey {engine:.3f}s (process {wall:.3f}s) vol {volume(vh, fh)!r} "
                      f"unpaired {r['unpaired_edges']} crossing {r['output_intersecting_pairs']}", flush=True)


if __name__ == "__main__":
    main()
