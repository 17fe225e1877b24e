#!/usr/bin/env bash
# THE test command (README, .ci/run). From a fresh Debian 12 machine, as root:
#   1. dependencies, model, sample video   (installs only what is missing)
#   2. the pinned OpenCV 4.10 from its local source (scripts/build_opencv.sh), what the README's
#      first command builds the product against
#   3. native build against it, Release, -Werror, every test (CTest + GoogleTest + system tests),
#      the detector benchmarks
#   4. AddressSanitizer + UndefinedBehaviorSanitizer, on Debian's OpenCV 4.6: the whole suite (the
#      build holds the fuzzers)
#   5. fuzzing: every libFuzzer target for FUZZ_SECONDS (default 10) each, from the ASan build
#   6. ThreadSanitizer, on Debian's OpenCV: the pipeline's lock-free hand-offs and every threaded
#      component
#   7. aarch64, on Debian's arm64 OpenCV: cross build in an isolated sysroot, the
#      architecture-sensitive tests (CTest label `arch`) under qemu, tracks equal x86's (the x86
#      side: the ASan build's rtmot, the same OpenCV 4.6)
# Both OpenCVs are built against and the whole suite runs on each once: 4.10 in the Release build,
# 4.6 under the sanitizers (and 4.6 for arm64). Until issue 28 the Release build and every test ran
# on both; the second time cost a build and a test run (about 13 minutes of CI's 90) and found
# nothing the sanitizer stage would not.
# CI's budget: the whole of it within 60 minutes on 2 cores from a fresh clone (the hard limit is 90).
# Each stage's time is printed when it ends and all of them again at the end, also when a stage
# fails (the summary runs on exit and names the stage that failed).
# A quick local run: RTMOT_QUICK=1 scripts/test.sh builds against Debian's OpenCV (no OpenCV build)
# and runs every test, and stops there.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

declare -a stage_names=() stage_seconds=()
stage_started=$SECONDS
current=""
finish_stage() {
  if [[ -n $current ]]; then
    stage_names+=("$current")
    stage_seconds+=($((SECONDS - stage_started)))
    # Also here, not only in the summary: a run killed at CI's limit still shows what each took.
    echo "=== $current: $((SECONDS - stage_started)) s"
  fi
}
stage() {
  finish_stage
  current="$*"
  stage_started=$SECONDS
  echo
  echo "=== $* ($(date -u +%H:%M:%S))"
}
summary() {
  local status=$? failed=$current
  finish_stage
  current=""
  echo
  echo "=== test.sh stage times"
  for i in "${!stage_names[@]}"; do printf '  %-34s %5d s\n' "${stage_names[$i]}" "${stage_seconds[$i]}"; done
  printf '  %-34s %5d s\n' "total" "$SECONDS"
  if ((status == 0)); then
    echo "test.sh: OK"
  else
    echo "test.sh: FAILED (exit $status) in: $failed"
  fi
}
trap summary EXIT
# Every ctest of every stage (the scripts' own included) prints a failing test's whole output.
export CTEST_OUTPUT_ON_FAILURE=1
# Every build goes through ccache (scripts/install_deps.sh installs it): a second run on the same
# machine recompiles only what changed, and with paths taken relative to the checkout
# (CCACHE_BASEDIR) sibling build folders of the same compiler and flags share their objects.
# CCACHE_DIR, if set, says where the cache lives.
export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1

stage "dependencies, model, sample video"
bash scripts/install_deps.sh
bash scripts/fetch_model.sh
bash scripts/fetch_sample_video.sh

if [[ ${RTMOT_QUICK:-0} == 1 ]]; then
  stage "native build (Release, -Werror, Debian's OpenCV)"
  bash scripts/build.sh "$root/build"
  stage "native tests"
  ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900
  exit 0
fi

# --- pinned OpenCV (docs/gpu.md): OpenCV 4.10 (CPU) from the local source in ../shared/opencv.
# Measured: 13.5 min of CPU time (about 7 min on two idle cores).
stage "pinned OpenCV 4.10 from source"
bash scripts/build_opencv.sh --source "$(ls "$root"/../shared/opencv/opencv-4.10.0-*.tar.xz | head -n 1)" \
  --prefix "$root/build-opencv/install" --jobs "$(nproc)"
stage "native build (Release, -Werror, pinned OpenCV 4.10)"
bash scripts/build.sh "$root/build" -DOpenCV_DIR="$root/build-opencv/install/lib/cmake/opencv4"
stage "native tests, detector benchmarks"
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900
"$root/build/bench/detector_bench" --benchmark_min_time=1
"$root/build/bench/detector_batch_bench" --backends cpu --batches 1,2,4 --iterations 5

stage "asan+ubsan: whole suite"
bash scripts/sanitize.sh asan
stage "fuzzing"
bash scripts/fuzz.sh "${FUZZ_SECONDS:-10}"
stage "tsan: threaded components"
bash scripts/sanitize.sh tsan
stage "aarch64: cross build, qemu tests, same tracks"
NATIVE_BUILD_DIR="$root/build-asan" bash scripts/cross_build.sh
