#!/usr/bin/env bash
# System test: lines and a zone in a source's `events:` section (docs/events.md). PETS09-S2L1
# (image-less, replay detector, every frame) through `rtmot run`: the events arrive in the binary
# messages (`rtmot listen --read` counts them per kind and index) and in the JSON lines, with the
# same counts, and both lines are crossed in both directions; the last message ends the stream with
# the exits of the tracks still inside the zone. A zero-length line is refused before
# anything runs: exit 3 naming file:line:field. The same section given inline with --events counts
# the same.
# Usage: events_in_stream.sh RTMOT SHARED_DIR
set -euo pipefail
rtmot=$1 shared_dir=$2
seq=$shared_dir/data/mot15-train/PETS09-S2L1
[[ -f $seq/seqinfo.ini ]] || { echo "FAIL: missing test input $seq/seqinfo.ini"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/run.yaml" <<YAML
source:
  uri: mot-seq://$seq
  events:
    dwell_s: 5
    lines:
      - {name: middle, units: fraction, from: [0.5, 0.0], to: [0.5, 1.0]}
      - {name: low, units: fraction, from: [0.0, 0.75], to: [1.0, 0.75]}
    zones:
      - {name: left, units: fraction, points: [[0.05, 0.3], [0.45, 0.3], [0.45, 0.95], [0.05, 0.95]]}
detector:
  kind: replay
  det_file: $seq/det/det.txt
playback:
  mode: every-frame
YAML
"$rtmot" run --config "$work/run.yaml" --binary "$work/m.bin" --jsonl "$work/m.jsonl" 2>"$work/run.err" ||
  { cat "$work/run.err"; echo "FAIL: rtmot run"; exit 1; }
"$rtmot" listen --read "$work/m.bin" --quiet > "$work/listen.txt"
checked=0
for kind in line_in line_out zone_enter zone_exit zone_dwell; do
  for index in 0 1; do
    from_listen=$(sed -n "s/^  stream 0: events $kind $index: //p" "$work/listen.txt")
    from_json=$({ grep -o "\"kind\":\"$kind\",\"index\":$index," "$work/m.jsonl" || true; } | wc -l)
    [[ "${from_listen:-0}" == "$from_json" ]] ||
      { echo "FAIL: $kind $index: listen ${from_listen:-0}, JSON $from_json"; exit 1; }
    checked=$((checked + from_json))
  done
done
for kind in line_in line_out; do
  for index in 0 1; do
    grep -q "^  stream 0: events $kind $index: [1-9]" "$work/listen.txt" ||
      { echo "FAIL: no $kind on line $index"; cat "$work/listen.txt"; exit 1; }
  done
done
grep -q "^  stream 0: events zone_dwell 0: [1-9]" "$work/listen.txt" ||
  { echo "FAIL: no dwell in the zone"; exit 1; }
# The end of the stream: one last message, flagged, with no tracks, in which the tracks still inside
# the zone leave it (lost): every enter has its exit.
tail -n 1 "$work/m.jsonl" | grep -q '"tracks":\[\].*"end_of_stream":true' ||
  { echo "FAIL: no end-of-stream message last"; tail -n 1 "$work/m.jsonl"; exit 1; }
[[ $(grep -c '"end_of_stream"' "$work/m.jsonl") == 1 ]] || { echo "FAIL: end of stream twice"; exit 1; }
tail -n 1 "$work/m.jsonl" | grep -q '"kind":"zone_exit","index":0,[^}]*"lost":true' ||
  { echo "FAIL: no lost exit at the end"; exit 1; }
enters=$(sed -n "s/^  stream 0: events zone_enter 0: //p" "$work/listen.txt")
exits=$(sed -n "s/^  stream 0: events zone_exit 0: //p" "$work/listen.txt")
[[ -n $enters && $enters == "$exits" ]] || { echo "FAIL: $enters enters, $exits exits"; exit 1; }

# The same lines and zone given on the command line (--events, the section written inline) count
# the same events as the file's section.
cat > "$work/plain.yaml" <<YAML
source:
  uri: mot-seq://$seq
detector:
  kind: replay
  det_file: $seq/det/det.txt
playback:
  mode: every-frame
YAML
"$rtmot" run --config "$work/plain.yaml" --jsonl "$work/flag.jsonl" --events "{dwell_s: 5, lines: [
  {name: middle, units: fraction, from: [0.5, 0.0], to: [0.5, 1.0]},
  {name: low, units: fraction, from: [0.0, 0.75], to: [1.0, 0.75]}], zones: [{name: left,
  units: fraction, points: [[0.05, 0.3], [0.45, 0.3], [0.45, 0.95], [0.05, 0.95]]}]}" \
  2>"$work/flag.err" || { cat "$work/flag.err"; echo "FAIL: rtmot run --events"; exit 1; }
events_of() { grep -o '"kind":"[a-z_]*","index":[0-9]*' "$1" | sort | uniq -c; }
[[ -n "$(events_of "$work/flag.jsonl")" && "$(events_of "$work/flag.jsonl")" == "$(events_of "$work/m.jsonl")" ]] ||
  { echo "FAIL: --events counted differently from the file's events section"; exit 1; }

sed 's/to: \[0.5, 1.0\]/to: [0.5, 0.0]/' "$work/run.yaml" > "$work/bad.yaml"
status=0
"$rtmot" run --config "$work/bad.yaml" 2>"$work/bad.err" || status=$?
[[ $status == 3 ]] || { echo "FAIL: exit $status for a zero-length line, expected 3"; exit 1; }
grep -q "bad.yaml:6: field 'source.events.lines\[0\]': line 'middle' has zero length" "$work/bad.err" ||
  { echo "FAIL: error does not name file:line:field"; cat "$work/bad.err"; exit 1; }

# The binary messages carry class ids: the ground station names them by COCO's table, or by the
# boards' model's labels file (--labels); a labels file that cannot be one is exit 4 naming its line.
"$rtmot" listen --read "$work/m.bin" --quiet --jsonl "$work/coco.jsonl" >/dev/null
grep -q '"label":"person"' "$work/coco.jsonl" || { echo "FAIL: no COCO label"; exit 1; }
printf 'BACKGROUND\npedestrian\n' > "$work/labels.txt"
"$rtmot" listen --read "$work/m.bin" --quiet --jsonl "$work/own.jsonl" --labels "$work/labels.txt" >/dev/null
grep -q '"label":"pedestrian"' "$work/own.jsonl" && ! grep -q '"label":"person"' "$work/own.jsonl" ||
  { echo "FAIL: --labels did not name the class"; exit 1; }
printf 'BACKGROUND\npedestrian\npedestrian\n' > "$work/twice.txt"
status=0
"$rtmot" listen --read "$work/m.bin" --quiet --jsonl "$work/x.jsonl" --labels "$work/twice.txt" \
  >/dev/null 2>"$work/twice.err" || status=$?
[[ $status == 4 ]] && grep -q "twice.txt:3" "$work/twice.err" ||
  { echo "FAIL: exit $status for a name given twice, expected 4 naming twice.txt:3"; cat "$work/twice.err"; exit 1; }
echo "PASS: $checked events, the same in listen and JSON; a zero-length line is exit 3; listen names classes by --labels"
