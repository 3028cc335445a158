"""`holey selfint` against trueform's `self_intersection_curves` on every
mesh of ../shared/data/meshes and ../shared/data/corpus, side by side in
one run. Each mesh is read once here (OBJ faces fanned, STL welded where
bit-identical) and trueform gets float64 arrays, timed in process (best of
`--runs`, fresh mesh object each run, construction included). holey's
figure is its own `seconds` from `--json` (no file reading), best of
`--runs`; the whole process is timed too. holey reads the file itself
(OBJ as written, STL welded the same way).

    cargo build --release -p holey-cli
    python3 bench/peers/selfint_all.py [--holey target/release/holey] [--runs 3]
"""
import glob, json, os, subprocess, time

import numpy as np
import trueform as tf

from peer_io import bench_args, read_obj, read_stl


def main():
    args = bench_args().parse_args()
    holey = os.path.abspath(args.holey)
    paths = sorted(glob.glob(os.path.join(args.shared, "meshes", "*.obj")))
    paths += sorted(glob.glob(os.path.join(args.shared, "corpus", "*.obj")))
    paths += sorted(glob.glob(os.path.join(args.shared, "corpus", "*.stl")))
    ratios = []
    for path in paths:
        v, f = read_stl(path) if path.endswith(".stl") else read_obj(path)
        f = f.astype(np.int32)
        best_tf, pairs_tf = 1e9, None
        for _ in range(args.runs):
            t = time.perf_counter()
            r = tf.self_intersection_curves(tf.Mesh(f, v))
            best_tf = min(best_tf, time.perf_counter() - t)
        best_h, wall, pairs = 1e9, 1e9, None
        for _ in range(args.runs):
            t = time.perf_counter()
            p = subprocess.run([holey, "selfint", "--json", path], capture_output=True, text=True)
            wall = min(wall, time.perf_counter() - t)
            if p.returncode != 0:
                pairs = p.stderr.strip().splitlines()[-1]
                break
            j = json.loads(p.stdout)
            best_h, pairs = min(best_h, j["seconds"]), j["intersecting_pairs"]
        ratio = best_h / best_tf if best_tf > 0 else float("nan")
        ratios.append(ratio)
        print(f"{os.path.basename(path):40s} {len(f):8d} tris | trueform {best_tf:.4f}s | holey {best_h:.4f}s "
              f"(process {wall:.3f}s) pairs {pairs} | holey/tf {ratio:.2f}", flush=True)
    print(f"median holey/trueform: {np.median(ratios):.2f}; worst {max(ratios):.2f}")


if __name__ == "__main__":
    main()
