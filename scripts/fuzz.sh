#!/usr/bin/env bash
# Runs the libFuzzer harnesses (tests/fuzz) under AddressSanitizer and UndefinedBehaviorSanitizer.
# Usage: scripts/fuzz.sh [SECONDS per harness, default 300] [BUILD folder, default build-asan]
# Seeds: the shipped scenarios, the invalid fixtures, the shipped lessons and tests/fuzz/*_seeds
# (edits, sessions, lesson blocks, sweep specs); new inputs go to a temporary corpus. A crash is
# saved in fuzz-artifacts/ and the script fails: turn it into a fixture in tests/fixtures/invalid/
# with its expected message, then fix it.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-300}
BUILD=${2:-build-asan}
for h in fuzz_scenario fuzz_set fuzz_session fuzz_lesson fuzz_sweep_spec fuzz_script; do
  [ -x "$BUILD/tests/fuzz/$h" ] || { bash scripts/sanitize.sh --build-only "$BUILD"; break; }
done
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
# The GL driver's own never-freed allocations (fuzz_script draws through OSMesa), as in ctest.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitizer/lsan.supp}
mkdir -p fuzz-artifacts
CORPUS=$(mktemp -d)
trap 'rm -rf "$CORPUS"' EXIT
ROOT=$PWD
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
run() {
  local harness=$1; shift
  local seeds=()
  for d in "$@"; do seeds+=("$ROOT/$d"); done
  # Each harness runs in a folder of its own: what a fuzzed action writes to a relative path
  # (fuzz_script's save, screenshot, export-figures) lands there, not in the checkout.
  mkdir -p "$CORPUS/$harness" "$CORPUS/work/$harness"
  echo "fuzz: $harness for ${SECONDS_EACH} s"
  (cd "$CORPUS/work/$harness" &&
    "$BUILD/tests/fuzz/$harness" -max_total_time="$SECONDS_EACH" -timeout=30 -rss_limit_mb=4096 \
      -max_len=16384 -print_final_stats=1 -artifact_prefix="$ROOT/fuzz-artifacts/$harness-" \
      "$CORPUS/$harness" "${seeds[@]}" 2>&1) |
    grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written|deadly" || true
  # libFuzzer leaves an artifact when it found something: a crash, a leak, a timeout (-timeout, a
  # hang) or an out-of-memory. A slow unit (over 10 s, not a hang) is kept aside and reported.
  local slow
  for slow in fuzz-artifacts/"$harness"-slow-unit-*; do
    [ -e "$slow" ] || continue
    mkdir -p fuzz-artifacts/slow && mv "$slow" fuzz-artifacts/slow/
    echo "fuzz: $harness: a slow input (not a failure), kept in fuzz-artifacts/slow/$(basename "$slow")"
  done
  if ls fuzz-artifacts/"$harness"-* >/dev/null 2>&1; then
    echo "fuzz: $harness found a failing input: $(ls fuzz-artifacts/"$harness"-*)"
    return 1
  fi
}
run fuzz_scenario assets/scenarios tests/fixtures/invalid
run fuzz_set tests/fuzz/set_seeds
run fuzz_session tests/fuzz/session_seeds tests/fuzz/session_seeds/invalid
run fuzz_lesson tests/fuzz/lesson_seeds assets/lessons
run fuzz_sweep_spec tests/fuzz/sweep_spec_seeds
run fuzz_script tests/fuzz/script_seeds
# The GUI chaos test with more actions than CI's 2000 (tests/app/gui_chaos_test.cpp).
if [ "$SECONDS_EACH" -gt 60 ] && [ -x "$BUILD/tests/tests_app" ]; then
  echo "fuzz: GUI chaos, $((SECONDS_EACH * 40)) actions"
  FORMSIM_CHAOS_ACTIONS=$((SECONDS_EACH * 40)) "$BUILD/tests/tests_app" --gtest_filter='GuiChaos.*'
fi
echo "fuzz: no crash, hang or sanitizer report"
