#!/usr/bin/env bash
# The tuning examples of docs/sweeps-and-tuning.md, end to end: `formsim tune` on seeds 1-5, then the shipped and
# the tuned gains each run on the held-out seeds 6-25 with `formsim sweep`, and a table of the
# numbers (markdown) on stdout.
#   1. formation_traj2_ukf: the two gains of each follower (R2: k_l, k_phi; R3: k_l, k_l2) for
#      the after-settle bearing and distance errors (sum of the four max |e| after settle)
#   2. agv_fused: the cross-track PID (kp, ki, kd) for the RMS cross-track error
# Usage: scripts/tune_examples.sh [OUT_DIR]  (default out/tune_examples; about a minute on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
formsim=${FORMSIM:-build/formsim}
out=${1:-out/tune_examples}
rm -rf "$out"
mkdir -p "$out"

# The value of column NAME in row ROW (1 = first data row) of a CSV with a header.
col() {
  awk -F, -v name="$2" -v row="${3:-1}" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) c = i; next }
    NR == row + 1 { print $c }' "$1"
}
# Per run (seed order): the sum of the named metric columns of runs.csv, one per line.
objective_per_run() {
  local file=$1; shift
  awk -F, -v names="$*" 'BEGIN { n = split(names, want, " ") }
    NR == 1 { for (i = 1; i <= NF; i++) for (k = 1; k <= n; k++) if ($i == want[k]) c[k] = i; next }
    { s = 0; for (k = 1; k <= n; k++) s += $c[k]; printf "%.17g\n", s }' "$file"
}
fmt() { awk -v v="$1" 'BEGIN { printf "%.3g", v }'; }
pm() { awk -v m="$1" -v s="$2" -v k="${3:-1}" 'BEGIN { printf "%.3g ± %.2g", m * k, s * k }'; }

# example NAME SCENARIO "METRIC..." PARAM...
example() {
  local name=$1 scenario=$2 metrics=$3
  shift 3
  local expr="" params=()
  for m in $metrics; do expr+="${expr:+ + }$m"; done
  for p in "$@"; do params+=(--param "$p"); done
  local d="$out/$name"
  "$formsim" tune "$scenario" "${params[@]}" --metric "$expr" --seeds 1..5 --budget 80 --method bobyqa --out "$d/tune" -q
  "$formsim" sweep "$scenario" --seeds 6..25 --out "$d/shipped" --no-figures -q
  "$formsim" sweep "$d/tune/best.yaml" --seeds 6..25 --out "$d/tuned" --no-figures -q
  local hist="$d/tune/history.csv" rows best
  rows=$(($(wc -l < "$hist") - 1))
  # The row of the lowest finite objective (column 3 + number of gains: eval, stage, the gains),
  # the first of equals.
  best=$(awk -F, -v c="$(($# + 3))" 'NR > 1 && $c ~ /^[0-9.eE+-]+$/ && (b == "" || $c + 0 < b + 0) { b = $c; row = NR - 1 }
    END { print row }' "$hist")
  echo
  echo "### $scenario"
  echo
  echo "Tuned with \`formsim tune\` (BOBYQA, $rows evaluations of seeds 1-5) for \`${expr}\`."
  echo
  echo "| gain | shipped | tuned |"
  echo "|---|---|---|"
  for p in "$@"; do
    echo "| \`$p\` | $(fmt "$(col "$hist" "$p" 1)") | $(fmt "$(col "$hist" "$p" "$best")") |"
  done
  echo
  echo "Held-out seeds 6-25 (20 runs each, mean ± std over the seeds):"
  echo
  echo "| metric | shipped | tuned |"
  echo "|---|---|---|"
  for m in $metrics; do
    echo "| \`$m\` | $(pm "$(col "$d/shipped/aggregate.csv" "$m.mean")" "$(col "$d/shipped/aggregate.csv" "$m.std")") |" \
         "$(pm "$(col "$d/tuned/aggregate.csv" "$m.mean")" "$(col "$d/tuned/aggregate.csv" "$m.std")") |"
  done
  # The objective per held-out seed, paired: how often the tuned gains do better.
  paste <(objective_per_run "$d/shipped/runs.csv" $metrics) <(objective_per_run "$d/tuned/runs.csv" $metrics) |
    awk '{ s += $1; t += $2; if ($2 < $1) w++; n++ }
      END { printf "| objective (sum) | %.4g | %.4g (%+.1f %%, better on %d of %d seeds) |\n", s / n, t / n, 100 * (t - s) / s, w, n }'
}

example formation formation_traj2_ukf \
  "links.R1-R2.max_abs_error_after_settle.phi links.R1-R2.max_abs_error_after_settle.l links.R1-R3.max_abs_error_after_settle.l links.R2-R3.max_abs_error_after_settle.l" \
  robots.R2.follow.k_l robots.R2.follow.k_phi robots.R3.follow.k_l robots.R3.follow.k_l2
example agv agv_fused "cross_track.rms_m" control.cross.kp control.cross.ki control.cross.kd
echo
echo "(outputs in $out: tune/history.csv, tune/best.yaml, tune/convergence.png, shipped/ and tuned/ sweeps)"
