#!/usr/bin/env bash
# The GPU verification run (docs/gpu.md §3) on a machine without network or apt (the lent H100:
# Ubuntu 24.04, CUDA 13, cuDNN from pip). Everything it needs is in the carried folder that
# scripts/gpu_prepare.sh made on Debian 12 (default .gpu-carry/ in this checkout).
#
#   scripts/opencv/gpu_machine.sh OUT_DIR [stages]
# stages (default "opencv rtmot tests bench profile pipeline"), each an error with its reason when it
# cannot run (never skipped):
#   opencv    build OpenCV 4.10 with CUDA (arch 9.0) from the carried source and pack the install to
#             OUT_DIR/opencv-4.10-cuda-sm90.tar.xz; or unpack a carried install (gpu_prepare.sh
#             --opencv-install)
#   rtmot     build rtmot (every target the stages below run) against it
#   tests     the detector tests, reference frames decoded as the reference was (FFmpeg)
#   bench     detector_batch_bench: cpu, cuda, cuda-fp16 at batch 1, 2, 4, 8, three passes
#   profile   scripts/opencv/forward_profile: host time per layer (Net::getPerfProfile) against the
#             forward's wall time, batch 1, per backend; Nsight Systems' kernel summary where nsys is
#   pipeline  rtmot run every-frame on the reference frames, per backend, 1/2/4/8 sources, with
#             nvidia-smi sampling the GPU's busy share
# Environment: RTMOT_CARRY (the carried folder), RTMOT_SOURCE (the rtmot source tree to build and
# run, default this checkout: e.g. an older commit to compare), RTMOT_PASSES (bench passes, 3),
# RTMOT_OPENCV_DIR (where the OpenCV install is or goes, /tmp/rtmot-opencv; its install/ folder),
# RTMOT_PIPELINE_BACKENDS ("cpu cuda cuda-fp16"), RTMOT_PIPELINE_SOURCES ("1 2 4 8"),
# RTMOT_PIPELINE_FORMAT (png, or bmp: the same pixels without a PNG decode per frame in the capture
# thread), RTMOT_PIPELINE_TAG (added to the pipeline logs' names, e.g. pass2),
# RTMOT_PIPELINE_IN_FLIGHT ("1 2": detector.in_flight values, each run per backend and source count;
# "-" leaves the setting out, for trees older than it), RTMOT_PIPELINE_LOOP (25: plays of the 16
# frames per source), RTMOT_PIPELINE_PLAYBACK ("every-frame"; also realtime: frames released at the
# source's rate, the latency a camera would see), RTMOT_PIPELINE_FPS (10: the images:// rate, which
# only realtime honours), RTMOT_TESTS_FILTER (a --gtest_filter for the tests stage),
# RTMOT_BENCH_ARGS (detector_batch_bench's arguments instead of every backend at batch 1, 2, 4, 8).
# Each pipeline run writes pipeline-TAG-FORMAT-PLAYBACK-BACKEND-N-ifK.{log,json,smi,threads} and one
# row of pipeline-summary-TAG-FORMAT.tsv (FPS, detector FPS, ms per image, p50/p99 capture->sent,
# GPU busy over the run proper and over the whole process, CPU seconds of the capture and detect
# threads).
set -euo pipefail
out="${1:?usage: gpu_machine.sh OUT_DIR [stages]}"
stages="${2:-opencv rtmot tests bench profile pipeline}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
carry="$(realpath "${RTMOT_CARRY:-$repo/.gpu-carry}")"
source_dir="$(realpath "${RTMOT_SOURCE:-$repo}")"
tag="$(basename "$source_dir")"
deps=/tmp/rtmot-deps
ocv="${RTMOT_OPENCV_DIR:-/tmp/rtmot-opencv}"
build="/tmp/rtmot-build-$tag"
frames=/tmp/rtmot-vtest-ref
mkdir -p "$out"
has() { [[ " $stages " == *" $1 "* ]]; }
step() { echo "=== $(date -u +%H:%M:%S) $*"; }
die() {
  echo "gpu_machine: $*" >&2
  exit 1
}
on_error() { echo "gpu_machine: FAILED at line $1 (stage above); nothing after it ran" >&2; }
trap 'on_error $LINENO' ERR

