"""formsim.Sim: one scenario, loaded through the one load path, stepped from Python."""

import json
import math
import numbers
import os
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from formsim import _core
from formsim._core import Error

_MAX_SEED = 2**64 - 1
_NAN = math.nan
# The bits of a value that is not sampled in a row (sim/core/recorder.hpp kNotSampledBits).
_NOT_SAMPLED_BITS = np.uint64(0x7FF800005E1F0001)


def _pictures():
    """The extension's pictures (render_world, figure_bytes): built with the app only."""
    if not hasattr(_core, "render_world"):
        raise Error("pictures need formsim built with the app (FORMSIM_BUILD_APP=ON): this "
                    "module was built without the offscreen renderer")
    return _core


def not_sampled(values):
    """A bool array: True where ``values`` (float64) holds the not-sampled mark, the empty cells
    of timeseries.csv; a NaN that was computed is False."""
    a = np.ascontiguousarray(values, dtype=np.float64)
    return a.view(np.uint64) == _NOT_SAMPLED_BITS


class NumericalFault(Error):
    """The run stopped at a non-finite value (a ``numerical_fault`` event), as ``formsim run``
    stops with exit code 3.

    What was computed up to the fault is kept, as the CLI keeps it: ``timeseries`` (dict of
    arrays, the row of the fault included), ``summary`` (status ``numerical_fault``, the stop
    reason), ``time`` (s) and ``sim`` (the Sim, still readable).
    """


@dataclass(frozen=True)
class Tunable:
    """One tunable of a loaded scenario, as the window's Parameters panel shows it.

    key: the YAML path, also the ``--set`` and ``Sim.set`` key ("robots.R2.follow.k_l").
    value: the value the run uses now (float, int, bool, or the choice's name).
    kind: "float", "int", "bool" or "choice".
    range: (low, high) of the valid values (inf when unbounded); ``validity`` says whether the
        ends are open ("> 0", "[0, 1]", "any").
    unit, label, group, help: as the window shows them.
    live: True when an edit applies between two steps; False when it waits for ``reset()``.
    choices: the names a "choice" takes.
    pending: the value (YAML text) an edit made that waits for ``reset()``, else None.
    """

    key: str
    value: object
    kind: str
    range: Tuple[float, float]
    validity: str
    unit: str
    label: str
    group: str
    help: str
    live: bool
    choices: Tuple[str, ...]
    pending: Optional[str]


