#!/usr/bin/python3
"""Speed of the Python module formsim (issue 27), against the same work in C++.

Run from the repository root after the build (formsim, formsim_python, formsim_bench):
    PYTHONPATH=build/python taskset -c 0 /usr/bin/python3 bench/python_bench.py [--dask]

Prints, as medians of several repetitions (CPU time of this process, so other jobs on the
machine matter less than for wall time):
  1. a full formation_traj2_ukf run through Sim.run() against BM_ShippedScenario of
     build/bench/formsim_bench (the same steps in C++, as `formsim run` takes them), and the whole
     `formsim run -q` process against load() + run() + the CSV's columns from Python;
  2. the cost of one Sim.step(1) call beyond the step itself;
  3. timeseries(): whether it copies (it hands out views of the recorder's rows) and its cost;
  4. with --dask: a 200-run sweep through formsim.dask.sweep on a LocalCluster of 2 worker
     processes against `formsim sweep --jobs 2` (wall time).
"""

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import formsim

SCENARIO = "formation_traj2_ukf"
BUILD = os.environ.get("FORMSIM_BUILD", "build")
FORMSIM = os.path.join(BUILD, "formsim")


def cpu():
    return time.process_time()


def median_of(f, reps):
    return statistics.median(f() for _ in range(reps))


def child_cpu(cmd):
    """CPU seconds (user + system) of a child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def full_run():
    def python_run():
        sim = formsim.load(SCENARIO, threads=1)
        t0 = cpu()
        sim.run()
        return cpu() - t0

    py = median_of(python_run, 21)
    bench = os.path.join(BUILD, "bench", "formsim_bench")
    out = subprocess.run([bench, "--benchmark_filter=BM_ShippedScenario/formation_traj2_ukf/",
                          "--benchmark_repetitions=9", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type") == "iteration"]
    cpp = statistics.median(b["cpu_time"] for b in runs) / 1e3  # ms -> s
    print(f"run only: Sim.run() {py * 1e3:.2f} ms CPU, BM_ShippedScenario {cpp * 1e3:.2f} ms CPU:"
          f" {100 * (py / cpp - 1):+.1f} %")

    with tempfile.TemporaryDirectory() as d:
        cli = median_of(lambda: child_cpu([FORMSIM, "run", SCENARIO, "-q", "--threads", "1",
                                           "--out", d]), 11)
        script = ("import formsim; s = formsim.load('%s', threads=1); s.run(); "
                  "s.timeseries(); s.summary()" % SCENARIO)
        pyproc = median_of(lambda: child_cpu([sys.executable, "-c", script]), 11)
        empty = median_of(lambda: child_cpu([sys.executable, "-c", "import formsim"]), 11)
    print(f"whole process: formsim run -q {cli * 1e3:.1f} ms CPU; python3 load+run+timeseries+"
          f"summary {pyproc * 1e3:.1f} ms CPU, of which `import formsim` alone {empty * 1e3:.1f} ms")
    return py, cpp


def step_overhead():
    # Long enough for every repetition below (2 x 5 x n steps of 0.01 s), never finished.
    sim = formsim.load(SCENARIO, set={"duration": 1000}, threads=1)
    sim.run(until=1.0)  # past the start
    n = 5000

    def per_step_calls():
        t0 = cpu()
        for _ in range(n):
            sim.step(1)
        return (cpu() - t0) / n

    def per_step_loop():
        t0 = cpu()
        sim.step(n)
        return (cpu() - t0) / n

    calls = median_of(per_step_calls, 5)
    loop = median_of(per_step_loop, 5)
    assert not sim.finished
    print(f"Sim.step(1): {calls * 1e6:.2f} us a call, the step itself {loop * 1e6:.2f} us "
          f"(step(n) per step): overhead {(calls - loop) * 1e6:.2f} us a call")


def timeseries_cost():
    sim = formsim.load(SCENARIO, threads=1)
    sim.run()
    ts = sim.timeseries()
    shared = np.shares_memory(ts["t"], sim.timeseries()["t"])
    rows, cols = len(ts["t"]), len(ts)
    t = median_of(lambda: (lambda t0: (sim.timeseries(), cpu() - t0)[1])(cpu()), 51)
    p = median_of(lambda: (lambda t0: (sim.to_pandas(), cpu() - t0)[1])(cpu()), 11)
    print(f"timeseries(): {rows} rows x {cols} columns, shares memory across calls: {shared}, "
          f"{t * 1e6:.0f} us a call; to_pandas() (a copy) {p * 1e3:.2f} ms")


def dask_sweep():
    from dask.distributed import Client, LocalCluster

    import formsim.dask

    vary = {"robots.R2.follow.k_phi": "0.02:0.4:40"}
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        subprocess.run([FORMSIM, "sweep", SCENARIO, "--vary", "robots.R2.follow.k_phi=0.02:0.4:40",
                        "--seeds", "1..5", "--jobs", "2", "--no-figures", "--out", d + "/cli",
                        "-q"], check=True, capture_output=True)
        cli = time.perf_counter() - t0
        t0 = time.perf_counter()
        with LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                          host="127.0.0.1", dashboard_address=None) as cluster, \
                Client(cluster) as client:
            started = time.perf_counter() - t0
            t1 = time.perf_counter()
            formsim.dask.sweep(client, SCENARIO, vary=vary, seeds=range(1, 6), out=d + "/dask")
            swept = time.perf_counter() - t1
        same = all(open(f"{d}/cli/{n}").read() == open(f"{d}/dask/{n}").read()
                   for n in ("runs.csv", "aggregate.csv"))
    print(f"200-run sweep: formsim sweep --jobs 2 --no-figures {cli:.2f} s wall; "
          f"formsim.dask.sweep on a 2-process LocalCluster {swept:.2f} s wall (+ {started:.2f} s "
          f"to start the cluster); tables equal: {same}")


if __name__ == "__main__":
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f}")
    full_run()
    step_overhead()
    timeseries_cost()
    if "--dask" in sys.argv:
        dask_sweep()
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f}")
