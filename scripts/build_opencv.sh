#!/usr/bin/env bash
# Builds the minimal OpenCV the detector needs (core, imgproc, imgcodecs, dnn; with --cuda also
# cudev and the CUDA/cuDNN DNN backend) into a prefix, pinned to one version, so that every machine
# runs the same DNN code: Debian 12's OpenCV 4.6 runs our SSD 1.6x slower on the CPU than 4.10
# (docs/gpu.md), and JetPack's OpenCV has no CUDA at all.
#
#   scripts/build_opencv.sh [--prefix DIR] [--source DIR|TARBALL] [--contrib DIR|TARBALL]
#                           [--cuda --cuda-arch "7.2;8.7"] [--cudnn DIR] [--build-dir DIR]
#                           [--jobs N] [--pack FILE.tar.xz] [--configure-only]
#
# Source: by default the official 4.10.0 release tarballs (opencv and, for --cuda, opencv_contrib)
# downloaded from GitHub and checked against pinned sizes; --source takes a local folder or tarball
# instead (a release folder opencv-4.10.0/, or a folder holding opencv/ and opencv_contrib/, such as
# ../shared/opencv/opencv-4.10.0-399-cuda-dnn-subset.tar.xz), for machines without network. The
# source is staged in the build folder and patched there with scripts/opencv/*.patch (the fixes
# CUDA 12.x/13 need; see docs/gpu.md): the folder or tarball you name is never modified.
#
# Then: cmake -DOpenCV_DIR=<prefix>/lib/cmake/opencv4 ... builds rtmot against it.
# Needs: cmake, a C++ compiler, ninja (or make), tar, xz; with --cuda the CUDA toolkit (nvcc on
# PATH or CUDA_HOME/CUDA_PATH) and cuDNN (found by OpenCV, or --cudnn DIR with include/ and lib/).
set -euo pipefail

readonly VERSION="4.10.0"
readonly OPENCV_URL="https://github.com/opencv/opencv/archive/refs/tags/${VERSION}.tar.gz"
readonly CONTRIB_URL="https://github.com/opencv/opencv_contrib/archive/refs/tags/${VERSION}.tar.gz"

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix="$repo/build-opencv/install"
build=""
source_arg=""
contrib_arg=""
cuda=0
cuda_arch=""
cudnn=""
jobs="$(nproc)"
pack=""
configure_only=0

log() { echo "build_opencv.sh: $*"; }
die() {
  echo "build_opencv.sh: error: $*" >&2
  exit 1
}
usage() {
  sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
  exit "${1:-0}"
}

while [[ $# -gt 0 ]]; do
  case "$1" in
    --prefix) prefix="$2"; shift 2 ;;
    --source) source_arg="$2"; shift 2 ;;
    --contrib) contrib_arg="$2"; shift 2 ;;
    --cuda) cuda=1; shift ;;
    --cuda-arch) cuda_arch="$2"; shift 2 ;;
    --cudnn) cudnn="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --pack) pack="$2"; shift 2 ;;
    --configure-only) configure_only=1; shift ;;
    -h | --help) usage 0 ;;
    *) echo "build_opencv.sh: unknown argument '$1'" >&2; usage 2 ;;
  esac
done
[[ $cuda == 0 || -n $cuda_arch ]] ||
  die "--cuda needs --cuda-arch (7.2 Xavier, 8.7 Orin, 11.0 Thor, 9.0 H100; several: \"8.7;9.0\")"
[[ $cuda == 1 || -z $cuda_arch ]] || die "--cuda-arch without --cuda"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "--jobs wants a positive number, not '$jobs'"
command -v cmake >/dev/null || die "cmake not found (apt-get install cmake)"
prefix="$(mkdir -p "$prefix" && cd "$prefix" && pwd)"
build="${build:-$(dirname "$prefix")/build}"
mkdir -p "$build"
build="$(cd "$build" && pwd)"
[[ $build != "$prefix" ]] || die "--build-dir and --prefix must differ"

# ---- the source, staged in $build/src (opencv/ and, for --cuda, opencv_contrib/)
stage="$build/src"

