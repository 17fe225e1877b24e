#!/usr/bin/env python3
"""The protocol's six cells averaged over jittered copies of the recordings, and the averaged
rule's verdict (docs/appearance.md, "How far a cell moves by chance").

One replay of a recording is one draw: moving every box by half a pixel (a null change,
scripts/jitter_detections.py) moves a cell's IDF1 by up to 5 points and its MOTA by up to 0.8. So each label is replayed on the original recording and on N jittered copies, named LABEL
and LABELj1 .. LABELjN (scripts/half_cells.sh's labels), and compared with the reference's copies
of the same seeds:
  d_s      the candidate's IDF1 sum minus the reference's, copy s
  MOTA     per cell, the mean over the copies of the candidate's MOTA minus the reference's
  first halves (--half first): chosen with mean(d) >= 1.5 and mean(d) >= 2 standard errors,
    no cell's mean MOTA difference below -0.2; the highest mean(d) among them;
  second halves (--half second): passes with mean(d) >= 0 and no cell's mean MOTA difference
    below -0.2.

With --spread it prints instead how far the reference's own copies spread: per cell, the range
of MOTA and IDF1 over the copies and their standard deviation, and the same for the sums (the
noise floor a rule must stand above).

Research tooling; the product never runs it. Usage:
  scripts/half_cells_averaged.py OUT --half first|second [--against head] [--labels A,B]
                                 [--copies 6] [--spread]
Exit 2: bad arguments or input (the file and line named); 1: the reference lacks a copy.
"""
import argparse
import collections
import math
import re
import sys

from half_cells_table import CELLS, HEADINGS, MOTA_TOLERANCE, cells_of, read_scores
from score_table import fail

FIRST_HALF_GAIN = 1.5
STANDARD_ERRORS = 2.0


def copies_of(runs, label, count):
    """The label's six cells on each copy (original first), or None where one lacks a cell."""
    names = [label] + [f"{label}j{s}" for s in range(1, count + 1)]
    copies = [cells_of(runs.get(name, {})) for name in names]
    return None if any(c is None for c in copies) else copies


def standard_deviation(values):
    mean = sum(values) / len(values)
    return math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))


def print_spread(copies):
    """Per cell and for the sums: MOTA and IDF1 as min-max (standard deviation) over the copies."""
    def shown(values):
        return f"{min(values):.1f}-{max(values):.1f} ({standard_deviation(values):.2f})"
    print("| " + " | ".join(HEADINGS) + " | MOTA sum | IDF1 sum |")
    print("|" + "---|" * (len(HEADINGS) + 2))
    cells = [shown([copy[c][0] for copy in copies]) + " / " + shown([copy[c][1] for copy in copies])
             for c in range(len(CELLS))]
    sums = [shown([sum(cell[i] for cell in copy) for copy in copies]) for i in (0, 1)]
    print("| " + " | ".join(cells + sums) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="the OUT folder of scripts/half_cells.sh")
    parser.add_argument("--half", choices=("first", "second"), required=True)
    parser.add_argument("--against", default="head", help="the reference label (default head)")
    parser.add_argument("--copies", type=int, default=6, help="jittered copies (default 6)")
    parser.add_argument("--labels", help="the candidates to compare, comma-separated (default: "
                        "every label in OUT; a round's verdict names its own candidates only)")
    parser.add_argument("--spread", action="store_true",
                        help="print the reference's spread over its copies instead")
    args = parser.parse_args()
    if args.copies < 1:
        fail(f"--copies must be at least 1, not {args.copies}")
    runs = collections.defaultdict(dict)
    for kind in ("off", "tiles"):
        read_scores(f"{args.out}/{kind}/scores.tsv", kind, runs)
    reference = copies_of(runs, args.against, args.copies)
    if reference is None:
        fail(f"{args.out}: the reference '{args.against}' lacks a cell on a copy", status=1)
    n = args.copies + 1
    if args.spread:
        print_spread(reference)
        return
    # The reference first, then the candidates by name.
    bases = sorted({name for name in runs if not re.search(r"j\d+$", name)},
                   key=lambda name: (name != args.against, name))
    if args.labels:
        wanted = [label for label in args.labels.split(",") if label]
        unknown = [label for label in wanted if label not in bases]
        if unknown:
            fail(f"{args.out}: no label {', '.join(unknown)}")
        bases = [args.against] + [label for label in wanted if label != args.against]
    print("| label | " + " | ".join(HEADINGS) + " | IDF1 sum | d: mean ± s.e. (range) | "
          "worst mean MOTA difference | verdict |")
    print("|" + "---|" * (len(HEADINGS) + 5))
    best = None
    for label in bases:
        copies = copies_of(runs, label, args.copies)
        if copies is None:
            print(f"half_cells_averaged.py: {label}: a copy lacks a cell, left out", file=sys.stderr)
            continue
        means = [tuple(sum(copy[c][i] for copy in copies) / n for i in range(3))
                 for c in range(len(CELLS))]
        d = [sum(cell[1] for cell in mine) - sum(cell[1] for cell in ref)
             for mine, ref in zip(copies, reference)]
        mean_d = sum(d) / n
        se = standard_deviation(d) / math.sqrt(n)
        mota = [sum(mine[c][0] - ref[c][0] for mine, ref in zip(copies, reference)) / n
                for c in range(len(CELLS))]
        worst = min(mota)
        if label == args.against:
            verdict = "reference"
        elif args.half == "first":
            chosen = (mean_d >= FIRST_HALF_GAIN - 1e-9 and mean_d >= STANDARD_ERRORS * se - 1e-9
                      and worst >= -MOTA_TOLERANCE - 1e-9)
            verdict = "qualifies" if chosen else "refused"
            if chosen and (best is None or mean_d > best[1]):
                best = (label, mean_d)
        else:
            verdict = "passes" if mean_d >= -1e-9 and worst >= -MOTA_TOLERANCE - 1e-9 else "refused"
        row = " | ".join("%.1f / %.1f / %.1f" % cell for cell in means)
        idf1 = sum(cell[1] for cell in means)
        print(f"| {label} | {row} | {idf1:.1f} | {mean_d:+.1f} ± {se:.1f} ({min(d):+.1f} to "
              f"{max(d):+.1f}) | {worst:+.2f} | {verdict} |")
    if args.half == "first":
        print(f"\nchosen for the second halves: {best[0] if best else 'none'}")


if __name__ == "__main__":
    main()
