"""formsim.sweep and formsim.dask.sweep: the tables equal formsim sweep's runs.csv and
aggregate.csv byte for byte."""

import subprocess

import pytest

import formsim

# Two gains x two seeds of a short AGV run: 4 runs, a second or so.
SCENARIO = "agv_fused"
VARY = {"control.cross.kp": "1,2"}
SETS = {"duration": 8}


def cli_tables(formsim_bin, out):
    subprocess.run([formsim_bin, "sweep", SCENARIO, "--vary", "control.cross.kp=1,2",
                    "--seeds", "1..2", "--set", "duration=8", "--out", str(out), "--no-figures",
                    "--quiet", "--jobs", "2"], check=True)
    return (out / "runs.csv").read_bytes(), (out / "aggregate.csv").read_bytes()


@pytest.fixture(scope="module")
def expected(formsim_bin, tmp_path_factory):
    return cli_tables(formsim_bin, tmp_path_factory.mktemp("cli_sweep"))


def test_sweep_equals_formsim_sweep(expected, tmp_path):
    res = formsim.sweep(SCENARIO, vary=VARY, seeds=range(1, 3), set=SETS, jobs=2, out=tmp_path)
    assert (res.runs_csv.encode(), res.aggregate_csv.encode()) == expected
    assert ((tmp_path / "runs.csv").read_bytes(), (tmp_path / "aggregate.csv").read_bytes()) == expected
    assert len(res.runs) == 4 and len(res.aggregate) == 2
    assert list(res.runs["status"]) == ["completed"] * 4


def test_sweep_refuses_bad_input():
    with pytest.raises(formsim.Error) as e:
        formsim.sweep(SCENARIO, vary={"no.such.key": "1,2"}, seeds="1")
    assert "no.such.key" in str(e.value)
    with pytest.raises(formsim.Error):
        formsim.sweep(SCENARIO, vary=VARY, seeds="")
    with pytest.raises(formsim.Error):
        formsim.sweep(SCENARIO, vary=VARY, seeds=[-1])
    with pytest.raises(formsim.Error):
        formsim.sweep(SCENARIO, vary=42)
    with pytest.raises(formsim.Error):
        formsim.sweep(SCENARIO, vary=VARY, jobs=0)


def test_dask_local_cluster_of_two_processes_equals_formsim_sweep(expected, tmp_path):
    distributed = pytest.importorskip("distributed")
    import formsim.dask

    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = formsim.dask.sweep(client, SCENARIO, vary=VARY, seeds=range(1, 3), set=SETS,
                                 out=tmp_path)
        workers = client.run(lambda: __import__("os").getpid())
    assert len(set(workers.values())) == 2  # two worker processes
    assert (res.runs_csv.encode(), res.aggregate_csv.encode()) == expected
    assert (tmp_path / "aggregate.csv").read_bytes() == expected[1]
