#!/usr/bin/env python3
"""Union and self-intersection of two 262,088-triangle spheres: holey
against manifold3d and trueform, measured side by side in one run.

The spheres are manifold3d's Manifold.sphere(1, 724) and the same shifted by
0.5 in x (the setting of issue 4). Peers are timed in-process (mesh already
in memory); holey is timed both by the engine's own report (in-process, no
file reading) and as a whole process (reading two OBJ files included), with
its peak memory.

Peers are timed two ways. *Prepared*: their mesh objects are built before
the clock starts and reused, so what they build once and keep (manifold3d's
half-edges and collider at construction, trueform's tree, face membership
and edge links, built on the first call and cached on the mesh object) is
not timed after the first run. *From arrays*: fresh objects from the
vertex and index arrays each run, construction included. holey keeps no
state between calls, so every holey time is "from arrays", and that is the
like-for-like ratio, except the line for holey's own prepared solids
(`PreparedSolid`, built once outside the clock, like the peers' objects),
which compares with the prepared peers.

    cargo build --release -p holey-cli -p holey-bench
    python3 bench/peers/topo_spheres.py [--holey target/release/holey] [--runs 3]
"""
import argparse, json, os, subprocess, sys, tempfile, time

import numpy as np
import manifold3d as m3d
import trueform as tf


def write_obj(path, v, f):
    with open(path, "w") as fh:
        fh.write("".join(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in v))
        fh.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f))


def best(fn, runs):
    times = []
    out = None
    for _ in range(runs):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def run_holey(cmd, runs, report=None):
    """Best wall time, peak RSS (KB), stdout of a holey command, and the
    report (JSON at `report`) of the run whose engine total was best."""
    best_t, peak, stdout, best_report = None, 0, "", None
    for _ in range(runs):
        t = time.perf_counter()
        p = subprocess.run(["/usr/bin/time", "-f", "%M"] + cmd, capture_output=True, text=True)
        dt = time.perf_counter() - t
        if p.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed: {p.stderr}")
        peak = max(peak, int(p.stderr.strip().splitlines()[-1]))
        best_t = dt if best_t is None else min(best_t, dt)
        stdout = p.stdout
        if report:
            r = json.load(open(report))
            if best_report is None or r["seconds"]["total"] < best_report["seconds"]["total"]:
                best_report = r
    return best_t, peak, stdout, best_report


