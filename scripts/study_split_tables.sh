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

# One row per detector and interval: configuration $1 (whose bar is checked) against the
# configurations listed in $2 ("config=title" entries separated by ";"), SORT and ByteTrack; $3
# names $1's column.
held_out_table() {
  local default_config="$1" others="$2" title="$3"; shift 3
  local header="| detector | N | ${title} |" rule="|---|---:|---:|" other
  local -a other_list
  IFS=';' read -r -a other_list <<< "$others"
  for other in "${other_list[@]}"; do
    header+=" ${other#*=} |"
    rule+="---:|"
  done
  echo "$header sort | bytetrack | bar met |"
  echo "$rule---:|---:|:---:|"
  local input n
  for input in "$@"; do
    for n in 1 5 10; do
      local value columns=""
      value="$(cell "$input" "$default_config" "$n")" || exit 1
      read -r dm di <<< "$value"
      for other in "${other_list[@]}"; do
        value="$(cell "$input" "${other%%=*}" "$n")" || exit 1
        read -r om oi <<< "$value"
        columns+=" $om / $oi |"
      done
      value="$(cell "$input" preset-sort "$n")" || exit 1
      read -r sm si <<< "$value"
      value="$(cell "$input" preset-bytetrack "$n")" || exit 1
      read -r bm bi <<< "$value"
      met=$(awk -v n="$n" -v dm="$dm" -v di="$di" -v sm="$sm" -v si="$si" -v bm="$bm" -v bi="$bi" 'BEGIN {
        f = (n == 1) ? 1 : 1.2
        ms = (sm < 0) ? sm : f * sm; is = f * si
        miss = ""
        if (dm < ms) miss = miss sprintf(" MOTA %.1f < %s", ms - dm, n == 1 || sm < 0 ? "SORT" : "1.2x SORT")
        if (di < is) miss = miss sprintf(" IDF1 %.1f < %s", is - di, n == 1 ? "SORT" : "1.2x SORT")
        if (dm < bm) miss = miss sprintf(" MOTA %.1f < BT", bm - dm)
        if (di < bi) miss = miss sprintf(" IDF1 %.1f < BT", bi - di)
        print (miss == "" ? "yes" : "no:" miss) }')
      echo "| $input | $n | $dm / $di |$columns $sm / $si | $bm / $bi | $met |"
    done
  done
}

# The held-back tables: the default against the default of issue 21's first round (the cap at the
# median on every shape, the since-match gate clock) and the one before issue 21.
before="preset-rtmot-issue21=default of issue 21's first round;preset-rtmot-issue20=default before issue 21"

echo "### Held back since issue 21 section 3: holdout-q..v"
echo
held_out_table preset-rtmot "$before" default holdout-q holdout-r holdout-s holdout-t holdout-u holdout-v
echo
echo "### Held back since issue 21 (first round): holdout-k..p"
echo
held_out_table preset-rtmot "$before" default holdout-k holdout-l holdout-m holdout-n holdout-o holdout-p
echo
echo "### Held back before: holdout-a..j"
echo
held_out_table preset-rtmot "$before" default holdout-a holdout-b holdout-c holdout-d holdout-e holdout-f holdout-g \
  holdout-h holdout-i holdout-j
echo
echo "### Cross-validation: the choosing procedure held out (cv-held-out), against the choice in-sample"
echo
held_out_table cv-held-out "cv-in-sample=cv-in-sample" "default, held out" det synth-frcnn synth-dpm synth-ssd \
  synth-clean synth-noisy synth-svm synth-raw
echo
echo "### MOT15 det/det.txt, every preset (in-sample for the default)"
echo
echo "| preset | N = 1 | N = 5 | N = 10 |"
echo "|---|---:|---:|---:|"
for config in preset-rtmot preset-rtmot-issue21 preset-rtmot-issue20 preset-sort preset-bytetrack preset-bytetrack+kalman-xyah; do
  row="| ${config#preset-} |"
  for n in 1 5 10; do
    value="$(cell det "$config" "$n")" || exit 1
    read -r m i <<< "$value"
    row+=" $m / $i |"
  done
  echo "$row"
done