for stage in $stages; do
  [[ " opencv rtmot tests bench profile pipeline " == *" $stage "* ]] || die "unknown stage '$stage'"
done
[[ -d $carry ]] || die "$carry: no carried folder (make it with scripts/gpu_prepare.sh on Debian 12: docs/gpu.md)"

step "machine"
nproc
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv
for tool in nvcc g++ cmake ninja pkg-config dpkg python3; do
  command -v "$tool" >/dev/null || die "$tool: not on this machine (needed by the build)"
done
nvcc --version | tail -n 2
g++ --version | head -n 1
cmake --version | head -n 1

step "requirements: the checkout's against the carried folder's"
# The packages were derived from the CMake requirements of the checkout gpu_prepare.sh ran in: a
# requirement added since then has no package here.
missing="$(comm -23 <(bash "$repo/scripts/gpu_deps.sh" requirements "$source_dir" | cut -f1,2 | sort -u) \
  <(cut -f1,2 "$carry/requirements.tsv" | sort -u))"
[[ -z $missing ]] || die "requirements the carried folder was not prepared for (run scripts/gpu_prepare.sh again): $missing"

step "dependencies: $(wc -l <"$carry/packages.txt") Debian packages, dpkg -x into $deps"
rm -rf "$deps" && mkdir -p "$deps/pkgconfig"
for f in "$carry"/debs/*.deb; do dpkg -x "$f" "$deps"; done
triplet="$(gcc -dumpmachine)"
lib="$deps/usr/lib/$triplet"
# Absolute symlinks of the packages (zlib1g-dev's libz.so -> /lib/.../libz.so.1.2.13) point into
# this machine's / : re-pointed into the unpacked tree.
while IFS= read -r link; do
  target="$(readlink "$link")"
  [[ -e $deps$target ]] && ln -sfn "$deps$target" "$link"
done < <(find "$deps" -type l -lname '/*')
# The carried .pc files name include folders as on Debian 12; one that no carried package ships
# (e.g. the multiarch /usr/include/<triplet>) is dropped: CMake refuses imported targets with
# non-existent include folders.
for f in "$carry"/pkgconfig/*.pc; do
  sed "s|^prefix=/usr\$|prefix=$deps/usr|" "$f" | while IFS= read -r line; do
    if [[ $line == Cflags:* ]]; then
      kept=()
      for flag in ${line#Cflags:}; do
        flag="${flag//\$\{prefix\}/$deps/usr}"
        [[ $flag == -I* && ! -d ${flag#-I} ]] && continue
        kept+=("$flag")
      done
      line="Cflags: ${kept[*]}"
    fi
    printf '%s\n' "$line"
  done >"$deps/pkgconfig/$(basename "$f")"
done
export PKG_CONFIG_LIBDIR="$deps/pkgconfig" PKG_CONFIG_PATH="$deps/pkgconfig"
while IFS=$'\t' read -r kind name _; do
  [[ $kind == pkg_* ]] || continue
  pkg-config --exists "$name" || die "pkg-config: $name not in the carried .pc files"
done <"$carry/requirements.tsv"
# cuDNN: the toolkit's own, else NVIDIA's pip package (headers + libcudnn.so.9 only: OpenCV links
# -lcudnn, so a folder with a libcudnn.so symlink)
cudnn_args=()
cudnn_lib=""
if [[ ! -f /usr/local/cuda/include/cudnn.h ]]; then
  pip_cudnn="$(python3 -c 'import nvidia.cudnn as m; print(m.__path__[0])')" ||
    die "no cuDNN: neither /usr/local/cuda/include/cudnn.h nor the pip package nvidia-cudnn"
  mkdir -p /tmp/cudnn/lib
  ln -sfn "$pip_cudnn/include" /tmp/cudnn/include
  ln -sf "$pip_cudnn/lib/libcudnn.so.9" /tmp/cudnn/lib/libcudnn.so
  cudnn_args=(--cudnn /tmp/cudnn)
  cudnn_lib="$pip_cudnn/lib"
fi
# Our programs only: Debian's libraries must not shadow this machine's for its own tools.
run_env=(env "LD_LIBRARY_PATH=$ocv/install/lib:$lib:$deps/lib/$triplet:/usr/local/cuda/lib64${cudnn_lib:+:$cudnn_lib}")

if has opencv; then
  if [[ -f $carry/opencv-4.10-cuda-sm90.tar.xz ]]; then
    step "opencv: unpacking the carried install"
    rm -rf "$ocv" && mkdir -p "$ocv" && tar -xJf "$carry/opencv-4.10-cuda-sm90.tar.xz" -C "$ocv"
  else
    source_tar="$(ls "$carry"/opencv-4.10.0-*.tar.xz 2>/dev/null | head -n 1)"
    [[ -n $source_tar ]] || die "$carry: neither opencv-4.10-cuda-sm90.tar.xz nor an opencv-4.10.0-*.tar.xz source"
    step "opencv: build from $(basename "$source_tar")"
    "$repo/scripts/build_opencv.sh" --source "$source_tar" --prefix "$ocv/install" --build-dir "$ocv/build" \
      --cuda --cuda-arch 9.0 "${cudnn_args[@]}" --jobs "$(nproc)" --pack "$out/opencv-4.10-cuda-sm90.tar.xz" \
      >"$out/opencv-build.log" 2>&1 || { tail -n 40 "$out/opencv-build.log"; die "OpenCV build failed (log above)"; }
    tail -n 3 "$out/opencv-build.log"
  fi
  cat "$ocv/install/BUILD_INFO.txt"
fi
[[ -d $ocv/install/lib/cmake/opencv4 ]] || die "no OpenCV at $ocv/install (run the opencv stage)"

if has rtmot; then
  step "rtmot ($source_dir): configure and build"
  # The model where the tests and configs look for it (models/ is git-ignored, a link here)
  if [[ ! -f $source_dir/models/ssdlite_mobilenet_v2_coco.onnx ]]; then
    rm -rf "$source_dir/models" && mkdir -p "$source_dir/models"
    cp "$carry"/model/* "$source_dir/models/"
  fi
  # -Wno-dangling-reference: g++ 13 (this machine's) flags runner/run_config.cpp, which the
  # project's compilers (g++ 9-12) do not. rpath-link: Debian's libraries' own dependencies.
  rm -f "$build/CMakeCache.txt" # pkg-config results are cached: a fresh configure each run
  cmake -S "$source_dir" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DOpenCV_DIR="$ocv/install/lib/cmake/opencv4" -DCMAKE_PREFIX_PATH="$deps/usr" \
    -DRTMOT_SHARED_DIR="$carry/shared" -DCMAKE_CXX_FLAGS=-Wno-dangling-reference \
    "-DCMAKE_EXE_LINKER_FLAGS=-Wl,-rpath-link,$lib:$deps/lib/$triplet:$ocv/install/lib" \
    "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,-rpath-link,$lib:$deps/lib/$triplet:$ocv/install/lib" \
    >"$out/rtmot-configure-$tag.log" 2>&1 || { tail -n 30 "$out/rtmot-configure-$tag.log"; die "rtmot: configure failed"; }
  grep -E "OpenCV 4" "$out/rtmot-configure-$tag.log" || true
  ninja -C "$build" detector_tests detector_model_layout_test detector_batch_bench rtmot >"$out/rtmot-build-$tag.log" 2>&1 ||
    { grep -E "error|FAILED|undefined" -A3 "$out/rtmot-build-$tag.log" | head -n 60; die "rtmot: build failed"; }
  echo "built: detector_tests detector_model_layout_test detector_batch_bench rtmot"
fi

if has tests || has bench || has pipeline; then
  if [[ ! -f $frames/751.png ]]; then
    step "reference frames: vtest.avi frames 1, 51, ..., 751 decoded by FFmpeg (this machine's opencv-python)"
    mkdir -p "$frames"
    python3 - "$carry/shared/data/video/vtest.avi" "$frames" <<'PY' || die "frame extraction failed (needs python3's cv2 with FFmpeg)"
import sys, cv2
capture = cv2.VideoCapture(sys.argv[1], cv2.CAP_FFMPEG)
assert capture.isOpened(), 'FFmpeg cannot open ' + sys.argv[1]
written = 0
for number in range(1, 752):
    ok, frame = capture.read()
    assert ok, f'frame {number} not decoded'
    if (number - 1) % 50 == 0:
        assert cv2.imwrite(f'{sys.argv[2]}/{number}.png', frame)
        written += 1
print(f'{written} frames')
PY
  fi
fi
export RTMOT_VTEST_FRAMES="$frames" RTMOT_BENCH_FRAMES="images://$frames"

if has tests; then
  step "detector tests ($tag)"
  (cd "$build" && "${run_env[@]}" ./tests/detector/detector_tests ${RTMOT_TESTS_FILTER:+"--gtest_filter=$RTMOT_TESTS_FILTER"}) >"$out/detector_tests-$tag.log" 2>&1 ||
    { grep -E "FAILED|Failure" -A3 "$out/detector_tests-$tag.log" | head -n 40; die "detector tests failed"; }
  grep -E "matched|PASSED|on (cpu|cuda)" "$out/detector_tests-$tag.log" | head -n 30
  # The other model layouts (docs/gpu.md, "Other model layouts on CUDA"): their fixtures are made on
  # the CPU machine (python3-onnx, which this machine lacks) and carried in .gpu-fixtures/ by a call
  # of their own (over 64 MiB with .gpu-carry/).
  if [[ -f $source_dir/.gpu-fixtures/decoded.onnx ]]; then
    step "model layout tests ($tag), fixtures from .gpu-fixtures/"
    (cd "$build" && RTMOT_MODEL_FIXTURES="$source_dir/.gpu-fixtures" "${run_env[@]}" ./tests/detector/detector_model_layout_test) >"$out/model_layout-$tag.log" 2>&1 ||
      { grep -E "FAILED|Failure" -A3 "$out/model_layout-$tag.log" | head -n 40; die "model layout tests failed"; }
    grep -E "vs|PASSED|SKIPPED" "$out/model_layout-$tag.log" | head -n 20
  else
    echo "model layout tests on CUDA: NOT RUN (no .gpu-fixtures/ carried; docs/gpu.md says how)"
  fi
fi

if has bench; then
  for pass in $(seq 1 "${RTMOT_PASSES:-3}"); do
    step "detector_batch_bench ($tag) pass $pass"
    # shellcheck disable=SC2086 # RTMOT_BENCH_ARGS: words
    "${run_env[@]}" "$build/bench/detector_batch_bench" ${RTMOT_BENCH_ARGS:---backends cpu,cuda,cuda-fp16 --batches 1,2,4,8 --iterations 60} 2>&1 | tee "$out/bench-$tag-$pass.log" | tail -n 14
    # the benchmark reports a backend it cannot run as "skipped": here that is a failure
    ! grep -q "skipped" "$out/bench-$tag-$pass.log" || die "detector_batch_bench skipped a backend (above)"
  done
fi

if has profile; then
  step "forward profile (host time per layer, batch 1)"
  g++ -std=c++17 -O2 "$repo/scripts/opencv/forward_profile.cpp" -o /tmp/forward_profile \
    -I"$ocv/install/include/opencv4" -L"$ocv/install/lib" -lopencv_dnn -lopencv_core
  for backend in cuda cuda-fp16 cpu; do
    "${run_env[@]}" /tmp/forward_profile "$carry"/model/*.onnx "$backend" 300 2>&1 |
      tee "$out/profile-$backend.log" | head -n 12
  done
  # scripts/opencv/cuda_graph.patch's switch: the same build layer by layer
  for backend in cuda cuda-fp16; do
    echo "--- $backend with OPENCV_DNN_CUDA_GRAPH=0 (layer by layer)"
    "${run_env[@]}" OPENCV_DNN_CUDA_GRAPH=0 /tmp/forward_profile "$carry"/model/*.onnx "$backend" 300 2>&1 |
      tee "$out/profile-$backend-nograph.log" | head -n 4
  done
  if command -v nsys >/dev/null; then
    "${run_env[@]}" nsys profile -o /tmp/forward-fp16 --force-overwrite true /tmp/forward_profile \
      "$carry"/model/*.onnx cuda-fp16 300 >/dev/null 2>&1 || die "nsys profile failed"
    nsys stats -r cuda_gpu_kern_sum,cuda_api_sum /tmp/forward-fp16.nsys-rep >"$out/nsys-fp16.txt" 2>&1 ||
      die "nsys stats failed"
    head -n 40 "$out/nsys-fp16.txt"
  else
    echo "nsys: not on this machine (Nsight Systems' summary not taken; the profile above is OpenCV's own)"
  fi
fi

if has pipeline; then
  [[ -x $build/apps/rtmot ]] || die "$build/apps/rtmot: not built (run the rtmot stage)"
  format="${RTMOT_PIPELINE_FORMAT:-png}"
  pipeline_frames="$frames"
  if [[ $format == bmp ]]; then
    pipeline_frames="$frames-bmp"
    mkdir -p "$pipeline_frames"
    python3 - "$frames" "$pipeline_frames" <<'PY' || die "PNG to BMP conversion failed"
import sys, glob, os, cv2
for path in glob.glob(sys.argv[1] + '/*.png'):
    image = cv2.imread(path, cv2.IMREAD_COLOR)
    assert image is not None, path
    assert cv2.imwrite(os.path.join(sys.argv[2], os.path.basename(path)[:-4] + '.bmp'), image)
PY
  elif [[ $format != png ]]; then
    die "RTMOT_PIPELINE_FORMAT: png or bmp, not '$format'"
  fi
  suffix="$format${RTMOT_PIPELINE_TAG:+-$RTMOT_PIPELINE_TAG}"
  summary="$out/pipeline-summary-$tag-$suffix.tsv"
  printf 'playback\tbackend\tsources\tin_flight\tfps\tdetector_fps\tms_per_image\tp50_ms\tp99_ms\tgpu_busy_run_pct\tgpu_busy_all_pct\tbatches\tcpu_s_capture\tcpu_s_detect\twall_s\n' >"$summary"
  for backend in ${RTMOT_PIPELINE_BACKENDS:-cpu cuda cuda-fp16}; do
    config="/tmp/rtmot-$tag-$backend.yaml"
    sed -e "s|^  model: .*|  model: $source_dir/models/ssdlite_mobilenet_v2_coco.onnx|" \
      -e "s|^  backend: auto|  backend: ${backend%-fp16}\n  fp16: $([[ $backend == *fp16 ]] && echo on || echo off)|" \
      -e "s|^  udp: .*|  udp: 127.0.0.1:5600|" -e "s|^  jsonl_file: .*|  jsonl_file: /tmp/tracks-$backend.jsonl|" \
      "$source_dir/configs/desktop.yaml" >"$config"
    for playback in ${RTMOT_PIPELINE_PLAYBACK:-every-frame}; do
    [[ $playback == every-frame || $playback == realtime ]] || die "RTMOT_PIPELINE_PLAYBACK: every-frame or realtime, not '$playback'"
    for n in ${RTMOT_PIPELINE_SOURCES:-1 2 4 8}; do
      # detector.in_flight (batches in flight in the detect stage); "-" = the tree's default (a
      # tree older than the setting)
      for k in ${RTMOT_PIPELINE_IN_FLIGHT:-1 2}; do
        name="pipeline-$tag-$suffix-$playback-$backend-$n-if$k"
        step "pipeline ($tag, $suffix) $playback on $backend, $n sources, in flight $k"
        args=()
        for ((i = 0; i < n; ++i)); do args+=(--source "images://$pipeline_frames?fps=${RTMOT_PIPELINE_FPS:-10}&loop=${RTMOT_PIPELINE_LOOP:-25}"); done
        [[ $k == - ]] || args+=(--in-flight "$k")
        nvidia-smi --query-gpu=timestamp,utilization.gpu --format=csv,noheader,nounits -lms 100 >"/tmp/smi-$n.txt" &
        smi=$!
        "${run_env[@]}" "$build/apps/rtmot" run --config "$config" "${args[@]}" --playback "$playback" \
          --report "$out/$name.json" >"$out/$name.log" 2>&1 &
        rtmot=$!
        # CPU seconds per thread (utime + stime from /proc, the last reading before the process
        # ends: a thread that ended earlier keeps its last reading), to show where the host time goes
        python3 - "$rtmot" >"$out/$name.threads" <<'PY' &
import os, sys, time
pid, tick, last = sys.argv[1], os.sysconf('SC_CLK_TCK'), {}
start = time.monotonic()
while os.path.exists(f'/proc/{pid}/stat'):
    try:
        for tid in os.listdir(f'/proc/{pid}/task'):
            try:
                name = open(f'/proc/{pid}/task/{tid}/comm').read().strip()
                fields = open(f'/proc/{pid}/task/{tid}/stat').read().rsplit(')', 1)[1].split()
                last[tid] = (name, (int(fields[11]) + int(fields[12])) / tick)
            except OSError:
                pass
    except OSError:
        break
    time.sleep(0.05)
print(f'wall_s\t{time.monotonic() - start:.2f}')
for tid, (name, cpu) in sorted(last.items(), key=lambda item: -item[1][1]):
    print(f'{name}\t{tid}\t{cpu:.2f}')
PY
        sampler=$!
        wait "$rtmot" ||
          { kill "$smi"; tail -n 20 "$out/$name.log"; die "rtmot run failed ($playback, $backend, $n sources, in flight $k)"; }
        wait "$sampler" || die "thread sampler failed ($name)"
        kill "$smi" && wait "$smi" 2>/dev/null || true
        cp "/tmp/smi-$n.txt" "$out/$name.smi"
        # GPU busy: the mean of the 100 ms samples over the whole process (start-up included) and
        # over the run proper (from the log's "detector: ..." line, once every detector is built,
        # to the final report line)
        python3 - "$out/$name.log" "/tmp/smi-$n.txt" "$out/$name.json" "$backend" "$n" "$k" "$playback" "$out/$name.threads" >>"$summary" <<'PY' || die "pipeline summary failed ($name)"
import json, re, sys
from datetime import datetime
log, smi, report, backend, n, k, playback, threads = sys.argv[1:]
def at(text, fmt):
    return datetime.strptime(text, fmt).timestamp()
start = end = None
for line in open(log):
    m = re.match(r'\[(\S+ \S+)\]', line)
    if not m:
        continue
    t = at(m.group(1), '%Y-%m-%d %H:%M:%S.%f')
    if '] detector: SSDLite' in line:
        start = t
    if '] frames captured' in line:
        end = t
samples = []
for line in open(smi):
    parts = [p.strip() for p in line.split(',')]
    if len(parts) == 2 and parts[1].isdigit():
        samples.append((at(parts[0], '%Y/%m/%d %H:%M:%S.%f'), int(parts[1])))
def mean(values):
    return sum(values) / len(values) if values else float('nan')
run = [u for t, u in samples if start is not None and end is not None and start <= t <= end]
r = json.load(open(report))
e2e = r['latency']['end_to_end']
cpu = {'capture': 0.0, 'detect': 0.0}
wall = 'nan'
for line in open(threads):
    parts = line.rstrip('\n').split('\t')
    if parts[0] == 'wall_s':
        wall = parts[1]
    elif 'captur' in parts[0]:
        cpu['capture'] += float(parts[2])
    elif 'detect' in parts[0] or 'lane' in parts[0]:
        cpu['detect'] += float(parts[2])
print('\t'.join([playback, backend, n, k, f"{r['fps']:.1f}", f"{r['detector_fps']:.1f}", f"{1000 / r['fps']:.3f}",
                 f"{e2e['p50_ms']:.1f}", f"{e2e['p99_ms']:.1f}", f"{mean(run):.0f} ({len(run)} samples)",
                 f"{mean([u for _, u in samples]):.0f}", str(r['detector_batches']),
                 f"{cpu['capture']:.2f}", f"{cpu['detect']:.2f}", wall]))
PY
        tail -n 1 "$summary"
      done
    done
    done
  done
  cat "$summary"
fi
trap - ERR
step "all stages passed: $stages"