def run_timing(timing, args, runs):
    """Best in-process time of the library, run `runs` times in one
    process (as the peers are timed), from the bench crate's timing
    program; None when it is not built."""
    if not os.path.exists(timing):
        return None
    p = subprocess.run([timing] + args + ["--runs", str(runs)], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{timing} failed: {p.stderr}")
    return json.loads(p.stdout)["best"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--timing", default="target/release/topo_timing",
                    help="in-process timing program (cargo build --release -p holey-bench --bin topo_timing)")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    holey = os.path.abspath(args.holey)
    timing = os.path.abspath(args.timing)

    a = m3d.Manifold.sphere(1, 724)
    b = a.translate([0.5, 0, 0])
    ma, mb = a.to_mesh(), b.to_mesh()
    va = np.asarray(ma.vert_properties, dtype=np.float64)[:, :3]
    fa = np.asarray(ma.tri_verts, dtype=np.int64)
    vb = np.asarray(mb.vert_properties, dtype=np.float64)[:, :3]
    fb = np.asarray(mb.tri_verts, dtype=np.int64)
    tris = len(fa) + len(fb)

    with tempfile.TemporaryDirectory() as d:
        pa, pb, pab = (os.path.join(d, n) for n in ("a.obj", "b.obj", "ab.obj"))
        write_obj(pa, va, fa)
        write_obj(pb, vb, fb)
        write_obj(pab, np.vstack([va, vb]), np.vstack([fa, fb + len(va)]))
        # Peers read the same rounded coordinates holey reads.
        def read(path):
            v, f = [], []
            for line in open(path):
                if line.startswith("v "):
                    v.append([float(t) for t in line.split()[1:4]])
                elif line.startswith("f "):
                    f.append([int(t) - 1 for t in line.split()[1:4]])
            return np.array(v), np.array(f, dtype=np.int64)
        va, fa = read(pa)
        vb, fb = read(pb)
        vab, fab = read(pab)

        def m3d_union():
            A = m3d.Manifold(m3d.Mesh(vert_properties=va.astype(np.float32), tri_verts=fa.astype(np.uint32)))
            B = m3d.Manifold(m3d.Mesh(vert_properties=vb.astype(np.float32), tri_verts=fb.astype(np.uint32)))
            t = time.perf_counter()
            u = A + B
            n = u.num_tri()
            return time.perf_counter() - t, n, u.volume()

        def m3d_union_from_arrays():
            A = m3d.Manifold(m3d.Mesh(vert_properties=va.astype(np.float32), tri_verts=fa.astype(np.uint32)))
            B = m3d.Manifold(m3d.Mesh(vert_properties=vb.astype(np.float32), tri_verts=fb.astype(np.uint32)))
            return (A + B).num_tri()

        m3d_runs = [m3d_union() for _ in range(args.runs)]
        t_m3d = min(r[0] for r in m3d_runs)
        t_m3d_arrays, _ = best(m3d_union_from_arrays, args.runs)
        TA, TB = tf.Mesh(fa, va), tf.Mesh(fb, vb)
        t_tf, tf_out = best(lambda: tf.boolean_union(TA, TB), args.runs)
        t_tf_arrays, _ = best(lambda: tf.boolean_union(tf.Mesh(fa, va), tf.Mesh(fb, vb)), args.runs)
        TAB = tf.Mesh(fab, vab)
        t_tf_si, _ = best(lambda: tf.self_intersection_curves(TAB), args.runs)
        t_tf_si_arrays, _ = best(lambda: tf.self_intersection_curves(tf.Mesh(fab, vab)), args.runs)

        out = os.path.join(d, "u.ply")
        rep = os.path.join(d, "r.json")
        t_hu, mem_hu, _, report = run_holey([holey, "union", pa, pb, out, "--report", rep], args.runs, rep)
        info = json.loads(subprocess.run([holey, "info", "--json", out], capture_output=True, text=True).stdout)
        t_hm, _, _, motion = run_holey([holey, "union", pa, pb, out, "--via-motion", "--report", rep], args.runs, rep)
        t_hs, mem_hs, si, _ = run_holey([holey, "selfint", "--json", pab], args.runs)
        si = json.loads(si)
        warm_union = run_timing(timing, ["union", pa, pb], max(args.runs, 5))
        warm_si = run_timing(timing, ["selfint", pab], max(args.runs, 5))
        warm_prepared = run_timing(timing, ["union-prepared", pa, pb], max(args.runs, 5))

    engine = report["seconds"]["total"]
    print(f"two spheres, {tris} triangles; best of {args.runs}")
    print(f"union    from arrays: manifold3d {t_m3d_arrays:.3f} s  trueform {t_tf_arrays:.3f} s  holey engine {engine:.3f} s; "
          f"holey/manifold3d {engine / t_m3d_arrays:.2f}x  holey/trueform {engine / t_tf_arrays:.2f}x")
    # The stages the report times depend on the method the policy took
    # (`containment`, or `winding` where the exact arrangement answered).
    stages = ", ".join(f"{k} {v:.3f}" for k, v in report["seconds"].items() if k != "total")
    print(f"         prepared: manifold3d {t_m3d:.3f} s  trueform {t_tf:.3f} s  holey engine {engine:.3f} s "
          f"(method {report.get('method')}: {stages})  "
          f"holey whole process {t_hu:.3f} s, peak {mem_hu / 1024:.0f} MB = {mem_hu * 1024 / tris:.0f} B/triangle")
    print(f"         holey/manifold3d {engine / t_m3d:.2f}x  holey/trueform {engine / t_tf:.2f}x (engine against prepared peers)")
    if warm_union is not None:
        print(f"         holey in one process, best of {max(args.runs, 5)}: {warm_union:.3f} s; "
              f"holey/manifold3d {warm_union / t_m3d:.2f}x  holey/trueform {warm_union / t_tf:.2f}x (prepared); "
              f"{warm_union / t_m3d_arrays:.2f}x  {warm_union / t_tf_arrays:.2f}x (from arrays)")
    if warm_prepared is not None:
        print(f"         prepared both sides (holey PreparedSolid, union_prepared), best of {max(args.runs, 5)}: "
              f"holey {warm_prepared:.3f} s; holey/manifold3d {warm_prepared / t_m3d:.2f}x  "
              f"holey/trueform {warm_prepared / t_tf:.2f}x")
    print(f"         --via-motion (collisions {motion['seconds'].get('collisions', 0.0):.3f} s): engine "
          f"{motion['seconds']['total']:.3f} s, whole process {t_hm:.3f} s")
    print(f"         result: {info['faces']} triangles, closed {info['closed']}, genus {info['genus']}, "
          f"volume {info['volume']:.9f}; manifold3d {m3d_runs[0][1]} triangles, volume {m3d_runs[0][2]:.9f}")
    print(f"selfint  trueform from arrays {t_tf_si_arrays:.3f} s; holey/trueform {si['seconds'] / t_tf_si_arrays:.2f}x (engine)")
    print(f"         trueform prepared {t_tf_si:.3f} s  holey engine {si['seconds']:.3f} s  holey whole process {t_hs:.3f} s, "
          f"peak {mem_hs / 1024:.0f} MB; holey/trueform {si['seconds'] / t_tf_si:.2f}x (engine); "
          f"{si['intersecting_pairs']} pairs, {si['intersection_curves']} curves")
    if warm_si is not None:
        print(f"         holey in one process, best of {max(args.runs, 5)}: {warm_si:.3f} s; holey/trueform {warm_si / t_tf_si:.2f}x")


if __name__ == "__main__":
    main()
