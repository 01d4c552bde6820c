#!/usr/bin/env bash
# ctest install.relocatable: `cmake --install` into a temporary prefix, move the prefix, and use
# the installed formsim from another folder with FORMSIM_ASSETS unset: --version, doctor, a run,
# a lesson check, snapshots with text, the man page, the completion, the desktop entry and the
# Python module. A scenario added to the moved prefix only shows that the assets come from the
# prefix and not from the source tree. Usage: install_test.sh BUILD_DIR
set -euo pipefail
BUILD=$(cd "$1" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "install_test: FAIL: $*" >&2; exit 1; }
unset FORMSIM_ASSETS DISPLAY
export FORMSIM_STATE_DIR="$T/state" XDG_CONFIG_HOME="$T/config"
# In the sanitizer build: LSan's list of the suppressed (GL driver) leaks is not output of ours.
export LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}print_suppressions=0"

cmake --install "$BUILD" --prefix "$T/first" >"$T/install.log"
mv "$T/first" "$T/moved"
P="$T/moved"
mkdir -p "$T/elsewhere" && cd "$T/elsewhere"

for f in bin/formsim share/formsim/scenarios/formation_traj2_ukf.yaml \
         share/formsim/lessons/lphi_time_constant.yaml share/formsim/fuzzy/inspection.fll \
         share/formsim/fonts/README.md share/applications/formsim.desktop \
         share/icons/hicolor/scalable/apps/formsim.svg share/icons/hicolor/256x256/apps/formsim.png \
         share/metainfo/io.github.formsim.metainfo.xml share/man/man1/formsim.1.gz \
         share/bash-completion/completions/formsim share/doc/formsim/README.md \
         share/doc/formsim/copyright share/doc/formsim/changelog.gz; do
  [ -s "$P/$f" ] || fail "the prefix lacks $f"
done

# --version: the version, the git commit and the build type.
"$P/bin/formsim" --version | tee "$T/version.txt"
grep -Eq '^formsim [0-9]+\.[0-9]+\.[0-9]+ \((git [0-9a-f]+, )?[A-Za-z]+\)$' "$T/version.txt" ||
  fail "--version printed: $(cat "$T/version.txt")"

# doctor: the assets were found beside the moved program.
"$P/bin/formsim" doctor | tee "$T/doctor.txt"
grep -Fq "assets           $P/share/formsim (installed beside $P/bin/formsim)" "$T/doctor.txt" ||
  fail "doctor did not find the assets in the moved prefix"
grep -Fq "scenarios      $P/share/formsim/scenarios" "$T/doctor.txt" || fail "doctor: scenarios"
grep -Fq "lessons        $P/share/formsim/lessons" "$T/doctor.txt" || fail "doctor: lessons"
grep -Eq "ok +GL renderer" "$T/doctor.txt" || fail "doctor: no GL renderer"

# A scenario that exists only in the moved prefix runs by name.
sed 's/^description: .*/description: "only in the installed prefix"/' \
  "$P/share/formsim/scenarios/formation_traj2.yaml" >"$P/share/formsim/scenarios/only_in_prefix.yaml"
"$P/bin/formsim" list >list.txt
grep -q "^only_in_prefix .*only in the installed prefix" list.txt ||
  fail "formsim list does not read the prefix's scenarios"
"$P/bin/formsim" run only_in_prefix --set duration=1 --out o1 -q
[ -s o1/timeseries.csv ] || fail "no CSV from only_in_prefix"

# A run with pictures that hold text (fonts found), a fuzzy scenario (its rule file relative
# to the scenario) and a lesson check.
"$P/bin/formsim" run formation_traj2_ukf --set duration=2 --out o2 -q --snapshot snap.svg 2>err.txt
"$P/bin/formsim" run formation_traj2_ukf --set duration=2 --out o3 -q --snapshot snap.png \
  --plots plots 2>>err.txt
[ ! -s err.txt ] || fail "the runs printed: $(cat err.txt)"
grep -q "<text" snap.svg || fail "the SVG snapshot has no text"
[ -s snap.png ] && [ -s plots/distance_error.png ] || fail "no PNG snapshot or figure"
"$P/bin/formsim" run inspection_u_route --set duration=2 --out o4 -q
"$P/bin/formsim" lessons check lphi_time_constant --seeds 1 | tee lesson.txt
grep -Eq "^[0-9]+ checks, [0-9]+ hold, 0 fail" lesson.txt || fail "the lesson check failed"

# The man page renders; the completion offers commands, options and scenario names.
man -l "$P/share/man/man1/formsim.1.gz" >man.txt 2>/dev/null
grep -q "formsim run" man.txt || fail "the man page does not render"
PATH="$P/bin:$PATH" bash -c '
  source "$0"
  COMP_WORDS=(formsim r); COMP_CWORD=1; _formsim; [[ " ${COMPREPLY[*]} " == *" run "* ]] || exit 1
  COMP_WORDS=(formsim run --se); COMP_CWORD=2; _formsim; [[ " ${COMPREPLY[*]} " == *" --seed "* ]] || exit 2
  COMP_WORDS=(formsim run only_in); COMP_CWORD=2; _formsim; [[ " ${COMPREPLY[*]} " == *" only_in_prefix "* ]] || exit 3
  COMP_WORDS=(formsim gui --lesson lphi); COMP_CWORD=3; _formsim; [[ " ${COMPREPLY[*]} " == *" lphi_time_constant "* ]] || exit 4
' "$P/share/bash-completion/completions/formsim" || fail "bash completion (case $?)"
grep -q "^Exec=formsim gui$" "$P/share/applications/formsim.desktop" || fail "desktop entry"

# The Python module installed under the prefix finds the same assets.
PYDIR=$(ls -d "$P"/lib/python3*/dist-packages 2>/dev/null | head -1 || true)
if [ -n "$PYDIR" ]; then
  PYTHONPATH="$PYDIR" /usr/bin/python3 - "$P" <<'PY'
import os, sys
import formsim
prefix = sys.argv[1]
assert formsim.__file__.startswith(prefix), formsim.__file__
names = [n for n, _, _ in formsim.scenarios()]
assert "only_in_prefix" in names, names
sim = formsim.load("formation_traj2", set={"duration": 1})
sim.run()
assert sim.finished and sim.status == "completed", sim.status
print("python: formsim from", os.path.dirname(formsim.__file__), "ran", sim.steps, "steps")
PY
  grep -Eq "ok +Python module +$PYDIR/formsim" "$T/doctor.txt" || fail "doctor did not see the module"
else
  echo "install_test: no Python module in the prefix (built without it)"
fi
echo "install_test: the moved prefix works from another folder without FORMSIM_ASSETS"
