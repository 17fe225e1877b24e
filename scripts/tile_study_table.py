#!/usr/bin/env python3
"""The tiling study's tables (scripts/tile_study.sh): every candidate's scores on the first halves
(where the choice is made), the rule applied, then the chosen candidate and the untiled one on the
second halves (never seen by the choice). Python's standard library only."""
import csv
import os
import sys

SEQUENCES = ["PETS09-S2L1", "ADL-Rundle-6"]
COLUMNS = ["Rcll", "Prcn", "DetA", "AssA", "MOTA", "IDF1", "HOTA"]


def scores(path):
    with open(path, newline="") as f:
        return {row["sequence"]: row for row in csv.DictReader(f)}


def line(name, table):
    cells = []
    for seq in SEQUENCES:
        row = table[seq]
        cells.append(" ".join(f"{float(row[c]):5.1f}" for c in COLUMNS))
    return f"| {name} | " + " | ".join(cells) + " |"


def main(out):
    runs = os.path.join(out, "runs")
    names = [l.split()[0] for l in open(os.path.join(out, "candidates.txt")) if l.strip()]
    first = {n: scores(os.path.join(runs, n, "first.csv")) for n in names}
    header = "| candidate | " + " | ".join(f"{s}: " + " ".join(COLUMNS) for s in SEQUENCES) + " |"
    print("## First halves (the choice is made here)\n")
    print(header)
    for n in names:
        print(line(n, first[n]))
    base = first["untiled"]
    eligible = [n for n in names
                if all(float(first[n][s]["Prcn"]) >= float(base[s]["Prcn"]) for s in SEQUENCES)]
    chosen = max(eligible, key=lambda n: sum(float(first[n][s]["MOTA"]) for s in SEQUENCES))
    print(f"\nRule: the best summed MOTA among candidates whose precision is not below 'untiled' on"
          f" either first half: {len(eligible)} eligible, chosen: **{chosen}**\n")
    print("## Second halves (not seen by the choice)\n")
    print(header)
    for n in ["untiled", chosen]:
        print(line(n, scores(os.path.join(runs, n, "second.csv"))))


if __name__ == "__main__":
    main(sys.argv[1])
