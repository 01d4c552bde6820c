#!/usr/bin/env bash
# Builds formsim as a WebAssembly page into out/web/ (index.html, formsim.js, formsim.wasm,
# formsim.data): the same window, scenarios and lessons, in a browser (issue 29).
#
#   bash scripts/web.sh            install what is missing (root), build, assemble out/web/
#   bash scripts/web.sh --serve    ... then serve out/web/ on http://127.0.0.1:8029/
#
# Everything comes from Debian: emscripten 3.1.6, and the sources of the same Box2D, Dear ImGui,
# yaml-cpp, fuzzylite, zlib and FreeType versions the desktop build links (Debian's source
# packages, fetched with `apt-get source` through a deb-src entry for the installed suite).
# Nothing is downloaded from anywhere else and no third-party source enters the repository.
# Work is kept in out/web-build/ (sources, the libraries built with emcc, formsim's objects): a
# second run rebuilds only what changed.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
WORK="$ROOT/out/web-build"
OUT="$ROOT/out/web"
JOBS="${JOBS:-$(nproc)}"
# Debian's emcc finds its acorn module through NODE_PATH when the machine's node is not Debian's.
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"

# ---- 1. Packages: emscripten, dpkg-dev (dpkg-source), the host tools the build runs ----
missing=()
for p in emscripten dpkg-dev cmake make libeigen3-dev libstb-dev libcli11-dev fonts-dejavu-core; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "web: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# ---- 2. Third-party sources: Debian's source packages of the versions installed here ----
# A deb-src entry for the suite the machine runs (the one its deb entries name), once.
SRC_LIST=/etc/apt/sources.list.d/formsim-deb-src.sources
have_src() { apt-cache showsrc box2d 2>/dev/null | grep -q '^Package: box2d'; }
if ! have_src; then
  suites="$(. /etc/os-release && echo "$VERSION_CODENAME $VERSION_CODENAME-updates")"
  echo "web: adding a deb-src entry ($SRC_LIST) for: $suites"
  printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: %s\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    "$suites" | $SUDO tee "$SRC_LIST" >/dev/null
  $SUDO apt-get update -qq
fi
mkdir -p "$WORK/src"
# fetch PKG BINARY: the source of PKG at the version of the installed binary package BINARY,
# unpacked into $WORK/src/PKG (kept between runs).
fetch() {
  local pkg="$1" bin="$2" ver dir="$WORK/src/$1"
  ver="$(dpkg-query -W -f='${source:Version}' "$bin" 2>/dev/null || true)"
  [ -n "$ver" ] || ver="$(apt-cache showsrc "$pkg" | awk '/^Version:/ {print $2; exit}')"
  if [ -f "$dir/.formsim-version" ] && [ "$(cat "$dir/.formsim-version")" = "$ver" ]; then return; fi
  echo "web: fetching the source of $pkg $ver"
  rm -rf "$dir" "$WORK/src/dl-$pkg" && mkdir -p "$WORK/src/dl-$pkg"
  (cd "$WORK/src/dl-$pkg" && apt-get source -qq --download-only "$pkg=$ver" >/dev/null 2>&1) || true
  local dsc; dsc="$(ls "$WORK/src/dl-$pkg"/*.dsc 2>/dev/null | head -1 || true)"
  if [ -n "$dsc" ] && (cd "$WORK/src/dl-$pkg" && dpkg-source -q -x "$(basename "$dsc")" "$dir" >/dev/null 2>&1); then
    :
  else
    # The mirror may lack a package's Debian tarball (fuzzylite 6.0+dfsg-6's is missing): the
    # upstream tarball is the code Debian compiles; its patches there only touch the build and
    # the tests (see its changelog). Unpack that.
    local orig; orig="$(ls "$WORK/src/dl-$pkg"/*.orig.tar.* 2>/dev/null | grep -v '\.asc$' | grep -v -- '-[a-z0-9]*\.tar' | head -1 || true)"
    [ -n "$orig" ] || orig="$(ls "$WORK/src/dl-$pkg"/*.orig.tar.* 2>/dev/null | grep -v '\.asc$' | head -1 || true)"
    [ -n "$orig" ] || { echo "web: cannot fetch the source of $pkg $ver (is deb.debian.org reachable?)" >&2; exit 1; }
    echo "web: $pkg: unpacking the upstream tarball $(basename "$orig") (Debian's own tarball is not on the mirror)"
    mkdir -p "$dir" && tar -xf "$orig" -C "$dir" --strip-components=1
  fi
  echo "$ver" >"$dir/.formsim-version"
  rm -rf "$WORK/src/dl-$pkg"
}
fetch box2d libbox2d-dev
fetch imgui libimgui-dev
fetch yaml-cpp libyaml-cpp-dev
fetch fuzzylite libfuzzylite-dev
fetch zlib zlib1g-dev
fetch freetype libfreetype-dev

