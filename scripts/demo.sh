#!/usr/bin/env bash
# Installs what the demo needs and is missing, builds the `formsim` program only (the tests and
# benchmarks are left to scripts/test.sh) and runs the main headless demo: the paper's
# figure-eight cascade formation with a UKF per link. Writes out/demo/{timeseries.csv,
# summary.json, snapshot.png, plots/*.png, frames/*.png}. No display needed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh demo
# A first configure leaves the tests and benchmarks out (their packages may not be installed
# yet); scripts/build.sh turns them on. The Python module is AUTO: built once its packages are
# there, decided again at every configure (scripts/test.sh requires it).
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFORMSIM_BUILD_TESTS=OFF \
    -DFORMSIM_BUILD_BENCH=OFF >/dev/null
fi
cmake --build build -j"$(nproc)" --target formsim
./build/formsim run formation_traj2_ukf --out out/demo --plots out/demo/plots \
  --snapshot out/demo/snapshot.png --frames out/demo/frames --fps 10 --size 1280x720
echo "demo: open out/demo/snapshot.png and out/demo/plots/*.png"
