#!/usr/bin/env bash
# Prints the latency sweep's part of docs/study.md from an `rtmot study --latency --out OUT` run
# and copies its MOTA plots (processed frames, full rate, full-rate output) to docs/study/plots/
# (called by scripts/study.sh).
#   scripts/study_latency_docs.sh OUT DOCS_STUDY_DIR
set -euo pipefail
out="${1:?usage: study_latency_docs.sh OUT DOCS_STUDY_DIR}" docs="${2:?usage: study_latency_docs.sh OUT DOCS_STUDY_DIR}"
for need in summary.md det-rtmot.md det-sort.md det-mota-processed.svg det-mota-full.svg \
  det-mota-full-output.svg det-idf1-full-output.svg; do
  [[ -e "$out/latency/$need" ]] || { echo "study_latency_docs.sh: $out/latency/$need missing (run rtmot study --latency --out $out)" >&2; exit 1; }
done
mkdir -p "$docs/plots"
for plot in det-mota-processed det-mota-full det-mota-full-output det-idf1-full-output; do
  cp "$out/latency/$plot.svg" "$docs/plots/latency-$plot.svg"
done
echo "## The latency sweep (generated)"
echo
echo "\`rtmot study --latency --dataset ../shared/data/mot15-train --out OUT\` (seconds); MOT15-train, all"
echo "11 sequences pooled, det/det.txt. Every other table and plot (gt/gt.txt as the detector, IDF1) is in"
echo "\`OUT/latency/\`."
echo
echo "![MOTA on the processed frames vs detector latency](study/plots/latency-det-mota-processed.svg)"
echo "![MOTA at the full frame rate vs detector latency](study/plots/latency-det-mota-full.svg)"
echo "![MOTA of the full-rate output vs detector latency](study/plots/latency-det-mota-full-output.svg)"
echo "![IDF1 of the full-rate output vs detector latency](study/plots/latency-det-idf1-full-output.svg)"
echo
echo "\"full-rate output\": processed frames plus each reported track's predicted box at every skipped"
echo "frame (docs/full-rate.md), scored at the full frame rate. \"5 frames\" and \"10 frames\": a detector"
echo "taking 5 or 10 of each sequence's frame periods (4 of 5, 9 of 10 frames skipped everywhere)."
for preset in rtmot sort; do
  echo
  echo "### $preset on det/det.txt"
  echo
  cat "$out/latency/det-$preset.md"
done
