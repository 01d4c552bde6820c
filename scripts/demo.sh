#!/usr/bin/env bash
# Installs what is missing, builds formsim and runs the main headless demo: the paper's
# figure-eight cascade formation with a UKF per link. Writes out/demo/{timeseries.csv,
# summary.json, snapshot.png, plots/*.png, frames/*.png}. No display needed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/formsim run formation_traj2_ukf --out out/demo --plots out/demo/plots \
  --snapshot out/demo/snapshot.png --frames out/demo/frames --fps 10 --size 1280x720
echo "demo: open out/demo/snapshot.png and out/demo/plots/*.png"
