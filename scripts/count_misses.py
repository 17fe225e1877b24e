#!/usr/bin/env python3
"""Why counts are missed when frames are skipped: what a tracker reported around each crossing.

For each sequence of a MOTChallenge dataset, the ground truth is kept at the processed frames 1,
1+N, 1+2N, ... (the study's floor, docs/events.md). A crossing step is a person whose feet (bottom
centre) change side of a line between two consecutive processed frames, more than 2 px from it at
both ends (the counter's fixed band). The study's lines: the vertical middle line and the horizontal
line at 3/4 of the height (configs/counting/mot15-lines.yaml), whole width and height. Each step is
classed by the tracker's reported boxes at its two frames (IoU >= 0.4 with the person's box):

  same id          one track reported at both ends: the counter can count it
  different ids    reported at both ends under two ids: the track broke across the crossing
  one end only     reported at one end only
  neither end      reported at neither end

and each end without a reported track by whether the public detections had the person there (IoU >=
0.4): detected but not reported is the tracker's doing (a track not confirmed, or not associated
across the gap); not detected is the detector's.

Ground-truth rows with conf 0 are left out (MOT15's ground truth has no classes: its columns 8-10
are world coordinates). A diagnosis, not the study's metric: the counter's hysteresis and pending crossings are left out.
Usage: count_misses.py DATASET RESULTS_DIR INTERVAL    (RESULTS_DIR: `rtmot track --out`)
Python's standard library only.
"""
import collections
import configparser
import os
import sys

from box_iou import iou

KINDS = ["same id", "different ids", "one end only", "neither end"]
BAND_PX = 2.0
MIN_IOU = 0.4


def read_rows(path, keep):
    """{frame: [(id, box)]} of a MOTChallenge file, rows for which keep(fields) holds."""
    rows = collections.defaultdict(list)
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.strip().split(",")
            if len(fields) < 6:
                sys.exit(f"count_misses.py: {path}:{number}: expected 6 or more fields")
            if keep(fields):
                rows[int(fields[0])].append((int(float(fields[1])), [float(x) for x in fields[2:6]]))
    return rows


def best_id(candidates, box):
    best, found = MIN_IOU, None
    for track_id, other in candidates:
        value = iou(box, other)
        if value >= best:
            best, found = value, track_id
    return found


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    dataset, results, interval = sys.argv[1], sys.argv[2], int(sys.argv[3])
    totals = collections.Counter()
    for sequence in sorted(os.listdir(dataset)):
        info = configparser.ConfigParser()
        if not info.read(os.path.join(dataset, sequence, "seqinfo.ini")):
            continue
        width = float(info["Sequence"]["imWidth"])
        height = float(info["Sequence"]["imHeight"])
        processed = lambda f: (int(f[0]) - 1) % interval == 0
        truth = read_rows(os.path.join(dataset, sequence, "gt", "gt.txt"),
                          lambda f: processed(f) and float(f[6]) != 0)
        detections = read_rows(os.path.join(dataset, sequence, "det", "det.txt"), processed)
        tracks_file = os.path.join(results, sequence + ".txt")
        if not os.path.exists(tracks_file):
            sys.exit(f"count_misses.py: {tracks_file} missing")
        tracks = read_rows(tracks_file, lambda f: True)
        people = collections.defaultdict(dict)
        for frame, boxes in truth.items():
            for person, box in boxes:
                people[person][frame] = box
        lines = {"middle": lambda b: b[0] + b[2] / 2 - width / 2,
                 "low": lambda b: b[1] + b[3] - 0.75 * height}
        for frames in people.values():
            ordered = sorted(frames)
            for a, b in zip(ordered, ordered[1:]):
                if b - a != interval:
                    continue
                for side in lines.values():
                    before, after = side(frames[a]), side(frames[b])
                    if abs(before) <= BAND_PX or abs(after) <= BAND_PX or (before > 0) == (after > 0):
                        continue
                    id_a = best_id(tracks.get(a, []), frames[a])
                    id_b = best_id(tracks.get(b, []), frames[b])
                    if id_a is not None and id_b is not None:
                        kind = "same id" if id_a == id_b else "different ids"
                    elif id_a is None and id_b is None:
                        kind = "neither end"
                    else:
                        kind = "one end only"
                    totals[kind] += 1
                    for frame, found in ((a, id_a), (b, id_b)):
                        if found is None:
                            seen = best_id(detections.get(frame, []), frames[frame]) is not None
                            totals["detected" if seen else "not detected"] += 1
    steps = sum(totals[k] for k in KINDS)
    print(f"interval {interval}: {steps} crossing steps of the ground truth at the processed frames")
    for kind in KINDS:
        print(f"  {kind:14s} {totals[kind]:5d}  {100.0 * totals[kind] / max(steps, 1):5.1f} %")
    ends = totals["detected"] + totals["not detected"]
    print(f"  ends without a reported track: {ends}, of them detected {totals['detected']} "
          f"({100.0 * totals['detected'] / max(ends, 1):.0f} %), not detected {totals['not detected']}")


if __name__ == "__main__":
    main()
