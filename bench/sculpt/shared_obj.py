"""Reading the shared meshes for the sculpting scripts of this folder:
an OBJ's positions and its faces fan-triangulated (1-based indices and
`v/vt/vn` forms as holey reads them), without numpy."""


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
