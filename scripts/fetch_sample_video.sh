#!/usr/bin/env bash
# Puts the sample video (vtest.avi, people walking, 768x576, 10 fps) at data/vtest.avi. It ships in
# Debian's opencv-doc package; we download that package with apt and extract the one file.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="$root/data/vtest.avi"
expected_sha256="45cddc9490be69345cbdab64ca583be65987e864ca408038e648db99e10516cf"

if [[ -f "$target" ]] && echo "$expected_sha256  $target" | sha256sum --check --status; then
  echo "fetch_sample_video: $target present"
  exit 0
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
chmod 777 "$work"  # apt's sandbox user must be able to write the download
(cd "$work" && apt-get download -qq opencv-doc >/dev/null 2>&1 || true)
deb=$(ls "$work"/opencv-doc_*.deb 2>/dev/null | head -n 1)
[[ -n "$deb" ]] || { echo "fetch_sample_video: could not download opencv-doc (run apt-get update?)" >&2; exit 1; }
dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$work" ./usr/share/doc/opencv-doc/examples/data/vtest.avi
mkdir -p "$root/data"
mv "$work/usr/share/doc/opencv-doc/examples/data/vtest.avi" "$target"
echo "$expected_sha256  $target" | sha256sum --check --status || {
  echo "fetch_sample_video: checksum mismatch for $target" >&2; rm -f "$target"; exit 1; }
echo "fetch_sample_video: wrote $target"
