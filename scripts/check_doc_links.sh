#!/usr/bin/env bash
# Every relative link of README.md and docs/**/*.md resolves to a file of the tree, and every
# `docs/...` path quoted in them exists (generated output lives outside docs/: a stale link is how
# a deleted file shows). Prints each broken one as FILE:LINE: TARGET and exits 1; 0 when none.
#   scripts/check_doc_links.sh [SOURCE_DIR]
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/.." && pwd)}"
cd "$root"
broken=0
while IFS= read -r md; do
  dir="$(dirname "$md")"
  # Markdown links and images: ](target) or ](target "title"); URLs and in-page anchors skipped.
  while IFS=: read -r line target; do
    target="${target%%#*}"
    [[ -z "$target" || "$target" =~ ^[a-z]+: ]] && continue
    [[ -e "$dir/$target" ]] || { echo "$md:$line: $target"; broken=1; }
  done < <(grep -noE '\]\([^) ]+' "$md" | sed -E 's/\]\(//')
  # Quoted repository paths under docs/ (globs, braces and placeholders are not paths).
  while IFS=: read -r line target; do
    target="${target//\`/}"
    [[ "$target" =~ [*{}\<\>] ]] && continue
    [[ -e "$target" ]] || { echo "$md:$line: $target"; broken=1; }
  done < <(grep -noE '`docs/[^` ]+`' "$md")
done < <(git ls-files 'README.md' 'docs/*.md' 'docs/**/*.md' 2>/dev/null || find README.md docs -name '*.md')
exit "$broken"
