"""The long calls (run, render, figure, sweep, tune) release the GIL: Python threads making them
at once get the results of the same calls made one after the other, and another Python thread
keeps running meanwhile."""

import threading
import time

import numpy as np

import formsim

SCENARIO = "formation_traj2_ukf"
PARAM = "robots.R2.follow.k_phi"
METRIC = "links.R1-R2.max_abs_error_after_settle.phi"


def work(seed):
    sim = formsim.load(SCENARIO, seed=seed, set={"duration": 1.5}, threads=1)
    sim.run()
    tuned = formsim.tune(SCENARIO, params=[PARAM], metric=METRIC, seeds=[seed], budget=3,
                         method="bobyqa", set={"duration": 1}, jobs=1)
    swept = formsim.sweep(SCENARIO, vary={PARAM: [0.2, 0.4]}, seeds=[seed],
                          set={"duration": 1}, jobs=1)
    return (sim.timeseries(), sim.summary()["results"], sim.render(96, 64),
            sim.figure(sim.figures()[0], "svg"), tuned.history_csv, swept.runs_csv)


def test_two_threads_give_the_sequential_results():
    sequential = [work(seed) for seed in (1, 2)]
    got = [None, None]
    start = threading.Barrier(2, timeout=60)

    def worker(i):
        start.wait()  # both start together
        got[i] = work(i + 1)

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sequential[0][1] != sequential[1][1]  # two seeds, two runs
    for one, other in zip(sequential, got):
        ts, ts2 = one[0], other[0]
        assert ts.keys() == ts2.keys()
        for k in ts:
            assert np.array_equal(ts[k].view(np.uint64), ts2[k].view(np.uint64)), k
        assert one[1] == other[1]
        assert np.array_equal(one[2], other[2])
        assert one[3:] == other[3:]


def longest_pause_while(call):
    """Runs `call` in a thread while this one spins; returns (the longest pause between two
    spins, the call's wall time), s."""
    t = threading.Thread(target=call)
    last = time.perf_counter()
    longest = 0.0
    t.start()
    began = last
    while t.is_alive():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    t.join()
    return longest, time.perf_counter() - began


def test_tune_and_render_let_other_threads_run():
    sim = formsim.load(SCENARIO, set={"duration": 1})
    sim.run()
    calls = {
        "tune": lambda: formsim.tune(SCENARIO, params=[PARAM], metric=METRIC, budget=6,
                                     method="bobyqa", set={"duration": 2}, jobs=1),
        "render": lambda: [sim.render(1024, 768) for _ in range(3)],
    }
    for name, call in calls.items():
        pause, wall = longest_pause_while(call)
        # Holding the GIL would stop this thread for the whole call.
        assert pause < 0.5 * wall, (name, pause, wall)
