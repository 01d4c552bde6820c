#!/usr/bin/env bash
# Which libm functions round differently in glibc (the desktop build) and emscripten's musl (the
# page)? Builds tests/web/libm_probe.c with gcc and with emcc, runs both on the same arguments
# and prints, per function, how many of its 2000 results differ. A measurement for issue 29's
# equality table (tests/web/equality.mjs), not a test.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"  # Debian's emcc finds acorn there
gcc -O2 "$HERE/libm_probe.c" -o "$TMP/probe" -lm
emcc -O2 "$HERE/libm_probe.c" -o "$TMP/probe.js" -sENVIRONMENT=node
"$TMP/probe" >"$TMP/glibc.txt"
# emcc 3.1.6's loader takes node 20's fetch for a browser's: read the .wasm from disk instead.
node --no-experimental-fetch "$TMP/probe.js" >"$TMP/musl.txt"
paste -d' ' "$TMP/glibc.txt" "$TMP/musl.txt" |
  awk '{n[$1]++; if ($2 != $4) d[$1]++; if (!($1 in o)) {o[$1] = ++k; name[k] = $1}}
       END {for (i = 1; i <= k; i++) printf "%-6s %4d of %d differ\n", name[i], d[name[i]], n[name[i]]}'
