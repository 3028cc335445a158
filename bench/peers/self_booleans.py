#!/usr/bin/env python3
"""A op A: each shared solid united with, intersected with and subtracted
from an exact copy of itself, against the peers.

Every face of one operand lies on a face of the other, so the whole
surface is coplanar contact. The answer is known: A ∪ A and A ∩ A are A
(its volume), A − A is empty. Prints, per tool, the time and the volume's
error (relative to A's volume), and for holey whether the output is a
closed 2-manifold, its crossing pairs and how it was made. The tools get
the same float64 arrays (manifold3d through `Mesh64`).

    cargo build --release -p holey-cli
    python3 bench/peers/self_booleans.py [--holey target/release/holey] [--shared ../shared] [--runs 3]
"""
import argparse, os, tempfile

from peer_io import holey_info, holey_run, peer_booleans, read_obj, read_stl, volume, write_obj

SOLIDS = [
    "data/meshes/menger_sponge_level3.obj",
    "data/meshes/spot_triangulated.obj",
    "data/meshes/bunny_oded.obj",
    "data/meshes/fertility_poly.obj",
    "data/corpus/thingi10k_1514499.stl",
    "data/corpus/thingi10k_88566.stl",
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "../../../shared"))
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    holey = os.path.abspath(args.holey)
    with tempfile.TemporaryDirectory() as d:
        for rel in SOLIDS:
            path = os.path.join(args.shared, rel)
            v, f = read_stl(path) if path.endswith(".stl") else read_obj(path)
            pa = os.path.join(d, "a.obj")
            write_obj(pa, v, f)
            whole = volume(v, f)
            for op, want in [("union", whole), ("intersection", whole), ("difference", 0.0)]:
                t_tf, v_tf, t_m3d, v_m3d = peer_booleans(op, (v, f), (v, f), args.runs)
                out, rep = os.path.join(d, "out.obj"), os.path.join(d, "r.json")
                wall, engine, report, err = holey_run(holey, op, [pa, pa], out, rep, args.runs)
                err_of = lambda x: "-" if x is None else f"{abs(x - want) / whole:.1e}"
                if err is None:
                    info = holey_info(holey, out)
                    v_h = info.get("volume") if want else 0.0 if info.get("faces", 0) == 0 else info.get("volume")
                    shape = "closed 2-manifold" if info.get("closed") and info.get("manifold") else "NOT a closed 2-manifold"
                    how = (f'{report["method"]}, {report["perturbation_retries"]} nudges, '
                           f'{report.get("output_intersecting_pairs")} crossing pairs')
                    line = f"holey {engine:.3f}s (process {wall:.3f}s) err {err_of(v_h)} {shape} ({how})"
                else:
                    line = f"holey: {err}"
                print(f"{os.path.basename(rel):28} {op:12} | m3d {t_m3d:.3f}s err {err_of(v_m3d)} | "
                      f"tf {t_tf:.3f}s err {err_of(v_tf)} | {line}", flush=True)


if __name__ == "__main__":
    main()
