#!/usr/bin/env bash
# THE test command (README, .ci/run). From a fresh Debian 12 machine, as root:
#   1. dependencies, model, sample video   (installs only what is missing)
#   2. native build, Release, -Werror, every test (CTest + GoogleTest + system tests)
#   2b. the pinned OpenCV 4.10 (scripts/build_opencv.sh), then the same build and every test on it
#   3. AddressSanitizer + UndefinedBehaviorSanitizer: the whole suite (the build holds the fuzzers)
#   4. fuzzing: every libFuzzer target for FUZZ_SECONDS (default 10) each, from the ASan build
#   5. ThreadSanitizer: the pipeline's lock-free hand-offs and every threaded component
#   6. aarch64: cross build in an isolated sysroot, the architecture-sensitive tests (CTest label
#      `arch`) under qemu, tracks equal x86's
# CI's budget: the whole of it within 60 minutes on 2 cores from a fresh clone (the hard limit is 90).
# Each stage's time is printed when it ends and all of them again at the end, also when a stage
# fails (the summary runs on exit and names the stage that failed).
# Stages after 2 can be skipped for a quick local run: RTMOT_QUICK=1 scripts/test.sh
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
# Every build goes through ccache (scripts/install_deps.sh installs it). In one cold run the pinned
# OpenCV build recompiles only the objects that include OpenCV (80 of 283): the others are the
# native build's, same compiler, same flags. With paths relative to the checkout (build/ and
# build-pinned/ are siblings) their command lines are the same. A second run on the same machine
# reuses everything unchanged. CCACHE_DIR, if set, says where the cache lives.
export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1

stage "dependencies, model, sample video"
bash scripts/install_deps.sh
bash scripts/fetch_model.sh
bash scripts/fetch_sample_video.sh

stage "native build (Release, -Werror)"
bash scripts/build.sh "$root/build"
stage "native tests"
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900

[[ ${RTMOT_QUICK:-0} == 1 ]] && exit 0

# --- pinned OpenCV (docs/gpu.md): build OpenCV 4.10 (CPU) from the local source in ../shared/opencv
# with scripts/build_opencv.sh, then the whole product and every test against it (what the README's
# first command builds), and the detector benchmarks. Measured: OpenCV 13.5 min of CPU time (about
# 7 min on two idle cores). The sanitizer, fuzz and aarch64 stages stay on Debian's OpenCV (the
# aarch64 comparison runs against the Debian build in build/).
stage "pinned OpenCV 4.10: build, every test, detector benchmarks"
bash scripts/build_opencv.sh --source "$(ls "$root"/../shared/opencv/opencv-4.10.0-*.tar.xz | head -n 1)" \
  --prefix "$root/build-opencv/install" --jobs "$(nproc)"
bash scripts/build.sh "$root/build-pinned" -DOpenCV_DIR="$root/build-opencv/install/lib/cmake/opencv4"
ctest --test-dir "$root/build-pinned" --output-on-failure -j"$(nproc)" --timeout 900
"$root/build-pinned/bench/detector_bench" --benchmark_min_time=1
"$root/build-pinned/bench/detector_batch_bench" --backends cpu --batches 1,2,4 --iterations 5
# --- end pinned OpenCV

stage "asan+ubsan: whole suite"
bash scripts/sanitize.sh asan
stage "fuzzing"
bash scripts/fuzz.sh "${FUZZ_SECONDS:-10}"
stage "tsan: threaded components"
bash scripts/sanitize.sh tsan
stage "aarch64: cross build, qemu tests, same tracks"
bash scripts/cross_build.sh
