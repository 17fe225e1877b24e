#!/usr/bin/env python3
"""A label's figures on a recording and on its jittered copies (labels LABEL, LABELj1 .. LABELjN
of a scripts/score_video.sh table, every frame): per sequence, the recording's figure and the mean
(lowest-highest) over all of them. One replay is one draw (docs/scoring.md, "Averaged over
jittered copies"): the band is what a half-pixel change of every box spans.

Research tooling; the product never runs it. Usage:
  scripts/copies_band.py OUT/scores.tsv LABEL... [--copies 6]
Exit 2: bad arguments or input (the file and line named); 1: a label lacks a copy.
"""
import argparse

from score_table import fail, read_rows

METRICS = ("MOTA", "IDF1", "HOTA", "AssA", "IDs")


def band(values, digits):
    """The recording's value, then the mean (lowest-highest) of all of them."""
    def shown(v):
        return f"{v:.{digits}f}"
    mean = sum(values) / len(values)
    return f"{shown(values[0])} · {mean:.1f} ({shown(min(values))}-{shown(max(values))})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("table")
    parser.add_argument("labels", nargs="+")
    parser.add_argument("--copies", type=int, default=6)
    args = parser.parse_args()
    if args.copies < 1:
        fail("--copies must be at least 1")
    rows = read_rows(args.table, ("label", "sequence", "latency_ms") + METRICS)
    scores = {}
    for number, row in rows:
        if row["latency_ms"] != "every":
            continue
        try:
            scores[(row["label"], row["sequence"])] = [float(row[m]) for m in METRICS]
        except ValueError:
            fail(f"{args.table}:{number}: a figure is not a number")
    sequences = sorted({sequence for _, sequence in scores}, key=lambda s: s != "PETS09-S2L1")
    table = [f"Each: the recording · the mean (lowest-highest) of it and {args.copies} copies.", "",
             "| label | sequence | " + " | ".join(METRICS) + " |",
             "|" + "---|" * (len(METRICS) + 2)]
    for label in args.labels:
        names = [label] + [f"{label}j{s}" for s in range(1, args.copies + 1)]
        if not any((label, sequence) in scores for sequence in sequences):
            fail(f"{args.table}: no every-frame row of {label}")
        for sequence in sequences:
            copies = [scores.get((name, sequence)) for name in names]
            if all(c is None for c in copies):
                continue
            if any(c is None for c in copies):
                fail(f"{args.table}: {label} on {sequence} lacks a copy", status=1)
            cells = [band([c[m] for c in copies], 0 if name == "IDs" else 1)
                     for m, name in enumerate(METRICS)]
            table.append(f"| {label} | {sequence} | " + " | ".join(cells) + " |")
    print("\n".join(table))


if __name__ == "__main__":
    main()
