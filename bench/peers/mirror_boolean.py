"""A CAD part against its own mirror image: holey against trueform and
manifold3d, measured side by side in one run.

`thingi10k_1063852.stl` (../shared/data/corpus; 68,548 triangles, x from
-8.457 to 8.543) is read as binary float32 and welded where bit-identical;
the second input is its image under x -> -x with each triangle turned back
over. The image lies 0.086 beside the part, and their faces normal to y
and z lie in the same planes: coplanar overlaps both ways (walls of no
thickness in the difference), and the cut merges points the perturbation
keeps apart. All three get the same float64 arrays: manifold3d through
Mesh64, trueform through float64 arrays, fresh objects each run. holey's
figure is the engine's own `seconds.total` from `--report` (every attempt
and check; no file reading), and the whole process is timed too.

    cargo build --release -p holey-cli
    python3 bench/peers/mirror_boolean.py [--holey target/release/holey] [--runs 3]
"""
import os
import tempfile

from peer_io import bench_args, holey_info, holey_run, peer_booleans, read_stl, write_obj


def main():
    args = bench_args(__doc__.splitlines()[0]).parse_args()
    holey = os.path.abspath(args.holey)
    va, fa = read_stl(os.path.join(args.shared, "corpus", "thingi10k_1063852.stl"))
    vb, fb = va.copy(), fa[:, ::-1].copy()
    vb[:, 0] = -vb[:, 0]
    with tempfile.TemporaryDirectory() as d:
        pa, pb = os.path.join(d, "a.obj"), os.path.join(d, "b.obj")
        write_obj(pa, va, fa)
        write_obj(pb, vb, fb)
        for op in ["union", "intersection", "difference"]:
            t_tf, v_tf, t_m3d, v_m3d = peer_booleans(op, (va, fa), (vb, fb), args.runs)
            out, rep = os.path.join(d, "out.obj"), os.path.join(d, "r.json")
            wall, engine, report, err = holey_run(holey, op, [pa, pb], out, rep, args.runs)
            if err is not None:
                print(f"{op:12} holey failed: {err}")
                continue
            info = holey_info(holey, out)
            shape = "closed manifold" if info.get("closed") and info.get("manifold") else "NOT closed manifold"
            off = abs(info.get("volume", float("nan")) - v_m3d) / abs(v_m3d)
            print(f"{op:12} m3d {t_m3d:.3f}s vol {v_m3d!r} | tf {t_tf:.3f}s vol {v_tf!r} | "
                  f"holey {engine:.3f}s (process {wall:.3f}s) vol {info.get('volume')!r} "
                  f"({off:.1e} off m3d) {shape}, method {report.get('method')}, "
                  f"nudges {report.get('perturbation_retries')}, "
                  f"crossing pairs {report.get('output_intersecting_pairs')} | "
                  f"holey/tf {engine / t_tf:.2f}, holey/m3d {engine / t_m3d:.2f}", flush=True)


if __name__ == "__main__":
    main()
