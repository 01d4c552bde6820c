#!/usr/bin/env bash
# The whole suite built with clang, AddressSanitizer and UndefinedBehaviorSanitizer (any report
# fails), plus the libFuzzer harnesses, in build-asan. Usage:
#   scripts/sanitize.sh [FUZZ_SECONDS, default 60]      build, run every test, fuzz each harness
#   scripts/sanitize.sh --build-only [BUILD]            only build
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build-asan
if [ "${1:-}" = "--build-only" ]; then BUILD=${2:-build-asan}; fi
CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DFORMSIM_SANITIZE=ON -DFORMSIM_FUZZ=ON -DFORMSIM_BUILD_BENCH=OFF >/dev/null
cmake --build "$BUILD" -j"$(nproc)"
[ "${1:-}" = "--build-only" ] && exit 0
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
(cd "$BUILD" && ctest --output-on-failure -j"$(nproc)")
bash scripts/fuzz.sh "${1:-60}" "$BUILD"