# Unpacks tarball $1 into folder $2 (made empty first).
unpack() {
  rm -rf "$2" && mkdir -p "$2"
  case "$1" in
    *.tar.xz | *.txz) tar -xJf "$1" -C "$2" ;;
    *.tar.gz | *.tgz) tar -xzf "$1" -C "$2" ;;
    *.tar) tar -xf "$1" -C "$2" ;;
    *) die "$1: not a .tar.gz, .tar.xz or .tar file" ;;
  esac
}

# Finds, under folder $1, the OpenCV tree (has modules/core and CMakeLists.txt) and the contrib
# tree (has modules/cudev); prints "OPENCV_DIR|CONTRIB_DIR" (either may be empty).
locate_trees() {
  local root="$1" opencv="" contrib="" d
  for d in "$root" "$root"/*/ "$root"/*/*/; do
    d="${d%/}"
    [[ -z $opencv && -f $d/CMakeLists.txt && -d $d/modules/core ]] && opencv="$d"
    [[ -z $contrib && -d $d/modules/cudev && ! -d $d/modules/core ]] && contrib="$d"
  done
  echo "$opencv|$contrib"
}

download() {  # url file
  command -v curl >/dev/null || die "curl not found (apt-get install curl), or give --source"
  log "downloading $1"
  curl -fL --retry 3 --connect-timeout 20 -o "$2.part" "$1" || die "download of $1 failed (no network? give --source)"
  mv "$2.part" "$2"
}

