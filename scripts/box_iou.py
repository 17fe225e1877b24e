"""Intersection over union of two MOTChallenge boxes (left, top, width, height), as the scorer and
the tracker compute it (no +1 pixel): shared by the research scripts that match boxes."""


def iou(a, b):
    w = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
    h = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    inter = w * h
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)
