"""formsim.tune: the tune of ``formsim tune`` run in this process, its tables as DataFrames."""

import io
import numbers
import os
from collections import namedtuple

from formsim import _core
from formsim._core import Error
from formsim._sim import _seed_text, _yaml_text
from formsim._sweep import _seeds_arg

#: A tune's result. ``history``: one row per evaluation (history.csv of ``formsim tune``: the
#: values tried, each metric's mean over the seeds, the objective, feasibility), a DataFrame;
#: ``validation``: validation.csv (per holdout run, then mean and CI rows) or None without
#: ``holdout``; ``best``: {key: value} of the best evaluation (the closest to feasible when
#: none meets every constraint: ``has_best`` False); ``objective`` and ``evaluation`` (1-based)
#: of it; ``stop_reason``: why the optimiser stopped; ``history_csv``, ``validation_csv``: the
#: files' text, byte for byte what ``formsim tune`` writes.
TuneResult = namedtuple("TuneResult", "history validation best objective evaluation has_best "
                                      "stop_reason history_csv validation_csv")


def _params_args(params):
    if isinstance(params, str):
        return [params]
    if hasattr(params, "items"):
        out = []
        for key, bounds in params.items():
            if not isinstance(key, str):
                raise Error(f"params: a key must be a string, got {key!r}")
            if bounds is None:
                out.append(key)
            elif isinstance(bounds, (list, tuple)) and len(bounds) == 2:
                out.append(f"{key}:{_yaml_text(key, bounds[0])}:{_yaml_text(key, bounds[1])}")
            else:
                raise Error(f"params: {key}: expected None or (low, high), got {bounds!r}")
        return out
    if isinstance(params, (list, tuple)) and params and all(isinstance(p, str) for p in params):
        return list(params)
    raise Error("params: expected {key: (low, high) or None} or a list of 'KEY' / 'KEY:LO:HI' "
                f"strings, got {params!r}")


def _strings(value, what):
    if isinstance(value, str):
        return [value]
    if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
        return list(value)
    raise Error(f"{what}: expected a string or a list of strings, got {value!r}")


def tune(scenario, params, metric, seeds=None, set=None, budget=60, method="direct-l+bobyqa",
         constraints=(), over="mean", holdout=None, search_seed=1, scenarios=(), jobs=None):
    """Optimises tunables of ``scenario`` for ``metric``, as ``formsim tune`` does (NLopt, the
    same evaluations in the same order): returns a :data:`TuneResult` whose ``history_csv`` is
    the CLI's history.csv byte for byte (and ``validation_csv`` its validation.csv).

    params: {key: (low, high)} or {key: None} (the declared slider range), or a list of
        ``--param`` texts ("KEY", "KEY:LO:HI").
    metric: ``--metric``: a result path of summary.json or a weighted sum ("a.b + 10*c.d").
    seeds: seeds averaged per evaluation ("1..5", a range or a list; None: the scenario's).
    set: {key: value} fixed for every run (``--set``).
    budget, method, constraints ("PATH<=VALUE" ...), over ("mean", "max", "quantile:Q"),
        holdout (seeds), search_seed, scenarios (more scenarios): as the CLI's flags.
    jobs: runs at once (default: every core); the results are the same for any number.

    Runs without the GIL; Ctrl-C ends it after the current evaluation with KeyboardInterrupt.
    Raises :class:`formsim.Error` for what the CLI refuses, naming the flag.
    """
    import pandas as pd

    sets = [f"{k}={_yaml_text(k, v)}" for k, v in (set or {}).items()]
    for what, v in (("budget", budget), ("jobs", jobs)):
        if v is not None and (isinstance(v, bool) or not isinstance(v, numbers.Integral)):
            raise Error(f"tune: {what} must be an integer, got {v!r}")
    if jobs is None:
        jobs = os.cpu_count() or 1
    for what, v in (("metric", metric), ("method", method), ("over", over)):
        if not isinstance(v, str):
            raise Error(f"tune: {what} must be a string, got {v!r}")
    d = _core.tune(os.fsdecode(os.fspath(scenario)),
                   [os.fsdecode(os.fspath(s)) for s in scenarios], sets, over,
                   _params_args(params), metric, _strings(constraints, "constraints"),
                   _seeds_arg(seeds), int(budget), method, _seed_text(search_seed, "search_seed"),
                   _seeds_arg(holdout), int(jobs))
    validation = None
    if d["validation_csv"] is not None:
        validation = pd.read_csv(io.StringIO(d["validation_csv"]), float_precision="round_trip")
    # round_trip: every number as the double the CSV's shortest text stands for.
    history = pd.read_csv(io.StringIO(d["history_csv"]), float_precision="round_trip")
    return TuneResult(history, validation, dict(d["best"]),
                      d["objective"], d["evaluation"], d["has_best"], d["stop_reason"],
                      d["history_csv"], d["validation_csv"])
