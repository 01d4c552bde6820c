#!/usr/bin/env bash
# Installs what is missing, builds everything and runs every test with ctest; then the whole
# suite again built with AddressSanitizer + UndefinedBehaviorSanitizer (clang), and each
# libFuzzer harness for 60 s under the same sanitizers. Any failure or report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
bash scripts/sanitize.sh 60
