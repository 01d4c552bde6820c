#!/usr/bin/env bash
# Executes docs/notebooks/*.ipynb exactly as the test does (python/tests/test_notebooks.py, ctest
# python.notebooks: nbconvert --execute with Debian's python3, PYTHONPATH=build/python) and, where
# the test passes, writes each back with the outputs of that run (text and plots), so that the
# committed notebooks show them on the repository's page. Commit the result.
# Usage: scripts/notebooks.sh [BUILD_DIR] [pytest -k expression, e.g. tuning]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
BUILD=$(cd "$BUILD" && pwd)
[ -x "$BUILD/formsim" ] || { echo "notebooks.sh: no $BUILD/formsim (run scripts/build.sh)" >&2; exit 1; }
export PYTHONPATH="$BUILD/python" FORMSIM_BIN="$BUILD/formsim" FORMSIM_NOTEBOOKS_WRITE=1 PYTHONDONTWRITEBYTECODE=1
unset DISPLAY
/usr/bin/python3 -m pytest -q -p no:cacheprovider python/tests/test_notebooks.py ${2:+-k "$2"}
ls -l docs/notebooks/*.ipynb
