#!/usr/bin/env python3
"""The protocol's six cells and its verdict (docs/appearance.md, "The gate on top of
re-identification" and since), from scripts/half_cells.sh's folders.

Reads OUT/off/scores.tsv and OUT/tiles/scores.tsv and prints, for every label that has all six
cells with as many runs as the reference, one markdown row: MOTA / IDF1 / AssA per cell (a latency
cell is the mean over its band), the MOTA and IDF1 sums, the worst cell's MOTA against the
reference, and the rule's verdict:
  first halves (--half first): a candidate qualifies with an IDF1 sum at least 1.0 above the
    reference's and no cell's MOTA more than 0.2 below it; the rule takes the qualifying candidate
    with the highest IDF1 sum;
  second halves (--half second): a candidate passes with an IDF1 sum not below the reference's and
    no cell's MOTA more than 0.2 below it.
The MOTA differences here come from score_video.sh's one-decimal figures; where a verdict hangs on
a tenth, compute it from the error counts in each run's eval.csv.

Research tooling; the product never runs it. Usage:
  scripts/half_cells_table.py OUT --half first|second [--against head]
Exit 2: bad arguments or input (the file and line named); 1: no run of the reference label.
"""
import argparse
import collections
import sys

from score_table import fail, read_rows

CELLS = (("PETS09-S2L1", "off", "every"), ("PETS09-S2L1", "tiles", "every"),
         ("PETS09-S2L1", "off", "band"), ("ADL-Rundle-6", "off", "every"),
         ("ADL-Rundle-6", "tiles", "every"), ("ADL-Rundle-6", "off", "band"))
HEADINGS = ("S2L1 off", "S2L1 tiles", "S2L1 behind 200-300 ms", "ADL-6 off", "ADL-6 tiles",
            "ADL-6 behind 200-300 ms")
BAND = ("200", "225", "250", "275", "300")
MOTA_TOLERANCE = 0.2
FIRST_HALF_GAIN = 1.0


def read_scores(path, kind, runs):
    """runs[label][(sequence, kind, latency)] = (MOTA, IDF1, AssA)."""
    for number, fields in read_rows(path, ("label", "sequence", "latency_ms", "MOTA", "IDF1",
                                           "AssA")):
        try:
            figures = tuple(float(fields[name]) for name in ("MOTA", "IDF1", "AssA"))
        except ValueError:
            fail(f"{path}:{number}: MOTA, IDF1 or AssA is not a number")
        runs[fields["label"]][(fields["sequence"], kind, fields["latency_ms"])] = figures


def cells_of(label_runs):
    """The six cells' (MOTA, IDF1, AssA), or None where one is missing."""
    cells = []
    for sequence, kind, latency in CELLS:
        if latency == "every":
            figures = label_runs.get((sequence, kind, "every"))
            if figures is None:
                return None
            cells.append(figures)
            continue
        band = [label_runs.get((sequence, kind, ms)) for ms in BAND]
        if any(figures is None for figures in band):
            return None
        cells.append(tuple(sum(figures[i] for figures in band) / len(band) for i in range(3)))
    return cells


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="the OUT folder of scripts/half_cells.sh")
    parser.add_argument("--half", choices=("first", "second"), required=True)
    parser.add_argument("--against", default="head", help="the reference label (default head)")
    args = parser.parse_args()
    runs = collections.defaultdict(dict)
    for kind in ("off", "tiles"):
        read_scores(f"{args.out}/{kind}/scores.tsv", kind, runs)
    reference = cells_of(runs.get(args.against, {}))
    if reference is None:
        fail(f"{args.out}: the reference label '{args.against}' lacks a cell", status=1)
    reference_idf1 = sum(cell[1] for cell in reference)
    print("| label | " + " | ".join(HEADINGS) + " | MOTA sum | IDF1 sum | worst MOTA cell | verdict |")
    print("|" + "---|" * (len(HEADINGS) + 5))
    best = None
    for label, label_runs in runs.items():
        cells = cells_of(label_runs)
        if cells is None:
            print(f"half_cells_table.py: {label}: a cell is missing, left out", file=sys.stderr)
            continue
        mota_sum = sum(cell[0] for cell in cells)
        idf1_sum = sum(cell[1] for cell in cells)
        worst = min(cell[0] - ref[0] for cell, ref in zip(cells, reference))
        if label == args.against:
            verdict = "reference"
        elif args.half == "first":
            qualifies = idf1_sum >= reference_idf1 + FIRST_HALF_GAIN - 1e-9 and \
                worst >= -MOTA_TOLERANCE - 1e-9
            verdict = "qualifies" if qualifies else "refused"
            if qualifies and (best is None or idf1_sum > best[1]):
                best = (label, idf1_sum)
        else:
            passes = idf1_sum >= reference_idf1 - 1e-9 and worst >= -MOTA_TOLERANCE - 1e-9
            verdict = "passes" if passes else "refused"
        row = " | ".join("%.1f / %.1f / %.1f" % cell for cell in cells)
        print(f"| {label} | {row} | {mota_sum:.1f} | {idf1_sum:.1f} | {worst:+.2f} | {verdict} |")
    if args.half == "first":
        print(f"\nchosen for the second halves: {best[0] if best else 'none'}")


if __name__ == "__main__":
    main()
