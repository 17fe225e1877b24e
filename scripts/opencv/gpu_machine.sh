#!/usr/bin/env bash
# The GPU verification run (docs/gpu.md), as run on the lent GPU machine (Ubuntu 24.04, CUDA 13,
# cuDNN from pip, no network, no apt): everything it needs travels in .devcarry/ (Debian 12 -dev
# packages unpacked with dpkg -x into a folder of its own, the OpenCV source subset or an OpenCV
# install built by an earlier run, the reference frames decoded as the reference was) and models/.
#
#   scripts/opencv/gpu_machine.sh OUT_DIR [stages]
# stages (default "opencv rtmot tests bench pipeline"):
#   opencv    build OpenCV 4.10 with CUDA (arch 9.0) from .devcarry/opencv-*.tar.xz and pack the
#             install to OUT_DIR/opencv-4.10-cuda-sm90.tar.xz (reused by later runs when it is
#             carried as .devcarry/opencv-4.10-cuda-sm90.tar.xz)
#   rtmot     build rtmot's detector tests, benchmarks (and rtmot itself where it links) against it
#   tests     the detector tests on cpu, cuda and cuda-fp16 (reference frames: .devcarry/vtest-ref)
#   bench     detector_batch_bench: forward ms per backend at batch 1, 2, 4, 8, 16 (twice), and
#             with batches varying by one image
#   pipeline  rtmot run every-frame on an image folder, per backend, 1/2/4/8 sources
# The logs are packed into OUT_DIR/logs.tar.xz (the device returns 8 files at most).
set -uo pipefail
out="${1:?usage: gpu_machine.sh OUT_DIR [stages]}"
stages="${2:-opencv rtmot tests bench pipeline}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
carry="$repo/.devcarry"
deps=/tmp/rtmot-deps
ocv=/tmp/rtmot-opencv
build=/tmp/rtmot-build
mkdir -p "$out" "$deps"
has() { [[ " $stages " == *" $1 "* ]]; }
step() { echo "=== $(date -u +%H:%M:%S) $*"; }

step "machine"
nproc
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv || true
nvcc --version | tail -2
g++ --version | head -1
cmake --version | head -1
ls /usr/local/cuda/include/npp.h /usr/local/cuda/include/cudnn.h 2>&1 | sed 's/^/  /'

