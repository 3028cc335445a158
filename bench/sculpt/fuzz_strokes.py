#!/usr/bin/env python3
"""Random strokes on the shared real meshes, replayed with the CLI: each
stroke's output audit is compared with its input's, and anything worse
is printed (issue 15's fuzz loop, at a scale the test suite cannot
afford: more seeds, more meshes, more brushes).

For every mesh and seed, four strokes are drawn as the test
`fuzz_random_strokes_on_real_meshes` draws them (radius 3-8% of the
diagonal, slider 0.2-1: inflate, deflate, a dwell, smooth or a grab of
up to 30% of the box), written as one stroke file and replayed by
`holey sculpt --audit -v` with remeshing. A run fails when the CLI exits
non-zero (a refusal or a panic) or when a stroke leaves more boundary
loops, non-manifold curves, misoriented edges, pinched vertices, degenerate triangles or
intersecting pairs than its input had. Usage:

    cargo build --release -p holey-cli
    python3 bench/sculpt/fuzz_strokes.py [--seeds 10] [--frames-of 1] [--holey target/release/holey]

With `--frames-of N`, every paint stroke's points go in frames of 1 to N
dabs drawn at random, which the engine paints together.
"""
import json, os, random, re, subprocess, tempfile

from shared_obj import read_obj, sculpt_args, shared_meshes

MESHES = ["stanford-bunny.obj", "teapot.obj", "beetle.obj", "suzanne.obj", "spot_triangulated.obj",
          "bigguyhalf.obj", "fertility_poly.obj", "self_intersectA.obj",
          "thingi10k_65004_arduino_case_soup.obj"]


def used_points(path):
    """The positions some face of the OBJ at `path` uses."""
    v, f = read_obj(path)
    return [v[i] for i in sorted({i for t in f for i in t})]


def strokes(points, rng):
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    diagonal = sum((b - a) ** 2 for a, b in zip(lo, hi)) ** 0.5

    def near(fraction):
        q = [a + (b - a) * t for a, b, t in zip(lo, hi, fraction)]
        return min(points, key=lambda p: sum((x - y) ** 2 for x, y in zip(p, q)))

    out = []
    for _ in range(4):
        r = rng.uniform(0.03, 0.08) * diagonal
        slider = rng.uniform(0.2, 1.0)
        k = slider * 0.05 * r
        a, b = near([rng.random() for _ in range(3)]), near([rng.random() for _ in range(3)])
        path = [[x + (y - x) * i / 11 for x, y in zip(a, b)] for i in range(12)]
        path = [near([(c - l) / (h - l) if h > l else 0.5 for c, l, h in zip(p, lo, hi)]) for p in path]
        kind = rng.randrange(5)
        if kind == 0:
            out.append({"brush": "inflate", "radius": r, "strength": k, "path": path})
        elif kind == 1:
            out.append({"brush": "inflate", "radius": r, "strength": -k, "path": path})
        elif kind == 2:
            out.append({"brush": "inflate", "radius": r, "strength": k, "path": [path[0]] * 12})
        elif kind == 3:
            out.append({"brush": "smooth", "radius": r, "strength": slider, "path": path})
        else:
            to = [p + (h - l) * rng.uniform(-0.3, 0.3) for p, l, h in zip(path[0], lo, hi)]
            drag = [[x + (y - x) * i / 7 for x, y in zip(path[0], to)] for i in range(8)]
            out.append({"brush": "grab", "radius": r, "strength": 1.0, "path": drag})
    return out


def group(drawn, most, rng):
    """Groups the points of every paint stroke in `drawn` into frames of
    1 to `most` dabs (a grab follows its pointer one point a frame)."""
    for s in drawn:
        if s["brush"] == "grab":
            continue
        left, frames = len(s["path"]), []
        while left:
            k = min(left, rng.randint(1, most))
            frames.append(k)
            left -= k
        s["frames"] = frames


def fuzz_args(first_seed=100):
    """The options of the fuzz scripts: the holey binary and the shared
    folder, and which seeds and frame grouping to draw."""
    ap = sculpt_args()
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--first-seed", type=int, default=first_seed)
    ap.add_argument("--frames-of", type=int, default=1,
                    help="group each paint stroke's points into frames of 1 to N dabs, drawn at "
                         "random (\"frames\" in the stroke file), as the modeler sends the dabs "
                         "that queue while a frame is computed")
    return ap


def stroke_files(args, d):
    """For every shared mesh and seed of `args`: (name, path, seed, file),
    the strokes drawn for it written to `file` in the folder `d`."""
    for name, path in shared_meshes(args.shared, MESHES):
        points = used_points(path)
        for seed in range(args.first_seed, args.first_seed + args.seeds):
            file = os.path.join(d, f"s{seed}.json")
            rng = random.Random(seed)
            drawn = strokes(points, rng)
            if args.frames_of > 1:
                group(drawn, args.frames_of, rng)
            with open(file, "w") as fh:
                json.dump({"strokes": drawn}, fh)
            yield name, path, seed, file


def main():
    args = fuzz_args().parse_args()
    failures = 0
    # Why the guard held frames, by what would have got worse: strokes per reason.
    reasons = {}
    with tempfile.TemporaryDirectory() as d:
        for name, path, seed, file in stroke_files(args, d):
            p = subprocess.run([args.holey, "sculpt", path, file, os.path.join(d, "out.obj"), "--audit", "-v"],
                               capture_output=True, text=True)
            if p.returncode != 0:
                failures += 1
                print(f"{name} seed {seed}: exit {p.returncode}: {p.stderr.strip().splitlines()[-1:]}")
                continue
            worse = [line for line in p.stderr.splitlines() if "worse" in line.lower() and "held" not in line]
            held = sum(int(x) for x in re.findall(r"(\d+) guarded frame", p.stderr))
            specks = sum(int(x) for x in re.findall(r"(\d+) speck\(s\) of debris", p.stderr))
            for line in p.stderr.splitlines():
                if "held frames that would have left" in line:
                    for why in line.split("would have left", 1)[1].split(","):
                        why = why.strip().split(":")[0]
                        reasons[why] = reasons.get(why, 0) + 1
            if worse:
                failures += 1
                print(f"{name} seed {seed}: " + "; ".join(worse))
            else:
                taken = f", {specks} specks of debris taken out" if specks else ""
                print(f"{name} seed {seed}: ok ({held} guarded frames{taken})")
    for why, n in sorted(reasons.items(), key=lambda x: -x[1]):
        print(f"strokes held for {why}: {n}")
    print(f"failures: {failures}")


if __name__ == "__main__":
    main()
