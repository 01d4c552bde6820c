#!/usr/bin/env bash
# Regenerates every PNG in screenshots/ with the headless mode (no display needed) and the GUI
# under Xvfb. Usage: scripts/screenshots.sh [path/to/formsim]   (default: build/formsim, built
# with scripts/build.sh when missing). Each picture is listed below with what it shows.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/formsim}
if [ ! -x "$BIN" ]; then bash scripts/build.sh; BIN=build/formsim; fi
OUT=screenshots
mkdir -p "$OUT"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
run() { env -u DISPLAY "$BIN" run "$@" -q; }

# World view mid-run: the figure-eight cascade with a UKF per link (t = 5.5 s), tracking camera.
run formation_traj2_ukf --set duration=5.5 --out "$TMP/a" --snapshot "$OUT/world_traj2_ukf.png"
# The whole 7-robot cascade run seen at once (camera keeps everything since the start).
run formation_cascade7 --out "$TMP/b" --snapshot "$OUT/world_cascade7_whole_run.png" --whole-run
# Paper-style figures (Fig. 3 (a)-(e) and the UKF estimation error) of the figure-eight run.
run formation_traj2_ukf --out "$TMP/c" --plots "$TMP/plots"
for f in "$TMP"/plots/*.png; do cp "$f" "$OUT/traj2_ukf_$(basename "$f")"; done
# The interface drawn headless (--ui) into a frame, as a video made with --ui would show it.
run formation_traj2 --set duration=6 --out "$TMP/d" --snapshot "$OUT/ui_headless_traj2.png" \
  --ui --size 1600x900
# Mecanum AGV (paper 002): world view at the end of the fused run and the Fig. 6-style tracks of
# the fused and odometry-only runs.
run agv_fused --out "$TMP/agv" --snapshot "$OUT/agv_world.png" --plots "$TMP/agv_plots"
cp "$TMP/agv_plots/trajectory.png" "$OUT/agv_fused_trajectory.png"
run agv_odometry_only --out "$TMP/agv_odo" --plots "$TMP/agv_odo_plots"
cp "$TMP/agv_odo_plots/trajectory.png" "$OUT/agv_odometry_trajectory.png"
# Inspection robot (paper 003): laser rays and posts mid-run, Fig. 8 style X coordinates, and the
# lateral-offset membership functions with the current input marked.
run inspection_u_route --set duration=20 --out "$TMP/insp_mid" --snapshot "$OUT/inspection_world.png"
run inspection_u_route --out "$TMP/insp" --plots "$TMP/insp_plots"
cp "$TMP/insp_plots/fig8_x.png" "$OUT/inspection_fig8_x.png"
cp "$TMP/insp_plots/mf_s_near.png" "$OUT/inspection_mf_s.png"
# Velocity control (paper 004): two robots crossing floors of different friction, keyframes and
# tracked features; the speed of the robot whose loop is fed by the fused estimate.
run velocity_constant --out "$TMP/vel" --snapshot "$OUT/velocity_world.png" --plots "$TMP/vel_plots"
cp "$TMP/vel_plots/speed_R_fused.png" "$OUT/velocity_speed_fused.png"
cp "$TMP/vel_plots/speed_R_odo.png" "$OUT/velocity_speed_odo.png"
# The GUI itself under Xvfb, 7 robots, every plot open, a gain changed live at frame 60.
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_cascade7 --size 1600x900 \
    --speed 2 --exit-after 150 --edit 60:robots.R2.follow.k_l=0.4 \
    --screenshot "$OUT/gui_cascade7.png" >/dev/null
else
  echo "screenshots: xvfb-run not installed, GUI screenshot skipped" >&2
fi
ls -1 "$OUT"/*.png
