"""Intersection over union of two MOTChallenge boxes (left, top, width, height), as the scorer and
the tracker compute it (no +1 pixel), and the share of one box another covers: shared by the
research scripts that match boxes."""


def iou(a, b):
    w = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
    h = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    inter = w * h
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def covered_share(box, other):
    """The share of `box`'s area that `other` covers, in [0, 1] (tracker/box_geometry.hpp's)."""
    w = min(box[0] + box[2], other[0] + other[2]) - max(box[0], other[0])
    h = min(box[1] + box[3], other[1] + other[3]) - max(box[1], other[1])
    area = box[2] * box[3]
    return w * h / area if w > 0 and h > 0 and area > 0 else 0.0
