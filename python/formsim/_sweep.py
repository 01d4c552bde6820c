"""Sweeps from Python: the runs of ``formsim sweep`` shared out over threads (formsim.sweep) or a
Dask cluster (formsim.dask.sweep). Each run is the CLI's own code; its record travels as the
text ``formsim sweep`` writes into runs/NNNNNN.run, and the tables are made by the same code
from those records, so runs.csv and aggregate.csv are the CLI's bytes."""

import io
import numbers
import os
from collections import namedtuple
from concurrent.futures import ThreadPoolExecutor

from formsim import _core
from formsim._core import Error
from formsim._sim import _seed_text, _yaml_text

#: What every run of a sweep needs, as plain text (picklable, sent once to every worker):
#: the scenario file as named, its text, the sweep's manifest, the number of runs.
SweepPlan = namedtuple("SweepPlan", "file text manifest runs")

#: A sweep's result: ``runs`` and ``aggregate`` as DataFrames (python3-pandas), and the two
#: tables as the text formsim sweep writes (``runs_csv``, ``aggregate_csv``).
SweepResult = namedtuple("SweepResult", "runs aggregate runs_csv aggregate_csv")


def _vary_args(vary):
    if isinstance(vary, str):
        return [vary]
    if hasattr(vary, "items"):
        out = []
        for key, spec in vary.items():
            if not isinstance(key, str):
                raise Error(f"vary: a key must be a string, got {key!r}")
            if isinstance(spec, (list, tuple, range)):
                spec = ",".join(_yaml_text(key, v) for v in spec)
            out.append(f"{key}={_yaml_text(key, spec)}")
        return out
    if isinstance(vary, (list, tuple)) and all(isinstance(v, str) for v in vary):
        return list(vary)
    raise Error("vary: expected {key: spec} or a list of 'KEY=SPEC' strings, got "
                f"{type(vary).__name__}")


def _seeds_arg(seeds):
    if seeds is None:
        return None
    if isinstance(seeds, str):
        return seeds
    try:
        items = list(seeds)
    except TypeError:
        raise Error(f"seeds: expected '1..20', a range or a list of seeds, got {seeds!r}") from None
    return ",".join(str(_seed_text(s, "seeds")) for s in items)


def plan(scenario, vary, seeds=None, set=None, sample_seed=1, max_runs=100000):
    """Defines a sweep as ``formsim sweep SCENARIO --vary ... --seeds ... --set ...`` does.

    vary: {key: spec} with a spec as ``--vary`` takes it ("0.1,0.2", "LO:HI:N", "log:LO:HI:N",
        "random:N", "all") or a list of values; or a list of "KEY=SPEC" strings.
    seeds: "1..20", a range or list of seeds, or None for the scenario's own.
    Returns a :data:`SweepPlan`. Raises :class:`formsim.Error` as the CLI refuses.
    """
    sets = []
    for key, value in (set or {}).items():
        sets.append((key, _yaml_text(key, value)))
    if isinstance(max_runs, bool) or not isinstance(max_runs, numbers.Integral) or max_runs < 1:
        raise Error(f"max_runs: expected a positive integer, got {max_runs!r}")
    return SweepPlan(*_core.sweep_define(os.fsdecode(os.fspath(scenario)), sets, _vary_args(vary),
                                         _seeds_arg(seeds), _seed_text(sample_seed, "sample_seed"),
                                         int(max_runs)))


def run_one(run, plan):
    """Run ``run`` of ``plan``: its record's text. What a worker executes."""
    return _core.sweep_run(plan.file, plan.text, plan.manifest, run)


def tables(plan, records, out=None):
    """The :data:`SweepResult` of ``records`` (their texts, any order); with ``out``, runs.csv and
    aggregate.csv are written there too (the folder is created)."""
    import pandas as pd

    runs_csv, aggregate_csv = _core.sweep_tables(plan.manifest, list(records))
    if out is not None:
        os.makedirs(out, exist_ok=True)
        for name, text in (("runs.csv", runs_csv), ("aggregate.csv", aggregate_csv)):
            with open(os.path.join(out, name), "w", newline="") as f:
                f.write(text)
    return SweepResult(pd.read_csv(io.StringIO(runs_csv)), pd.read_csv(io.StringIO(aggregate_csv)),
                       runs_csv, aggregate_csv)


def sweep(scenario, vary, seeds=None, set=None, jobs=None, out=None, sample_seed=1,
          max_runs=100000):
    """Runs a sweep in this process, as ``formsim sweep`` does, on ``jobs`` threads (default: all
    cores); returns a :data:`SweepResult` whose tables equal formsim sweep's runs.csv and
    aggregate.csv byte for byte. With ``out``, both files are written there. Arguments as
    :func:`plan`."""
    p = plan(scenario, vary, seeds, set, sample_seed, max_runs)
    if jobs is None:
        jobs = os.cpu_count() or 1
    if isinstance(jobs, bool) or not isinstance(jobs, numbers.Integral) or jobs < 1:
        raise Error(f"jobs: expected a positive integer, got {jobs!r}")
    with ThreadPoolExecutor(max_workers=int(jobs)) as pool:
        records = list(pool.map(lambda r: run_one(r, p), range(p.runs)))
    return tables(p, records, out)
