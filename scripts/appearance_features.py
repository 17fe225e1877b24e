#!/usr/bin/env python3
"""Which appearance tells a sequence's people apart across a gap? (docs/appearance.md, "Features the
SSD already computed" and "Other colour statistics and a texture").

For every ground-truth person no other person covers (> 10 % of their box, the tracker's rule for
learning), this measures
  - `colour`: vision::ColourSignature's histogram (the same core, bins and thresholds, re-implemented
    here with OpenCV's Python binding; its figure one frame apart matches the C++ test's);
  - the SSD's own feature maps (the model rtmot runs, whole frame to 300x300), averaged over the cells
    whose centres fall in the same core of the box, L2-normalised, compared by cosine distance;
  - other colour statistics of the same core (COLOUR_KINDS: soft bins, 16 hues, three parts, joint
    BGR and Lab histograms) and a texture (gradient orientations), by the Hellinger distance;
  - `A+B`: the mean of two distances (default: colour+ssd-10x10x1280).
`--descriptors` chooses which (default: the signature and the SSD's maps).
Then, for each gap of L frames: every person seen clear at frame t and again at t + L is a query; the
gallery is everyone seen clear at t, each by their model at t (`--models`: `ema`, the tracker's
exponential average, 0.9 kept per sighting; `galleryK`, their last K clear sightings, the nearest
counting, as DeepSORT keeps its gallery). Printed per descriptor, model and gap: rank-1 (the
nearest model is the person's own), rank-1 with the re-identification margin (and the next is at
least 0.1 further), and the AUC of own-against-other distances (scale-free).

Research tooling: needs ground truth (../shared) and Debian's python3-opencv; the product never
runs it. Usage:
  scripts/appearance_features.py --source data/vtest.avi \
      --gt ../shared/data/mot15-train/PETS09-S2L1/gt/gt.txt --fps 7 [--last-frame N] [--from-frame N] \
      [--descriptors colour,colour-soft,gradient,colour+gradient] [--gaps-s 1,3,5] [--models ema,gallery4]
--source is a video file or a folder of numbered .jpg images. Exit 2: bad arguments or input.
"""
import argparse
import collections
import glob
import os
import sys

import cv2
import numpy as np

SSD_LAYERS = {  # name -> the ONNX node whose output is pooled
    "ssd-38x38x192": "FeatureExtractor/MobilenetV2/expanded_conv_6/expand/Relu6",
    "ssd-19x19x576": "FeatureExtractor/MobilenetV2/expanded_conv_13/expand/Relu6",
    "ssd-10x10x1280": "FeatureExtractor/MobilenetV2/Conv_1/Relu6",
}
CORE_LEFT, CORE_RIGHT, CORE_TOP, CORE_BOTTOM = 0.25, 0.75, 0.12, 0.85  # vision/colour_signature.cpp
COVERED = 0.1  # tracker: a detection another covers more than this teaches no appearance
MOMENTUM = 0.9  # tracker.appearance_momentum
MARGIN = 0.1  # re-identification's margin (tracker/reidentification)


