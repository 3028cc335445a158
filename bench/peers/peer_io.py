"""Reading meshes and timing for the peer scripts in this folder: one home
for what they all need (OBJ and STL as float64 arrays, volumes, best-of-n
timing)."""
import argparse
import json
import os
import subprocess
import time

import numpy as np


def read_obj(path):
    """Vertices (n, 3) float64 and triangles (m, 3) int64; polygons fanned,
    negative indices resolved, nothing welded."""
    verts, faces = [], []
    with open(path, errors="replace") as fh:
        for line in fh:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(verts) + i for i in ids]
                faces += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64).reshape(-1, 3)


def read_stl(path):
    """A binary STL's corners welded where bit-identical (float32 read,
    float64 out) and its triangles (m, 3) int64."""
    data = open(path, "rb").read()
    n = int.from_bytes(data[80:84], "little")
    rec = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                        count=n, offset=84)
    corners = rec["v"].reshape(-1, 3)
    keys = corners.view(np.uint32).reshape(-1, 3)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return corners[first].astype(np.float64), inverse.reshape(-1, 3).astype(np.int64)


def write_obj(path, v, f):
    """An OBJ of float64 vertices written exactly (repr) and 1-based
    triangles."""
    with open(path, "w") as fh:
        fh.write("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist()))
        fh.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f.tolist()))


def volume(v, f):
    """Signed volume, summed about the first vertex (about the origin,
    coordinates near 2e4 lose a part in 1e8 to cancellation)."""
    if len(f) == 0:
        return 0.0
    p = (v - v[0])[f]
    return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0)


def best(fn, runs):
    """The shortest of `runs` timings of `fn()`, and its last result."""
    times, out = [], None
    for _ in range(runs):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def peer_booleans(op, a, b, runs):
    """trueform's and manifold3d's `op` ("union", "intersection" or
    "difference", A − B) of `a` and `b`, each a (vertices float64,
    triangles) pair, built afresh from the arrays in every run (manifold3d
    through `Mesh64`): (trueform seconds, its volume, manifold3d seconds,
    its volume), each the best of `runs`."""
    import manifold3d as m3d
    import trueform as tf

    (va, fa), (vb, fb) = a, b
    tf_op = {"union": tf.boolean_union, "intersection": tf.boolean_intersection,
             "difference": tf.boolean_difference}[op]
    m3d_op = {"union": lambda A, B: A + B, "intersection": lambda A, B: A ^ B,
              "difference": lambda A, B: A - B}[op]
    t_tf, r_tf = best(lambda: tf_op(tf.Mesh(fa, va), tf.Mesh(fb, vb)), runs)
    v_tf = volume(r_tf[0][1], r_tf[0][0])

    def m3d_run():
        A = m3d.Manifold(m3d.Mesh64(vert_properties=va, tri_verts=fa.astype(np.uint64)))
        B = m3d.Manifold(m3d.Mesh64(vert_properties=vb, tri_verts=fb.astype(np.uint64)))
        return m3d_op(A, B).volume()

    t_m3d, v_m3d = best(m3d_run, runs)
    return t_tf, v_tf, t_m3d, v_m3d


def holey_run(holey, op, inputs, out, report, runs, extra=()):
    """`holey op inputs... out --report report`, `runs` times: (the best
    whole-process seconds, the best engine seconds `seconds.total`, the
    last report, None), or (None, None, None, the error's last line)."""
    wall = engine = r = None
    for _ in range(runs):
        t = time.perf_counter()
        p = subprocess.run([holey, op, *inputs, out, "--report", report, *extra],
                           capture_output=True, text=True)
        dt = time.perf_counter() - t
        if p.returncode != 0:
            return None, None, None, p.stderr.strip().splitlines()[-1]
        r = json.load(open(report))
        wall = dt if wall is None else min(wall, dt)
        engine = r["seconds"]["total"] if engine is None else min(engine, r["seconds"]["total"])
    return wall, engine, r, None


def holey_info(holey, path):
    """`holey info --json path`, parsed."""
    p = subprocess.run([holey, "info", "--json", path], capture_output=True, text=True)
    return json.loads(p.stdout)


def bench_args(description=None):
    """The options every peer script takes: the holey binary (made
    absolute), the shared data folder, and the number of runs."""
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--shared", default=os.path.join(here, "../../../shared/data"))
    ap.add_argument("--runs", type=int, default=3)
    return ap
