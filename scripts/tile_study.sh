#!/usr/bin/env bash
# The tiling study (docs/tiling.md, "How the settings were chosen"): the SSD on every frame of the
# two in-sample videos with ground truth, whole and tiled, once (bench/tile_study dump); then each
# candidate merge setting through the product's merge (tile_study merge), the default tracker
# (rtmot track) and the devkit-exact scorer (rtmot eval), scored on the FIRST half of each sequence
# only. The candidate with the best summed MOTA there whose precision is not below the untiled
# detector's on either sequence is chosen; then, and only then, the second halves are scored.
# Research code: the product never runs it. Needs ../shared (the sequences and their ground truth).
#
# Usage: scripts/tile_study.sh [OUT] (default build/tile-study). Env: BUILD (default build),
# BACKEND (xnnpack), THREADS (1: run beside other work, XNNPACK's threads spin for their cores),
# FRAMES (all).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/build/tile-study}"
build="${BUILD:-$root/build}"
shared="$root/../shared/data"
tool="$build/bench/tile_study"
rtmot="$build/apps/rtmot"
for f in "$tool" "$rtmot" "$shared/mot15-train/PETS09-S2L1/gt/gt.txt" "$shared/video-gt/ADL-Rundle-6/gt/gt.txt"; do
  [[ -e $f ]] || { echo "tile_study.sh: $f is missing (build the bench targets; ../shared beside the project)" >&2; exit 1; }
done
mkdir -p "$out"

# sequence name, source URI, gt folder, grids to dump
sequences=(
  "PETS09-S2L1|$root/data/vtest.avi|$shared/mot15-train/PETS09-S2L1|2x2,3x2"
  "ADL-Rundle-6|images://$shared/video-gt/ADL-Rundle-6/img1?fps=30|$shared/video-gt/ADL-Rundle-6|2x2,3x2,4x2"
)
for entry in "${sequences[@]}"; do
  IFS='|' read -r name uri gt grids <<<"$entry"
  raw="$out/raw/$name.csv"
  if [[ ! -s $raw ]]; then
    mkdir -p "$out/raw"
    echo "tile_study.sh: dumping $name (grids $grids)"
    "$tool" dump --source "$uri" --out "$raw.tmp" --grids "$grids" --overlap 0.2 --cut 0.1 \
      --backend "${BACKEND:-xnnpack}" --threads "${THREADS:-1}" --frames "${FRAMES:-1000000}"
    mv "$raw.tmp" "$raw"
  fi
done

# One candidate: NAME, the grid for PETS09-S2L1 (768x576), the grid for ADL-Rundle-6 (1920x1080),
# then tile_study merge arguments. Writes $out/runs/NAME/{ds,res}, and the scores of each half
# into $out/runs/NAME/{first,second}.csv.
run_candidate() {
  local cname="$1"
  local -A grid_of=([PETS09-S2L1]="$2" [ADL-Rundle-6]="$3")
  shift 3
  local dir="$out/runs/$cname"
  rm -rf "$dir"
  mkdir -p "$dir/ds" "$dir/res"
  for entry in "${sequences[@]}"; do
    IFS='|' read -r name uri gt grids <<<"$entry"
    mkdir -p "$dir/ds/$name/det" "$dir/ds/$name/gt"
    cp "$gt/seqinfo.ini" "$dir/ds/$name/"
    cp "$gt/gt/gt.txt" "$dir/ds/$name/gt/"
    "$tool" merge --raw "$out/raw/$name.csv" --grid "${grid_of[$name]}" "$@" >"$dir/ds/$name/det/det.txt"
  done
  "$rtmot" track --dataset "$dir/ds" --out "$dir/res" >/dev/null 2>"$dir/track.log"
  for half in first second; do
    mkdir -p "$dir/$half"
    for entry in "${sequences[@]}"; do
      IFS='|' read -r name uri gt grids <<<"$entry"
      cp "$dir/res/$name.txt" "$dir/$half/"
      local length
      length=$(sed -n 's/^seqLength=//p' "$gt/seqinfo.ini")
      local middle=$((length / 2))
      if [[ $half == first ]]; then seq 1 "$middle"; else seq $((middle + 1)) "$length"; fi >"$dir/$half/$name.frames"
    done
    "$rtmot" eval --gt "$dir/ds" --results "$dir/$half" --processed-frames --csv "$dir/$half.csv" \
      >/dev/null 2>>"$dir/eval.log"
  done
}

# The candidates: what is swept is written here. Added after the first run (docs/tiling.md says
# so): the containment values 0.5 and 0.6 (0.7, then the grid's edge, won), and 3x2 on
# PETS09-S2L1 (the grid auto's near-square rule gives a 768x576 frame).
candidates_file="$out/candidates.txt"
{
  echo "untiled off off --shapes off"
  echo "untiled-shapes off off --shapes on"
  for grids in "off 2x2" "off 3x2" "off 4x2" "2x2 3x2" "2x2 4x2" "3x2 3x2" "3x2 4x2"; do
    for tcut in 0.3 0.4 0.5; do
      for contain in 0.5 0.6 0.7 0.9; do
        echo "${grids/ /-}-t$tcut-c$contain $grids --tile-cut $tcut --containment $contain"
      done
    done
  done
} >"$candidates_file"
while read -r cname args; do
  # shellcheck disable=SC2086
  run_candidate "$cname" $args
  echo "tile_study.sh: $cname done"
done <"$candidates_file"
python3 "$root/scripts/tile_study_table.py" "$out"
