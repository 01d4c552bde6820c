"""formsim.dask.sweep: the runs of a sweep mapped over a dask.distributed cluster.

    from dask.distributed import Client, LocalCluster
    import formsim.dask
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1) as cluster, \\
            Client(cluster) as client:
        result = formsim.dask.sweep(client, "agv_fused", vary={"control.cross.kp": "0.5:2:4"},
                                    seeds=range(1, 6), out="out/sweep")
    result.aggregate        # a DataFrame; out/sweep/aggregate.csv is formsim sweep's file

In a script, create the LocalCluster under ``if __name__ == "__main__":`` (its worker processes
import the script again). On several machines: start ``dask scheduler`` on one and ``dask worker tcp://HOST:8786`` on
each (with the same formsim build importable: PYTHONPATH=<build>/python for /usr/bin/python3),
then ``Client("tcp://HOST:8786")`` and the same call. The scenario's text travels with the
plan, so workers need no copy of it; files a scenario names (a fuzzy rule base) must exist at
the same path on every worker.
"""

from formsim._sweep import SweepPlan, SweepResult, plan, run_one, tables

__all__ = ["sweep", "SweepPlan", "SweepResult"]


def sweep(client, scenario, vary, seeds=None, set=None, out=None, sample_seed=1,
          max_runs=100000):
    """Runs a sweep's runs as tasks of ``client`` (a dask.distributed Client) and returns the
    :data:`formsim.SweepResult` whose tables equal ``formsim sweep``'s runs.csv and aggregate.csv
    byte for byte (written into ``out`` when given). Arguments as :func:`formsim.sweep`.

    The plan (scenario text and manifest) is sent to every worker once; each task returns its
    run's record text, and the tables are made here from all of them.
    """
    p = plan(scenario, vary, seeds, set, sample_seed, max_runs)
    # In a list: scatter would send a tuple's fields as separate pieces.
    [shared] = client.scatter([p], broadcast=True)
    futures = client.map(run_one, range(p.runs), plan=shared, pure=False)
    return tables(p, client.gather(futures), out)
