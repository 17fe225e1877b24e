#!/usr/bin/env bash
# Fuzzes every parser of untrusted input for SECONDS each (default 60) with libFuzzer + ASan + UBSan.
# Builds the targets in BUILD_DIR (default build-asan: scripts/sanitize.sh asan configures it with
# them, and a folder not configured for fuzzing is configured the same way), makes seed corpora from
# the real data (tests/fuzz/make_corpus.sh), runs each target and prints executions and time. Exits 1
# if any target found a crash (the reproducer is in BUILD_DIR/artifacts/; turn it into a
# tests/regression case).
# Usage: scripts/fuzz.sh [SECONDS]   Env: JOBS (build parallelism, default 2), BUILD_DIR,
# RTMOT_SHARED_DIR (default ../shared).
set -euo pipefail
seconds=${1:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build-asan}
shared=${RTMOT_SHARED_DIR:-$root/../shared}
export RTMOT_SHARED_DIR=$shared
jobs=${JOBS:-2}

# -fsanitize=fuzzer-no-link instruments our libraries for coverage; the targets link libFuzzer.
# UBSan must abort (not just print) for the fuzzer to notice. One configuration, sanitize.sh's
# (asan), so that CI compiles the instrumented project once for the tests and the fuzzers.
if ! grep -qs '^RTMOT_BUILD_FUZZERS:BOOL=ON' "$build/CMakeCache.txt"; then
  JOBS=$jobs ASAN_DIR=$build bash "$root/scripts/sanitize.sh" configure-asan
fi
cmake --build "$build" --target fuzzers -j "$jobs"

"$root/tests/fuzz/make_corpus.sh" "$build" "$build/seeds"
mkdir -p "$build/artifacts"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
failed=()
printf '%-22s %12s %8s %s\n' target executions seconds result
for target in mot_rows seqinfo run_config host_port video_uri message_decoder output_uri \
  model_description; do
  binary=$build/tests/fuzz/fuzz_$target
  if [[ ! -x $binary ]]; then
    echo "fuzz_$target: not built" >&2
    failed+=("$target")
    continue
  fi
  corpus=$build/corpus/$target  # grows across runs; the seeds stay read-only
  mkdir -p "$corpus"
  log=$build/fuzz_$target.log
  start=$(date +%s)
  status=ok
  "$binary" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build/artifacts/$target-" "$corpus" "$build/seeds/$target" >"$log" 2>&1 ||
    status=CRASH
  elapsed=$(($(date +%s) - start))
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  printf '%-22s %12s %8s %s\n' "fuzz_$target" "$execs" "$elapsed" "$status"
  if [[ $status != ok ]]; then
    failed+=("$target")
    grep -m 5 -E 'ERROR|SUMMARY|terminate|Test unit written' "$log" >&2 || true
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in: ${failed[*]} (logs: $build/fuzz_*.log, inputs: $build/artifacts/)" >&2
  exit 1
fi
echo "fuzz: no findings"
