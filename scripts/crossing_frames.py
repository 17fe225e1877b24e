#!/usr/bin/env python3
"""Crossings of two people in the ground truth, and whether the tracker kept their ids.

Usage: crossing_frames.py GT_SEQ RESULTS.txt OUT [--video-raw] [--kept N] [--not-kept N]
  GT_SEQ       a MOTChallenge sequence folder (gt/gt.txt, seqinfo.ini)
  RESULTS.txt  the tracker's MOTChallenge results for it (rtmot run --mot-results)
  OUT          writes OUT/crossings.tsv, and with --video-raw OUT/crossing-kept.jpg and
               OUT/crossing-not-kept.jpg
  --video-raw  standard input is the run's annotated video decoded to raw RGBx frames of the
               sequence's size (scripts/crossing_frames.sh pipes gst-launch-1.0 into it); frame i of
               it is frame i of the ground truth
  --kept N, --not-kept N   draw crossing number N of the table instead of the one chosen

A crossing: two ground-truth people whose boxes overlap (IoU >= 0.3, or the centre of one inside
the other) in a run of frames (runs less than GAP frames apart are one), both present from WINDOW
frames before the run to WINDOW frames after it. Each person is matched, frame by frame, to the
tracker's boxes (IoU >= 0.5, one to one, greedy by IoU: at these overlaps the same as an optimal
assignment); their id before is the id matched most often in the WINDOW frames before the run, after
in the WINDOW frames after it. Classes, first that applies:
  untracked   one of them had no id before (the tracker did not have them: not a crossing it could keep)
  swapped     one of them has the other's id after
  lost        one of them has no id after
  fragmented  one of them has a new id after
  kept        both have their ids
Research tooling (the ground truth lies in ../shared): the product never runs it.
"""
import argparse
import configparser
import os
import sys
from collections import Counter, defaultdict

from box_iou import iou

OVERLAP_IOU, MATCH_IOU, WINDOW, GAP = 0.3, 0.5, 7, 3
SCALE, MARGIN = 2, 24


def read_boxes(path, skip_ignored, by_id=True):
    """frame -> {id: (x, y, w, h)} from a MOTChallenge file; gt rows with conf 0 are ignored.
    by_id=False: frame -> [(x, y, w, h)], for a det.txt (whose ids are all -1)."""
    frames = defaultdict(dict if by_id else list)
    with open(path) as f:
        for line_number, line in enumerate(f, 1):
            fields = line.strip().split(",")
            if len(fields) < 7:
                sys.exit(f"{os.path.basename(sys.argv[0])}: {path}:{line_number}: fewer than 7 fields")
            if skip_ignored and float(fields[6]) == 0:
                continue
            box = tuple(float(v) for v in fields[2:6])
            if by_id:
                frames[int(fields[0])][int(fields[1])] = box
            else:
                frames[int(fields[0])].append(box)
    return frames


def centre_inside(a, b):
    cx, cy = a[0] + a[2] / 2, a[1] + a[3] / 2
    return b[0] <= cx <= b[0] + b[2] and b[1] <= cy <= b[1] + b[3]


def overlapping(a, b):
    return iou(a, b) >= OVERLAP_IOU or centre_inside(a, b) or centre_inside(b, a)


def match(gt_boxes, our_boxes):
    """gt id -> our id, one to one, greedy by IoU among pairs with IoU >= MATCH_IOU."""
    pairs = sorted(((iou(g, o), gid, oid) for gid, g in gt_boxes.items()
                    for oid, o in our_boxes.items()), reverse=True)
    matched, used = {}, set()
    for value, gid, oid in pairs:
        if value < MATCH_IOU:
            break
        if gid not in matched and oid not in used:
            matched[gid] = oid
            used.add(oid)
    return matched


def find_crossings(gt, length):
    runs = defaultdict(list)  # (a, b) -> [[first, last], ...]
    for frame in range(1, length + 1):
        people = sorted(gt.get(frame, {}).items())
        for i, (a, box_a) in enumerate(people):
            for b, box_b in people[i + 1:]:
                if overlapping(box_a, box_b):
                    pair_runs = runs[(a, b)]
                    if pair_runs and frame - pair_runs[-1][1] <= GAP:
                        pair_runs[-1][1] = frame
                    else:
                        pair_runs.append([frame, frame])
    crossings = []
    for (a, b), pair_runs in runs.items():
        for first, last in pair_runs:
            before, after = first - WINDOW, last + WINDOW
            if before < 1 or after > length:
                continue
            if not all(a in gt.get(f, {}) and b in gt.get(f, {}) for f in range(before, after + 1)):
                continue
            peak = max(range(first, last + 1),
                       key=lambda f: iou(gt[f][a], gt[f][b]) if a in gt[f] and b in gt[f] else -1)
            crossings.append(dict(a=a, b=b, first=first, last=last, peak=peak,
                                  peak_iou=iou(gt[peak][a], gt[peak][b])))
    crossings.sort(key=lambda c: (c["first"], c["a"], c["b"]))
    return crossings