def _yaml_text(key, value):
    """A Python value as the YAML text the loader reads; Error for a type it cannot take."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        # repr: the shortest text that reads back to the same double ('nan', 'inf' included,
        # which the loader refuses by name).
        return repr(float(value))
    if isinstance(value, str):
        return value
    raise Error(f"{key}: expected a number, a bool or a string, got {type(value).__name__}")


def _seed_text(seed, what):
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, numbers.Integral):
        raise Error(f"{what}: expected an integer seed 0 ... 2^64-1, got {seed!r}")
    if not 0 <= int(seed) <= _MAX_SEED:
        raise Error(f"{what}: a seed must be in 0 ... 2^64-1, got {int(seed)}")
    return int(seed)


def load(name_or_path, seed=None, set=None, threads=None):
    """Loads a scenario through the same loader as ``formsim run``, with the same checks.

    name_or_path: a shipped scenario or lesson name (see :func:`formsim.scenarios`) or the path
        of a YAML file.
    seed: the run's seed (0 ... 2^64-1), as ``--seed``. None (the default) keeps the
        scenario's own ``seed:``, as ``formsim run`` without ``--seed`` does. (The issue wrote
        ``seed=1``; that default would match the CLI only for scenarios whose seed is 1, and the
        shipped ones use 1, 4, 5, 7, 11, 12 and 21: agv_fused is seed 7.)
    set: {key: value} applied in order, as ``--set key=value`` ("duration", "robots.R2.follow.k_l";
        list items by their name or index); values are numbers, bools or YAML text.
    threads: threads for the work inside a step (None: all cores, as the CLI); the results are
        the same for any number.

    Returns a :class:`Sim` at t = 0. Raises :class:`Error` naming the file:line:key or the
    ``--set`` that the loader refused, for an unknown scenario, or an unreadable file.
    """
    if not isinstance(name_or_path, (str, bytes)) and not hasattr(name_or_path, "__fspath__"):
        raise Error(f"load: expected a scenario name or path, got {type(name_or_path).__name__}")
    path = os.fsdecode(os.fspath(name_or_path))
    if set is None:
        set = {}
    if not hasattr(set, "items"):
        raise Error(f"load: set must be a dict of key: value, got {type(set).__name__}")
    sets = []
    for key, value in set.items():
        if not isinstance(key, str):
            raise Error(f"load: a set key must be a string, got {key!r}")
        sets.append((key, _yaml_text(key, value)))
    seed_text = None if seed is None else str(_seed_text(seed, "load"))
    if threads is None:
        threads = 0
    elif isinstance(threads, bool) or not isinstance(threads, numbers.Integral) or threads < 1:
        raise Error(f"load: threads must be a positive integer, got {threads!r}")
    return Sim(_core.Session(path, sets, seed_text, int(threads)))


class Sim:
    """A loaded scenario and its run. Made by :func:`formsim.load`.

    The run advances with :meth:`step` and :meth:`run`; :meth:`set` edits a tunable as the
    window does; :meth:`reset` starts again with every edit. Results: :meth:`timeseries`,
    :meth:`to_pandas`, :meth:`summary`, :meth:`events`.
    """

    def __init__(self, session):
        self._s = session

    def __repr__(self):
        return (f"<formsim.Sim {self._s.name} ({self._s.type}) t={self._s.time:g} s "
                f"status={self._s.status}>")

    # ---- the run ----
    @property
    def time(self):
        """Simulated time now, s."""
        return self._s.time

    @property
    def steps(self):
        """Fixed steps taken since the start of the run."""
        return self._s.steps

    @property
    def dt(self):
        """The fixed step, s."""
        return self._s.dt

    @property
    def duration(self):
        """The run's duration, s (the scenario's ``duration``)."""
        return self._s.duration

    @property
    def finished(self):
        """True once the run reached its duration or stopped at a fault."""
        return self._s.finished

    @property
    def status(self):
        """"running", "completed" or "numerical_fault" (summary.json's status)."""
        return self._s.status

    @property
    def seed(self):
        """The seed of the current run."""
        return self._s.seed

    @property
    def scenario(self):
        """The scenario's name."""
        return self._s.name

    @property
    def type(self):
        """The experiment kind: formation, agv, inspection or velocity."""
        return self._s.type

    @property
    def file(self):
        """The scenario file the run was loaded from."""
        return self._s.file

    def step(self, n=1):
        """Takes ``n`` fixed steps (fewer when the run ends). Returns the steps taken.

        Raises :class:`NumericalFault` when the run stops at a non-finite value.
        """
        if type(n) is not int:  # the common case costs one check (True's type is bool)
            if isinstance(n, (bool, np.bool_)) or not isinstance(n, numbers.Integral):
                raise Error(f"step: n must be an integer >= 0, got {n!r}")
            n = int(n)
        if n < 0:
            raise Error(f"step: n must be an integer >= 0, got {n!r}")
        done = self._s.advance(n, _NAN)
        if done < 0:  # this call stopped the run at a fault
            self._raise_fault()
        return done

    def run(self, until=None):
        """Runs to the end (``until`` None) or until the time reaches ``until`` s.

        Returns the steps taken. The GIL is released while it runs, so Python threads can run
        several Sims at once; Ctrl-C stops it with KeyboardInterrupt (the run stays valid and
        can go on). Raises :class:`NumericalFault` when the run stops at a non-finite value.
        """
        if until is None:
            limit = math.nan
        elif isinstance(until, bool) or not isinstance(until, numbers.Real) or math.isnan(until):
            raise Error(f"run: until must be a time in s, got {until!r}")
        else:
            limit = float(until)
        done = self._s.advance(2**62, limit)
        if done < 0:
            self._raise_fault()
        return done

    def reset(self, seed=None):
        """Starts the run again from t = 0 with every accepted edit (and ``seed`` when given).

        Raises :class:`Error` with the reason when the scenario no longer loads; the run then
        stays as it was.
        """
        s = None if seed is None else _seed_text(seed, "reset")
        why = self._s.reset(s)
        if why:
            raise Error(why)

    # ---- tunables ----
    @property
    def tunables(self):
        """Every tunable: a dict key -> :class:`Tunable`, in the order the scenario declares them."""
        out = {}
        for d in self._s.tunables():
            d = dict(d)
            d["range"] = tuple(d["range"])
            d["choices"] = tuple(d["choices"])
            out[d["key"]] = Tunable(**d)
        return out

    def set(self, key, value):
        """Edits tunable ``key`` to ``value`` (a number, bool, or the choice's name).

        Checked as the window checks an edit: the whole scenario is read again with it by the
        loader's rules. A live tunable applies before the next step; one that is not live
        waits for :meth:`reset` (``tunables[key].pending``). A refused value raises
        :class:`Error` naming the key with the loader's reason, and leaves the Sim unchanged.
        """
        if not isinstance(key, str):
            raise Error(f"set: the key must be a string, got {key!r}")
        why = self._s.edit(key, _yaml_text(key, value))
        if why:
            err = Error(why)
            err.location, err.key, err.reason = "Python edit", key, why
            raise err

    # ---- results ----
    def columns(self):
        """The recorded channels, in the CSV's order ("t" first)."""
        return list(self._s.columns())

    def timeseries(self):
        """Every recorded row: a dict column name -> float64 array, named as timeseries.csv.

        Nothing is copied: the arrays are read-only views of the recorder's rows, which later
        steps, a reset or the Sim's end never change or free (a recorder that needs room moves
        on to a new buffer and leaves these to the arrays). ``np.array(a)`` for a writable copy;
        :meth:`to_pandas` gives one. A value
        that is not sampled in a row (an empty CSV cell) is a NaN with its own payload
        (``formsim.not_sampled(a)`` tells them apart); a computed NaN is an ordinary NaN.
        """
        data = self._s.data()
        return {name: data[:, i] for i, name in enumerate(self._s.columns())}

    def to_pandas(self):
        """The timeseries as a pandas DataFrame, one column per CSV column (python3-pandas)."""
        import pandas as pd

        return pd.DataFrame(self.timeseries(), copy=True)

    def summary(self):
        """summary.json of the run so far, as a dict (equal to what ``formsim run`` writes)."""
        return json.loads(self._s.summary_json())

    def summary_text(self):
        """What ``formsim run`` prints after a run: the results' tables and the event counts."""
        return self._s.summary_text()

    def events(self):
        """The stored events, oldest first: dicts with t, kind, robots, message (and subject)."""
        return list(self._s.events())

    # ---- pictures ----
    def render(self, width=1280, height=720, theme="light", overlays=None, legend=False):
        """The world view now as an ``height`` x ``width`` x 3 uint8 numpy array (RGB, top row
        first), drawn offscreen (OSMesa, no display needed) by the renderer of ``formsim run
        --snapshot``: at the end of a run it equals the pixels of ``formsim run NAME --snapshot
        F.png --size WxH --theme THEME``. The camera frames the robots at once, as a snapshot.

        width, height: pixels, 64 ... 8192 (as ``--size``).
        theme: "light", "dark", "print" or "high-contrast" (as ``--theme``).
        overlays: None for the defaults, or names as ``--overlay`` takes them (a list, or one
            comma-separated string), applied to the defaults in order: "graph" adds one,
            "-links" removes one, "all", "none", "default"; an empty list draws none.
        legend: draw the legend of the marks (``--legend``).

        Raises :class:`Error` naming the argument that was refused. The GIL is released while
        drawing; pictures are drawn one at a time in a process.
        """
        for what, v in (("width", width), ("height", height)):
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Integral):
                raise Error(f"render: {what} must be an integer number of pixels, got {v!r}")
        if not isinstance(theme, str):
            raise Error(f"render: theme must be a string, got {theme!r}")
        if overlays is None:
            text = ""
        elif isinstance(overlays, str):
            text = overlays
        elif isinstance(overlays, (list, tuple)) and all(isinstance(o, str) for o in overlays):
            if any("," in o for o in overlays):
                raise Error(f"overlays: a name holds a comma: {list(overlays)!r}")
            text = ",".join(overlays) if overlays else "none"
        else:
            raise Error(f"overlays: expected a list of overlay names, got {overlays!r}")
        if not isinstance(legend, (bool, np.bool_)):
            raise Error(f"render: legend must be True or False, got {legend!r}")
        core = _pictures()
        return core.render_world(self._s, int(width), int(height), theme, text, bool(legend))

    def figures(self):
        """The names of the run's figures now: what :meth:`figure` takes, the files ``formsim run
        --plots DIR`` writes (DIR/NAME.png ...). Some appear with the first recorded row."""
        return list(_pictures().figure_names(self._s))

    def figure(self, name, format="png", theme="light"):
        """The bytes of figure ``name`` as a file: equal to DIR/NAME.FORMAT that ``formsim run
        --plots DIR --plot-format FORMAT --theme THEME`` writes at the same point of the run
        (960x600 px, 96 dpi, full titles). ``format``: "png", "svg" or "pdf".

        The figure is drawn from every recorded row; ``formsim run`` keeps at most 20000 rows
        for its figures (halving longer histories), so the two equal each other for runs of at
        most 20000 rows. Raises :class:`Error` for an unknown name (listing the figures there
        are), format or theme.
        """
        for what, v in (("name", name), ("format", format), ("theme", theme)):
            if not isinstance(v, str):
                raise Error(f"figure: {what} must be a string, got {v!r}")
        return _pictures().figure_bytes(self._s, name, format, theme)

    def _raise_fault(self):
        err = NumericalFault(f"the run stopped at t = {self._s.time:g} s: {self._s.stop_reason}")
        err.location, err.key, err.reason = "", "", self._s.stop_reason
        err.sim = self
        err.time = self._s.time
        err.summary = self.summary()
        err.timeseries = self.timeseries()
        raise err
