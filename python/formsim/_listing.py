"""The shipped scenarios and lessons, as `formsim list` shows them."""

from formsim import _core


def scenarios():
    """The shipped scenarios: a list of (name, type, description), sorted by name.

    ``name`` is what :func:`formsim.load` (and ``formsim run``) takes, ``type`` the experiment
    kind (formation, agv, inspection, velocity), ``description`` the scenario's one line.
    """
    return [tuple(s) for s in _core.scenarios()]


def lessons():
    """The shipped lessons: a list of (name, type, title), sorted by name.

    A lesson is a scenario with a text (``formsim gui --lesson NAME``); :func:`formsim.load`
    takes its name too.
    """
    return [tuple(s) for s in _core.lessons()]


def version():
    """The version formsim was built as, e.g. ``"0.1 (git 1a2b3c4)"`` (as in summary.json)."""
    return _core.version()
