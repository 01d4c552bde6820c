#!/usr/bin/env bash
# Runs every check of every shipped lesson on seeds 1..30 (CI, ctest lessons.check, runs each
# check on its own seeds only) and prints, per lesson, how many checks hold on all 30 seeds,
# then the failing lines, the warnings (a seed effect the text claims and the values do not show)
# and the total. Exits 1 when a check fails on any seed, or on such a warning.
#
#   scripts/lessons_all_seeds.sh [--formsim PATH] [--seeds 1..30] [--jobs N] [LESSON...]
#
# FORMSIM (or --formsim) names the program; default: build/formsim. The full log is kept in
# $OUT (default: lessons_all_seeds.log in the current directory).
set -euo pipefail
cd "$(dirname "$0")/.."
formsim="${FORMSIM:-build/formsim}"
seeds="1..30"
jobs="$(nproc 2>/dev/null || echo 2)"
lessons=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --formsim) formsim="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) lessons+=("$1"); shift ;;
  esac
done
if [[ ! -x "$formsim" ]]; then
  echo "lessons_all_seeds.sh: no program at $formsim (build it, or pass --formsim PATH)" >&2
  exit 2
fi
out="${OUT:-lessons_all_seeds.log}"
start=$(date +%s)
status=0
"$formsim" lessons check "${lessons[@]}" --seeds "$seeds" --jobs "$jobs" > "$out" || status=$?
end=$(date +%s)
echo "formsim lessons check --seeds $seeds ($("$formsim" --version 2>/dev/null | head -1), $(date -u +%Y-%m-%d), $((end - start)) s)"
echo
printf '%-30s %7s %7s\n' lesson checks hold
awk '$0 ~ /  seeds [0-9]+  / { n[$1]++; if ($0 ~ / holds( |$)/) h[$1]++ }
     END { for (l in n) printf "%-30s %7d %7d\n", l, n[l], h[l] }' "$out" | sort
echo
grep -E ' FAILS( |$)' "$out" || true
grep -E '^warning: ' "$out" || true
tail -1 "$out"
exit "$status"
