#!/usr/bin/env python3
"""Which of a run's covered detections hide someone, against the ground truth (docs/appearance.md,
"Where the models' sightings go").

Usage: covered_sightings.py GT.txt DETECTIONS.txt [--last N] [--without-second-boxes OUT]
  GT.txt          the sequence's MOTChallenge ground truth (rows with conf 0 ignored)
  DETECTIONS.txt  the detections the tracker got (rtmot run --mot-detections true: NAME.det.txt)
  --last N        frames 1..N only (e.g. a first half)
  --without-second-boxes OUT
                  instead, write the detections (frames 1..N with --last) to OUT without their
                  second boxes: a detection nearest (IoU >= 0.2) to a person whose own detection
                  (IoU >= 0.5) is another one, which it covers by more than a tenth. An oracle (the
                  ground truth decides), for what a detector without them would give: replay OUT.

The tracker learns no appearance from a detection that another detection of the frame covers by
more than a tenth (tracker/association_rounds.cpp's kOccludedShare). For each such detection that
is a person (IoU >= 0.5 with a ground-truth box, the best one), this says whether the cover is
real (another person's ground-truth box covers a tenth of theirs) or not (the cover is a false box
or a second box on the same person), and for both rows the share that simple rules on the
covering boxes would keep (RULES: scores, the cores the signature reads, containment); and what
the false covers are.
Research tooling (the ground truth lies in ../shared): the product never runs it. Python's
standard library only. Exit 2: unreadable input (the file and line named).
"""
import argparse
import os
import sys
from collections import Counter, defaultdict

from box_iou import covered_share, iou

COVERED_SHARE = 0.1  # tracker/association_rounds.cpp's kOccludedShare
MATCH_IOU = 0.5


def fail(message):
    print(f"{os.path.basename(sys.argv[0])}: {message}", file=sys.stderr)
    sys.exit(2)


def read_rows(path, skip_ignored, last):
    """frame -> [(id, (x, y, w, h), score or conf, the line)] of a MOTChallenge file."""
    frames = defaultdict(list)
    try:
        with open(path) as f:
            for line_number, line in enumerate(f, 1):
                fields = line.strip().split(",")
                try:
                    if len(fields) < 7:
                        raise ValueError("fewer than 7 fields")
                    frame, confidence = int(float(fields[0])), float(fields[6])
                    box = tuple(float(v) for v in fields[2:6])
                    identity = int(float(fields[1]))
                except ValueError as problem:
                    fail(f"{path}:{line_number}: {problem}")
                if (skip_ignored and confidence == 0) or (last and frame > last):
                    continue
                frames[frame].append((identity, box, confidence, line))
    except OSError as problem:
        fail(f"{path}: {problem.strerror}")
    return frames


def person_of(box, people):
    """The ground-truth (id, box) best overlapping `box` at MATCH_IOU or more, or None."""
    best = max(people, key=lambda person: iou(person[1], box), default=None)
    return best if best is not None and iou(best[1], box) >= MATCH_IOU else None


def cover_kind(cover, person, people):
    """What a covering box is, where the person it covers stands clear of everyone else."""
    its_person = person_of(cover, people)
    if its_person is not None:
        return ("a second box on the same person" if its_person[0] == person[0] else
                "another person's box (their annotated boxes overlap by a tenth or less)")
    nearest = max(people, key=lambda other: iou(other[1], cover), default=None)
    if nearest is not None and iou(nearest[1], cover) >= 0.2:
        return ("a poor second box on the same person (IoU 0.2-0.5)" if nearest[0] == person[0] else
                "a poor box on another person (IoU 0.2-0.5)")
    return "a false box (IoU below 0.2 with every annotated box)"


def core(box):
    """The part of a box the colour signature reads (vision/colour_signature.hpp): the middle half
    of its width, from 12 % to 85 % of its height."""
    return (box[0] + 0.25 * box[2], box[1] + 0.12 * box[3], 0.5 * box[2], 0.73 * box[3])


