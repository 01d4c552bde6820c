#!/usr/bin/env bash
# The cascade-formation reproduction table of docs/papers/formation.md (paper 000), kept as a thin wrapper: it is
# `formsim reproduce formation`, which runs the 18 cases through the sweep engine over the seeds
# and reads their metrics (never printed text).
# Usage: scripts/reproduce_formation.sh [path/to/formsim] [reproduce flags, e.g. --seeds 1..10]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=build/formsim
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then BIN=$1; shift; fi
[ -x "$BIN" ] || { bash scripts/build.sh; BIN=build/formsim; }
exec "$BIN" reproduce formation "$@"
