"""Reading the shared meshes for the sculpting scripts of this folder:
their common options and the meshes of the shared folder that are there,
an OBJ's positions and its faces fan-triangulated (1-based indices and
`v/vt/vn` forms as holey reads them), without numpy."""
import argparse
import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))


def sculpt_args():
    """The options every script here takes: the holey binary and the
    shared folder (by default the release build and `../shared` beside
    the checkout)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default=os.path.join(ROOT, "target", "release", "holey"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    return ap


def shared_meshes(shared, names):
    """(name, path) of each of `names` in the shared folder's meshes, in
    order; a missing one is said on stderr and skipped."""
    for name in names:
        path = os.path.join(shared, "data", "meshes", name)
        if not os.path.exists(path):
            print(f"{name}: not found, skipped", file=sys.stderr)
            continue
        yield name, path


def read_obj(path):
    """The positions and the fan-triangulated faces of the OBJ at `path`."""
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                v.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = [int(x.split("/")[0]) - 1 for x in line.split()[1:]]
                f.extend((idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1))
    return v, f


def used_bounds(v, f):
    """The corners of the box around the positions some face uses, and its
    diagonal (unreferenced positions, as the bunny has, do not count)."""
    used = sorted({i for t in f for i in t})
    lo = [min(v[i][k] for i in used) for k in range(3)]
    hi = [max(v[i][k] for i in used) for k in range(3)]
    return lo, hi, sum((b - a) ** 2 for a, b in zip(lo, hi)) ** 0.5
