#!/usr/bin/env bash
# The tables of docs/study.md's "A split for the shape of any detector's scores" (issue 21), cut
# from a full study run's OUT (scripts/study.sh or `rtmot study --dataset ... --out OUT`):
#   scripts/study_split_tables.sh OUT
# MOTA / IDF1 at intervals 1, 5 and 10, all sequences pooled, and whether the bar is met: at N = 1
# at least SORT and ByteTrack, at N = 5 and 10 at least 1.2 x SORT (SORT itself where its MOTA is
# negative) and ByteTrack, in MOTA and in IDF1.
set -euo pipefail
out="${1:?usage: scripts/study_split_tables.sh OUT}"
tables="$out/tables"
[[ -d "$tables" ]] || { echo "study_split_tables.sh: $tables missing (not a study run?)" >&2; exit 1; }

# "MOTA IDF1" of configuration $2 on input $1 at interval $3.
cell() {
  local file="$tables/$1/$2.md"
  [[ -f "$file" ]] || { echo "study_split_tables.sh: $file missing" >&2; exit 1; }
  awk -F'|' -v n="$3" '$2 + 0 == n && $2 ~ /[0-9]/ { gsub(/ /, "", $14); gsub(/ /, "", $16); print $14, $16; found = 1 }
    END { if (!found) exit 1 }' "$file" || { echo "study_split_tables.sh: no interval $3 in $file" >&2; exit 1; }
}

# One row per detector and interval: configuration $1 (whose bar is checked) against $2, SORT and
# ByteTrack; $3 names $1's column.
held_out_table() {
  local default_config="$1" other="$2" title="$3"; shift 3
  echo "| detector | N | ${title} | ${other#preset-} | sort | bytetrack | bar met |"
  echo "|---|---:|---:|---:|---:|---:|:---:|"
  local input n
  for input in "$@"; do
    for n in 1 5 10; do
      read -r dm di <<< "$(cell "$input" "$default_config" "$n")"
      read -r om oi <<< "$(cell "$input" "$other" "$n")"
      read -r sm si <<< "$(cell "$input" preset-sort "$n")"
      read -r bm bi <<< "$(cell "$input" preset-bytetrack "$n")"
      met=$(awk -v n="$n" -v dm="$dm" -v di="$di" -v sm="$sm" -v si="$si" -v bm="$bm" -v bi="$bi" 'BEGIN {
        f = (n == 1) ? 1 : 1.2
        ms = (sm < 0) ? sm : f * sm; is = f * si
        miss = ""
        if (dm < ms) miss = miss sprintf(" MOTA %.1f < %s", ms - dm, n == 1 || sm < 0 ? "SORT" : "1.2x SORT")
        if (di < is) miss = miss sprintf(" IDF1 %.1f < %s", is - di, n == 1 ? "SORT" : "1.2x SORT")
        if (dm < bm) miss = miss sprintf(" MOTA %.1f < BT", bm - dm)
        if (di < bi) miss = miss sprintf(" IDF1 %.1f < BT", bi - di)
        print (miss == "" ? "yes" : "no:" miss) }')
      echo "| $input | $n | $dm / $di | $om / $oi | $sm / $si | $bm / $bi | $met |"
    done
  done
}

echo "### Held back since issue 21: holdout-k..p"
echo
held_out_table preset-rtmot preset-rtmot-issue20 default holdout-k holdout-l holdout-m holdout-n holdout-o holdout-p
echo
echo "### Held back before: holdout-a..j"
echo
held_out_table preset-rtmot preset-rtmot-issue20 default holdout-a holdout-b holdout-c holdout-d holdout-e holdout-f holdout-g \
  holdout-h holdout-i holdout-j
echo
echo "### Cross-validation: the choosing procedure held out (cv-held-out), against the choice in-sample"
echo
held_out_table cv-held-out cv-in-sample "default, held out" det synth-frcnn synth-dpm synth-ssd \
  synth-clean synth-noisy synth-svm synth-raw
echo
echo "### MOT15 det/det.txt, every preset (in-sample for the default)"
echo
echo "| preset | N = 1 | N = 5 | N = 10 |"
echo "|---|---:|---:|---:|"
for config in preset-rtmot preset-rtmot-issue20 preset-sort preset-bytetrack preset-bytetrack+kalman-xyah; do
  row="| ${config#preset-} |"
  for n in 1 5 10; do
    read -r m i <<< "$(cell det "$config" "$n")"
    row+=" $m / $i |"
  done
  echo "$row"
done