# ---- 3. The libraries, built with emcc and installed into $WORK/deps ----
DEPS="$WORK/deps"
mkdir -p "$DEPS"
# WebAssembly exceptions: formsim reports invalid input by throwing (yaml-cpp throws too), and
# emcc's default build aborts on a throw. Every library is compiled with the same setting.
WEB_FLAGS="-fwasm-exceptions"
# cmake_dep NAME SRC_SUBDIR ARGS...: configure, build and install once per source version.
cmake_dep() {
  local name="$1" src="$2"; shift 2
  local stamp="$DEPS/.$name" ver; ver="$(cat "$WORK/src/$name/.formsim-version") $WEB_FLAGS $*"
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$ver" ]; then return; fi
  echo "web: building $name with emcc"
  rm -rf "$WORK/obj/$name"
  emcmake cmake -S "$src" -B "$WORK/obj/$name" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$DEPS" -DBUILD_SHARED_LIBS=OFF -DCMAKE_CXX_FLAGS="$WEB_FLAGS" \
    -DCMAKE_C_FLAGS="$WEB_FLAGS" "$@" >"$WORK/obj-$name.log" 2>&1 \
    || { tail -30 "$WORK/obj-$name.log"; exit 1; }
  cmake --build "$WORK/obj/$name" -j "$JOBS" >>"$WORK/obj-$name.log" 2>&1 \
    && cmake --install "$WORK/obj/$name" >>"$WORK/obj-$name.log" 2>&1 \
    || { tail -30 "$WORK/obj-$name.log"; exit 1; }
  echo "$ver" >"$stamp"
}
cmake_dep box2d "$WORK/src/box2d" -DBOX2D_BUILD_UNIT_TESTS=OFF -DBOX2D_BUILD_TESTBED=OFF
cmake_dep yaml-cpp "$WORK/src/yaml-cpp" -DYAML_CPP_BUILD_TESTS=OFF -DYAML_CPP_BUILD_TOOLS=OFF \
  -DYAML_CPP_BUILD_CONTRIB=OFF
cmake_dep fuzzylite "$WORK/src/fuzzylite/fuzzylite" -DFL_BUILD_SHARED=OFF -DFL_BUILD_STATIC=ON \
  -DFL_BUILD_BINARY=OFF -DFL_BUILD_TESTS=OFF -DFL_USE_FLOAT=OFF -DFL_BACKTRACE=OFF \
  -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG -Wno-error"  # its -Werror meets clang's -Wvarargs
# zlib: Debian's source drops the win32/ folder its CMakeLists.txt names, so its C files are
# compiled directly (the library is those 15 files).
zlib_ver="$(cat "$WORK/src/zlib/.formsim-version") $WEB_FLAGS"
if [ ! -f "$DEPS/.zlib" ] || [ "$(cat "$DEPS/.zlib")" != "$zlib_ver" ]; then
  echo "web: building zlib with emcc"
  rm -rf "$WORK/obj/zlib" && mkdir -p "$WORK/obj/zlib" "$DEPS/lib" "$DEPS/include"
  cp -f "$WORK/src/zlib/zconf.h.in" "$WORK/obj/zlib/zconf.h"  # zconf.h as ./configure leaves it
  for c in adler32 compress crc32 deflate gzclose gzlib gzread gzwrite infback inffast inflate \
           inftrees trees uncompr zutil; do
    emcc -O2 $WEB_FLAGS -DHAVE_UNISTD_H -I"$WORK/obj/zlib" -c "$WORK/src/zlib/$c.c" -o "$WORK/obj/zlib/$c.o"
  done
  rm -f "$DEPS/lib/libz.a" && emar rcs "$DEPS/lib/libz.a" "$WORK/obj/zlib"/*.o
  cp -f "$WORK/src/zlib/zlib.h" "$WORK/obj/zlib/zconf.h" "$DEPS/include/"
  echo "$zlib_ver" >"$DEPS/.zlib"
fi
# FreeType's gzip module uses the zlib above (its own copy would define zlib's symbols twice).
cmake_dep freetype "$WORK/src/freetype" -DFT_REQUIRE_ZLIB=ON -DZLIB_LIBRARY="$DEPS/lib/libz.a" \
  -DZLIB_INCLUDE_DIR="$DEPS/include" -DFT_DISABLE_BZIP2=ON -DFT_DISABLE_PNG=ON \
  -DFT_DISABLE_HARFBUZZ=ON -DFT_DISABLE_BROTLI=ON

# ---- 4. formsim itself: the same CMake project, in its web configuration (app/web/) ----
emcmake cmake -S "$ROOT" -B "$WORK/formsim" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS="$WEB_FLAGS" -DCMAKE_C_FLAGS="$WEB_FLAGS" -DCMAKE_EXE_LINKER_FLAGS="$WEB_FLAGS" \
  -DFORMSIM_WEB_DEPS="$DEPS" -DFORMSIM_WEB_IMGUI_SRC="$WORK/src/imgui" \
  -DFORMSIM_BUILD_TESTS=OFF -DFORMSIM_BUILD_BENCH=OFF -DFORMSIM_BUILD_PYTHON=OFF >/dev/null
cmake --build "$WORK/formsim" -j "$JOBS" --target formsim_web

# ---- 5. The page ----
mkdir -p "$OUT"
for f in formsim.js formsim.wasm formsim.data; do cp -f "$WORK/formsim/$f" "$OUT/$f"; done
if [ -d "$ROOT/web" ]; then cp -rf "$ROOT/web/." "$OUT/"; fi
echo "web: $OUT: $(cd "$OUT" && ls | tr '\n' ' ')"
echo "web: wasm $(stat -c %s "$OUT/formsim.wasm") bytes, data $(stat -c %s "$OUT/formsim.data") bytes"
if [ "${1:-}" = "--serve" ]; then
  echo "web: serving $OUT on http://127.0.0.1:8029/ (Ctrl-C ends it)"
  cd "$OUT" && exec python3 -m http.server 8029 --bind 127.0.0.1
fi
