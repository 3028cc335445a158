#!/usr/bin/env python3
"""Strokes the modeler recorded, replayed with their frames grouped at
random: how often a build keeps the surface in one piece (issue 15: a
stroke may split or join pieces only where it collides; the browser's
scenario 10 drags an inflate across the Stanford bunny's haunch and
deflates back, and wants one piece).

The page sends the dabs that queued while a frame was computed as one
frame, so how a stroke's dabs group depends on the machine's load. For
each seed, one of the recordings (round robin) has every stroke's path
regrouped into frames of 1 to K dabs, K drawn from 2, 4 and 8, keeping
each stroke's own remeshing range; every build given replays the same
file with `holey sculpt` on the shared bunny, and `holey info` counts
its pieces and genus. Usage:

    cargo build --release -p holey-cli
    python3 bench/sculpt/regroup_strokes.py [--seeds 0:60] [--holey A,B] [RECORDING.json ...]

Without recordings: `crates/sculpt/tests/data/bunny_haunch_deflate_in_frames_of_seven.json`
and `bench/sculpt/recorded/*.json` (scenario 10's strokes from browser
runs of stop 41, as `e2e/run.mjs` writes them). A build before stop 41
cannot read the strokes' own `remesh`.
"""
import glob, json, os, random, re, subprocess, sys, tempfile

from shared_obj import ROOT, sculpt_args

DEFAULT = [os.path.join(ROOT, "crates", "sculpt", "tests", "data",
                        "bunny_haunch_deflate_in_frames_of_seven.json")]
DEFAULT += sorted(glob.glob(os.path.join(ROOT, "bench", "sculpt", "recorded", "*.json")))


def regrouped(strokes, rng):
    """The strokes with each path cut into frames of 1 to K dabs."""
    out = []
    for s in strokes:
        s = dict(s)
        biggest = rng.choice([2, 4, 8])
        frames, left = [1], len(s["path"]) - 1
        while left > 0:
            k = min(left, rng.randint(1, biggest))
            frames.append(k)
            left -= k
        s["frames"] = frames
        out.append(s)
    return out


def shape(holey, bunny, strokes_path, out_path):
    """(pieces, genus) of the replay, or the first line of its error."""
    r = subprocess.run([holey, "sculpt", bunny, strokes_path, out_path], capture_output=True, text=True)
    if r.returncode != 0:
        return r.stderr.strip().splitlines()[0] if r.stderr.strip() else f"exit {r.returncode}"
    info = subprocess.run([holey, "info", out_path], capture_output=True, text=True).stdout
    pieces = re.search(r"components:\s+(\d+)", info)
    genus = re.search(r"genus:\s+(-?\d+)", info)
    return (int(pieces.group(1)) if pieces else None, int(genus.group(1)) if genus else None)


def main():
    ap = sculpt_args()
    ap.add_argument("--seeds", default="0:60", help="first:end (end excluded)")
    ap.add_argument("recordings", nargs="*", default=DEFAULT)
    args = ap.parse_args()
    bunny = os.path.join(args.shared, "data", "meshes", "stanford-bunny.obj")
    if not os.path.exists(bunny):
        sys.exit(f"{bunny}: not found (the shared meshes)")
    builds = args.holey.split(",")
    recordings = [json.load(open(p))["strokes"] for p in args.recordings]
    first, end = (int(x) for x in args.seeds.split(":"))
    one_piece = {b: 0 for b in builds}
    runs = 0
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(first, end):
            rng = random.Random(seed)
            strokes = regrouped(recordings[seed % len(recordings)], rng)
            path = os.path.join(tmp, "strokes.json")
            with open(path, "w") as fh:
                json.dump({"strokes": strokes}, fh)
            got = []
            for b in builds:
                s = shape(b, bunny, path, os.path.join(tmp, "out.obj"))
                if isinstance(s, tuple) and s[0] == 1:
                    one_piece[b] += 1
                got.append(f"{os.path.basename(b)}: {s}")
            runs += 1
            print(f"seed {seed} (recording {seed % len(recordings)}): " + "; ".join(got), flush=True)
    for b in builds:
        print(f"{b}: one piece in {one_piece[b]} of {runs}")


if __name__ == "__main__":
    main()
