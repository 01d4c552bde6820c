#!/usr/bin/env bash
# Builds and runs the benchmarks on one core (taskset), writing build/bench.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
taskset -c 0 ./build/bench/formsim_bench --benchmark_out=build/bench.json --benchmark_out_format=json "$@"
