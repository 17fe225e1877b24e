#!/usr/bin/env python3
"""How much identity a run loses to fragments (a person under several tracks in turn), and what
perfect re-identification or perfect association would score (docs/appearance.md, round 23).

Usage: fragments.py GT.txt RESULTS.txt --fps F --out DIR
  GT.txt       the sequence's MOTChallenge ground truth (rows with conf 0 ignored)
  RESULTS.txt  the tracker's MOTChallenge results (rtmot run --mot-results)
  --fps        the sequence's true frame rate (gaps are printed in seconds)
  --out        writes DIR/merged/NAME and DIR/perfect/NAME (NAME: RESULTS.txt's file name):
               merged  each track takes the id of the person it was matched to most often, so a
                       person's fragments become one track (perfect re-identification; a track
                       that went on with someone else keeps that someone else's rows)
               perfect each row matched to a person takes that person's id (no takeover either)
               Score them with `rtmot eval --gt <the gt folder> --results DIR/merged` (and
               DIR/perfect): upper bounds of what the two mechanisms could give on that run.

Each ground-truth person is matched to the tracker's boxes frame by frame (IoU >= 0.5, one to one,
greedy: scripts/crossing_frames.py's matching). A fragment join is two tracks of one person (by
the person each track matched most often) one after the other; printed by the gap between the
first's last frame on the person and the second's first (none or negative: the first was still
on the person when the second began). Research tooling (ground truth in ../shared); Python's
standard library only. Exit 1: unreadable input (the file and line named).
"""
import argparse
import os
import sys
from collections import Counter, defaultdict

from crossing_frames import match, read_boxes

GAP_BINS_S = (0.0, 0.5, 1.0, 2.0, 5.0)  # upper bounds; beyond the last, "more"


def read_rows(path):
    """frame -> [(id, the line's fields)] of a results file, for rewriting with other ids."""
    rows = defaultdict(list)
    with open(path) as f:
        for line_number, line in enumerate(f, 1):
            fields = line.strip().split(",")
            if len(fields) < 7:
                sys.exit(f"fragments.py: {path}:{line_number}: fewer than 7 fields")
            try:
                rows[int(fields[0])].append((int(fields[1]), fields))
            except ValueError:
                sys.exit(f"fragments.py: {path}:{line_number}: frame or id is not an integer")
    return rows


def write(path, rows, new_id, spare):
    """The results with each row's id replaced by new_id(frame, id); a second row of one frame on
    an id already taken there gets spare + its own id (an id is one box per frame)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        for frame in sorted(rows):
            taken = set()
            for track, fields in rows[frame]:
                chosen = new_id(frame, track)
                if chosen in taken:
                    chosen = spare + track
                taken.add(chosen)
                f.write(",".join([fields[0], str(chosen), *fields[2:]]) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("gt")
    parser.add_argument("results")
    parser.add_argument("--fps", type=float, required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    if args.fps <= 0:
        sys.exit(f"fragments.py: --fps must be positive, not {args.fps}")
    gt = read_boxes(args.gt, skip_ignored=True)
    ours = read_boxes(args.results, skip_ignored=False)
    rows = read_rows(args.results)

    person_of = {}  # (frame, track) -> person
    for frame, boxes in ours.items():
        for person, track in match(gt.get(frame, {}), boxes).items():
            person_of[(frame, track)] = person
    tally = defaultdict(Counter)
    for (frame, track), person in person_of.items():
        tally[track][person] += 1
    majority = {track: count.most_common(1)[0][0] for track, count in tally.items()}
    # People's ids shifted past every track id, so that no relabelled track meets an unmatched one;
    # a clash within a frame goes past those too.
    offset = 1 + max((i for frame_rows in rows.values() for i, _ in frame_rows), default=0)
    spare = offset + 1 + max(majority.values(), default=0)

    def merged(frame, track):
        return offset + majority[track] if track in majority else track

    def perfect(frame, track):
        person = person_of.get((frame, track))
        return offset + person if person is not None else merged(frame, track)

    name = os.path.basename(args.results)
    write(os.path.join(args.out, "merged", name), rows, merged, spare)
    write(os.path.join(args.out, "perfect", name), rows, perfect, spare)

    spans = defaultdict(list)  # person -> (first, last frame on them, track) of their tracks
    for track, person in majority.items():
        frames = sorted(f for (f, t), p in person_of.items() if t == track and p == person)
        spans[person].append((frames[0], frames[-1], track))
    gaps = []
    for person_spans in spans.values():
        person_spans.sort()
        for (_, last, _), (first, _, _) in zip(person_spans, person_spans[1:]):
            gaps.append((first - last) / args.fps)
    print(f"{len(majority)} tracks matched to {len(spans)} people: {len(gaps)} fragment joins")
    low = None
    for high in (*GAP_BINS_S, float("inf")):
        count = sum(1 for g in gaps if (g <= high if low is None else low < g <= high))
        label = f"<= {high:g} s (the first still on them)" if low is None else f"{low:g}-{high:g} s"
        print(f"  gap {label}: {count}")
        low = high
    print(f"relabelled results: {args.out}/merged/{name}, {args.out}/perfect/{name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
