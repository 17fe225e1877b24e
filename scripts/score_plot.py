#!/usr/bin/env python3
"""Score against detector latency, one SVG per sequence, from scripts/score_video.sh's table.

Usage: score_plot.py OUT/scores.tsv OUT_PREFIX [METRIC...]   (default metrics MOTA IDF1 AssA)
Writes OUT_PREFIX-SEQUENCE.svg: one panel per metric, latency on x ("every" first, then the
simulated latencies in ms), one line per label (e.g. a preset with and without the image's
re-identification). Plain SVG written here: research tooling, no plotting library needed.
"""
import csv
import sys
from collections import defaultdict

WIDTH, HEIGHT, MARGIN = 300, 220, 44
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]


def panel(rows, labels, latencies, metric, left):
    values = [float(r[metric]) for r in rows]
    low, high = min(values + [0.0]), max(values + [1.0])
    top = high + 0.05 * (high - low)
    def x(i):
        return left + MARGIN + i * (WIDTH - 1.5 * MARGIN) / max(len(latencies) - 1, 1)
    def y(v):
        return HEIGHT - MARGIN + (v - low) / (top - low) * -(HEIGHT - 1.6 * MARGIN)
    out = [f'<text x="{left + WIDTH / 2}" y="16" text-anchor="middle" font-weight="bold">{metric}</text>',
           f'<line x1="{left + MARGIN}" y1="{y(low)}" x2="{left + WIDTH - MARGIN / 2}" y2="{y(low)}" stroke="black"/>',
           f'<line x1="{left + MARGIN}" y1="{y(low)}" x2="{left + MARGIN}" y2="{y(top)}" stroke="black"/>']
    for tick in range(5):
        v = low + tick * (top - low) / 4
        out.append(f'<text x="{left + MARGIN - 4}" y="{y(v) + 4}" text-anchor="end">{v:.0f}</text>')
    for i, latency in enumerate(latencies):
        out.append(f'<text x="{x(i)}" y="{HEIGHT - MARGIN + 16}" text-anchor="middle">{latency}</text>')
    out.append(f'<text x="{left + WIDTH / 2}" y="{HEIGHT - 8}" text-anchor="middle">detector latency (ms)</text>')
    for k, label in enumerate(labels):
        points = [(i, float(r[metric])) for i, latency in enumerate(latencies)
                  for r in rows if r["label"] == label and r["latency_ms"] == latency]
        colour = COLOURS[k % len(COLOURS)]
        path = " ".join(f"{x(i):.1f},{y(v):.1f}" for i, v in points)
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
        out += [f'<circle cx="{x(i):.1f}" cy="{y(v):.1f}" r="3" fill="{colour}"/>' for i, v in points]
    return out


def main(table, prefix, metrics):
    rows = list(csv.DictReader(open(table), delimiter="\t"))
    by_sequence = defaultdict(list)
    for row in rows:
        by_sequence[row["sequence"]].append(row)
    for sequence, seq_rows in by_sequence.items():
        labels = list(dict.fromkeys(r["label"] for r in seq_rows))
        latencies = sorted({r["latency_ms"] for r in seq_rows},
                           key=lambda l: -1 if l == "every" else float(l))
        width = WIDTH * len(metrics)
        svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{HEIGHT + 24}" '
               f'font-family="sans-serif" font-size="11">',
               f'<rect width="100%" height="100%" fill="white"/>']
        for m, metric in enumerate(metrics):
            svg += panel(seq_rows, labels, latencies, metric, m * WIDTH)
        for k, label in enumerate(labels):
            svg.append(f'<text x="{10 + 150 * k}" y="{HEIGHT + 18}" fill="{COLOURS[k % len(COLOURS)]}">'
                       f'— {label} ({sequence})</text>')
        svg.append("</svg>")
        with open(f"{prefix}-{sequence}.svg", "w") as f:
            f.write("\n".join(svg) + "\n")
        print(f"wrote {prefix}-{sequence}.svg")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3:] or ["MOTA", "IDF1", "AssA"])
