#!/usr/bin/env bash
# Regenerates every picture in screenshots/ with the headless mode (no display needed) and the GUI
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
# The window's pictures with its default settings (UI scale, angle unit), whatever the user's
# ~/.config/formsim says, and no journals left in the user's state folder.
export XDG_CONFIG_HOME="$TMP/config" FORMSIM_STATE_DIR="$TMP/state"
run() { env -u DISPLAY "$BIN" run "$@" -q; }

# Every paper figure of the scenarios shown below, drawn by `formsim figures` on all cores as PNG
# and SVG (into FIGS/<scenario>/<figure>.<format>).
env -u DISPLAY "$BIN" figures formation_traj2_ukf agv_fused agv_odometry_only inspection_u_route \
  velocity_constant --out "$TMP/figs" --plot-format png,svg --quiet
FIGS="$TMP/figs"

# World view mid-run: the figure-eight cascade with a UKF per link (t = 5.5 s), tracking camera.
run formation_traj2_ukf --set duration=5.5 --out "$TMP/a" --snapshot "$OUT/world_traj2_ukf.png"
# The whole 7-robot cascade run seen at once (camera keeps everything since the start).
run formation_cascade7 --out "$TMP/b" --snapshot "$OUT/world_cascade7_whole_run.png" --whole-run
# Paper-style figures (Fig. 3 (a)-(e) and the UKF estimation error) of the figure-eight run;
# (a) also as SVG, the vector figure of docs/figures.md.
for f in "$FIGS"/formation_traj2_ukf/*.png; do
  [ "$(basename "$f")" = world.png ] && continue
  cp "$f" "$OUT/traj2_ukf_$(basename "$f")"
done
cp "$FIGS/formation_traj2_ukf/trajectories.svg" "$OUT/traj2_ukf_trajectories.svg"
# Themes: the distance errors for a dark room, for print (greys told apart by dash patterns) and
# for a projector (high contrast); the light theme is the figure above.
for theme in dark print high-contrast; do
  run formation_traj2_ukf --out "$TMP/theme_$theme" --plots "$TMP/theme_$theme/plots" \
    --plot-size 640x400 --theme "$theme"
  cp "$TMP/theme_$theme/plots/distance_error.png" "$OUT/theme_${theme}_distance_error.png"
done
# The interface drawn headless (--ui) into a frame, as a video made with --ui would show it.
run formation_traj2 --set duration=6 --out "$TMP/d" --snapshot "$OUT/ui_headless_traj2.png" \
  --ui --size 1600x900
# Mecanum AGV (paper 002): world view at the end of the fused run and the Fig. 6-style tracks of
# the fused and odometry-only runs.
run agv_fused --out "$TMP/agv" --snapshot "$OUT/agv_world.png"
cp "$FIGS/agv_fused/trajectory.png" "$OUT/agv_fused_trajectory.png"
cp "$FIGS/agv_odometry_only/trajectory.png" "$OUT/agv_odometry_trajectory.png"
# The paper's Fig. 6: (a) the beacon's fixes alone, (b) the fused estimate, on the fused run.
cp "$FIGS/agv_fused/fig6a_beacon_points.png" "$OUT/agv_fig6a_beacon.png"
cp "$FIGS/agv_fused/fig6b_fused_points.png" "$OUT/agv_fig6b_fused.png"
# Inspection robot (paper 003): laser rays and posts mid-run, Fig. 8 style X coordinates, and the
# lateral-offset membership functions with the current input marked.
run inspection_u_route --set duration=20 --out "$TMP/insp_mid" --snapshot "$OUT/inspection_world.png"
cp "$FIGS/inspection_u_route/fig8_x.png" "$OUT/inspection_fig8_x.png"
cp "$FIGS/inspection_u_route/mf_s_near.png" "$OUT/inspection_mf_s.png"
# The paper's Fig. 9 (Y on the route) and the u3 (steering) membership functions, fired set marked.
cp "$FIGS/inspection_u_route/fig9_y.png" "$OUT/inspection_fig9_y.png"
cp "$FIGS/inspection_u_route/mf_u3.png" "$OUT/inspection_mf_u3.png"
# Velocity control (paper 004): two robots crossing floors of different friction, keyframes and
# tracked features; the speed of the robot whose loop is fed by the fused estimate.
run velocity_constant --out "$TMP/vel" --snapshot "$OUT/velocity_world.png"
cp "$FIGS/velocity_constant/speed_R_fused.png" "$OUT/velocity_speed_fused.png"
cp "$FIGS/velocity_constant/speed_R_odo.png" "$OUT/velocity_speed_odo.png"
# The paper's Fig. 6 as bars over seeds 1-10 (mean ± std per floor), from `formsim reproduce`.
env -u DISPLAY "$BIN" reproduce velocity --tables fig6 --seeds 1..10 --out "$TMP/repro_vel" -q \
  >/dev/null
cp "$TMP/repro_vel/fig6_speed_rmse.png" "$OUT/velocity_fig6_bars.png"
# Sweeps and tuning: R2's bearing error over k_phi (log range) x estimator, mean of 5 seeds (a
# heatmap, each cell mean ± CI half-width); the AGV's RMS cross-track error against the cross-track
# kp with the 95% confidence interval of the mean over 5
# seeds; the convergence of tuning the cross-track PID.
env -u DISPLAY "$BIN" sweep formation_traj2_ukf --vary robots.R2.follow.k_phi=log:0.01:1:9 \
  --vary robots.R2.follow.estimator=all --seeds 1..5 --metric links.R1-R2.max_abs_error_after_settle.phi \
  --out "$TMP/sweep2" -q
cp "$TMP/sweep2/plot_links.R1-R2.max_abs_error_after_settle.phi.png" "$OUT/sweep_heatmap_traj2_kphi.png"
env -u DISPLAY "$BIN" sweep agv_fused --vary control.cross.kp=0.25:4:16 --seeds 1..5 \
  --metric cross_track.rms_m --out "$TMP/sweep1" -q
cp "$TMP/sweep1/plot_cross_track.rms_m.png" "$OUT/sweep_agv_cross_kp.png"
env -u DISPLAY "$BIN" tune agv_fused --param control.cross.kp --param control.cross.ki \
  --param control.cross.kd --metric cross_track.rms_m --seeds 1..5 --budget 80 --out "$TMP/tune" -q
cp "$TMP/tune/convergence.png" "$OUT/tune_agv_convergence.png"
# The GUI itself under Xvfb, 7 robots, every plot open, a gain changed live at frame 60.
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_cascade7 --size 1600x900 \
    --speed 2 --exit-after 150 --edit 60:robots.R2.follow.k_l=0.4 \
    --screenshot "$OUT/gui_cascade7.png" >/dev/null
  # The menu bar generated from the command table (View open, keys shown) and the command
  # palette filtering "k_l" (commands and tunables), at 1920x1080 after a few seconds of run.
  cat >"$TMP/menu.txt" <<'SCRIPT'
60 pause
61 menu View
64 screenshot screenshots/gui_menu_view.png
66 dismiss
67 palette k_l
70 screenshot screenshots/gui_palette.png
SCRIPT
  xvfb-run -a -s "-screen 0 1920x1080x24" "$BIN" gui formation_traj2_ukf --size 1920x1080 \
    --speed 2 --exit-after 72 --script "$TMP/menu.txt" >/dev/null
  # Tuning in the window, driven by scripts (frames of the script; `wait` holds it while pins
  # replay and the Monte Carlo runs). A pinned run: the shipped gains (k_l 0.15) kept, then both
  # followers' k_l at 0.5 and the run again: dashed in the plots, faded in the world view.
  cat >"$TMP/pinned.txt" <<'SCRIPT'
30 pin
31 wait
32 edit robots.R2.follow.k_l=0.5
33 edit robots.R3.follow.k_l=0.5
34 reset
35 play
80 screenshot screenshots/tuning_pinned.png
SCRIPT
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_traj2 --size 1600x900 --speed max \
    --exit-after 82 --script "$TMP/pinned.txt" >/dev/null
  # The history of six runs of the UKF cascade (gains and a seed changed between them), one of
  # them pinned from its row.
  cat >"$TMP/history.txt" <<'SCRIPT'
30 edit robots.R2.follow.k_l=0.3
31 reset
32 play
60 edit robots.R2.follow.k_l=0.6
61 reset
62 play
90 reset-seed 2
91 play
120 edit robots.R2.follow.k_phi=0.2
121 reset
122 play
150 edit robots.R2.follow.k_l=0.15
151 reset
152 play
180 pin-row 2
181 wait
182 tab history
190 screenshot screenshots/tuning_history.png
SCRIPT
  xvfb-run -a -s "-screen 0 1920x1080x24" "$BIN" gui formation_traj2_ukf --size 1920x1000 \
    --speed max --exit-after 192 --script "$TMP/history.txt" >/dev/null
  # Monte Carlo in the window: the UKF cascade over 20 seeds, bands on every time plot.
  cat >"$TMP/montecarlo.txt" <<'SCRIPT'
2 seeds 20
3 wait
30 screenshot screenshots/tuning_montecarlo.png
SCRIPT
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_traj2_ukf --size 1600x900 \
    --speed max --exit-after 32 --script "$TMP/montecarlo.txt" >/dev/null
else
  echo "screenshots: xvfb-run not installed, GUI screenshot skipped" >&2
fi
# Formation switching and obstacle avoidance (issue 13): the column in the gap (t = 10 s), the
# whole switching run, the field of posts with R4 avoiding post_1 (t = 4.3 s) and the whole field
# run; the formation error of each against the 1e-2 tolerance and the followers' obstacle
# distances against the safety distance.
run formation_switching --set duration=10 --out "$TMP/sw_mid" --snapshot "$OUT/switching_gap.png"
run formation_switching --out "$TMP/sw" --plots "$TMP/sw/plots" --whole-run \
  --snapshot "$OUT/switching_whole_run.png"
cp "$TMP/sw/plots/formation_error.png" "$OUT/switching_formation_error.png"
run formation_obstacle_field --set duration=4.3 --out "$TMP/of_mid" \
  --snapshot "$OUT/obstacle_field_avoiding.png"
run formation_obstacle_field --out "$TMP/of" --plots "$TMP/of/plots" --whole-run \
  --snapshot "$OUT/obstacle_field_whole_run.png"
cp "$TMP/of/plots/formation_error.png" "$OUT/obstacle_field_formation_error.png"
cp "$TMP/of/plots/obstacle_distance.png" "$OUT/obstacle_field_distance.png"
# A lesson in the window: formsim gui --lesson, run to t = 16.3 s (R2 avoiding the post).
if command -v xvfb-run >/dev/null; then
  printf '200 screenshot screenshots/lesson_switching.png\n' >"$TMP/lesson.txt"
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui --lesson switching_around_obstacles \
    --set duration=16.3 --size 1600x900 --speed max --exit-after 202 --script "$TMP/lesson.txt" \
    >/dev/null
fi
# A guided lesson at 1920x1080 (docs/teaching.md): lphi_time_constant at step 3 after its run,
# and step 4's prediction judged once the run has shown its check, in the light and the
# high-contrast theme (each window with a settings folder of its own: no progress carried over).
if command -v xvfb-run >/dev/null; then
  for theme in light high-contrast; do
    printf '2 lesson-step 3\n240 screenshot %s/lesson_step3_%s.png\n' "$OUT" "$theme" >"$TMP/step3.txt"
    printf '2 lesson-step 4\n3 lesson-predict 1\n4 lesson-action\n5 play\n240 screenshot %s/lesson_prediction_%s.png\n' \
      "$OUT" "$theme" >"$TMP/prediction.txt"
    for step in step3 prediction; do
      XDG_CONFIG_HOME="$TMP/config_${step}_$theme" xvfb-run -a -s "-screen 0 1920x1080x24" "$BIN" gui \
        --lesson lphi_time_constant --size 1920x1080 --speed max --theme "$theme" --exit-after 245 \
        --script "$TMP/$step.txt" >/dev/null
    done
  done
fi
# Large formations (issue 15): 100 robots mid-run and their first trajectories, 1000 robots after
# their S-turns (robots drawn as dots at this scale, a subset of trails) with the errors of all
# 1997 links, and the window with 1000 robots.
run formation_swarm_100 --set duration=8 --out "$TMP/s100" --plots "$TMP/s100/plots" \
  --snapshot "$OUT/swarm100_world.png"
cp "$TMP/s100/plots/trajectories.png" "$OUT/swarm100_trajectories.png"
run formation_swarm_1000 --out "$TMP/s1000" --plots "$TMP/s1000/plots" --whole-run \
  --snapshot "$OUT/swarm1000_world.png"
cp "$TMP/s1000/plots/distance_error_all.png" "$OUT/swarm1000_distance_error_all.png"
if command -v xvfb-run >/dev/null; then
  printf '298 screenshot screenshots/gui_swarm1000.png\n' >"$TMP/swarm.txt"
  xvfb-run -a -s "-screen 0 1600x900x24" "$BIN" gui formation_swarm_1000 --size 1600x900 \
    --speed max --exit-after 300 --script "$TMP/swarm.txt" >/dev/null
fi
# Teaching: the formation editor, overlays, presentation mode (docs/teaching.md).
bash scripts/screenshots_teaching.sh "$BIN"
bash scripts/screenshots_lecture.sh "$BIN"
ls -1 "$OUT"/*.png "$OUT"/*.svg
