#!/usr/bin/env bash
# A sweep spread with GNU parallel: `formsim sweep ... --print-jobs` gives one self-contained
# command line per run; parallel runs them (here on this host through an --sshloginfile that
# names the local machine, the way a file of ssh logins spreads them over hosts), then
# `formsim sweep collect` merges the records. The tables must be byte-identical to a local
# one-process sweep; so must those of three --shard K/3 slices run by parallel and collected.
# Exit 77 (skipped) when GNU parallel is not installed.
# Usage: parallel_sweep_test.sh FORMSIM_BINARY
set -euo pipefail
formsim=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
command -v parallel >/dev/null || { echo "SKIPPED: GNU parallel is not installed (scripts/setup.sh installs it)"; exit 77; }
parallel --version 2>/dev/null | grep -q "GNU parallel" || { echo "SKIPPED: 'parallel' is not GNU parallel"; exit 77; }

T=$(mktemp -d /tmp/formsim-parallel.XXXXXX)
trap 'rm -rf "$T"' EXIT
export HOME="$T"  # parallel keeps its state (citation notice, sshlogin cache) in ~/.parallel
args=(formation_traj2_ukf --set duration=2 --vary robots.R2.follow.k_phi=0.05,0.1 --vary robots.R2.follow.estimator=truth,ukf --seeds 1..2
      --metric links.R1-R2.max_abs_error_after_settle.phi)
"$formsim" sweep "${args[@]}" --out "$T/local" --jobs 1 -q

# One line per run, two at a time on the hosts of the login file (':' is this machine).
echo "2/:" > "$T/hosts"
"$formsim" sweep "${args[@]}" --print-jobs --out "$T/jobs" > "$T/jobs.txt"
[ "$(wc -l < "$T/jobs.txt")" -eq 8 ] || { echo "FAILED: expected 8 job lines"; cat "$T/jobs.txt"; exit 1; }
parallel --will-cite --halt now,fail=1 --sshloginfile "$T/hosts" < "$T/jobs.txt"
# Run again: every run is recorded, so nothing is printed and nothing runs twice.
[ -z "$("$formsim" sweep "${args[@]}" --print-jobs --out "$T/jobs")" ] || { echo "FAILED: finished runs listed again"; exit 1; }
"$formsim" sweep collect "$T/jobs" --out "$T/jobs_merged" --metric links.R1-R2.max_abs_error_after_settle.phi -q

# Three shards, run by parallel, then collected.
parallel --will-cite --halt now,fail=1 -j2 "$formsim" sweep "${args[@]@Q}" --shard {}/3 --out "$T/shard{}" -q ::: 1 2 3
"$formsim" sweep collect "$T/shard1" "$T/shard2" "$T/shard3" --out "$T/shards_merged" --metric links.R1-R2.max_abs_error_after_settle.phi -q

for d in jobs_merged shards_merged; do
  for f in runs.csv aggregate.csv ranking_links.R1-R2.max_abs_error_after_settle.phi.txt; do
    cmp "$T/local/$f" "$T/$d/$f" || { echo "FAILED: $d/$f differs from the local sweep's"; exit 1; }
  done
done
echo "PASSED: job lines through GNU parallel and three shards collect to the local sweep's tables byte for byte"
