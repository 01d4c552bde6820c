#!/usr/bin/env bash
# Installs every Debian package formsim needs that is not installed yet. Idempotent; run as root.
set -euo pipefail
PKGS=(build-essential cmake pkg-config libbox2d-dev libeigen3-dev libimgui-dev libglfw3-dev libosmesa6-dev
      libstb-dev libyaml-cpp-dev libcli11-dev libfuzzylite-dev libgtest-dev libgmock-dev libbenchmark-dev
      xvfb xauth ffmpeg fonts-dejavu-core zlib1g-dev
      clang libclang-rt-14-dev  # clang: the sanitizer build and the libFuzzer harnesses
      libnlopt-dev              # formsim tune: BOBYQA, Nelder-Mead, COBYLA
      parallel slurm-wlm munge  # the sweep's GNU parallel and single-node Slurm tests
      libcairo2-dev libfreetype-dev poppler-utils libxml2-utils)  # vector figures; PDF and SVG checks
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
