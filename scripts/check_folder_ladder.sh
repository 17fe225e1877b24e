#!/usr/bin/env bash
# The folder ladder (docs/architecture.md) holds in the source, not only in the link lines: every
# `#include "FOLDER/..."` of a library folder names itself or a folder whose library it links
# (directly or through others, as its CMakeLists.txt's target_link_libraries say). A header-only
# include across the ladder links fine, so the build alone cannot catch it. And the research code
# stays apart: no folder the product runs reaches mot/ (the scorer) or study/ (the frame-rate
# study), mot/ does not reach study/, and in apps/ only `rtmot eval` and `rtmot study` include them.
# Prints each breach as FILE: includes FOLDER/ and exits 1; 0 when none.
#   scripts/check_folder_ladder.sh [SOURCE_DIR]
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/.." && pwd)}"
cd "$root"

# Library folders: those whose CMakeLists.txt adds an rtmot_ library (apps/ links everything).
declare -A folder_of_lib lib_deps
folders=()
for cmake in */CMakeLists.txt; do
  folder="${cmake%/CMakeLists.txt}"
  [[ "$folder" == tests || "$folder" == bench || "$folder" == apps ]] && continue
  text="$(tr '\n' ' ' < "$cmake")"
  libs="$(grep -oE 'add_library\( *rtmot_[a-z_]+' <<<"$text" | grep -oE 'rtmot_[a-z_]+' || true)"
  [[ -z "$libs" ]] && continue
  folders+=("$folder")
  for lib in $libs; do
    folder_of_lib[$lib]="$folder"
    deps="$(grep -oE "target_link_libraries\( *$lib [^)]*\)" <<<"$text" | grep -oE 'rtmot_[a-z_]+' |
      grep -vx -e "$lib" -e rtmot_options || true)"
    lib_deps[$lib]="${lib_deps[$lib]:-} $deps"
  done
done
if ((${#folders[@]} < 10)); then
  echo "check_folder_ladder: found only ${#folders[@]} library folders under $root" >&2
  exit 1
fi

# The folders a folder may include: itself and every folder its libraries reach.
reach() {
  local folder="$1" lib dep
  declare -A seen_lib=()
  local queue=()
  for lib in "${!folder_of_lib[@]}"; do
    [[ "${folder_of_lib[$lib]}" == "$folder" ]] && queue+=("$lib")
  done
  while ((${#queue[@]})); do
    lib="${queue[0]}"
    queue=("${queue[@]:1}")
    [[ -n "${seen_lib[$lib]:-}" ]] && continue
    seen_lib[$lib]=1
    for dep in ${lib_deps[$lib]:-}; do
      [[ -z "${folder_of_lib[$dep]:-}" ]] && { echo "$folder: links $dep, which no folder defines" >&2; return 1; }
      queue+=("$dep")
    done
  done
  for lib in "${!seen_lib[@]}"; do echo "${folder_of_lib[$lib]}"; done | sort -u
}

broken=0
is_folder() { local f; for f in "${folders[@]}"; do [[ "$f" == "$1" ]] && return 0; done; return 1; }
for folder in "${folders[@]}"; do
  allowed=" $(reach "$folder" | tr '\n' ' ') "
  # The research rule, stated here once more on purpose: it is the product's promise.
  case "$folder" in
    mot) forbidden=" study " ;;
    study) forbidden=" " ;;
    *) forbidden=" mot study " ;;
  esac
  for research in $forbidden; do
    if [[ "$allowed" == *" $research "* ]]; then
      echo "$folder/CMakeLists.txt: links $research/ (research code)"
      broken=1
    fi
  done
  while IFS=: read -r file included; do
    # Every enum's name table lives at the bottom of the ladder, in tracker/, header-only, for every
    # folder to include (tracker/enum_names.hpp says why).
    [[ "$included" == *'"tracker/enum_names.hpp'* ]] && continue
    target="${included#*\"}"
    target="${target%%/*}"
    is_folder "$target" || continue
    if [[ "$allowed" != *" $target "* ]]; then
      echo "$file: includes $target/ (not linked by $folder/)"
      broken=1
    fi
  done < <(grep -oE '^#include "[a-z_]+/[a-z_./]+' "$folder"/*.cpp "$folder"/*.hpp 2>/dev/null || true)
done

# apps/ links everything; of its subcommands only the research ones, `rtmot eval` (the scorer) and
# `rtmot study`, include the research code: `rtmot run`, `listen`, `track`, `count`, `soak` do not.
while IFS=: read -r file included; do
  case "$file" in
    apps/cmd_eval.cpp | apps/cmd_study.cpp) ;;
    *)
      echo "$file: includes ${included#*\"} (research code outside the research subcommands)"
      broken=1
      ;;
  esac
done < <(grep -oE '^#include "(mot|study)/' apps/*.cpp apps/*.hpp 2>/dev/null || true)
exit "$broken"