def usual_id(gt, ours, person, frames):
    ids = Counter(match(gt.get(f, {}), ours.get(f, {})).get(person) for f in frames)
    ids.pop(None, None)
    return ids.most_common(1)[0][0] if ids else None


def windows(crossing):
    return (range(crossing["first"] - WINDOW, crossing["first"]),
            range(crossing["last"] + 1, crossing["last"] + WINDOW + 1))


def showing(gt, ours, c, frames, when):
    """The frames where both people have the ids the table gives them (`when`: before or after)."""
    def agrees(f):
        matched = match(gt.get(f, {}), ours.get(f, {}))
        return all(matched.get(c[p]) == c[f"{p}_{when}"] for p in ("a", "b"))
    return [f for f in frames if agrees(f)]


def classify(gt, ours, crossing):
    before_frames, after_frames = windows(crossing)
    for person in ("a", "b"):
        crossing[person + "_before"] = usual_id(gt, ours, crossing[person], before_frames)
        crossing[person + "_after"] = usual_id(gt, ours, crossing[person], after_frames)
    # The figure's frames: the earliest before and the latest after where both show those ids
    # (the ids of a window's every frame need not agree: a detection missed, a track not yet born).
    before_shown = showing(gt, ours, crossing, before_frames, "before")
    after_shown = showing(gt, ours, crossing, after_frames, "after")
    crossing["panels"] = [("before", before_shown[0] if before_shown else before_frames[0]),
                          ("crossing", crossing["peak"]),
                          ("after", after_shown[-1] if after_shown else after_frames[-1])]
    both_at_peak = len(match(gt[crossing["peak"]], ours.get(crossing["peak"], {}))
                       .keys() & {crossing["a"], crossing["b"]}) == 2
    # How clearly a figure of it would show its class: frames agreeing with the table, both seen at the peak.
    crossing["clarity"] = len(before_shown) + len(after_shown) + WINDOW * both_at_peak
    before = (crossing["a_before"], crossing["b_before"])
    after = (crossing["a_after"], crossing["b_after"])
    if None in before or before[0] == before[1]:
        return "untracked"
    if after[0] == before[1] or after[1] == before[0]:
        return "swapped"
    if None in after:
        return "lost"
    if after != before:
        return "fragmented"
    return "kept"


def shown(value):
    return "-" if value is None else f"#{value}"


def write_table(crossings, path):
    header = ["n", "gt_a", "gt_b", "before", "overlap", "peak", "after", "peak_iou",
              "a_ids", "b_ids", "class"]
    rows = []
    for n, c in enumerate(crossings, 1):
        rows.append([str(n), str(c["a"]), str(c["b"]), str(c["first"] - WINDOW),
                     f"{c['first']}-{c['last']}", str(c["peak"]), str(c["last"] + WINDOW),
                     f"{c['peak_iou']:.2f}",
                     f"{shown(c['a_before'])}>{shown(c['a_after'])}",
                     f"{shown(c['b_before'])}>{shown(c['b_after'])}", c["class"]])
    with open(path, "w") as f:
        f.write("\t".join(header) + "\n")
        f.writelines("\t".join(r) + "\n" for r in rows)
    widths = [max(len(x) for x in column) for column in zip(header, *rows)]
    for r in [header] + rows:
        print("  ".join(x.ljust(w) for x, w in zip(r, widths)).rstrip())


def choose(crossings, classes, override):
    if override:
        if not 1 <= override <= len(crossings):
            sys.exit(f"crossing_frames.py: no crossing number {override} (1..{len(crossings)})")
        return override
    candidates = [(c["clarity"], c["peak_iou"], n) for n, c in enumerate(crossings, 1)
                  if c["class"] in classes]
    return max(candidates)[2] if candidates else None


def crop_of(gt, c, size):
    """One crop for all panels: both people over the whole crossing, with a margin."""
    boxes = [gt[f][p] for f in range(c["first"] - WINDOW, c["last"] + WINDOW + 1) for p in (c["a"], c["b"])]
    left = max(0, int(min(b[0] for b in boxes)) - MARGIN)
    top = max(0, int(min(b[1] for b in boxes)) - MARGIN - 20)  # room for the id labels above
    right = min(size[0], int(max(b[0] + b[2] for b in boxes)) + MARGIN)
    bottom = min(size[1], int(max(b[1] + b[3] for b in boxes)) + MARGIN)
    return left, top, right, bottom


