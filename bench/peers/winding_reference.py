"""Reference volumes for the winding-number Booleans of crossing and
overlapping solids, from libigl's exact mesh_boolean (CGAL kernel).

libigl's Python wheels dropped the CGAL module after 2.5.1, so this runs in
its own virtualenv:

    python3 -m venv /tmp/igl25 && /tmp/igl25/bin/pip install libigl==2.5.1 numpy
    /tmp/igl25/bin/python bench/peers/winding_reference.py [../shared/data]

It prints each operation's volume (repr, all digits) and libigl's time; the
figures are recorded in crates/topo/tests/winding_booleans.rs. Meshes are
read as float64, faces fanned, nothing welded.
"""

import sys
import time

import numpy as np
import igl.copyleft.cgal as cgal

from peer_io import read_obj, volume


def main():
    shared = sys.argv[1] if len(sys.argv) > 1 else "../shared/data"
    a = read_obj(f"{shared}/meshes/self_intersectA.obj")
    b = read_obj(f"{shared}/meshes/self_intersectB.obj")
    o1 = read_obj(f"{shared}/corpus/Offset1.obj")
    o2 = read_obj(f"{shared}/corpus/Offset2.obj")
    empty = (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
    cases = [
        ("self_intersectA | self_intersectB", a, b, "union"),
        ("self_intersectA & self_intersectB", a, b, "intersection"),
        ("self_intersectA - self_intersectB", a, b, "minus"),
        ("Offset1 | Offset2", o1, o2, "union"),
        ("Offset1 & Offset2", o1, o2, "intersection"),
        ("Offset1 - Offset2", o1, o2, "minus"),
        ("self_intersectA alone", a, empty, "union"),
        ("self_intersectB alone", b, empty, "union"),
        ("Offset1 alone", o1, empty, "union"),
        ("Offset2 alone", o2, empty, "union"),
    ]
    for name, x, y, op in cases:
        start = time.perf_counter()
        v, f, _ = cgal.mesh_boolean(x[0], x[1], y[0], y[1], op)
        took = time.perf_counter() - start
        print(f"{name:38s} volume {volume(v, f)!r:24s} libigl {took:.2f} s", flush=True)


if __name__ == "__main__":
    main()
