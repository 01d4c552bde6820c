#!/usr/bin/env bash
# Builds the Debian package formsim_<version>_amd64.deb with CPack (packaging/cpack.cmake) from the
# Release build in build/ and puts it in the repository's root folder:
#   bash scripts/package.sh            build the .deb (then: apt install ./formsim_*.deb)
#   bash scripts/package.sh --check    ... and check it: its contents, the desktop entry and the
#                                      AppStream metadata validate, lintian reports no error
#                                      (E:) line, and the binary unpacked with `dpkg -x` runs a
#                                      scenario (with its Python module) from another folder.
# Installs what it needs (dpkg-dev; with --check lintian, desktop-file-utils, appstream) when
# missing. Exits non-zero when a check fails.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
CHECK=0
[ "${1:-}" = "--check" ] && CHECK=1
need=(dpkg-dev)
[ $CHECK = 1 ] && need+=(lintian desktop-file-utils appstream man-db)
missing=()
for p in "${need[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The Release build with everything the package holds (the Python module is required here).
[ -f build/CMakeCache.txt ] || bash scripts/build.sh -DFORMSIM_BUILD_PYTHON=ON
cmake --build build -j"$(nproc)" --target formsim formsim_python formsim_install_files
rm -rf build/package
(cd build && cpack -G DEB >/dev/null)
DEB=$(ls build/package/formsim_*_amd64.deb)
cp "$DEB" "$ROOT/"
DEB="$ROOT/$(basename "$DEB")"
echo "package: $DEB ($(du -h "$DEB" | cut -f1))"
[ $CHECK = 1 ] || exit 0

fail() { echo "package: FAIL: $*" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
dpkg-deb -c "$DEB" | awk '{print $6}' >"$T/contents.txt"
dpkg-deb -I "$DEB" >"$T/info.txt"
for f in ./usr/bin/formsim ./usr/share/formsim/scenarios/formation_traj2_ukf.yaml \
         ./usr/share/formsim/lessons/deep_cascade.yaml ./usr/share/formsim/fuzzy/inspection.fll \
         ./usr/share/applications/formsim.desktop ./usr/share/icons/hicolor/scalable/apps/formsim.svg \
         ./usr/share/icons/hicolor/256x256/apps/formsim.png \
         ./usr/share/metainfo/io.github.formsim.metainfo.xml ./usr/share/man/man1/formsim.1.gz \
         ./usr/share/bash-completion/completions/formsim ./usr/share/doc/formsim/copyright \
         ./usr/share/doc/formsim/changelog.gz ./usr/lib/python3/dist-packages/formsim/__init__.py; do
  grep -qx "$f" "$T/contents.txt" || fail "the package lacks $f"
done
grep -q "^./usr/lib/python3/dist-packages/formsim/_core.*\.so$" "$T/contents.txt" ||
  fail "the package lacks the Python extension"
grep -q "^ Section: science$" "$T/info.txt" || fail "Section is not science"
grep -q "^ Depends:.*libbox2d" "$T/info.txt" || fail "shlibdeps did not name libbox2d"
echo "package: $(wc -l <"$T/contents.txt") entries; $(grep '^ Depends:' "$T/info.txt")"

dpkg -x "$DEB" "$T/root"
desktop-file-validate "$T/root/usr/share/applications/formsim.desktop"
appstreamcli validate --no-net "$T/root/usr/share/metainfo/io.github.formsim.metainfo.xml"
echo "package: the desktop entry and the AppStream metadata validate"

# lintian: every line is shown; an error (E:) fails.
lintian --allow-root --tag-display-limit 0 "$DEB" >"$T/lintian.txt" 2>&1 || true
cat "$T/lintian.txt"
if grep -q "^E:" "$T/lintian.txt"; then fail "lintian reports errors"; fi
echo "package: lintian reports no error ($(grep -c '^W:' "$T/lintian.txt" || true) warnings)"

# The unpacked binary runs from another folder, with its assets and its Python module.
mkdir "$T/work" && cd "$T/work"
env -u FORMSIM_ASSETS -u DISPLAY "$T/root/usr/bin/formsim" --version
env -u FORMSIM_ASSETS -u DISPLAY "$T/root/usr/bin/formsim" doctor >"$T/doctor.txt" || true
grep -Fq "assets           $T/root/usr/share/formsim (installed" "$T/doctor.txt" ||
  { cat "$T/doctor.txt"; fail "the unpacked formsim did not find its assets"; }
env -u FORMSIM_ASSETS -u DISPLAY "$T/root/usr/bin/formsim" run formation_traj2_ukf \
  --set duration=3 --out o --snapshot s.png -q
[ -s o/timeseries.csv ] && [ -s s.png ] || fail "the unpacked formsim did not run"
env -u FORMSIM_ASSETS PYTHONPATH="$T/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c "
import formsim
sim = formsim.load('agv_fused', set={'duration': 2})
sim.run()
assert sim.status == 'completed', sim.status
print('package: python3 imports formsim from', formsim.__file__)"
man -l "$T/root/usr/share/man/man1/formsim.1.gz" >"$T/man.txt" 2>/dev/null
grep -q "formsim doctor" "$T/man.txt" || fail "the man page does not render"
echo "package: $DEB passes its checks"
