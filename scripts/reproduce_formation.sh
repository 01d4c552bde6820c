#!/usr/bin/env bash
# Regenerates the README's cascade-formation reproduction table (paper 000): trajectories 1-3,
# gains as printed and per sample, estimators truth / raw / UKF with the paper's angle noise.
# Usage: scripts/reproduce_formation.sh [path/to/formsim]   (default build/formsim)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/formsim}
[ -x "$BIN" ] || { bash scripts/build.sh; BIN=build/formsim; }
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
NOISE=(--set noise.l_sigma=0.003 --set noise.phi_variance=0.9186e-4 --set noise.alpha_variance=0.9186e-4)

# Prints "max|e_phi12| max|e_l| phi12-estimate-RMS" from formsim's summary table.
measure() {
  "$BIN" run "$@" --out "$OUT/run" | awk '
    $1 ~ /^R[0-9]+-R[0-9]+$/ { if ($4 + 0 > el) el = $4 + 0;
                               if ($1 == "R1-R2") { ephi = $5; est = $8 } }
    END { printf "%s | %.2g | %s", ephi, el, est }'
}

echo "| traj | gains | estimator | max|e_φ12| [rad] | max|e_l| [m] | φ12 estimate RMS [rad] |"
echo "|---|---|---|---|---|---|"
for traj in 1 2 3; do
  for gains in printed per_sample; do
    scenario=formation_traj${traj}
    [ "$gains" = per_sample ] && scenario+=_per_sample
    for est in truth raw ukf; do
      args=("$scenario")
      if [ "$est" != truth ]; then
        args+=("${NOISE[@]}" --set robots.R2.follow.estimator=$est --set robots.R3.follow.estimator=$est)
      fi
      echo "| $traj | $gains | $est | $(measure "${args[@]}") |"
    done
  done
done
