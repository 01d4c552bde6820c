#!/usr/bin/env bash
# The browser test of formsim's WebAssembly page (issue 29): Debian's chromium, headless, drives
# the page in out/web/ (bash scripts/web.sh builds it) through puppeteer-core, and compares every
# shipped scenario run in the page with the native build's CSV (tests/web/browser_test.mjs).
#
#   bash scripts/web_test.sh [--measure] [OPTIONS]
#     --web DIR      the page to test (default out/web/; also FORMSIM_WEB_DIR)
#     --native FILE  the native formsim (default build/formsim; also FORMSIM_NATIVE)
#     --out DIR      pictures, tables, logs (default out/web_test/; also FORMSIM_WEB_OUT)
#     --scenarios A,B  --skip-equality   (see node tests/web/browser_test.mjs --help)
#     --measure      size and speed for docs/benchmarks.md instead (tests/web/measure.mjs)
# Installs what is missing first: chromium (apt, as root) and the test's npm packages (npm ci
# from tests/web/package-lock.json). Exits non-zero when a check fails.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TESTS="$ROOT/tests/web"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "web_test: node and npm are needed (the machine's Node.js 20)" >&2
  exit 1
fi
if [ ! -x "${CHROMIUM:-/usr/bin/chromium}" ]; then
  echo "web_test: installing chromium"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends chromium
fi
# puppeteer-core never downloads a browser; npm ci takes what the lockfile names (a cached copy
# when there is one).
if [ ! -d "$TESTS/node_modules/puppeteer-core" ] || [ ! -d "$TESTS/node_modules/pngjs" ] ||
   [ "$TESTS/package-lock.json" -nt "$TESTS/node_modules/.package-lock.json" ]; then
  echo "web_test: npm ci in tests/web"
  (cd "$TESTS" && npm ci --no-audit --no-fund --prefer-offline)
fi

driver="$TESTS/browser_test.mjs"
if [ "${1:-}" = "--measure" ]; then
  driver="$TESTS/measure.mjs"
  shift
fi
cd "$ROOT"
exec node "$driver" "$@"
