#!/usr/bin/env bash
# Sanitizer builds of the whole suite, sized for CI (2 cores):
#   build-asan: -DRTMOT_SANITIZE=address,undefined, every test (ctest).
#   build-tsan: -DRTMOT_SANITIZE=thread, the concurrency tests (pipeline, queues, slot, signals,
#               reconnecting source): where ThreadSanitizer can find something.
# Uses the default compiler (g++ works with Debian's OpenCV/GStreamer; CXX=clang++ also works).
# Suppressions for uninstrumented system libraries only: TSan's in scripts/sanitizers/tsan.supp; LSan's
# are compiled into every executable by platform/ (platform/sanitizer/lsan_suppressions.cpp).
# Prints the wall time of each half. Usage: scripts/sanitize.sh [asan|tsan|all]
# Env: JOBS (default 2), ASAN_DIR, TSAN_DIR (build folders), TSAN_TESTS (ctest -R regex).
set -euo pipefail
which=${1:-all}
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${JOBS:-2}
asan_dir=${ASAN_DIR:-$root/build-asan}
tsan_dir=${TSAN_DIR:-$root/build-tsan}
tsan_tests=${TSAN_TESTS:-pipeline|spsc|Spsc|slot|Slot|queue|Queue|signal|Signal|Reconnect|thread|Thread}
supp=$root/scripts/sanitizers

configure() {  # DIR SANITIZERS
  cmake -S "$root" -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRTMOT_BUILD_BENCH=OFF \
    -DRTMOT_SANITIZE="$2" >"$1.configure.log"
}

status=0
if [[ $which == asan || $which == all ]]; then
  start=$(date +%s)
  configure "$asan_dir" address,undefined
  cmake --build "$asan_dir" -j "$jobs"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --test-dir "$asan_dir" -j "$jobs" --output-on-failure || status=1
  echo "sanitize: asan+ubsan build and tests took $(($(date +%s) - start)) s"
fi
if [[ $which == tsan || $which == all ]]; then
  start=$(date +%s)
  configure "$tsan_dir" thread
  # Build only what the selected tests need: the test executables (and rtmot for the catalogue).
  cmake --build "$tsan_dir" -j "$jobs"
  TSAN_OPTIONS="suppressions=$supp/tsan.supp halt_on_error=1 second_deadlock_stack=1" \
    ctest --test-dir "$tsan_dir" -j "$jobs" -R "$tsan_tests" --output-on-failure || status=1
  echo "sanitize: tsan build and tests took $(($(date +%s) - start)) s"
fi
exit $status