def fail(message):
    print(f"appearance_features.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_gt(path):
    boxes = collections.defaultdict(list)
    try:
        lines = open(path, encoding="ascii").read().splitlines()
    except OSError as error:
        fail(f"{path}: {error.strerror}")
    fields = ("frame", "id", "x", "y", "width", "height", "confidence")
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        parts = line.split(",")
        if len(parts) < len(fields):
            fail(f"{path}:{number}: {len(parts)} fields, expected at least {len(fields)}")
        values = []
        for name, text in zip(fields, parts):
            try:
                values.append(float(text))
            except ValueError:
                fail(f"{path}:{number}: field '{name}' is not a number: {text!r}")
        frame, person, x, y, w, h, confidence = values
        if confidence != 0 and w > 0 and h > 0:  # confidence 0: a region to ignore
            boxes[int(frame)].append((int(person), x, y, w, h))
    if not boxes:
        fail(f"{path}: no boxes")
    return boxes


def frames_of(source):
    if os.path.isdir(source):
        paths = sorted(glob.glob(os.path.join(source, "*.jpg")))
        if not paths:
            fail(f"{source}: no .jpg images")
        for path in paths:
            image = cv2.imread(path)
            if image is None:
                fail(f"{path}: cannot be decoded")
            yield image
        return
    capture = cv2.VideoCapture(source)
    if not capture.isOpened():
        fail(f"{source}: cannot be opened")
    while True:
        ok, image = capture.read()
        if not ok:
            return
        yield image


def covered_share(box, others):
    x, y, w, h = box
    share = 0.0
    for ox, oy, ow, oh in others:
        ix = max(0.0, min(x + w, ox + ow) - max(x, ox))
        iy = max(0.0, min(y + h, oy + oh) - max(y, oy))
        share = max(share, ix * iy / (w * h))
    return share


def core_part(frame, box, top, bottom):
    """The pixels of one part of the box's core (BGR, n x 3), or None if too few."""
    x, y, w, h = box
    x0, x1 = max(0, int(np.floor(x + CORE_LEFT * w))), min(frame.shape[1], int(np.ceil(x + CORE_RIGHT * w)))
    y0, y1 = max(0, int(np.floor(y + top * h))), min(frame.shape[0], int(np.ceil(y + bottom * h)))
    if x1 <= x0 or y1 <= y0 or (x1 - x0) * (y1 - y0) < 12:
        return None
    return frame[y0:y1, x0:x1]


def hue_saturation_bins(patch, hue_bins=8, soft=False):
    """vision::ColourSignature's per-part histogram: hue_bins x 2 saturations for coloured pixels,
    8 brightness bins for the rest; soft: each coloured pixel shared between its two nearest hues
    (circular) and each grey one between its two nearest brightnesses."""
    hsv = cv2.cvtColor(patch, cv2.COLOR_BGR2HSV).reshape(-1, 3).astype(float)
    hue, saturation, value = hsv[:, 0], hsv[:, 1], hsv[:, 2]
    bins = np.zeros(hue_bins * 2 + 8)
    grey = (saturation < 50) | (value < 40)
    high = (saturation[~grey] >= 140).astype(int)
    if soft:
        position = hue[~grey] * hue_bins / 180 - 0.5
        low = np.floor(position)
        weight = position - low
        np.add.at(bins, (low.astype(int) % hue_bins) * 2 + high, 1 - weight)
        np.add.at(bins, ((low.astype(int) + 1) % hue_bins) * 2 + high, weight)
        position = np.clip(value[grey] * 8 / 256 - 0.5, 0, 7)
        low = np.minimum(np.floor(position).astype(int), 6)
        weight = position - low
        np.add.at(bins, hue_bins * 2 + low, 1 - weight)
        np.add.at(bins, hue_bins * 2 + low + 1, weight)
    else:
        np.add.at(bins, hue_bins * 2 + value[grey].astype(int) * 8 // 256, 1)
        np.add.at(bins, np.minimum(hue[~grey].astype(int) * hue_bins // 180, hue_bins - 1) * 2 + high, 1)
    return bins / len(hsv)


def joint_bins(patch, code=None, low=0, high=256):
    """A 4 x 4 x 4 joint histogram of the patch's three channels (after cvtColor(code))."""
    pixels = (cv2.cvtColor(patch, code) if code is not None else patch).reshape(-1, 3).astype(float)
    cells = np.clip(((pixels - low) * 4 / (high - low)).astype(int), 0, 3)
    bins = np.zeros(64)
    np.add.at(bins, cells[:, 0] * 16 + cells[:, 1] * 4 + cells[:, 2], 1)
    return bins / len(pixels)


def gradient_bins(patch):
    """Texture: the share of the part's pixels at each of 8 gradient orientations (unsigned, 0..180
    degrees), each pixel counting once, and one bin for flat pixels (a gradient below 4 gray levels
    per pixel)."""
    gray = cv2.cvtColor(patch, cv2.COLOR_BGR2GRAY).astype(np.float32)
    dx, dy = cv2.Sobel(gray, cv2.CV_32F, 1, 0, ksize=3), cv2.Sobel(gray, cv2.CV_32F, 0, 1, ksize=3)
    magnitude, angle = cv2.cartToPolar(dx, dy, angleInDegrees=True)
    magnitude, angle = magnitude.ravel(), angle.ravel() % 180
    bins = np.zeros(9)
    flat = magnitude < 32  # Sobel 3x3 gives 8 for a ramp of one gray level per pixel
    bins[8] = flat.sum()
    np.add.at(bins, np.minimum((angle[~flat] * 8 / 180).astype(int), 7), 1)
    return bins / len(magnitude)


TWO_PARTS = ((CORE_TOP, 0.5), (0.5, CORE_BOTTOM))
THREE_PARTS = ((CORE_TOP, 0.35), (0.35, 0.6), (0.6, CORE_BOTTOM))
# Colour candidates: name -> (parts, one part's histogram). Each part weighs the same; the whole
# sums to 1 and is compared by the Hellinger distance, as the tracker compares.
COLOUR_KINDS = {
    "colour": (TWO_PARTS, hue_saturation_bins),
    "colour-soft": (TWO_PARTS, lambda p: hue_saturation_bins(p, soft=True)),
    "colour-16hues": (TWO_PARTS, lambda p: hue_saturation_bins(p, hue_bins=16)),
    "colour-3parts": (THREE_PARTS, hue_saturation_bins),
    "colour-3parts-soft": (THREE_PARTS, lambda p: hue_saturation_bins(p, soft=True)),
    "bgr-4x4x4": (TWO_PARTS, joint_bins),
    "lab-4x4x4": (TWO_PARTS, lambda p: joint_bins(p, cv2.COLOR_BGR2Lab)),
    "gradient": (TWO_PARTS, gradient_bins),
}


def colour(frame, box, kind="colour"):
    parts, part_bins = COLOUR_KINDS[kind]
    histograms = []
    for top, bottom in parts:
        patch = core_part(frame, box, top, bottom)
        if patch is None:
            return None
        histograms.append(part_bins(patch) / len(parts))
    return np.concatenate(histograms)


def pooled(feature_map, box, width, height):
    channels, rows, cols = feature_map.shape
    x, y, w, h = box
    centres_x = (np.arange(cols) + 0.5) * width / cols
    centres_y = (np.arange(rows) + 0.5) * height / rows
    xs = np.where((centres_x >= x + CORE_LEFT * w) & (centres_x <= x + CORE_RIGHT * w))[0]
    ys = np.where((centres_y >= y + CORE_TOP * h) & (centres_y <= y + CORE_BOTTOM * h))[0]
    if len(xs) == 0:  # a box narrower than a cell: the cell under its centre
        xs = [int(np.clip((x + w / 2) * cols / width, 0, cols - 1))]
    if len(ys) == 0:
        ys = [int(np.clip((y + h / 2) * rows / height, 0, rows - 1))]
    vector = feature_map[:, ys][:, :, xs].mean(axis=(1, 2))
    norm = np.linalg.norm(vector)
    return vector / norm if norm > 0 else None


def distance(kind, a, b):
    if kind in COLOUR_KINDS:
        return float(np.sqrt(max(0.0, 1.0 - np.sum(np.sqrt(a[kind] * b[kind])))))
    if "+" in kind:
        first, second = kind.split("+")
        return 0.5 * (distance(first, a, b) + distance(second, a, b))
    return float(1.0 - np.dot(a[kind], b[kind]))


def auc(own, other):
    values = np.concatenate([own, other])
    ranks = values.argsort().argsort() + 1
    return (ranks[len(own):].sum() - len(other) * (len(other) + 1) / 2) / (len(own) * len(other))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--gt", required=True)
    parser.add_argument("--fps", type=float, required=True, help="the sequence's true frame rate")
    parser.add_argument("--model", default="models/ssdlite_mobilenet_v2_coco.onnx")
    parser.add_argument("--gaps-s", default="0,1,3,5,10", help="gaps in seconds (0: the next frame)")
    parser.add_argument("--from-frame", type=int, default=1, help="queries from this frame on")
    parser.add_argument("--last-frame", type=int, default=0, help="stop after this frame (0: all)")
    parser.add_argument("--models", default="ema",
                        help="each person's model, comma-separated: ema (the tracker's average) or "
                        "galleryK (their last K clear sightings, the nearest counting: DeepSORT's)")
    parser.add_argument("--descriptors", default="colour," + ",".join(SSD_LAYERS) + ",colour+ssd-10x10x1280",
                        help="which to compare, comma-separated: " + ", ".join([*COLOUR_KINDS, *SSD_LAYERS])
                        + ", or A+B (the mean of two distances)")
    args = parser.parse_args()
    if args.fps <= 0:
        fail(f"--fps must be positive, not {args.fps}")
    try:
        gaps = sorted({max(1, round(float(g) * args.fps)) for g in args.gaps_s.split(",")})
    except ValueError:
        fail(f"--gaps-s: not a list of numbers: {args.gaps_s!r}")
    kinds = args.descriptors.split(",")
    model_kinds = args.models.split(",")
    for model_kind in model_kinds:
        if model_kind != "ema" and not (model_kind.startswith("gallery") and model_kind[7:].isdigit()
                                        and int(model_kind[7:]) > 0):
            fail(f"--models: unknown {model_kind!r} (ema or galleryK, K > 0)")
    used = {part for kind in kinds for part in kind.split("+")}
    unknown = sorted(used - set(COLOUR_KINDS) - set(SSD_LAYERS))
    if unknown:
        fail(f"--descriptors: unknown {', '.join(unknown)}")
    layers = {kind: SSD_LAYERS[kind] for kind in SSD_LAYERS if kind in used}
    boxes = read_gt(args.gt)
    nodes = {}
    if layers and not os.path.isfile(args.model):
        fail(f"{args.model}: not found (scripts/fetch_model.sh)")
    net = cv2.dnn.readNetFromONNX(args.model) if layers else None
    names = net.getLayerNames() if layers else []
    for kind, suffix in layers.items():
        found = [n for n in names if n.endswith(suffix)]
        if len(found) != 1:
            fail(f"{args.model}: layer {suffix} not found once (the model's export changed?)")
        nodes[kind] = found[0]

    sightings = collections.defaultdict(dict)  # frame -> person -> descriptors
    for frame_number, image in enumerate(frames_of(args.source), 1):
        if args.last_frame and frame_number > args.last_frame:
            break
        people = boxes.get(frame_number, [])
        clear = [(p[0], p[1:]) for k, p in enumerate(people)
                 if covered_share(p[1:], [o[1:] for j, o in enumerate(people) if j != k]) <= COVERED]
        if not clear:
            continue
        maps = {}
        if nodes:
            rgb = cv2.cvtColor(image, cv2.COLOR_BGR2RGB)  # the detector's input: RGB, x * 2/255 - 1
            net.setInput(cv2.dnn.blobFromImage(rgb, 2 / 255.0, (300, 300), (127.5, 127.5, 127.5)))
            maps = dict(zip(nodes, net.forward(list(nodes.values()))))
        height, width = image.shape[:2]
        for person, box in clear:
            descriptors = {kind: colour(image, box, kind) for kind in COLOUR_KINDS if kind in used}
            for kind, output in maps.items():
                descriptors[kind] = pooled(output[0], box, width, height)
            if all(d is not None for d in descriptors.values()):
                sightings[frame_number][person] = descriptors
    if not sightings:
        fail(f"{args.source}: no frame matched the ground truth's people")

    # Each person's models after each frame: the running average, and their last sightings.
    models, recent, model_at, recent_at = {}, collections.defaultdict(list), {}, {}
    longest = max([int(m[7:]) for m in model_kinds if m != "ema"], default=1)
    for frame_number in sorted(sightings):
        for person, d in sightings[frame_number].items():
            if person in models:
                models[person] = {k: MOMENTUM * models[person][k] + (1 - MOMENTUM) * d[k] for k in d}
            else:
                models[person] = dict(d)
            model = dict(models[person])
            for kind in layers:  # the average of unit vectors, compared by cosine: unit again
                model[kind] = model[kind] / np.linalg.norm(model[kind])
            model_at[(frame_number, person)] = model
            recent[person] = (recent[person] + [d])[-longest:]
            recent_at[(frame_number, person)] = recent[person]

    def model_distance(model_kind, kind, frame_number, person, query):
        if model_kind == "ema":
            return distance(kind, model_at[(frame_number, person)], query)
        size = int(model_kind[7:])
        return min(distance(kind, seen, query) for seen in recent_at[(frame_number, person)][-size:])

    print("| descriptor | model | gap | queries | rank-1 | rank-1 by the margin 0.1 | AUC |")
    print("|---|---|---|---|---|---|---|")
    for gap in gaps:
        for kind, model_kind in ((k, m) for k in kinds for m in model_kinds):
            queries = right = by_margin = 0
            own, other = [], []
            for frame_number, gallery_people in sightings.items():
                later = sightings.get(frame_number + gap)
                if not later or frame_number + gap < args.from_frame or len(gallery_people) < 2:
                    continue
                for person, query in later.items():
                    if person not in gallery_people:
                        continue
                    ranked = sorted((model_distance(model_kind, kind, frame_number, p, query), p)
                                    for p in gallery_people)
                    queries += 1
                    right += ranked[0][1] == person
                    by_margin += ranked[0][1] == person and ranked[1][0] - ranked[0][0] >= MARGIN
                    own += [d for d, p in ranked if p == person]
                    other += [d for d, p in ranked if p != person]
            if queries == 0:
                print(f"| {kind} | {model_kind} | {gap} frames | 0 | | | |")
                continue
            print(f"| {kind} | {model_kind} | {gap} frames ({gap / args.fps:.1f} s) | {queries} | {right / queries:.3f} | "
                  f"{by_margin / queries:.3f} | {auc(np.array(own), np.array(other)):.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
