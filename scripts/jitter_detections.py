#!/usr/bin/env python3
"""A recording's detections moved by a fraction of a pixel: a null change, for how much the
protocol's cells move when nothing that should matter changes (docs/appearance.md, "How far a
cell moves by chance").

Usage: jitter_detections.py FROM TO --px P --seed S
  FROM   a recording: a folder whose subfolders hold `*/mot/*.det.txt` (score_video.sh's run
         folders, e.g. a half_cells.sh OUT/off/head)
  TO     where the same tree is written with only the detection files (replay it with
         REPLAY_FROM: the run folders and their `mot/NAME.det.txt`)
  --px   each box's x, y, w and h move by a uniform amount in [-P, P] pixels, independently
  --seed the random generator's seed (the same seed, the same boxes)

Sub-pixel moves are far below the detector's own noise from one frame to the next (several
pixels), so any mechanism's verdict that they change is chance. Scores and every other field are
kept as written. Research tooling; Python's standard library only. Exit 2: unreadable input (the
file and line named), or FROM without recordings.
"""
import argparse
import glob
import os
import random

from score_table import fail


def jitter_file(source, target, px, rng):
    lines = []
    with open(source) as f:
        for number, line in enumerate(f, 1):
            fields = line.rstrip("\n").split(",")
            if len(fields) < 7:
                fail(f"{source}:{number}: a detection row needs at least 7 fields, got {len(fields)}")
            try:
                box = [float(v) for v in fields[2:6]]
            except ValueError:
                fail(f"{source}:{number}: x, y, w, h must be numbers")
            moved = [v + rng.uniform(-px, px) for v in box]
            moved[2] = max(moved[2], 1e-3)  # a box keeps a positive size
            moved[3] = max(moved[3], 1e-3)
            fields[2:6] = [f"{v:.5f}" for v in moved]
            lines.append(",".join(fields) + "\n")
    os.makedirs(os.path.dirname(target), exist_ok=True)
    with open(target, "w") as f:
        f.writelines(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source")
    parser.add_argument("target")
    parser.add_argument("--px", type=float, required=True)
    parser.add_argument("--seed", type=int, required=True)
    args = parser.parse_args()
    if not args.px >= 0:
        fail(f"--px must be at least 0, not {args.px}")
    files = sorted(glob.glob(os.path.join(args.source, "*", "mot", "*.det.txt")))
    if not files:
        fail(f"{args.source}: no */mot/*.det.txt recordings")
    rng = random.Random(args.seed)
    for source in files:
        relative = os.path.relpath(source, args.source)
        jitter_file(source, os.path.join(args.target, relative), args.px, rng)
    print(f"jitter_detections.py: {len(files)} recordings moved by up to {args.px} px into {args.target}")


if __name__ == "__main__":
    main()
