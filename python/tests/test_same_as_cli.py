"""Same results as the CLI: a Sim run from Python gives the same timeseries (bit for bit) and
the same summary.json as `formsim run`, for one scenario of every experiment kind."""

import json

import pytest

import formsim
from conftest import assert_same_bits, read_csv_bits, run_cli

# One scenario per kind: the first two whole (as the scenario says, and `--seed`), the slower
# two shortened with `--set duration=...` (the whole Python suite stays within seconds).
CASES = [
    ("formation_traj2_ukf", None, None),
    ("agv_fused", None, 7),
    ("inspection_u_route", "5", None),
    ("velocity_steps", "3", 3),
]


def test_every_kind_is_covered():
    kinds = {t for _, t, _ in formsim.scenarios()}
    covered = {formsim.load(name).type for name, _, _ in CASES}
    assert covered == kinds


@pytest.mark.parametrize("scenario,duration,seed", CASES)
def test_run_equals_formsim_run(formsim_bin, tmp_path, scenario, duration, seed):
    sets = [] if duration is None else [("duration", duration)]
    assert run_cli(formsim_bin, scenario, tmp_path, sets, seed) == 0
    sim = formsim.load(scenario, seed=seed, set=dict(sets))
    sim.run()
    assert sim.status == "completed"

    header, expected = read_csv_bits(tmp_path / "timeseries.csv")
    series = sim.timeseries()
    assert list(series) == header
    assert len(series["t"]) == len(expected["t"]) > 10
    for name in header:
        assert_same_bits(expected[name], series[name])

    with open(tmp_path / "summary.json") as f:
        assert sim.summary() == json.load(f)


def test_a_run_in_pieces_equals_one_run():
    whole = formsim.load("formation_traj2_ukf", set={"duration": 2})
    whole.run()
    pieces = formsim.load("formation_traj2_ukf", set={"duration": 2})
    pieces.step(1)
    pieces.step(37)
    pieces.run(until=1.0)
    assert pieces.time == pytest.approx(1.0)
    pieces.run()
    a, b = whole.timeseries(), pieces.timeseries()
    for name in a:
        assert a[name].tobytes() == b[name].tobytes()
    assert whole.summary() == pieces.summary()


def test_thread_count_does_not_change_results():
    one = formsim.load("formation_traj2_ukf", set={"duration": 1}, threads=1)
    two = formsim.load("formation_traj2_ukf", set={"duration": 1}, threads=2)
    one.run()
    two.run()
    assert one.to_pandas().equals(two.to_pandas())
