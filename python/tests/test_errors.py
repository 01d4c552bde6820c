"""Bad input raises formsim.Error with the loader's reason, never takes the interpreter down,
and leaves a Sim as it was."""

import json
import math

import numpy as np
import pytest

import formsim
from conftest import assert_same_bits, read_csv_bits, run_cli

SCENARIO = "formation_traj2_ukf"
K_PHI = "robots.R2.follow.k_phi"


def test_error_is_a_value_error():
    assert issubclass(formsim.Error, ValueError)
    assert issubclass(formsim.NumericalFault, formsim.Error)


@pytest.mark.parametrize("name,words", [
    ("no_such_scenario", "no_such_scenario"),
    ("/dev/zero", "/dev/zero"),
    ("/tmp", "/tmp"),
])
def test_bad_scenario(name, words):
    with pytest.raises(formsim.Error) as e:
        formsim.load(name)
    assert words in str(e.value)


def test_missing_file(tmp_path):
    missing = tmp_path / "missing.yaml"
    with pytest.raises(formsim.Error) as e:
        formsim.load(str(missing))
    assert "missing.yaml" in str(e.value)
    with pytest.raises(formsim.Error):
        formsim.load(missing)  # a pathlib.Path too


def test_bad_yaml_names_file_and_line(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text("type: formation\ndt: [1, 2\n")
    with pytest.raises(formsim.Error) as e:
        formsim.load(str(p))
    assert "bad.yaml" in str(e.value)


@pytest.mark.parametrize("sets,words", [
    ({"no.such.key": 1}, "no.such.key"),
    ({"duration": math.nan}, "duration"),
    ({"duration": -1}, "duration"),
    ({"duration": "abc"}, "duration"),
    ({"dt": 1e308}, "dt"),
    ({"duration": [1, 2]}, "duration"),
    ({"duration": None}, "duration"),
    ({K_PHI: math.inf}, K_PHI),
])
def test_bad_set_at_load(sets, words):
    with pytest.raises(formsim.Error) as e:
        formsim.load(SCENARIO, set=sets)
    assert words in str(e.value)


def test_loader_error_carries_location_key_and_reason():
    with pytest.raises(formsim.Error) as e:
        formsim.load(SCENARIO, set={"duration": -1})
    assert e.value.key == "duration"
    assert "--set" in e.value.location and e.value.reason


@pytest.mark.parametrize("seed", [-1, 2**64, 1.5, "7", True])
def test_bad_seed(seed):
    with pytest.raises(formsim.Error):
        formsim.load(SCENARIO, seed=seed)


@pytest.mark.parametrize("args", [(42,), (None,), (SCENARIO, 1, "notadict")])
def test_wrong_argument_types(args):
    with pytest.raises(formsim.Error):
        formsim.load(*args)


@pytest.mark.parametrize("key,value,words", [
    ("no.such.key", 1.0, "unknown"),
    (K_PHI, math.nan, K_PHI),
    (K_PHI, math.inf, K_PHI),
    (K_PHI, -1.0, K_PHI),
    (K_PHI, "abc", K_PHI),
    (K_PHI, [1], K_PHI),
    (K_PHI, {"a": 1}, K_PHI),
    (K_PHI, "x" * 70000, K_PHI),
    (7, 1.0, "key"),
], ids=["unknown", "nan", "inf", "negative", "text", "list", "dict", "70k-text", "int-key"])
def test_refused_edit_leaves_the_sim_unchanged(key, value, words):
    sim = formsim.load(SCENARIO, set={"duration": 0.5})
    sim.step(10)
    before = sim.tunables
    with pytest.raises(formsim.Error) as e:
        sim.set(key, value)
    assert words in str(e.value)
    assert sim.tunables == before
    sim.run()
    ref = formsim.load(SCENARIO, set={"duration": 0.5})
    ref.run()
    assert sim.to_pandas().equals(ref.to_pandas())


def test_huge_value_is_accepted_or_refused_never_a_crash():
    sim = formsim.load(SCENARIO, set={"duration": 0.5})
    try:
        sim.set(K_PHI, 1e308)
    except formsim.Error:
        return
    try:
        sim.run()
    except formsim.NumericalFault as f:
        assert f.summary["status"] == "numerical_fault"


@pytest.mark.parametrize("call", [
    lambda s: s.step(-1), lambda s: s.step(1.5), lambda s: s.step("3"),
    lambda s: s.run(until="x"), lambda s: s.run(until=math.nan),
    lambda s: s.reset(seed=-3), lambda s: s.reset(seed=2**64),
])
def test_bad_run_arguments(call):
    sim = formsim.load(SCENARIO, set={"duration": 0.2})
    with pytest.raises(formsim.Error):
        call(sim)
    assert sim.time == 0


def test_numerical_fault_keeps_the_results_as_the_cli(formsim_bin, tmp_path):
    # A formation spacing of 1e300 m overflows the followers' estimates within a step.
    sets = [("duration", "2"), ("formation.L", "1e300")]
    assert run_cli(formsim_bin, "formation_obstacle_field", tmp_path, sets) == 3
    sim = formsim.load("formation_obstacle_field", set=dict(sets))
    with pytest.raises(formsim.NumericalFault) as e:
        sim.run()
    f = e.value
    assert f.summary["status"] == "numerical_fault" and f.summary["stop_reason"]
    assert f.time < 2 and f.sim is sim and f.reason == f.summary["stop_reason"]
    with open(tmp_path / "summary.json") as file:
        assert f.summary == json.load(file)
    header, expected = read_csv_bits(tmp_path / "timeseries.csv")
    assert list(f.timeseries) == header
    for name in header:
        assert_same_bits(expected[name], f.timeseries[name])
    assert any(ev["kind"] == "numerical_fault" for ev in sim.events())
    assert sim.finished and sim.step(1) == 0  # stopped; nothing raised again
    sim.set("formation.L", 0.15)
    sim.reset()
    assert sim.status == "running"
    sim.run()
    assert sim.status == "completed"
