"""Reading meshes and timing for the peer scripts in this folder: one home
for what they all need (OBJ and STL as float64 arrays, volumes, best-of-n
timing)."""
import argparse
import os
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


def bench_args(description=None):
    """The options every peer script takes: the holey binary (made
    absolute), the shared data folder, and the number of runs."""
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--shared", default=os.path.join(here, "../../../shared/data"))
    ap.add_argument("--runs", type=int, default=3)
    return ap