RULES = (
    ("the covers all score lower", lambda d, covers: all(c[2] < d[2] for c in covers)),
    ("no cover's core covers a tenth of its core",
     lambda d, covers: all(covered_share(core(d[1]), core(c[1])) <= COVERED_SHARE
                           for c in covers)),
    ("the covers all score below 0.5", lambda d, covers: all(c[2] < 0.5 for c in covers)),
    ("the covers all lie 60 % inside it",
     lambda d, covers: all(covered_share(c[1], d[1]) >= 0.6 for c in covers)),
)


def second_boxes(rows, people):
    """The indices of `rows` that are a second box on someone: nearest (IoU >= 0.2) to a person
    whose own detection (IoU >= MATCH_IOU, the best) is another row, which they cover by more than
    a tenth."""
    second = set()
    for identity, box in people:
        own = max(range(len(rows)), key=lambda r: iou(rows[r][1], box), default=None)
        if own is None or iou(rows[own][1], box) < MATCH_IOU:
            continue
        for r, row in enumerate(rows):
            nearest = max(people, key=lambda person: iou(person[1], row[1]))
            if (r != own and nearest[0] == identity and iou(nearest[1], row[1]) >= 0.2 and
                    covered_share(rows[own][1], row[1]) > COVERED_SHARE):
                second.add(r)
    return second


def write_without_second_boxes(gt, detections, path):
    """An oracle's detections (the ground truth decides): the file without its second boxes."""
    removed = 0
    try:
        with open(path, "w") as out:
            for frame in sorted(detections):
                rows = detections[frame]
                second = second_boxes(rows, [(row[0], row[1]) for row in gt.get(frame, [])])
                removed += len(second)
                out.writelines(row[3].rstrip("\n") + "\n"
                               for r, row in enumerate(rows) if r not in second)
    except OSError as problem:
        fail(f"{path}: {problem.strerror}")
    print(f"wrote {path}: {removed} second boxes left out")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("gt")
    parser.add_argument("detections")
    parser.add_argument("--last", type=int, default=0)
    parser.add_argument("--without-second-boxes", metavar="OUT")
    args = parser.parse_args()
    gt = read_rows(args.gt, skip_ignored=True, last=args.last)
    detections = read_rows(args.detections, skip_ignored=False, last=args.last)
    if args.without_second_boxes:
        write_without_second_boxes(gt, detections, args.without_second_boxes)
        return 0
    counts = Counter()
    kinds = Counter()
    for frame, rows in detections.items():
        people = [(row[0], row[1]) for row in gt.get(frame, [])]
        for index, detection in enumerate(rows):
            counts["detections"] += 1
            covers = [other for j, other in enumerate(rows)
                      if j != index and covered_share(detection[1], other[1]) > COVERED_SHARE]
            if not covers:
                counts["clear"] += 1
                continue
            person = person_of(detection[1], people)
            if person is None:
                continue
            real = any(other_id != person[0] and covered_share(person[1], other) > COVERED_SHARE
                       for other_id, other in people)
            row = "real" if real else "false"
            counts[row] += 1
            for name, keeps in RULES:
                counts[(row, name)] += keeps(detection, covers)
            if not real:
                for cover in covers:
                    kinds[cover_kind(cover[1], person, people)] += 1
    print(f"{counts['detections']} detections, {counts['clear']} covered by no other")
    print("covered detections of a person | the cover is real | the cover is a false or duplicate box")
    print(f"count | {counts['real']} | {counts['false']}")
    for name, _ in RULES:
        shares = [counts[(row, name)] / counts[row] if counts[row] else 0.0 for row in ("real", "false")]
        print(f"{name} | {shares[0]:.0%} | {shares[1]:.0%}")
    print("the false covers (one detection may have several):")
    for kind, count in kinds.most_common():
        print(f"  {kind}: {count}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
