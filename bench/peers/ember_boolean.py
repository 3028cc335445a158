"""The EMBER pairs of ../shared/data/corpus (A minus B, and A union B):
holey against trueform and manifold3d, measured side by side in one run.

Each STL is read as binary float32 and welded where coordinates are
bit-identical, then moved by its pair's 3x4 transform in float64
(ember_pairs.json). All three get the same float64 arrays: manifold3d
through Mesh64, trueform through float64 arrays. Peers are timed in
process from arrays (fresh mesh objects each run, construction included);
holey's figure is the engine's own `seconds.total` from `--report` (in
process, no file reading), and the whole process is timed too.

    cargo build --release -p holey-cli
    python3 bench/peers/ember_boolean.py [--holey target/release/holey] [--runs 3]
    python3 bench/peers/ember_boolean.py --holey-args=--no-check

By default holey first checks exactly that neither solid crosses itself
(its winding-number arrangement takes those); `--no-check` skips that, as
the peers do, for inputs known to be solids.

With holey's Python package importable (`pip install .` from the
repository), holey is also timed as the peers are: in this process, from
the same float64 arrays, best of `--runs` (the call's whole wall time,
array conversion included), the same method as the peers'. (A fresh CLI
process touches its heap for the first time: in a profile of
1706459 - 1514499 the kernel zeroing fresh pages was 27-34% of the
samples. Timed in process, holey was not measurably faster, 2026-12-03.)
"""
import argparse, json, os, tempfile

import numpy as np

from peer_io import best, holey_info, holey_run, peer_booleans, read_stl, write_obj

try:
    import holey as holey_py
except ImportError:
    holey_py = None


def transform(v, m):
    m = np.asarray(m, dtype=np.float64)
    return v @ m[:, :3].T + m[:, 3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--holey", default="target/release/holey")
    ap.add_argument("--corpus", default=os.path.join(os.path.dirname(__file__), "../../../shared/data/corpus"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--holey-args", default="", help="extra holey flags, space-separated")
    args = ap.parse_args()
    holey = os.path.abspath(args.holey)
    pairs = json.load(open(os.path.join(args.corpus, "ember_pairs.json")))["pairs"]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for pair in pairs:
            va, fa = read_stl(os.path.join(args.corpus, pair["a"]))
            vb, fb = read_stl(os.path.join(args.corpus, pair["b"]))
            va, vb = transform(va, pair["transform_a"]), transform(vb, pair["transform_b"])
            pa, pb = os.path.join(d, "a.obj"), os.path.join(d, "b.obj")
            write_obj(pa, va, fa)
            write_obj(pb, vb, fb)
            name = f'{pair["a"][9:-4]} {{}} {pair["b"][9:-4]}'
            for op, sym in [("difference", "-"), ("union", "+")]:
                t_tf, v_tf, t_m3d, v_m3d = peer_booleans(op, (va, fa), (vb, fb), args.runs)
                out, rep = os.path.join(d, "out.obj"), os.path.join(d, "r.json")
                wall, engine, _, err = holey_run(holey, op, [pa, pb], out, rep, args.runs, args.holey_args.split())
                if err is None:
                    info = holey_info(holey, out)
                    v_h = info.get("volume")
                    shape = "closed manifold" if info.get("closed") and info.get("manifold") else "NOT closed manifold"
                else:
                    v_h, shape = None, err
                t_py = None
                if holey_py is not None:
                    call = getattr(holey_py, op)
                    t_py, _ = best(lambda: call(va, fa, vb, fb, check="--no-check" not in args.holey_args), args.runs)
                rows.append((name.format(sym), t_m3d, v_m3d, t_tf, v_tf, engine, wall, v_h, shape, t_py))
                in_process = f"in process {t_py:.3f}s (/tf {t_py / t_tf:.2f}) | " if t_py is not None else ""
                print(f"{name.format(sym):24} m3d {t_m3d:.3f}s vol {v_m3d:.6g} | tf {t_tf:.3f}s vol {v_tf:.6g} | "
                      f"holey {engine if engine is not None else float('nan'):.3f}s (process {wall if wall else float('nan'):.3f}s) "
                      f"vol {v_h} {shape} | {in_process}holey/tf {engine / t_tf if engine else float('nan'):.2f}", flush=True)
    ratios = [r[5] / r[3] for r in rows if r[5] is not None]
    if ratios:
        print(f"median holey/trueform (engine, from arrays): {np.median(ratios):.2f} over {len(ratios)} of {len(rows)}")
    in_process = [r[9] / r[3] for r in rows if r[9] is not None]
    if in_process:
        print(f"median holey/trueform (both in process from arrays, best of {args.runs}): {np.median(in_process):.2f}")


if __name__ == "__main__":
    main()
