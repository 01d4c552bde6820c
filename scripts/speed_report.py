#!/usr/bin/env python3
"""Measures where users wait (issue 28) and prints one Markdown report: frame export (PNG, MP4,
GIF), `formsim figures`, and the simulation's real-time factor against the number of robots at
one, two and all threads. Each figure is the median of --runs runs; with --instructions, the
instruction counts (callgrind) stand beside the times.

    python3 scripts/speed_report.py [--build build] [--runs 3] [--instructions] [--out FILE]

It needs a Release build with the benchmarks (scripts/build.sh): build/formsim and
build/bench/formsim_bench. --quick runs one short repetition of everything (a smoke test of this
script, not a measurement). Run it on an idle machine: the wall times are the machine's.
"""

import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The export runs the issue names: formation_traj2 at 1280x720, 30 frames per second (330 frames).
EXPORT_SCENARIO = "formation_traj2"
EXPORT_ARGS = ["--fps", "30", "--size", "1280x720"]
ROBOTS = [10, 100, 1000, 10000]
GOALS = {"png": 200.0, "mp4": 150.0}


def timed(cmd, cwd):
    """Runs cmd; returns (wall seconds, CPU seconds of it and its children, stdout)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit("speed_report: %s failed (exit %d):\n%s" % (" ".join(cmd), p.returncode, p.stderr))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, p.stdout


def instructions(cmd, cwd, only=None):
    """Instructions of cmd, every thread and child (callgrind's total Ir); with `only`, those
    executed inside that function (callgrind's --toggle-collect)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.%p")
        vg = ["valgrind", "--tool=callgrind", "--trace-children=yes", "--callgrind-out-file=" + out]
        if only:
            vg.append("--toggle-collect=" + only)
        p = subprocess.run(vg + cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
        if p.returncode != 0:
            sys.exit("speed_report: callgrind of %s failed:\n%s" %
                     (" ".join(cmd), p.stderr[-2000:]))
        total = 0
        for name in os.listdir(tmp):
            with open(os.path.join(tmp, name)) as f:
                for line in f:
                    if line.startswith("summary:") or line.startswith("totals:"):
                        total += int(line.split()[1])
                        break
        return total


def export_runs(formsim, runs, quick, work):
    """PNG, MP4 and GIF export of the issue's run: frames, wall and CPU medians."""
    extra = ["--set", "duration=1"] if quick else []
    kinds = [
        ("png", "PNG frames (`--frames`)", lambda d: ["--frames", os.path.join(d, "frames")]),
        ("mp4", "MP4 (`--video`, x264 ultrafast)", lambda d: ["--video", os.path.join(d, "v.mp4")]),
        ("gif", "GIF (`--gif`, 15 frames/s, 640 px)",
         lambda d: ["--gif", os.path.join(d, "g.gif")]),
    ]
    rows = []
    for key, label, args in kinds:
        walls, cpus, frames = [], [], 0
        for _ in range(runs):
            d = tempfile.mkdtemp(dir=work)
            cmd = [formsim, "run", EXPORT_SCENARIO, "--out", os.path.join(d, "out")] + \
                EXPORT_ARGS + extra + args(d)
            wall, cpu, out = timed(cmd, work)
            m = re.search(r"(\d+) frames", out)
            frames = int(m.group(1)) if m else 0
            walls.append(wall)
            cpus.append(cpu)
            shutil.rmtree(d)
        rows.append({"key": key, "label": label, "frames": frames,
                     "wall": statistics.median(walls), "cpu": statistics.median(cpus),
                     "walls": walls})
    return rows


def figures_runs(formsim, runs, quick, work):
    """`formsim figures` of every shipped scenario (one in --quick): files, wall and CPU."""
    walls, cpus, files = [], [], 0
    for _ in range(runs):
        d = tempfile.mkdtemp(dir=work)
        cmd = [formsim, "figures", "--out", d, "-q"] + (["formation_traj2"] if quick else [])
        wall, cpu, _ = timed(cmd, work)
        files = sum(len(f) for _, _, f in os.walk(d))
        walls.append(wall)
        cpus.append(cpu)
        shutil.rmtree(d)
    return {"files": files, "wall": statistics.median(walls), "cpu": statistics.median(cpus),
            "walls": walls}


def bench_runs(bench, runs, quick):
    """Real-time factors from the benchmarks (medians of `runs` repetitions)."""
    robots = [10] if quick else ROBOTS
    names = ["BM_ShippedScenario/formation_traj2_ukf"]
    for n in robots:
        names += ["BM_CascadeUkfOneThread/%d" % n, "BM_CascadeUkfTwoThreads/%d" % n,
                  "BM_CascadeUkf/%d" % n, "BM_CascadeTruth/%d" % n, "BM_Box2DOnly/%d" % n]
    filt = "^(" + "|".join(re.escape(n) for n in names) + ")/real_time$"
    cmd = [bench, "--benchmark_filter=" + filt, "--benchmark_format=json",
           "--benchmark_repetitions=%d" % runs]
    if quick:
        cmd.append("--benchmark_min_time=0.01")
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("speed_report: %s failed:\n%s" % (" ".join(cmd), p.stderr))
    try:
        found = json.loads(p.stdout)["benchmarks"]
    except ValueError:
        sys.exit("speed_report: %s gave no results:\n%s" % (" ".join(cmd), p.stdout + p.stderr))
    per = {}
    for b in found:
        if b.get("run_type") == "aggregate":
            continue
        per.setdefault(b["run_name"].replace("/real_time", ""), []).append(b)
    result = {}
    for name, reps in per.items():
        result[name] = {
            "realtime_x": statistics.median(r["realtime_x"] for r in reps),
            "ms": statistics.median(r["real_time"] for r in reps),
            "threads": reps[0].get("threads", 0),
        }
    # Every benchmark asked for must have reported (a renamed one would leave a gap).
    missing = [n for n in names if n not in result or not result[n]["realtime_x"] > 0]
    if missing:
        sys.exit("speed_report: no real-time factor from " + ", ".join(missing))
    cores = os.cpu_count() or 1
    return result, robots, cores


def export_instructions(formsim, work):
    """Instructions per frame of PNG export: 90 frames less 30 frames (the start-up cancels)."""
    counts = {}
    for seconds in (1, 3):
        d = tempfile.mkdtemp(dir=work)
        cmd = [formsim, "run", EXPORT_SCENARIO, "--out", os.path.join(d, "out"), "--set",
               "duration=%d" % seconds, "--frames", os.path.join(d, "frames")] + EXPORT_ARGS
        counts[seconds] = instructions(cmd, work)
        shutil.rmtree(d)
    return (counts[3] - counts[1]) / 60.0


def step_instructions(formsim, work, scenario, steps, dt):
    """Instructions per step of a shipped scenario run by `formsim run --threads 1`: everything
    inside Experiment::Step, which includes formatting the CSV rows the run writes as it goes."""
    d = tempfile.mkdtemp(dir=work)
    cmd = [formsim, "run", scenario, "-q", "--threads", "1", "--out", d, "--set",
           "duration=%g" % (steps * dt)]
    n = instructions(cmd, work, only="formsim::sim::Experiment::Step()")
    shutil.rmtree(d)
    return n / float(steps)


def fmt_ins(n):
    return "%.2f G" % (n / 1e9) if n >= 1e9 else "%.1f M" % (n / 1e6) if n >= 1e6 else \
        "%.1f k" % (n / 1e3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build folder")
    ap.add_argument("--runs", type=int, default=3, help="runs per figure (median; default 3)")
    ap.add_argument("--instructions", action="store_true", help="add callgrind counts (slow)")
    ap.add_argument("--quick", action="store_true", help="one short run of each (a smoke test)")
    ap.add_argument("--out", help="also write the report to this file")
    ap.add_argument("--formsim", help="the formsim program (default BUILD/formsim)")
    ap.add_argument("--bench", help="the benchmarks (default BUILD/bench/formsim_bench)")
    a = ap.parse_args()
    if a.runs < 1:
        sys.exit("speed_report: --runs must be 1 or more")
    formsim = a.formsim or os.path.join(a.build, "formsim")
    bench = a.bench or os.path.join(a.build, "bench", "formsim_bench")
    for f in (formsim, bench):
        if not os.access(f, os.X_OK):
            sys.exit("speed_report: %s is missing or not a program: build with "
                     "`bash scripts/build.sh` first" % f)
    # A report that cannot be written fails now, not after minutes of measuring.
    if a.out and not os.access(os.path.dirname(os.path.abspath(a.out)), os.W_OK):
        sys.exit("speed_report: --out %s: its folder does not exist or is not writable" % a.out)
    runs = 1 if a.quick else a.runs
    work = tempfile.mkdtemp(prefix="formsim_speed_")
    try:
        lines = report(formsim, bench, runs, a, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)


def report(formsim, bench, runs, a, work):
    load = os.getloadavg()
    lines = ["A smoke test (--quick): short runs, not a measurement.", ""] if a.quick else []
    lines += ["Measured %s UTC on %d cores, load average %.2f %.2f %.2f at the start; medians "
              "of %d run%s." % (time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
                                os.cpu_count() or 1, load[0], load[1], load[2], runs,
                                "" if runs == 1 else "s"), ""]
    exports = export_runs(formsim, runs, a.quick, work)
    for r in exports:
        if r["frames"] <= 0:
            sys.exit("speed_report: formsim did not report the frames of its %s" % r["label"])
    ins_frame = export_instructions(formsim, work) if a.instructions else None
    lines += ["**Export**: `formsim run %s %s` (1280x720); CPU counts every thread and child "
              "(llvmpipe, the encoders, ffmpeg)." % (EXPORT_SCENARIO, " ".join(EXPORT_ARGS)), "",
              "| output | frames | wall | frames/s | CPU | goal |", "|---|---|---|---|---|---|"]
    for r in exports:
        fps = r["frames"] / r["wall"] if r["wall"] > 0 else 0.0
        goal = GOALS.get(r["key"])
        verdict = "" if goal is None or a.quick else (
            "%d frames/s: %s" % (goal, "met" if fps >= goal else "not met"))
        lines.append("| %s | %d | %.2f s (%s) | %.0f | %.2f s | %s |" % (
            r["label"], r["frames"], r["wall"], ", ".join("%.2f" % w for w in r["walls"]), fps,
            r["cpu"], verdict))
    if ins_frame is not None:
        lines += ["", "Instructions per PNG frame (callgrind, every thread; 90 frames less 30): "
                  "%s." % fmt_ins(ins_frame)]
    fig = figures_runs(formsim, runs, a.quick, work)
    if fig["files"] <= 0:
        sys.exit("speed_report: formsim figures wrote no file")
    lines += ["", "**Figures**: `formsim figures` of %s: %d files in %.2f s (%s), %.0f files/s, "
              "%.2f s of CPU; goal under 5 s: %s." % (
                  "one scenario" if a.quick else "every shipped scenario", fig["files"],
                  fig["wall"], ", ".join("%.2f" % w for w in fig["walls"]),
                  fig["files"] / fig["wall"], fig["cpu"],
                  "-" if a.quick else "met" if fig["wall"] < 5 else "not met"), ""]
    res, robots, cores = bench_runs(bench, runs, a.quick)
    paper = res.get("BM_ShippedScenario/formation_traj2_ukf")
    lines += ["**Simulation** (Google Benchmark, real time, no rendering; real-time factor = "
              "simulated seconds per second):", ""]
    if paper:
        lines += ["- the paper scenario (`BM_ShippedScenario/formation_traj2_ukf`, one thread): "
                  "%.2f ms a run, %.0fx real time (goal 8000x: %s)" % (
                      paper["ms"], paper["realtime_x"],
                      "-" if a.quick else "met" if paper["realtime_x"] >= 8000 else "not met")]
    ins_step = {}
    if a.instructions:
        ins_step["paper"] = step_instructions(formsim, work, "formation_traj2_ukf", 600, 0.01)
        ins_step[1000] = step_instructions(formsim, work, "formation_swarm_1000", 30, 0.01)
        lines += ["- instructions per step (callgrind, `Experiment::Step` of `formsim run "
                  "--threads 1`, with the CSV rows it formats): the paper scenario %s (600 "
                  "steps), 1000 robots (`formation_swarm_1000`, 30 steps) %s" % (
                      fmt_ins(ins_step["paper"]), fmt_ins(ins_step[1000]))]
    lines += ["", "| robots | 1 thread | 2 threads | all %d threads | goal |" % cores,
              "|---|---|---|---|---|"]
    goals = {1000: 40.0, 10000: 3.0}
    for n in robots:
        cells = []
        for name in ("BM_CascadeUkfOneThread", "BM_CascadeUkfTwoThreads", "BM_CascadeUkf"):
            r = res.get("%s/%d" % (name, n))
            cells.append("%.1fx (%.1f ms per 100 steps)" % (r["realtime_x"], r["ms"]) if r else "-")
        g = goals.get(n)
        best = res.get("BM_CascadeUkf/%d" % n)
        verdict = "" if g is None or best is None or a.quick else "%gx: %s" % (
            g, "met" if best["realtime_x"] >= g else "not met")
        lines.append("| %d | %s | %s |" % (n, " | ".join(cells), verdict))
    # What bounds the goals: the same cascades with no estimator at all, and Box2D alone.
    lines += ["", "Without the link filters, all %d threads: the same cascades with every "
              "estimator off (`BM_CascadeTruth`: Box2D, drives, control laws, recording; no "
              "sensor noise, no filter) and Box2D alone with ideal drives (`BM_Box2DOnly`, its "
              "step is serial):" % cores, "",
              "| robots | UKF per link | no estimator | Box2D alone |", "|---|---|---|---|"]
    for n in robots:
        cells = []
        for name in ("BM_CascadeUkf", "BM_CascadeTruth", "BM_Box2DOnly"):
            r = res.get("%s/%d" % (name, n))
            cells.append("%.1fx" % r["realtime_x"] if r else "-")
        lines.append("| %d | %s |" % (n, " | ".join(cells)))
    return lines


if __name__ == "__main__":
    main()
