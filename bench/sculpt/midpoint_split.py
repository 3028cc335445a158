#!/usr/bin/env python3
"""Split every triangle of an OBJ into four at its edge midpoints, K times.

The surface stays exactly where it was (every new vertex is the midpoint
of an edge), so a stroke file recorded on the original replays on the
finer mesh: `python3 bench/sculpt/midpoint_split.py stanford-bunny.obj
bunny1m.obj 2` makes the 1.1M-triangle bunny of BENCHMARKS.md.
"""
import sys

from shared_obj import read_obj


def split(v, f):
    v = [tuple(p) for p in v]
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            mids[key] = len(v)
            v.append(tuple((x + y) / 2 for x, y in zip(v[a], v[b])))
        return mids[key]

    out = []
    for a, b, c in f:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return v, out


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: midpoint_split.py IN.obj OUT.obj K")
    v, f = read_obj(sys.argv[1])
    for _ in range(int(sys.argv[3])):
        v, f = split(v, f)
    with open(sys.argv[2], "w") as out:
        out.write("".join("v %r %r %r\n" % p for p in v))
        out.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in f))
    print(f"{len(v)} vertices, {len(f)} triangles")


if __name__ == "__main__":
    main()
