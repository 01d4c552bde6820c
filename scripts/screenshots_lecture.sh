#!/usr/bin/env bash
# The lecture hall's pictures of docs/teaching.md: the window at 1920x1080 at UI scale 1 and 2,
# in presentation mode and in the high-contrast theme, and a lesson at 1280x720 (a projector),
# each with its layout report: the script fails when a report finds text cut, overlapping,
# under 18 px at scale 2 or under 4.5:1, a plot under 120 px, or the world view under its share
# (issue 46). Called by scripts/screenshots.sh; alone:
#   scripts/screenshots_lecture.sh [path/to/formsim]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/formsim}
OUT=screenshots
mkdir -p "$OUT"
if ! command -v xvfb-run >/dev/null; then
  echo "screenshots_lecture: xvfb-run not installed, skipped" >&2
  exit 0
fi
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export XDG_CONFIG_HOME="$TMP/config" FORMSIM_STATE_DIR="$TMP/state"

# shot NAME SIZE SCENARIO SCRIPT-LINES: the window on SCENARIO, the lines, then at frame 90
# (1.5 s of the run) the report and the picture.
shot() {
  local name=$1 size=$2 scenario=$3 lines=$4
  printf '%s\n90 layout-report %s\n91 screenshot %s\n92 quit\n' "$lines" "$TMP/$name.json" \
    "$OUT/$name.png" >"$TMP/$name.txt"
  xvfb-run -a -s "-screen 0 ${size}x24" "$BIN" gui "$scenario" --size "$size" \
    --script "$TMP/$name.txt" >"$TMP/$name.log" 2>&1 || { cat "$TMP/$name.log" >&2; exit 1; }
}
shot lecture_scale1 1920x1080 formation_cascade7 "1 ui-scale 1"
shot lecture_scale2 1920x1080 formation_cascade7 "1 ui-scale 2"
shot lecture_presentation 1920x1080 formation_cascade7 "$(printf '1 ui-scale 2\n2 present on')"
shot lecture_high_contrast 1920x1080 formation_cascade7 \
  "$(printf '1 ui-scale 2\n2 theme high-contrast\n3 overlay all')"
shot lecture_lesson_1280x720 1280x720 formation_cascade7 \
  "$(printf '1 ui-scale 1.5\n2 lesson deep_cascade\n3 tab lesson')"

# Every report clean; the world view's share printed for docs/teaching.md.
/usr/bin/python3 - "$TMP" <<'PY'
import json, pathlib, sys
bad = 0
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    r = json.loads(f.read_text())
    found = {k: r[k] for k in ("clipped", "overlaps", "small_text", "low_contrast", "small_plots") if r[k]}
    share = r["world_view_share"]
    need = 0.8 if r["layout"] == "presentation" else 0.5
    print(f"{f.stem}: {r['window'][0]}x{r['window'][1]} scale {r['ui_scale']:g}, {r['layout']}, "
          f"world view {share:.0%} of the window, {r['text_runs']} pieces of text, "
          f"{sum(len(v) for v in found.values())} findings")
    for k, v in found.items():
        for e in v:
            print(f"  {k}: {e['widget']}: {e['text']!r} {e.get('over', '')}{e.get('colours', '')}")
    bad += bool(found) or share < need
sys.exit(1 if bad else 0)
PY