shopt -s nullglob
patches=("$repo"/scripts/opencv/*.patch)
shopt -u nullglob
fingerprint="$VERSION|$source_arg|$contrib_arg|$cuda|$(cat "${patches[@]}" /dev/null | sha256sum)"
if [[ -f $stage/.staged && "$(cat "$stage/.staged")" == "$fingerprint" ]]; then
  log "reusing the patched source in $stage"
else
  rm -rf "$stage" && mkdir -p "$stage/in"
  if [[ -z $source_arg ]]; then
    download "$OPENCV_URL" "$build/opencv-$VERSION.tar.gz"
    unpack "$build/opencv-$VERSION.tar.gz" "$stage/in/opencv"
    if [[ $cuda == 1 && -z $contrib_arg ]]; then
      download "$CONTRIB_URL" "$build/opencv_contrib-$VERSION.tar.gz"
      unpack "$build/opencv_contrib-$VERSION.tar.gz" "$stage/in/contrib"
    fi
  elif [[ -d $source_arg ]]; then
    cp -a "$source_arg" "$stage/in/opencv"
  elif [[ -f $source_arg ]]; then
    unpack "$source_arg" "$stage/in/opencv"
  else
    die "--source $source_arg: no such folder or tarball"
  fi
  if [[ -n $contrib_arg ]]; then
    if [[ -d $contrib_arg ]]; then
      cp -a "$contrib_arg" "$stage/in/contrib"
    elif [[ -f $contrib_arg ]]; then
      unpack "$contrib_arg" "$stage/in/contrib"
    else
      die "--contrib $contrib_arg: no such folder or tarball"
    fi
  fi
  IFS='|' read -r opencv_tree contrib_tree < <(locate_trees "$stage/in")
  [[ -n $opencv_tree ]] || die "no OpenCV source tree (CMakeLists.txt + modules/core) in ${source_arg:-the download}"
  mv "$opencv_tree" "$stage/opencv"
  if [[ -n $contrib_tree ]]; then
    mkdir -p "$stage/opencv_contrib/modules"
    # Only cudev: the DNN CUDA backend needs it, and any other contrib module would be built too.
    mv "$contrib_tree/modules/cudev" "$stage/opencv_contrib/modules/cudev"
  fi
  rm -rf "$stage/in"
  for patch_file in "${patches[@]}"; do
    # Checked first, so a patch that does not fit leaves the source untouched. It only changes CUDA
    # code: a CPU build goes on without it (saying so), a CUDA build cannot.
    if patch -p1 --forward --batch --dry-run --silent -d "$stage/opencv" <"$patch_file" >/dev/null; then
      log "applying $(basename "$patch_file")"
      patch -p1 --forward --batch --silent -d "$stage/opencv" <"$patch_file"
    elif [[ $cuda == 1 ]]; then
      die "$(basename "$patch_file") does not apply to this source (not OpenCV $VERSION?)"
    else
      log "warning: $(basename "$patch_file") does not apply to this source; not needed without CUDA"
    fi
  done
  echo "$fingerprint" >"$stage/.staged"
fi
version_file="$stage/opencv/modules/core/include/opencv2/core/version.hpp"
found_version="$(awk '/define CV_VERSION_(MAJOR|MINOR|REVISION) /{printf "%s%s", sep, $3; sep="."}' "$version_file")"
log "OpenCV source $found_version ($stage/opencv)"
[[ $found_version == "$VERSION" ]] || die "expected OpenCV $VERSION, the source is $found_version"

# ---- configure
modules="core,imgproc,imgcodecs,dnn"
args=(
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix"
  -DBUILD_SHARED_LIBS=ON -DOPENCV_GENERATE_PKGCONFIG=OFF
  # CMake 4 refuses cmake_minimum_required() below 3.5, which parts of OpenCV 4.10 still say.
  -DCMAKE_POLICY_VERSION_MINIMUM=3.5
  # C++17 like rtmot (and as CUDA 13 requires of code that includes its headers).
  -DCMAKE_CXX_STANDARD=17
  # Nothing but the libraries: no tests, apps, bindings or docs.
  -DBUILD_TESTS=OFF -DBUILD_PERF_TESTS=OFF -DBUILD_EXAMPLES=OFF -DBUILD_opencv_apps=OFF
  -DBUILD_JAVA=OFF -DBUILD_opencv_python2=OFF -DBUILD_opencv_python3=OFF -DBUILD_DOCS=OFF
  -DINSTALL_C_EXAMPLES=OFF -DINSTALL_PYTHON_EXAMPLES=OFF
  # Nothing that downloads at configure time (IPP, ADE) or that the detector does not use.
  -DWITH_IPP=OFF -DWITH_ADE=OFF -DWITH_OPENCL=OFF -DWITH_VA=OFF -DWITH_VA_INTEL=OFF
  -DWITH_TBB=OFF -DWITH_OPENMP=OFF -DWITH_EIGEN=OFF -DWITH_LAPACK=OFF -DWITH_ITT=OFF
  -DWITH_FFMPEG=OFF -DWITH_GSTREAMER=OFF -DWITH_V4L=OFF -DWITH_1394=OFF -DWITH_GTK=OFF
  -DWITH_QT=OFF -DWITH_OPENGL=OFF -DWITH_VTK=OFF -DWITH_PROTOBUF=ON -DBUILD_PROTOBUF=ON
  # Image files: PNG (bundled) and JPEG (the system's libjpeg when there is one), as the image-folder
  # source reads; no TIFF, WebP, JPEG 2000, OpenEXR, AVIF.
  -DWITH_TIFF=OFF -DWITH_WEBP=OFF -DWITH_OPENJPEG=OFF -DWITH_JASPER=OFF -DWITH_OPENEXR=OFF
  -DWITH_AVIF=OFF -DWITH_IMGCODEC_HDR=OFF -DWITH_IMGCODEC_SUNRASTER=OFF -DWITH_IMGCODEC_PFM=OFF
  -DBUILD_PNG=ON -DBUILD_ZLIB=ON
)
if [[ -d $stage/opencv/3rdparty/libjpeg-turbo ]]; then
  args+=(-DWITH_JPEG=ON)
elif [[ -f /usr/include/jpeglib.h || -f /usr/include/$(uname -m)-linux-gnu/jpeglib.h ]]; then
  args+=(-DWITH_JPEG=ON -DBUILD_JPEG=OFF)
else
  log "no libjpeg headers (apt-get install libjpeg62-turbo-dev) and none in the source: JPEG off"
  args+=(-DWITH_JPEG=OFF)
fi
if [[ $cuda == 1 ]]; then
  [[ -d $stage/opencv_contrib/modules/cudev ]] ||
    die "--cuda needs opencv_contrib's cudev: give --contrib, or a --source that holds opencv_contrib/"
  nvcc="$(command -v nvcc || true)"
  for home in "${CUDA_HOME:-}" "${CUDA_PATH:-}" /usr/local/cuda; do
    [[ -z $nvcc && -n $home && -x $home/bin/nvcc ]] && nvcc="$home/bin/nvcc"
  done
  [[ -n $nvcc ]] || die "--cuda: nvcc not found (PATH, CUDA_HOME, /usr/local/cuda)"
  cuda_home="$(cd "$(dirname "$nvcc")/.." && pwd)"
  log "CUDA $("$nvcc" --version | sed -n 's/.*release \([0-9.]*\).*/\1/p') at $cuda_home, arch $cuda_arch"
  modules+=",cudev"
  args+=(
    -DOPENCV_EXTRA_MODULES_PATH="$stage/opencv_contrib/modules"
    -DWITH_CUDA=ON -DWITH_CUDNN=ON -DWITH_CUBLAS=ON -DOPENCV_DNN_CUDA=ON -DWITH_CUFFT=OFF
    -DWITH_NVCUVID=OFF -DWITH_NVCUVENC=OFF -DCUDA_FAST_MATH=OFF
    -DCUDA_TOOLKIT_ROOT_DIR="$cuda_home" -DCUDA_ARCH_BIN="$cuda_arch" -DCUDA_ARCH_PTX=""
    # Given explicitly: CUDA 13's arch detection comes back empty without it (opencv issue 28952).
    -DCUDA_HOST_COMPILER="$(command -v "${CXX:-g++}")"
  )
  if [[ -n $cudnn ]]; then
    [[ -f $cudnn/include/cudnn.h ]] || die "--cudnn $cudnn: no include/cudnn.h"
    lib="$(ls "$cudnn"/lib/libcudnn.so "$cudnn"/lib64/libcudnn.so 2>/dev/null | head -1 || true)"
    [[ -n $lib ]] || die "--cudnn $cudnn: no lib/libcudnn.so (a symlink to libcudnn.so.9 will do)"
    args+=(-DCUDNN_INCLUDE_DIR="$cudnn/include" -DCUDNN_LIBRARY="$lib")
  fi
else
  args+=(-DWITH_CUDA=OFF)
fi
args+=(-DBUILD_LIST="$modules")
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

log "configuring ($modules) in $build/cmake"
started=$SECONDS
cmake -S "$stage/opencv" -B "$build/cmake" "${generator[@]}" "${args[@]}" >"$build/configure.log" 2>&1 ||
  { tail -40 "$build/configure.log" >&2; die "configure failed: $build/configure.log"; }
if [[ $cuda == 1 ]] && ! grep -q "NVIDIA CUDA:.*YES" "$build/configure.log"; then
  grep -n -i "cuda\|cudnn" "$build/configure.log" | tail -20 >&2
  die "configure did not enable CUDA (see $build/configure.log)"
fi
if [[ $cuda == 1 ]] && ! grep -q "cuDNN:.*YES" "$build/configure.log"; then
  die "configure found no cuDNN (give --cudnn DIR; see $build/configure.log)"
fi
log "configured in $((SECONDS - started)) s"
if [[ $configure_only == 1 ]]; then
  log "--configure-only: build with cmake --build $build/cmake"
  exit 0
fi
log "building with $jobs jobs"
started=$SECONDS
cmake --build "$build/cmake" --parallel "$jobs" >"$build/build.log" 2>&1 ||
  { grep -n -B2 -A8 "error" "$build/build.log" | head -60 >&2; die "build failed: $build/build.log"; }
log "built in $((SECONDS - started)) s"
cmake --install "$build/cmake" --strip >"$build/install.log" 2>&1 ||
  die "install failed: $build/install.log"
# What the build is, for the logs of whoever uses it (rtmot logs the OpenCV version at start-up).
grep -E "^  (OpenCV modules|    To be built|  NVIDIA CUDA|    NVIDIA GPU arch|    cuDNN|  Parallel framework|    Baseline|    Dispatched)" \
  "$build/configure.log" | sed 's/^ *//' >"$prefix/BUILD_INFO.txt" || true
echo "source: ${source_arg:-$OPENCV_URL}" >>"$prefix/BUILD_INFO.txt"
log "installed OpenCV $VERSION in $prefix: cmake -DOpenCV_DIR=$prefix/lib/cmake/opencv4"
if [[ -n $pack ]]; then
  tar -C "$(dirname "$prefix")" -cJf "$pack" "$(basename "$prefix")"
  log "packed $(du -h "$pack" | cut -f1) into $pack"
fi
