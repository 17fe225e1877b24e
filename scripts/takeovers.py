#!/usr/bin/env python3
"""Where a track goes on with another person: each takeover in a run, and who had that person.

Usage: takeovers.py GT.txt RESULTS.txt [--from N] [--to N] [--detections DET.txt] [--list]
  GT.txt       the sequence's MOTChallenge ground truth (rows with conf 0 ignored)
  RESULTS.txt  the tracker's MOTChallenge results (rtmot run --mot-results)
  --from, --to score frames N.. and ..N only (e.g. a first half)
  --detections the detections the tracker got in that run (rtmot run --mot-detections true:
               NAME.det.txt): also count the takeovers with a merged box, one detection covering
               at least half of each of the two people's boxes, from the frame before the track's
               last frame on A to f2
  --list       also print every takeover

Each ground-truth person is matched to the tracker's boxes frame by frame (IoU >= 0.5, one to one,
greedy by IoU: scripts/crossing_frames.py's matching). A takeover is a track matched to person A
and, at its next matched frame f2, to another person B. It is classed by B's own track: the track
matched to B in the 7 frames before f2 (the nearest), if any:

  B untracked before       no track had B in those frames
  B's track lost them      B's track is matched to no one at f2
  B's track took A         a swap: B's track is on A at f2
  B's track on a third     B's track is on someone else at f2

and, apart, by how long the track was matched to no one between its last frame on A and f2, and
whether A and B overlapped (IoU >= 0.2) in the 3 frames before f2. Research tooling (the ground
truth lies in ../shared): the product never runs it. Python's standard library only.
"""
import argparse
import sys
from collections import Counter, defaultdict

from box_iou import covered_share, iou
from crossing_frames import match, read_boxes

LOOK_BACK = 7        # frames before a takeover searched for the taken person's own track
NEAR_FRAMES = 3      # frames before a takeover in which the two people may overlap
NEAR_IOU = 0.2
MERGED_SHARE = 0.5   # of each person's box inside one detection


def merged_box_between(gt, detections, a, b, first, last):
    """Whether one detection covers MERGED_SHARE of both a's and b's boxes in a frame first..last."""
    for f in range(first, last + 1):
        if a not in gt.get(f, {}) or b not in gt.get(f, {}):
            continue
        if any(covered_share(gt[f][a], d) >= MERGED_SHARE and covered_share(gt[f][b], d) >= MERGED_SHARE
               for d in detections.get(f, [])):
            return True
    return False


def gap_class(gap):
    if gap == 0:
        return "the frame after"
    return "after 1-2 frames" if gap <= 2 else "after 3-7 frames" if gap <= 7 else "after 8+ frames"


def takeovers(gt, ours, first, last):
    """[(f2, track, a, b, gap, kind, apart)] for every takeover in frames first..last."""
    matched = {f: match(gt.get(f, {}), ours.get(f, {})) for f in range(first, last + 1)}
    owner = {(f, person): track for f, m in matched.items() for person, track in m.items()}
    history = defaultdict(list)  # track -> [(frame, person)]
    for f in range(first, last + 1):
        for person, track in matched[f].items():
            history[track].append((f, person))
    found = []
    for track, seen in history.items():
        for (f1, a), (f2, b) in zip(seen, seen[1:]):
            if a == b:
                continue
            before = next((owner[(f, b)] for f in range(f2 - 1, max(first, f2 - LOOK_BACK) - 1, -1)
                           if (f, b) in owner), None)
            if before is None:
                kind = "B untracked before"
            else:
                on_now = [p for p, t in matched[f2].items() if t == before]
                kind = ("B's track lost them" if not on_now else
                        "B's track took A" if on_now == [a] else "B's track on a third")
            near = max((iou(gt[f][a], gt[f][b]) for f in range(max(first, f2 - NEAR_FRAMES), f2 + 1)
                        if a in gt.get(f, {}) and b in gt.get(f, {})), default=0.0)
            found.append((f2, track, a, b, f2 - f1 - 1, kind, near < NEAR_IOU, f1))
    return sorted(found)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("gt")
    parser.add_argument("results")
    parser.add_argument("--from", dest="first", type=int, default=1)
    parser.add_argument("--to", dest="last", type=int, default=None)
    parser.add_argument("--detections")
    parser.add_argument("--list", action="store_true")
    args = parser.parse_args()
    gt = read_boxes(args.gt, True)
    ours = read_boxes(args.results, False)
    if not gt:
        sys.exit(f"takeovers.py: {args.gt}: no ground-truth rows")
    last = args.last if args.last is not None else max(gt)
    found = takeovers(gt, ours, args.first, last)
    if args.list:
        for f2, track, a, b, gap, kind, apart, _ in found:
            print(f"frame {f2}: track {track} from person {a} to {b}, {gap} frames between, {kind}, "
                  f"{'apart' if apart else 'overlapping'}")
    print(f"{len(found)} takeovers in frames {args.first}-{last}")
    for title, key in (("by the taken person's own track", 5), ("by the time between", 4),
                       ("by the two people", 6)):
        counts = Counter(gap_class(t[key]) if key == 4 else
                         ("apart" if t[key] else "overlapping") if key == 6 else t[key] for t in found)
        print(f"{title}: " + ", ".join(f"{k} {v}" for k, v in counts.most_common()))
    if args.detections:
        rows = read_boxes(args.detections, False, by_id=False)
        merged = sum(merged_box_between(gt, rows, t[2], t[3], max(args.first, t[7] - 1), t[0])
                     for t in found)
        print(f"with a merged box (one detection over half of each person) between: {merged} of "
              f"{len(found)}")


if __name__ == "__main__":
    main()