def draw_strip(frames, gt, c, n, size, path):
    from PIL import Image, ImageDraw

    crop = crop_of(gt, c, size)
    panels = []
    for label, frame in c["panels"]:
        image = frames[frame].crop(crop)
        panels.append((label, frame, image.resize((image.width * SCALE, image.height * SCALE),
                                                  Image.LANCZOS)))
    caption_h, gap = 18, 6
    width = sum(p[2].width for p in panels) + gap * (len(panels) - 1)
    height = panels[0][2].height + 2 * caption_h
    strip = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(strip)
    x = 0
    for label, frame, image in panels:
        strip.paste(image, (x, caption_h))
        draw.text((x + 4, 3), f"frame {frame} ({label})", fill="black")
        x += image.width + gap
    draw.text((4, height - caption_h + 3),
              f"crossing {n}: gt {c['a']} {shown(c['a_before'])} -> {shown(c['a_after'])}, "
              f"gt {c['b']} {shown(c['b_before'])} -> {shown(c['b_after'])}: {c['class']}",
              fill="black")
    strip.save(path, quality=85, optimize=True)
    print(f"wrote {path} ({os.path.getsize(path) // 1024} KiB)")


def read_frames(size, wanted, length):
    from PIL import Image

    frame_bytes = size[0] * size[1] * 4
    frames, count = {}, 0
    while True:
        data = sys.stdin.buffer.read(frame_bytes)
        if not data:
            break
        if len(data) < frame_bytes:
            sys.exit(f"crossing_frames.py: the video ends inside frame {count + 1}")
        count += 1
        if count in wanted:
            frames[count] = Image.frombytes("RGB", size, data, "raw", "RGBX")
    if count != length:
        sys.exit(f"crossing_frames.py: the video has {count} frames, the ground truth {length}: "
                 "frame i of the video would not be frame i of the ground truth")
    return frames


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("gt_seq")
    parser.add_argument("results")
    parser.add_argument("out")
    parser.add_argument("--video-raw", action="store_true")
    parser.add_argument("--kept", type=int, default=0)
    parser.add_argument("--not-kept", type=int, default=0)
    args = parser.parse_args()

    info = configparser.ConfigParser()
    if not info.read(os.path.join(args.gt_seq, "seqinfo.ini")):
        sys.exit(f"crossing_frames.py: {args.gt_seq}/seqinfo.ini missing")
    seq = info["Sequence"]
    length, size = int(seq["seqLength"]), (int(seq["imWidth"]), int(seq["imHeight"]))
    gt = read_boxes(os.path.join(args.gt_seq, "gt", "gt.txt"), skip_ignored=True)
    ours = read_boxes(args.results, skip_ignored=False)

    crossings = find_crossings(gt, length)
    if not crossings:
        sys.exit("crossing_frames.py: no crossing found in the ground truth")
    for c in crossings:
        c["class"] = classify(gt, ours, c)
    write_table(crossings, os.path.join(args.out, "crossings.tsv"))
    counts = Counter(c["class"] for c in crossings)
    tracked = len(crossings) - counts["untracked"]
    print(f"crossings {len(crossings)}: tracked before {tracked}: " + ", ".join(
        f"{k} {counts[k]}" for k in ("kept", "swapped", "fragmented", "lost")) +
        f"; untracked {counts['untracked']}")
    if not args.video_raw:
        return

    kept = choose(crossings, {"kept"}, args.kept)
    # Not kept: a swap if there is one (the failure the figure is about), else a new id, else a loss.
    not_kept = args.not_kept or next(filter(None, (choose(crossings, {k}, 0)
                                                   for k in ("swapped", "fragmented", "lost"))), None)
    chosen = [(n, name) for n, name in ((kept, "kept"), (not_kept, "not-kept")) if n]
    wanted = {f for n, _ in chosen for _, f in crossings[n - 1]["panels"]}
    frames = read_frames(size, wanted, length)
    for n, name in chosen:
        draw_strip(frames, gt, crossings[n - 1], n, size, os.path.join(args.out, f"crossing-{name}.jpg"))
    missing = {"kept", "not-kept"} - {name for _, name in chosen}
    if missing:
        sys.exit(f"crossing_frames.py: no crossing of class {' or '.join(sorted(missing))} to draw")


if __name__ == "__main__":
    main()
