#!/usr/bin/env python3
"""Prints docs/full-rate.md's table from an `rtmot study --latency --out OUT` run.

    scripts/full_rate_table.py OUT

Per fixed latency (the jittered ones are in docs/study.md) and preset, from OUT/latency/det-*.csv:
(c) on the processed frames, (a) the processed frames only at the full frame rate, (b) the
full-rate output at the full frame rate, and (b') the same predicting every reported track.
"""
import csv
import sys
from pathlib import Path


def label(row):
    frames, ms, jitter = float(row["latency_frames"]), float(row["latency_ms"]), float(row["jitter"])
    if frames > 0:
        return f"{frames:g} frames"
    if ms <= 0:
        return "0 ms (every frame)"
    return f"{ms:g} ms" + (f" ±{100 * jitter:g}%" if jitter > 0 else "")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: full_rate_table.py OUT")
    tables = {}
    for preset in ("rtmot", "sort"):
        path = Path(sys.argv[1]) / "latency" / f"det-{preset}.csv"
        if not path.is_file():
            sys.exit(f"full_rate_table.py: {path} missing (run rtmot study --latency --out OUT)")
        with path.open() as f:
            tables[preset] = list(csv.DictReader(f))
    print("| latency | frames processed | preset | (c) MOTA / IDF1 on processed frames "
          "| (a) processed only, full rate | (b) full-rate output | (b) − (a) "
          "| (b') every reported track predicted |")
    print("|---|---:|---|---:|---:|---:|---:|---:|")
    for i, row in enumerate(tables["rtmot"]):
        if float(row["jitter"]) > 0:
            continue
        for preset in ("rtmot", "sort"):
            r = tables[preset][i]
            v = {k: float(x) for k, x in r.items()}
            share = 100 * v["frames_processed"] / v["frames"]
            print(f"| {label(r)} | {share:.1f} % | {preset} "
                  f"| {v['mota_processed']:.1f} / {v['idf1_processed']:.1f} "
                  f"| {v['mota_full_rate']:.1f} / {v['idf1_full_rate']:.1f} "
                  f"| {v['mota_full_output']:.1f} / {v['idf1_full_output']:.1f} "
                  f"| {v['mota_full_output'] - v['mota_full_rate']:+.1f} / "
                  f"{v['idf1_full_output'] - v['idf1_full_rate']:+.1f} "
                  f"| {v['mota_full_output_every']:.1f} / {v['idf1_full_output_every']:.1f} |")


main()
