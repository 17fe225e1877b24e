#!/usr/bin/env bash
# Rewrites the absolute symlinks inside a copied root file system (a Jetson's /usr rsync'ed to the host,
# or a Debian sysroot) into relative ones, so that `usr/lib/aarch64-linux-gnu/libfoo.so -> /lib/...`
# points into the sysroot instead of into the host's own /lib. Idempotent.
# Usage: scripts/cross_fix_sysroot_links.sh SYSROOT
set -euo pipefail

sysroot="${1:?usage: cross_fix_sysroot_links.sh SYSROOT}"
sysroot="$(cd "$sysroot" && pwd)"

fixed=0
while IFS= read -r -d '' link; do
  target="$(readlink "$link")"
  # The target as seen from inside the sysroot, made relative to the link's own folder.
  relative="$(realpath --relative-to="$(dirname "$link")" --canonicalize-missing --no-symlinks "$sysroot$target")"
  ln -sfn "$relative" "$link"
  fixed=$((fixed + 1))
done < <(find "$sysroot" -type l -lname '/*' -print0)
echo "cross_fix_sysroot_links: made $fixed absolute symlinks under $sysroot relative"
