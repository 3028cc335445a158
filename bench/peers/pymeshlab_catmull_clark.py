#!/usr/bin/env python3
"""Peer comparison: N Catmull-Clark levels with pymeshlab (comparison only;
pymeshlab is never a dependency of holey).

    python3 bench/peers/pymeshlab_catmull_clark.py IN.obj OUT.ply LEVELS

Prints the in-process time of the subdivision filter alone, then writes the
result, so the script can also be timed as a whole process against
`holey subdivide IN.obj OUT.ply --scheme catmull-clark -n LEVELS`.
"""
import sys
import time

import pymeshlab


def main():
    src, dst, levels = sys.argv[1], sys.argv[2], int(sys.argv[3])
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(src)
    start = time.perf_counter()
    ms.meshing_surface_subdivision_catmull_clark(iterations=levels)
    elapsed = time.perf_counter() - start
    m = ms.current_mesh()
    print(f"pymeshlab catmull-clark x{levels}: {elapsed:.3f} s, V={m.vertex_number()} F={m.face_number()}")
    ms.save_current_mesh(dst)


if __name__ == "__main__":
    main()
