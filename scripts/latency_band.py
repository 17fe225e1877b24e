#!/usr/bin/env python3
"""Scores behind a slow detector over a band of latencies, not one (docs/scoring.md, "One latency is
one skip pattern").

A simulated latency decides which frames the detector processes; 250 ms and 275 ms are the same
detector to a user and different skip patterns to the tracker, and on the in-sample videos that
alone moves IDF1 by up to 17 points. So a latency cell of a study is better the mean over several
latencies close together. This reads the OUT/scores.tsv of scripts/score_video.sh runs made with a
list of latencies (e.g. 200,225,250,275,300) and prints, for each label and sequence, the mean of
MOTA, IDF1, AssA and ID switches over the latencies in the band and each figure's range; with
--against LABEL, each label's mean difference from that label's at the same latencies, and the
smallest and largest difference.

Research tooling; the product never runs it. Usage:
  scripts/latency_band.py OUT/scores.tsv [--band 200-300] [--against head] [--labels head,tried]
Exit 2: bad arguments or input (the file and line named); 1: no run in the band, or a label that
lacks a latency the reference has.
"""
import argparse
import collections
import sys

from score_table import fail, read_rows

COLUMNS = ("MOTA", "IDF1", "AssA", "IDs")


def read_scores(path, low, high):
    """label -> sequence -> latency -> {column: value}, for the latencies in [low, high]."""
    runs = collections.defaultdict(lambda: collections.defaultdict(dict))
    for number, fields in read_rows(path, ("label", "sequence", "latency_ms", *COLUMNS)):
        if fields["latency_ms"] == "every":
            continue
        try:
            latency = float(fields["latency_ms"])
            scores = {c: float(fields[c]) for c in COLUMNS}
        except ValueError:
            fail(f"{path}:{number}: latency_ms or a score is not a number")
        if low <= latency <= high:
            # A label run twice at one latency: the later line is the one that counts.
            runs[fields["label"]][fields["sequence"]][latency] = scores
    if not runs:
        fail(f"{path}: no run between {low:g} and {high:g} ms", 1)
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scores")
    parser.add_argument("--band", default="200-300", help="LOW-HIGH in ms (default 200-300)")
    parser.add_argument("--against", help="a label: print the others' differences from it")
    parser.add_argument("--labels", help="only these labels, comma-separated (default: every one)")
    args = parser.parse_args()
    try:
        low, high = (float(x) for x in args.band.split("-"))
    except ValueError:
        fail(f"--band: not LOW-HIGH: {args.band!r}")
    runs = read_scores(args.scores, low, high)
    if args.labels:
        wanted = args.labels.split(",")
        unknown = [label for label in wanted if label not in runs]
        if unknown:
            fail(f"--labels: no run of {', '.join(unknown)} in the band", 1)
        runs = {label: runs[label] for label in wanted}
    if args.against and args.against not in runs:
        fail(f"--against: no label {args.against!r} in the band", 1)

    print("| label | sequence | latencies | " + " | ".join(f"{c} mean (range)" for c in COLUMNS) + " |")
    print("|---|---|---|" + "---|" * len(COLUMNS))
    for label, sequences in runs.items():
        for sequence, by_latency in sequences.items():
            cells = []
            for column in COLUMNS:
                values = [run[column] for run in by_latency.values()]
                cells.append(f"{sum(values) / len(values):.1f} ({min(values):g}-{max(values):g})")
            latencies = ",".join(f"{x:g}" for x in sorted(by_latency))
            print(f"| {label} | {sequence} | {latencies} | " + " | ".join(cells) + " |")
    if not args.against:
        return 0

    print()
    print(f"| label | sequence | " + " | ".join(f"{c} - {args.against}'s: mean (min, max)" for c in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    reference = runs[args.against]
    for label, sequences in runs.items():
        if label == args.against:
            continue
        for sequence, by_latency in sequences.items():
            base = reference.get(sequence, {})
            lacking = sorted(set(base) - set(by_latency))
            if lacking:
                fail(f"{label} on {sequence} lacks {', '.join(f'{x:g}' for x in lacking)} ms", 1)
            cells = []
            for column in COLUMNS:
                differences = [by_latency[x][column] - base[x][column] for x in base]
                cells.append(f"{sum(differences) / len(differences):+.2f} ({min(differences):+g}, "
                             f"{max(differences):+g})")
            print(f"| {label} | {sequence} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
