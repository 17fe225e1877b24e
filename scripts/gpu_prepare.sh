#!/usr/bin/env bash
# Prepares the carried folder for a GPU machine without network or apt (docs/gpu.md §3): everything
# scripts/opencv/gpu_machine.sh needs, fetched here on Debian 12.
#
#   scripts/gpu_prepare.sh [--carry DIR] [--build-dir DIR] [--opencv-install FILE.tar.xz]
#
#   --carry DIR        where to put it (default: .gpu-carry in this checkout, git-ignored)
#   --build-dir DIR    a configured build of this checkout on this machine, whose CMakeCache.txt says
#                      what CMake found (default: build/, configured here when it is not)
#   --opencv-install F an OpenCV install packed by an earlier GPU run (gpu_machine.sh's
#                      opencv-4.10-cuda-sm90.tar.xz) instead of the source to build it from
#
# What it holds:
#   requirements.tsv   the CMake requirements it was derived from (scripts/gpu_deps.sh requirements):
#                      gpu_machine.sh refuses to start when the checkout requires something more
#   packages.txt, debs/ the Debian 12 packages (scripts/gpu_deps.sh packages), apt-get download
#   pkgconfig/         one .pc per pkg-config module, flattened (its own and its requirements' flags
#                      as this machine's pkg-config gives them) with /usr as ${prefix}, so that the
#                      other machine needs none of the modules' private requirements
#   opencv-*.tar.xz    the OpenCV source subset (../shared/opencv) or the packed install
#   model/             the SSD model, its anchors and checksum (models/ssdlite_mobilenet_v2_coco.*)
#   shared/            the test data the detector tests and benchmarks read (reference detections,
#                      vtest.avi, one MOT15 det.txt); gpu_machine.sh extracts the reference frames from
#                      vtest.avi there with FFmpeg, as the reference detections were decoded
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
carry="$repo/.gpu-carry"
build_dir="$repo/build"
opencv_install=""
while (($#)); do
  case $1 in
    --carry) carry="$(realpath -m "$2")"; shift 2 ;;
    --build-dir) build_dir="$(realpath -m "$2")"; shift 2 ;;
    --opencv-install) opencv_install="$(realpath "$2")"; shift 2 ;;
    *) echo "gpu_prepare: unknown option '$1' (see the script's header)" >&2; exit 2 ;;
  esac
done
step() { echo "=== gpu_prepare: $*"; }
die() {
  echo "gpu_prepare: $*" >&2
  exit 1
}
shared="$repo/../shared"
model="$repo/models/ssdlite_mobilenet_v2_coco.onnx"
[[ -f $model ]] || die "$model: not found: run scripts/fetch_model.sh first (a fresh clone has no model; docs/gpu.md §3)"
for f in data/reference/ssdlite-coco-vtest-detections.csv data/video/vtest.avi \
  data/mot15-train/TUD-Campus/det/det.txt; do
  [[ -f $shared/$f ]] || die "$shared/$f: not found (../shared, see its README)"
done
command -v apt-get >/dev/null && command -v dpkg >/dev/null || die "needs apt-get and dpkg (Debian 12)"

if [[ ! -f $build_dir/CMakeCache.txt ]]; then
  step "configuring $build_dir (CMake says what it requires and where it found it)"
  cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi

rm -rf "$carry"
mkdir -p "$carry/debs" "$carry/pkgconfig" "$carry/model" "$carry/shared"
step "requirements and packages (scripts/gpu_deps.sh)"
"$repo/scripts/gpu_deps.sh" requirements >"$carry/requirements.tsv"
"$repo/scripts/gpu_deps.sh" packages "$build_dir" >"$carry/packages.txt"
echo "$(wc -l <"$carry/packages.txt") packages: $(tr '\n' ' ' <"$carry/packages.txt")"

step "apt-get download"
(cd "$carry/debs" && xargs apt-get download -q <"$carry/packages.txt") || die "apt-get download failed (run apt-get update once)"
[[ $(ls "$carry/debs"/*.deb | wc -l) -eq $(wc -l <"$carry/packages.txt") ]] ||
  die "downloaded $(ls "$carry/debs"/*.deb | wc -l) .debs for $(wc -l <"$carry/packages.txt") packages"

step "pkg-config files, flattened, prefix relocatable"
for module in $(awk -F'\t' '$1 ~ /^pkg_/ {print $2}' "$carry/requirements.tsv" | sort -u); do
  pkg-config --exists "$module" || die "pkg-config: $module not found here"
  {
    echo "prefix=/usr"
    echo "Name: $module"
    echo "Description: $module as Debian 12's pkg-config resolves it (scripts/gpu_prepare.sh)"
    echo "Version: $(pkg-config --modversion "$module")"
    echo "Cflags: $(pkg-config --cflags "$module" | sed 's|-I/usr/|-I${prefix}/|g')"
    echo "Libs: -L\${prefix}/lib/$(gcc -dumpmachine) $(pkg-config --libs "$module")"
  } >"$carry/pkgconfig/$module.pc"
done

step "OpenCV"
if [[ -n $opencv_install ]]; then
  cp "$opencv_install" "$carry/opencv-4.10-cuda-sm90.tar.xz"
else
  source_tar="$(ls "$shared"/opencv/opencv-4.10.0-*.tar.xz 2>/dev/null | head -n 1)"
  [[ -n $source_tar ]] || die "$shared/opencv/opencv-4.10.0-*.tar.xz: not found"
  cp "$source_tar" "$carry/"
fi

step "model and test data"
cp -L "$repo"/models/ssdlite_mobilenet_v2_coco.* "$carry/model/" # model, anchors, checksum
for f in data/reference/ssdlite-coco-vtest-detections.csv data/video/vtest.avi \
  data/mot15-train/TUD-Campus/det/det.txt; do
  mkdir -p "$carry/shared/$(dirname "$f")"
  cp "$shared/$f" "$carry/shared/$f"
done

tracked=$(git -C "$repo" ls-files -z | (cd "$repo" && xargs -0 du -cb 2>/dev/null) | tail -n 1 | cut -f1)
size=$(du -sb "$carry" | cut -f1)
step "$carry: $((size / 1024 / 1024)) MiB (+ $((tracked / 1024 / 1024)) MiB tracked files)"
((size + tracked < 64 * 1024 * 1024)) || die "more than the 64 MiB a device call carries"