step "dependencies: dpkg -x into $deps"
for f in "$carry"/debs/*.deb; do dpkg -x "$f" "$deps"; done
lib="$deps/usr/lib/x86_64-linux-gnu"
# cuDNN: the toolkit's own, else NVIDIA's pip package (headers + libcudnn.so.9 only: OpenCV links
# -lcudnn, so a folder with a libcudnn.so symlink)
cudnn_args=()
if [[ ! -f /usr/local/cuda/include/cudnn.h ]]; then
  pip_cudnn="$(python3 -c 'import nvidia.cudnn as m; print(m.__path__[0])')"
  mkdir -p /tmp/cudnn/lib
  ln -sfn "$pip_cudnn/include" /tmp/cudnn/include
  ln -sf "$pip_cudnn/lib/libcudnn.so.9" /tmp/cudnn/lib/libcudnn.so
  cudnn_args=(--cudnn /tmp/cudnn)
  export LD_LIBRARY_PATH="$pip_cudnn/lib:${LD_LIBRARY_PATH:-}"
fi
export LD_LIBRARY_PATH="$ocv/install/lib:$lib:$deps/lib/x86_64-linux-gnu:/usr/local/cuda/lib64:${LD_LIBRARY_PATH:-}"
# GStreamer through pkg-config files of our own: the packages' own ones name /usr and pull in
# private requirements (libffi, pcre2, ...) that this machine has no -dev files for.
mkdir -p /tmp/rtmot-pc
for pc in gstreamer-1.0:gstreamer-1.0 gstreamer-app-1.0:"gstapp-1.0 -lgstbase-1.0" \
  gstreamer-video-1.0:"gstvideo-1.0 -lgstbase-1.0"; do
  name="${pc%%:*}"
  libs="${pc#*:}"
  cat >"/tmp/rtmot-pc/$name.pc" <<PC
Name: $name
Description: Debian 12's, unpacked in $deps
Version: 1.22.0
Cflags: -I$deps/usr/include/gstreamer-1.0 -I$deps/usr/include/glib-2.0 -I$lib/glib-2.0/include
Libs: -L$lib -l$libs -lgstreamer-1.0 -lgobject-2.0 -lglib-2.0
PC
done
export PKG_CONFIG_LIBDIR=/tmp/rtmot-pc PKG_CONFIG_PATH=/tmp/rtmot-pc
pkg-config --version || echo "no pkg-config here"

if has opencv; then
  if [[ -f $carry/opencv-4.10-cuda-sm90.tar.xz ]]; then
    step "opencv: reusing the carried install"
    mkdir -p "$ocv" && tar -xJf "$carry/opencv-4.10-cuda-sm90.tar.xz" -C "$ocv"
  else
    step "opencv: build"
    /usr/bin/time -v "$repo/scripts/build_opencv.sh" --source "$(ls "$carry"/opencv-4.10.0-*.tar.xz)" \
      --prefix "$ocv/install" --build-dir "$ocv/build" --cuda --cuda-arch 9.0 "${cudnn_args[@]}" \
      --jobs "$(nproc)" --pack "$out/opencv-4.10-cuda-sm90.tar.xz" 2>&1 | tail -40
    cp "$ocv/build/configure.log" "$out/opencv-configure.log" 2>/dev/null
    grep -E "error|Error" "$ocv/build/build.log" | head -30
  fi
  cat "$ocv/install/BUILD_INFO.txt"
fi

if has rtmot; then
  if [[ ! -e $ocv/install/lib/libopencv_videoio.so ]]; then
    # pipeline/ still links cv::VideoWriter (the annotated video, not written in these runs) and
    # this OpenCV has no videoio: link rtmot against a stub whose every call fails.
    step "rtmot: videoio stub for pipeline/"
    mkdir -p /tmp/videoio-stub
    g++ -std=c++17 -O2 -shared -fPIC -I"$carry/videoio-stub/include" -I"$ocv/install/include/opencv4" \
      "$carry/videoio-stub/stub.cpp" -o /tmp/videoio-stub/libopencv_videoio.so
    export CPLUS_INCLUDE_PATH="$carry/videoio-stub/include" LIBRARY_PATH=/tmp/videoio-stub
    export LD_LIBRARY_PATH="/tmp/videoio-stub:$LD_LIBRARY_PATH"
  fi
  step "rtmot: configure and build"
  # -Wno-dangling-reference: g++ 13 (this machine's) flags runner/run_config.cpp, which the
  # project's compilers (g++ 9-12) do not.
  cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DOpenCV_DIR="$ocv/install/lib/cmake/opencv4" -DCMAKE_PREFIX_PATH="$deps/usr" \
    -DRTMOT_SHARED_DIR="$carry/shared" -DCMAKE_CXX_FLAGS=-Wno-dangling-reference \
    >"$out/rtmot-configure.log" 2>&1 || tail -30 "$out/rtmot-configure.log"
  grep -E "OpenCV 4" "$out/rtmot-configure.log"
  ninja -C "$build" detector_tests detector_batch_bench detector_bench >"$out/rtmot-build.log" 2>&1 ||
    grep -E "error|FAILED" -A5 "$out/rtmot-build.log" | head -60
  ninja -C "$build" rtmot >"$out/rtmot-app-build.log" 2>&1 ||
    { echo "rtmot (the app) did not build:"; grep -E "error|FAILED|undefined" "$out/rtmot-app-build.log" | head -8; }
fi

export RTMOT_VTEST_FRAMES="$carry/vtest-ref" RTMOT_BENCH_FRAMES="images://$carry/vtest-ref"
if has tests; then
  step "detector tests"
  (cd "$build" && ./tests/detector/detector_tests 2>&1 | tee "$out/detector_tests.log" |
    grep -E "matched|OK \]|FAILED|SKIPPED \]|PASSED|on (cpu|cuda)" | head -80)
fi
if has bench; then
  step "detector_batch_bench"
  "$build/bench/detector_batch_bench" --backends cpu,cuda,cuda-fp16 --batches 1,2,4,8,16 \
    --iterations 50 2>&1 | tee "$out/detector_batch_bench.log"
  "$build/bench/detector_batch_bench" --backends cpu,cuda,cuda-fp16 --batches 1,2,4,8,16 \
    --iterations 50 2>&1 | tee "$out/detector_batch_bench_repeat.log" | tail -18
  "$build/bench/detector_batch_bench" --backends cpu,cuda,cuda-fp16 --batches 2,8 --vary \
    --iterations 50 2>&1 | tee "$out/detector_batch_bench_vary.log" | tail -9
fi
if has pipeline && [[ -x $build/apps/rtmot ]]; then
  for backend in cpu cuda cuda-fp16; do
    config="/tmp/rtmot-$backend.yaml"
    sed -e "s|^  model: .*|  model: $repo/models/ssdlite_mobilenet_v2_coco.onnx|" \
      -e "s|^  backend: auto|  backend: ${backend%-fp16}\n  fp16: $([[ $backend == *fp16 ]] && echo on || echo off)|" \
      -e "s|^  udp: .*|  udp: 127.0.0.1:5600|" -e "s|^  jsonl_file: .*|  jsonl_file: /tmp/tracks-$backend.jsonl|" \
      "$repo/configs/desktop.yaml" >"$config"
    for n in 1 2 4 8; do
      step "pipeline every-frame on $backend, $n sources"
      args=()
      for ((i = 0; i < n; ++i)); do args+=(--source "images://$carry/vtest-ref?fps=10&loop=25"); done
      "$build/apps/rtmot" run --config "$config" "${args[@]}" --playback every-frame \
        --report "$out/pipeline-$backend-$n.json" >"$out/pipeline-$backend-$n.log" 2>&1
      grep -E "detector:|frames captured" "$out/pipeline-$backend-$n.log" | cut -c 40- | tail -3
    done
  done
fi
step "done"
tar -C "$out" -cJf /tmp/logs.tar.xz --exclude '*.tar.xz' . && mv /tmp/logs.tar.xz "$out/logs.tar.xz"
find "$out" -maxdepth 1 -type f ! -name '*.tar.xz' ! -name run.log -delete
