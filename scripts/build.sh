#!/usr/bin/env bash
# Configures and builds formsim, its tests and benchmarks in ./build (Release).
# Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFORMSIM_BUILD_TESTS=ON -DFORMSIM_BUILD_BENCH=ON \
  "$@" >/dev/null
cmake --build build -j"$(nproc)"
