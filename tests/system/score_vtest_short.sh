#!/usr/bin/env bash
# System test, the short version of the pipeline's scoring on real video (docs/scoring.md, "The
# pipeline on real video"; issue 29): `rtmot run` with the real SSD on vtest.avi's first 150 frames
# (PETS09-S2L1), every frame and behind a simulated 250 ms detector with full-rate output, scored
# by `rtmot eval` against the sequence's ground truth. Simulated playback is deterministic, so the
# figures are asserted: within TOLERANCE points of the ones measured (docs/scoring.md says where),
# and the frames processed exactly. A change of the tracker, the detector's numbers or the frame
# selection that moves a score more than that fails here.
# Usage: score_vtest_short.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Both engines gave the same figures to the digit on this project's VM (OpenCV 4.6 and the pinned
# 4.10; these, since the video plays at its true 7 fps in round 25, measured with 4.6): a
# tolerance of 2 points is about 20 of the ~1000 true boxes, room for another CPU's rounding to
# flip a detection at the score cut, not for a changed tracker.
tolerance=2.0
cd "$source_dir"  # the default configuration's model path is relative to the checkout
score() {  # LABEL LATENCIES [rtmot run arguments...]
  BUILD=$build FRAMES=150 SEQUENCES=PETS09-S2L1 bash "$source_dir/scripts/score_video.sh" \
    "$work" "$@" --tiles off --backend xnnpack --detector-threads 1 >>"$work/score.log" 2>&1 ||
    { cat "$work/score.log"; echo "FAIL: score_video.sh $1"; exit 1; }
}
score boxes every,250 --follow-image false
# Following the image, the default (docs/full-rate.md, "Observed boxes"): across the frames the
# detector skipped and, since round 26, from each processed frame to the next.
score image every,250
cat "$work/scores.tsv"
# label latency processed MOTA IDF1 DetA AssA (measured again in round 28: re-identification's
# narrower reach moved both IDF1s past the tolerance)
expected=$'boxes/every 150 38.2 57.2 43.6 39.1\nboxes/250 87 30.8 57.9 39.8 43.3\nimage/every 150 42.6 60.0 43.8 40.2\nimage/250 87 42.8 58.2 43.5 37.9'
awk -F'\t' -v tolerance="$tolerance" -v expected="$expected" '
  BEGIN {
    n = split(expected, lines, "\n")
    for (i = 1; i <= n; ++i) { split(lines[i], f, " "); want[f[1]] = lines[i] }
  }
  NR == 1 { for (i = 1; i <= NF; ++i) column[$i] = i; next }
  {
    latency = $column["label"] "/" $column["latency_ms"]
    if (!(latency in want)) { print "FAIL: unexpected row " latency; bad = 1; next }
    split(want[latency], f, " ")
    if ($column["processed"] != f[2]) { print "FAIL: " latency ": processed " $column["processed"] ", expected " f[2]; bad = 1 }
    split("MOTA IDF1 DetA AssA", names, " ")
    for (k = 1; k <= 4; ++k) {
      got = $column[names[k]]
      if (got < f[k + 2] - tolerance || got > f[k + 2] + tolerance) {
        print "FAIL: " latency ": " names[k] " " got ", expected " f[k + 2] " +- " tolerance; bad = 1
      }
    }
    seen[latency] = 1
  }
  END {
    for (l in want) if (!(l in seen)) { print "FAIL: no row for " l; bad = 1 }
    exit bad
  }' "$work/scores.tsv"
# The image's gain is beyond the tolerance (4.4 every frame, 11.8 at 250 ms): asserted as such too,
# so a tolerance widened later cannot hide that following the image stopped helping.
awk -F'\t' 'NR > 1 { mota[$1 "/" $3] = $8 }
  END {
    if (mota["image/250"] < mota["boxes/250"] + 5) { print "FAIL: image MOTA " mota["image/250"] " not 5 above boxes " mota["boxes/250"] " at 250 ms"; bad = 1 }
    if (mota["image/every"] < mota["boxes/every"] + 2) { print "FAIL: image MOTA " mota["image/every"] " not 2 above boxes " mota["boxes/every"] " every frame"; bad = 1 }
    exit bad
  }' "$work/scores.tsv"
echo "PASS: vtest.avi 150 frames scored within $tolerance points, every frame and at 250 ms, with and without the image"
