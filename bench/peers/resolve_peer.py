"""`holey resolve` against libigl's exact arrangement of a mesh with
itself: `remesh_self_intersections` (CGAL, exact, `stitch_all`) followed by
`resolve_duplicated_faces` (identical faces facing opposite ways cancel,
one of a majority is kept), side by side on one mesh. libigl gets the
float64 arrays; its time is in process (best of `--runs`). holey's is the
whole process (reading and writing the file included), best of `--runs`.
Both outputs are written and then measured by the same `holey selfint
--overlaps` and `holey info`, so the counts compare.

    cargo build --release -p holey-cli
    python3 bench/peers/resolve_peer.py [MESH] [--runs 3]
"""
import os, subprocess, tempfile, time

import igl
import igl.copyleft.cgal as cgal

from peer_io import bench_args, best, read_obj, write_obj


def measure(holey, path):
    """Intersecting pairs, coplanar overlapping pairs, boundary edges and
    edges on more than two triangles, by holey's own commands."""
    si = subprocess.run([holey, "selfint", path, "--overlaps"], capture_output=True, text=True).stdout
    info = subprocess.run([holey, "info", path], capture_output=True, text=True).stdout
    get = lambda text, key: next(l.split()[-1] for l in text.splitlines() if l.startswith(key))
    closed = next(l for l in info.splitlines() if l.startswith("closed:")).split()[1]
    boundary = next(l for l in info.splitlines() if l.startswith("closed:")).split("(")[1].split()[0]
    nonmanifold = next(l for l in info.splitlines() if l.startswith("manifold:"))
    nonmanifold = nonmanifold.split("(")[1].split()[0] if "(" in nonmanifold else "0"
    faces = next(l for l in info.splitlines() if l.startswith("faces:")).split()[1]
    return {
        "triangles": int(faces),
        "intersecting pairs": int(get(si, "intersecting pairs")),
        "coplanar overlaps": int(get(si, "coplanar overlaps")),
        "boundary edges": int(boundary),
        "edges on >2 triangles": int(nonmanifold),
        "closed": closed,
    }


def main():
    ap = bench_args(__doc__)
    ap.add_argument("mesh", nargs="?", default=None)
    args = ap.parse_args()
    holey = os.path.abspath(args.holey)
    mesh = args.mesh or os.path.join(args.shared, "meshes", "openscad-nonmanifold-crash.obj")
    v, f = read_obj(mesh)

    def remesh():
        vv, ff, _, _, _ = cgal.remesh_self_intersections(v, f, stitch_all=True)
        return vv, ff

    def remesh_and_cancel():
        vv, ff = remesh()
        return vv, igl.resolve_duplicated_faces(ff)[0]

    t_remesh, (vr, fr) = best(remesh, args.runs)
    t_igl, (vv, ff) = best(remesh_and_cancel, args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        ours = os.path.join(tmp, "holey.obj")
        raw, theirs = os.path.join(tmp, "remesh.obj"), os.path.join(tmp, "libigl.obj")
        write_obj(raw, vr, fr)
        write_obj(theirs, vv, ff)

        def run_holey():
            subprocess.run([holey, "resolve", mesh, ours], check=True, capture_output=True)

        t_holey, _ = best(run_holey, args.runs)
        rows = [("holey resolve", t_holey, measure(holey, ours)),
                ("libigl remesh_self_intersections", t_remesh, measure(holey, raw)),
                ("libigl remesh + resolve_duplicated_faces", t_igl, measure(holey, theirs))]
    print(f"mesh: {os.path.basename(mesh)} ({len(f)} triangles)")
    for name, t, m in rows:
        print(f"{name:42s} {t:8.3f} s  " + ", ".join(f"{k} {v}" for k, v in m.items()))
    print(f"time ratio holey/libigl: {t_holey / t_igl:.2f}")


if __name__ == "__main__":
    main()
