#!/usr/bin/env bash
# The teaching pictures of docs/teaching.md (formation editor, overlays, presentation mode), from the
# GUI under Xvfb driven by scripts and from headless runs. Called by scripts/screenshots.sh;
# alone: scripts/screenshots_teaching.sh [path/to/formsim].
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/formsim}
OUT=screenshots
mkdir -p "$OUT"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# The window's settings (UI scale, angle unit) go to a folder of their own, not the user's.
export XDG_CONFIG_HOME="$TMP/config" FORMSIM_STATE_DIR="$TMP/state"

# Headless: every overlay of "what the law sees" with the legend, the UKF cascade at t = 4 s.
env -u DISPLAY "$BIN" run formation_traj2_ukf --set duration=4 -q --out "$TMP/ov" \
  --overlay all --legend --snapshot "$OUT/teach_overlays.png" --size 1280x720

if ! command -v xvfb-run >/dev/null; then
  echo "screenshots: xvfb-run not installed, GUI teaching screenshots skipped" >&2
  exit 0
fi
# The editor in use, paused at t = 0 (R1 (0, 0), R2 (-0.2, -0.223), R3 (-0.285, -0.09)): R4
# added l-φ behind R1 (leader picked, then the place clicked), R5 l-l to R2 and R3, R6 l-l to R3
# and R5; then an l-l follower being added: its leaders R4 and R1 picked (rings), the graph and
# the triangles drawn.
cat >"$TMP/editor.txt" <<'SCRIPT'
3 overlay graph,triangles
4 editor add l_phi
5 click 0 0
6 click -0.55 0.3
7 editor add l_l
8 click -0.2 -0.223
9 click -0.285 -0.09
10 click -0.7 -0.5
11 editor add l_l
12 click -0.285 -0.09
13 click -0.7 -0.5
14 click -0.8 -0.05
15 editor add l_l
16 click -0.55 0.3
17 click 0 0
20 screenshot screenshots/teach_editor.png
SCRIPT
xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_traj2_per_sample --paused \
  --size 1600x900 --exit-after 22 --script "$TMP/editor.txt" >/dev/null
# A refused change: R1 made a follower of R4 (a cycle); the reason in the status line, the run
# unchanged.
cat >"$TMP/refused.txt" <<'SCRIPT'
3 formation add l_phi R1 -0.55 0.3
4 editor attach l_phi
5 click 0 0
6 click -0.55 0.3
10 screenshot screenshots/teach_refused.png
SCRIPT
xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_traj2_per_sample --paused \
  --size 1600x900 --exit-after 12 --script "$TMP/refused.txt" >/dev/null
# A named shape in one click while running: the 7-robot cascade becomes a diamond at frame 30
# (each robot placed on its slot, the graph rebuilt with l-l triangles, the run going on from
# there), the error vectors drawn; then paused with "Drag slots" on.
cat >"$TMP/shape.txt" <<'SCRIPT'
2 overlay graph,errors
30 formation shape diamond 0.6
70 editor slots
71 pause
SCRIPT
xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_cascade7 --size 1600x900 \
  --speed 1 --exit-after 75 --script "$TMP/shape.txt" --screenshot "$OUT/teach_shape.png" >/dev/null
# A slot dragged (here by the script's clicks): paused at t = 0 of the printed-gain run, R2's
# desired distance to R1 moved from 0.3 m to 0.4 m (same bearing); playing, R2 falls back to it
# with the law's time constant (1/k_l = 6.7 s) and R3 keeps its triangle with R1 and R2; the
# error vectors and the measured l and φ drawn.
cat >"$TMP/slot.txt" <<'SCRIPT'
2 overlay errors,measured
3 editor slots
4 click -0.2 -0.223
5 click -0.126 -0.38
6 play
90 screenshot screenshots/teach_slot.png
SCRIPT
xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_traj1 --paused --size 1600x900 \
  --speed 1 --exit-after 92 --script "$TMP/slot.txt" >/dev/null
# Presentation mode at 1920x1080: panels hidden, UI scale 2, the high-contrast theme, graph and
# triangles, the legend; taken once the camera has flown in (the legend is placed for where the
# robots are, once a second).
cat >"$TMP/present.txt" <<'SCRIPT'
2 ui-scale 2
3 present on
4 overlay graph,triangles,errors
240 screenshot screenshots/teach_presentation.png
241 help on
243 screenshot screenshots/teach_help.png
SCRIPT
xvfb-run -a -s "-screen 0 1920x1080x24" "$BIN" gui formation_cascade7 --size 1920x1080 \
  --theme high-contrast --speed 1 --exit-after 245 --script "$TMP/present.txt" >/dev/null
# The window at lecture sizes and scales: scripts/screenshots_lecture.sh.
