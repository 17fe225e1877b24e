#!/usr/bin/env python3
"""Group boxes: one detection drawn around two people, matching neither.

Usage: group_boxes.py GT.txt DET.txt [--from N] [--to N]
  GT.txt   the sequence's MOTChallenge ground truth (rows with conf 0 ignored)
  DET.txt  the detections the tracker got (rtmot run --mot-results DIR --mot-detections true:
           DIR/NAME.det.txt)
  --from, --to  frames N.. and ..N only (e.g. a first half)

A group box covers at least half of each of two people's boxes (takeovers.py's merged box) and has
IoU < 0.5 with every person it covers: a box that matches one person and overlaps another is not
one. For each, whether the frame's other detections found the two people apart (IoU >= 0.5), and
how many of them lie inside it (60 % of their area): what a rule dropping group boxes in favour of
the people inside would see. Also how often such a rule (two other detections inside a box) would
fire on a box that does match a person. Research tooling (the ground truth lies in ../shared): the
product never runs it. Python's standard library only.
"""
import argparse
from collections import Counter, defaultdict

from box_iou import iou
from crossing_frames import read_boxes
from takeovers import MERGED_SHARE, covered

MATCH_IOU = 0.5
INSIDE = 0.6


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gt")
    parser.add_argument("detections")
    parser.add_argument("--from", dest="first", type=int, default=1)
    parser.add_argument("--to", dest="last", type=int, default=10**9)
    args = parser.parse_args()
    gt = read_boxes(args.gt, skip_ignored=True)
    detections = read_boxes(args.detections, skip_ignored=False, by_id=False)
    counts = Counter()
    for frame, boxes in sorted(detections.items()):
        if not args.first <= frame <= args.last:
            continue
        people = list(gt.get(frame, {}).values())
        counts["detections"] += len(boxes)
        for i, box in enumerate(boxes):
            others = boxes[:i] + boxes[i + 1:]
            inside = sum(covered(o, box) >= INSIDE for o in others)
            matches_someone = any(iou(p, box) >= MATCH_IOU for p in people)
            if inside >= 2:
                counts["a rule would fire: on a box matching a person" if matches_someone
                       else "a rule would fire: on a box matching no one"] += 1
            covering = [p for p in people if covered(p, box) >= MERGED_SHARE]
            if len(covering) < 2 or matches_someone:
                continue
            counts["group boxes"] += 1
            found = sum(any(iou(p, o) >= MATCH_IOU for o in others) for p in covering[:2])
            counts[f"group boxes: the two people found apart: {found}"] += 1
            counts[f"group boxes: detections inside: {min(inside, 3)}{'+' if inside >= 3 else ''}"] += 1
    for key in sorted(counts):
        print(f"{counts[key]:6d}  {key}")


if __name__ == "__main__":
    main()
