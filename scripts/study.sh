#!/usr/bin/env bash
# Runs the frame-rate study and refreshes the part of it that docs/ keeps:
#   scripts/study.sh [BUILD_DIR] [DATASET] [OUT]      (OUT defaults to BUILD_DIR/study)
#   scripts/study.sh --from OUT                        (refresh docs/ from an earlier run's OUT)
# The study writes ~350 tables, ~120 SVG plots, cv-folds.md and summary.md into OUT, outside the
# source tree: that is reproducible output, not committed. docs/ keeps what a reader needs:
#   docs/study.md          = docs/study/reading.md (hand-written) + the tables and plots the default
#                            rests on (presets on det.txt, cross-validation), cut from OUT/summary.md
#   docs/study/cv-folds.md   per-fold choices of the cross-validation
#   docs/study/plots/det-{presets,cv}-{mota,idf1}.svg, docs/study/det-grid-mota.png
#   docs/study/plots/latency-det-mota-{processed,full}.svg and the latency sweep's det tables
#                            (`rtmot study --latency`, scripts/study_latency_docs.sh)
#   docs/study/tables.sha256 sha256 of every table of the full run (pinned)
# A run whose tables differ from docs/study/tables.sha256 still refreshes docs/ but exits 1 naming
# the tables that changed: review `git diff docs/`, then accept with
#   cp OUT/tables.sha256 docs/study/tables.sha256
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
docs="$root/docs/study"

if [[ "${1:-}" == "--from" ]]; then
  out="${2:?usage: scripts/study.sh --from OUT}"
else
  build="${1:-$root/build}"
  dataset="${2:-$root/../shared/data/mot15-train}"
  out="${3:-$build/study}"
  cmake --build "$build" --target rtmot
  rm -rf "$out"
  "$build/apps/rtmot" study --dataset "$dataset" --out "$out" --jobs 2 --link-prefix study/
  "$build/apps/rtmot" study --latency --dataset "$dataset" --out "$out" --jobs 2
fi
for need in summary.md cv-folds.md tables plots latency/summary.md; do
  [[ -e "$out/$need" ]] || { echo "study.sh: $out/$need missing (not a full study run?)" >&2; exit 1; }
done

(cd "$out" && find tables -type f | LC_ALL=C sort | xargs sha256sum) > "$out/tables.sha256"

kept_plots=(det-presets-mota det-presets-idf1 det-cv-mota det-cv-idf1)
rm -rf "$docs/plots"
mkdir -p "$docs/plots"
for plot in "${kept_plots[@]}"; do
  cp "$out/plots/$plot.svg" "$docs/plots/"
done
cp "$out/cv-folds.md" "$docs/cv-folds.md"
if command -v rsvg-convert > /dev/null; then
  # One PNG preview for viewers without SVG support (librsvg2-bin).
  rsvg-convert "$out/plots/det-grid-mota.svg" -o "$docs/det-grid-mota.png"
else
  echo "study.sh: rsvg-convert missing (librsvg2-bin): docs/study/det-grid-mota.png not refreshed" >&2
fi

{
  cat "$docs/reading.md"
  echo
  echo "## The tables and plots the default rests on"
  echo
  echo "Cut from the study's summary.md; every other table and plot is in the \`OUT\` folder of a"
  echo "\`scripts/study.sh\` run (pinned by \`docs/study/tables.sha256\`)."
  echo
  plot_pattern="$(IFS='|'; echo "${kept_plots[*]}")"
  grep -E "^!\[.*\]\(study/plots/(${plot_pattern})\.svg\)$" "$out/summary.md"
  echo
  # Sections "### NAME on DETECTOR" of the summary's tables part, up to the next heading.
  awk '
    /^## Tables/ { tables = 1; next }
    /^##/ { keep = tables && ($0 ~ /^### (cv-held-out|cv-in-sample) on / ||
                              $0 ~ /^### preset-[^ ]* on det\/det\.txt$/) }
    keep { print }
  ' "$out/summary.md"
  echo
  "$root/scripts/study_latency_docs.sh" "$out" "$docs"
} > "$root/docs/study.md"

if ! diff -q "$docs/tables.sha256" "$out/tables.sha256" > /dev/null 2>&1; then
  echo "study.sh: tables differ from docs/study/tables.sha256:" >&2
  diff "$docs/tables.sha256" "$out/tables.sha256" >&2 || true
  echo "study.sh: docs/ refreshed; if the change is intended: cp $out/tables.sha256 $docs/tables.sha256" >&2
  exit 1
fi
echo "wrote $root/docs/study.md and $docs/ (the full output is in $out)"
