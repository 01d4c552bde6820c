#!/usr/bin/env bash
# Installs the Debian packages formsim needs that are not installed yet. Idempotent; run as root.
#   scripts/setup.sh        everything: the build, the tests, the sanitizers, the cluster tests,
#                           the Python module
#   scripts/setup.sh demo   only what building `formsim` and running the headless demo need
set -euo pipefail
# Building formsim and running it headless.
DEMO_PKGS=(build-essential cmake pkg-config libbox2d-dev libeigen3-dev libimgui-dev libglfw3-dev
           libosmesa6-dev libstb-dev libyaml-cpp-dev libcli11-dev libfuzzylite-dev zlib1g-dev
           fonts-dejavu-core
           libnlopt-dev                             # formsim tune: NLopt's methods
           libfmt-dev                               # numbers as text (header only)
           libcairo2-dev libfreetype-dev)           # vector figures (PDF)
PKGS=("${DEMO_PKGS[@]}"
      libgtest-dev libgmock-dev libbenchmark-dev
      xvfb xauth ffmpeg         # the window's tests under Xvfb; video export
      clang libclang-rt-14-dev  # clang: the sanitizer build and the libFuzzer harnesses
      parallel slurm-wlm munge  # the sweep's GNU parallel and single-node Slurm tests
      poppler-utils libxml2-utils   # PDF and SVG checks
      pybind11-dev python3-pybind11 python3-dev python3-numpy  # the Python module (python/)
      python3-pandas python3-pytest python3-distributed        # ... to_pandas, tests, Dask
      jupyter-nbconvert python3-ipykernel python3-nbformat     # ... the notebooks, executed
      python3-scipy python3-matplotlib                         #     by the tests
      emscripten dpkg-dev chromium   # the browser page (scripts/web.sh) and its test in chromium
      lintian desktop-file-utils appstream man-db  # the .deb's checks (scripts/package.sh --check)
      mkdocs python3-yaml)           # the documentation site (scripts/docs.sh) and its tests
if [ "${1:-}" = "demo" ]; then PKGS=("${DEMO_PKGS[@]}"); fi
missing=()
for p in "${PKGS[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi
# The browser test drives chromium with puppeteer-core from npm (tests/web/package-lock.json):
# npm comes with Node.js; Debian's npm package only where no npm is installed.
if [ "${1:-}" != "demo" ] && ! command -v npm >/dev/null 2>&1; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends npm
fi
