"""formsim.tune: the evaluations and tables of `formsim tune`."""

import subprocess

import pytest

import formsim

SCENARIO = "formation_traj2_ukf"
PARAM = "robots.R2.follow.k_phi"
METRIC = "links.R1-R2.max_abs_error_after_settle.phi"


def test_tune_equals_the_cli(formsim_bin, tmp_path):
    out = tmp_path / "tune"
    subprocess.run([formsim_bin, "tune", SCENARIO, "--param", f"{PARAM}:0.05:1", "--metric",
                    METRIC, "--seeds", "1..2", "--budget", "4", "--method", "bobyqa",
                    "--holdout", "3..4", "--set", "duration=2", "--jobs", "2", "--out", str(out),
                    "-q"], check=True, capture_output=True)
    r = formsim.tune(SCENARIO, params={PARAM: (0.05, 1)}, metric=METRIC, seeds=range(1, 3),
                     budget=4, method="bobyqa", holdout="3..4", set={"duration": 2}, jobs=2)
    assert r.history_csv == (out / "history.csv").read_text()
    assert r.validation_csv == (out / "validation.csv").read_text()
    assert len(r.history) == 4 and METRIC in " ".join(r.history.columns)
    assert r.has_best and r.objective == r.history["objective"].min()
    assert set(r.best) == {PARAM} and 0.05 <= r.best[PARAM] <= 1
    # best.yaml holds the same value (its comment line names the objective).
    assert f"{r.objective:.6g}"[:5] in (out / "best.yaml").read_text().splitlines()[0]
    assert r.validation is not None and len(r.validation) > 2


@pytest.mark.parametrize("kwargs,words", [
    ({"params": {"no.such.key": None}}, "no.such.key"),
    ({"params": [PARAM], "metric": "no_such.metric"}, "no_such.metric"),
    ({"params": [PARAM], "budget": 0}, "--budget"),
    ({"params": [PARAM], "method": "newton"}, "newton"),
    ({"params": [PARAM], "method": "direct-l+bobyqa"}, "--budget 3"),
    ({"params": [PARAM], "seeds": "1..2", "holdout": "2..3"}, "--holdout"),
    ({"params": {PARAM: "wide"}}, PARAM),
])
def test_tune_refuses_what_the_cli_refuses(kwargs, words):
    args = {"metric": METRIC, "budget": 3, "method": "bobyqa", "set": {"duration": 0.5}, "jobs": 1}
    args.update(kwargs)
    with pytest.raises(formsim.Error) as e:
        formsim.tune(SCENARIO, **args)
    assert words in str(e.value)


def test_ctrl_c_ends_a_tune_after_its_evaluation():
    import _thread
    import threading
    import time

    threading.Timer(0.3, _thread.interrupt_main).start()  # Ctrl-C after 0.3 s
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        # A global method that searches until its budget (it cannot end before the Ctrl-C).
        formsim.tune(SCENARIO, params=[PARAM], metric=METRIC, budget=100000, method="isres",
                     seeds=range(1, 21), set={"duration": 2}, jobs=1)
    assert time.perf_counter() - t0 < 30  # not the 100000 evaluations
