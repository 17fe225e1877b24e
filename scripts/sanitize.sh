#!/usr/bin/env bash
# Sanitizer builds of the whole suite, sized for CI (2 cores):
#   build-asan: -DRTMOT_SANITIZE=address,undefined, every test (ctest). The same build holds the
#               libFuzzer targets (scripts/fuzz.sh runs them from it): its code is instrumented for
#               the fuzzers' coverage too (-fsanitize=fuzzer-no-link, which only counts edges
#               outside a fuzzer), so CI compiles the project once for both, not twice.
#   build-tsan: -DRTMOT_SANITIZE=thread, the concurrency tests (pipeline, queues, slot, signals,
#               reconnecting source, the study's thread pool and cross-validation): where
#               ThreadSanitizer can find something.
# Uses clang (SANITIZE_CC/SANITIZE_CXX to change it): see configure() below for why.
# Suppressions for uninstrumented system libraries only: TSan's in scripts/sanitizers/tsan.supp; LSan's
# are compiled into every executable by platform/ (platform/sanitizer/suppressions.cpp).
# Prints the wall time of each half. Usage: scripts/sanitize.sh [asan|tsan|all]
# Env: JOBS (default 2), ASAN_DIR, TSAN_DIR (build folders), TSAN_TARGETS (test programs run under TSan).
set -euo pipefail
which=${1:-all}
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${JOBS:-2}
asan_dir=${ASAN_DIR:-$root/build-asan}
tsan_dir=${TSAN_DIR:-$root/build-tsan}
tsan_targets=${TSAN_TARGETS:-pipeline_handoff_test pipeline_follow_image_test pipeline_playback_test pipeline_outage_test pipeline_multi_source_test pipeline_detect_lanes_test pipeline_stage_threads_test test_platform_capture test_platform_signals test_platform_thread test_reconnecting_source messages_test study_tests outputs_mqtt_test
  pipeline_events_mailbox_test pipeline_score_cut_test pipeline_full_rate_test}
supp=$root/scripts/sanitizers

# clang, not g++: g++ took over 16 minutes for half of the ASan+UBSan build on CI's 2 cores (its
# sanitizer instrumentation of the template-heavy CLI/JSON/format code at -O2), clang a few minutes.
# -O1 with line tables keeps stack traces exact and builds faster. Warnings are the Release build's
# job (g++, -Werror): clang warns differently, and that must not hide a sanitizer finding.
configure() {  # DIR SANITIZERS [CMAKE ARGS...]
  local dir=$1 sanitizers=$2
  shift 2
  CC=${SANITIZE_CC:-clang} CXX=${SANITIZE_CXX:-clang++} cmake -S "$root" -B "$dir" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DRTMOT_BUILD_BENCH=OFF -DRTMOT_WERROR=OFF -DRTMOT_SANITIZE="$sanitizers" "$@" >"$dir.configure.log"
}

# UBSan aborts on its first finding (what the fuzzers need, and the tests' halt_on_error).
configure_asan() {
  configure "$asan_dir" address,undefined -DRTMOT_BUILD_FUZZERS=ON \
    -DRTMOT_SHARED_DIR="${RTMOT_SHARED_DIR:-$root/../shared}" \
    -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link -fno-sanitize-recover=all"
}
case $which in
  asan | tsan | all) ;;
  configure-asan) # scripts/fuzz.sh: the same build for its targets
    configure_asan
    exit 0
    ;;
  *)
    echo "usage: scripts/sanitize.sh [asan|tsan|all]" >&2
    exit 2
    ;;
esac

status=0
if [[ $which == asan || $which == all ]]; then
  start=$(date +%s)
  configure_asan
  cmake --build "$asan_dir" -j "$jobs"
  LSAN_OPTIONS=print_suppressions=0 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --test-dir "$asan_dir" -j "$jobs" --output-on-failure || status=1
  echo "sanitize: asan+ubsan build and tests took $(($(date +%s) - start)) s"
fi
if [[ $which == tsan || $which == all ]]; then
  start=$(date +%s)
  configure "$tsan_dir" thread
  # Only the threaded components, to fit CI: the hand-off stress test and the four-thread Pipeline
  # (playback tests), capture and signal threads, the reconnecting source, UDP loopback, the
  # events mailbox, the live score cut, and rtmot itself streaming a real vtest.avi run to a
  # listener and serving its page.
  cmake --build "$tsan_dir" -j "$jobs" --target $tsan_targets rtmot
  export TSAN_OPTIONS="suppressions=$supp/tsan.supp halt_on_error=1 second_deadlock_stack=1"
  for target in $tsan_targets; do
    binary=$(find "$tsan_dir/tests" -type f -name "$target" -perm -u+x | head -n 1)
    echo "--- tsan: $target"
    "$binary" --gtest_brief=1 || status=1
  done
  echo "--- tsan: rtmot run -> rtmot listen on loopback"
  bash "$root/tests/system/listen_receives_vtest_run.sh" "$tsan_dir/apps/rtmot" "$root" \
    "${RTMOT_SHARED_DIR:-$root/../shared}" 15 || status=1
  # The operator's page: its MJPEG hand-off (capture and sink threads to the encoder thread) and a
  # line saved while the track stage runs (pipeline/events_mailbox.hpp), on a real run.
  echo "--- tsan: rtmot run --web-port, watched and written to"
  bash "$root/tests/system/web_view.sh" "$tsan_dir/apps/rtmot" "$root" \
    "${RTMOT_SHARED_DIR:-$root/../shared}" || status=1
  # SIGHUP's reload thread and the page's settings against the running pipeline (the score cut's
  # hand-over to the detect stage, the events' to the track stage).
  echo "--- tsan: rtmot run, SIGHUP and POST /api/settings"
  bash "$root/tests/system/web_reload.sh" "$tsan_dir/apps/rtmot" "$root" \
    "${RTMOT_SHARED_DIR:-$root/../shared}" || status=1
  echo "sanitize: tsan build and tests took $(($(date +%s) - start)) s"
fi
exit $status
