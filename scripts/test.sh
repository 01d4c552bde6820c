#!/usr/bin/env bash
# Installs what is missing, builds everything with every part explicitly ON and runs every suite:
#   Release     the GoogleTest suites, the scripts' tests, the lessons and the install test (ctest)
#   Python      the module's pytest suite and the notebooks (ctest runs them; counted by pytest)
#   docs        every command in the docs, links, images, generated pages, and the site built
#               with mkdocs build --strict (ctest docs.*)
#   package     the .deb built, inspected, validated, linted and run (scripts/package.sh --check)
#   page        the browser page built with emcc, in headless chromium (scripts/web*.sh)
#   sanitizers  the whole ctest suite again with AddressSanitizer + UndefinedBehaviorSanitizer
#   fuzzing     each libFuzzer harness for 20 s under the same sanitizers
# Ends with one table (each suite: tests run, passed, failed, seconds; the seconds of a suite run
# by itself are its wall time, those of the suites inside the Release ctest run the sum of their
# tests' times). A failing suite, or one
# that ran no test although its packages are installed, fails the run; every suite runs anyway,
# so the table shows all of them.
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
LOGS=$ROOT/build/test-logs
bash scripts/setup.sh || exit 1
# Configure with every part ON: a missing package fails here, naming it, instead of a suite
# quietly dropping out.
bash scripts/build.sh -DFORMSIM_BUILD_PYTHON=ON -DFORMSIM_BUILD_TESTS=ON -DFORMSIM_BUILD_BENCH=ON ||
  exit 1
mkdir -p "$LOGS"
ROWS=$LOGS/rows.tsv
: >"$ROWS"
status=0
count() { /usr/bin/python3 scripts/test_counts.py "$@"; }
# row SUITE RC SECONDS RUN PASSED FAILED: one line of the table; a non-zero exit or no test run
# is noted and fails the run.
row() {
  local note=""
  if [ "$2" -ne 0 ] && [ "$6" -eq 0 ]; then note="exit status $2"; fi
  if [ "$4" -eq 0 ]; then note="${note:+$note; }ran no test"; fi
  if [ "$2" -ne 0 ] || [ "$4" -eq 0 ] || [ "$6" -ne 0 ]; then status=1; fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$4" "$5" "$6" "$3" "$note" >>"$ROWS"
}
# timed LOG CMD...: runs CMD with its output shown and kept in LOG; sets RC and SECS.
timed() {
  local log=$1 t0=$SECONDS
  shift
  "$@" 2>&1 | tee "$log"
  RC=${PIPESTATUS[0]}
  SECS=$((SECONDS - t0))
}

# Release: ctest, with JUnit output; the Python suites also write pytest's own.
rm -f build/ctest-release.xml build/pytest-*.xml
timed "$LOGS/release.log" bash -c 'cd build && ctest --output-on-failure -j"$(nproc)" --output-junit ctest-release.xml'
ctest_rc=$RC
read -r n p f s < <(count junit build/ctest-release.xml --skip python.,docs.)
row "Release (ctest)" "$ctest_rc" "$s" "$n" "$p" "$f"
read -r n p f s < <(count junit build/pytest-*.xml)
row "Python (pytest)" "$ctest_rc" "$s" "$n" "$p" "$f"
read -r n p f s < <(count junit build/ctest-release.xml --only docs.)
row "docs (ctest)" "$ctest_rc" "$s" "$n" "$p" "$f"

timed "$LOGS/package.log" bash scripts/package.sh --check
row "package (.deb)" "$RC" "$SECS" 1 $((RC == 0)) $((RC != 0))

t0=$SECONDS
bash scripts/web.sh 2>&1 | tee "$LOGS/web_build.log"
web_rc=${PIPESTATUS[0]}
if [ "$web_rc" -eq 0 ]; then
  bash scripts/web_test.sh 2>&1 | tee "$LOGS/web.log"
  web_rc=${PIPESTATUS[0]}
fi
read -r n p f < <(count line "$LOGS/web.log")
row "page (chromium)" "$web_rc" $((SECONDS - t0)) "$n" "$p" "$f"

# The sanitizer build and its ctest run, then the fuzzers (scripts/sanitize.sh does both; here
# in two steps for the table).
t0=$SECONDS
bash scripts/sanitize.sh --build-only 2>&1 | tee "$LOGS/asan_build.log"
asan_rc=${PIPESTATUS[0]}
if [ "$asan_rc" -eq 0 ]; then
  rm -f build-asan/ctest-asan.xml
  ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=1 \
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    bash -c 'cd build-asan && ctest --output-on-failure -j"$(nproc)" --output-junit ctest-asan.xml' 2>&1 |
    tee "$LOGS/asan.log"
  asan_rc=${PIPESTATUS[0]}
fi
read -r n p f s < <(count junit build-asan/ctest-asan.xml)
row "ASan+UBSan (ctest)" "$asan_rc" $((SECONDS - t0)) "$n" "$p" "$f"

timed "$LOGS/fuzz.log" bash scripts/fuzz.sh 20 build-asan
read -r n p f < <(count fuzz "$LOGS/fuzz.log")
row "fuzzing (20 s each)" "$RC" "$SECS" "$n" "$p" "$f"

echo
count table "$ROWS"
# The failed tests by name, last, where a CI log's tail shows them.
count failures build/ctest-release.xml build/pytest-*.xml build-asan/ctest-asan.xml
exit $status
