"""formsim in Python: load a scenario, step or run it, tune it, read its results.

The same simulator as the ``formsim`` program, through the same loader: a scenario loaded
here with the same seed and ``set`` values gives the same timeseries (bit for bit) and the
same summary as ``formsim run NAME --seed S --set key=value``.

    >>> import formsim
    >>> [name for name, _, _ in formsim.scenarios()][:2]
    >>> sim = formsim.load("formation_traj2_ukf", set={"duration": 5})
    >>> sim.tunables["robots.R2.follow.k_phi"].value
    >>> sim.set("robots.R2.follow.k_phi", 0.5)   # checked as the window checks an edit
    >>> sim.run()
    >>> sim.summary()["results"]
    >>> sim.to_pandas()                           # one column per CSV column

Needs Debian's interpreter /usr/bin/python3 (with python3-numpy; python3-pandas for
to_pandas) and ``PYTHONPATH=<build>/python`` (or ``cmake --install``); see the README.

``formsim.sweep(...)`` runs a sweep as ``formsim sweep`` does (same runs.csv and aggregate.csv),
``formsim.dask.sweep(client, ...)`` maps its runs over a dask.distributed cluster, and
``formsim.tune(...)`` optimises tunables as ``formsim tune`` does (same history.csv).
``Sim.render(...)`` and ``Sim.figure(...)`` draw the world view and the figures in memory, as
``formsim run --snapshot`` and ``--plots`` draw them.

Every refused input raises :class:`Error` (a ``ValueError``) with the loader's reason; a run
that stops at a non-finite value raises :class:`NumericalFault`, which carries the results up
to the fault.
"""

from formsim._core import Error
from formsim._sim import NumericalFault, Sim, Tunable, load, not_sampled
from formsim._listing import lessons, scenarios, version
from formsim._sweep import SweepResult, sweep
from formsim._tune import TuneResult, tune

__all__ = ["Error", "NumericalFault", "Sim", "Tunable", "load", "not_sampled", "scenarios", "lessons", "version",
           "sweep", "SweepResult", "tune", "TuneResult"]
