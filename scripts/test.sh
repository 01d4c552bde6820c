#!/usr/bin/env bash
# Installs what is missing, builds everything and runs every test with ctest; then the browser
# page (built with emcc) in headless chromium; then the whole suite again built with
# AddressSanitizer + UndefinedBehaviorSanitizer (clang), and each libFuzzer harness for 20 s
# under the same sanitizers. Any failure or report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
bash scripts/web.sh
bash scripts/web_test.sh
bash scripts/sanitize.sh 20
