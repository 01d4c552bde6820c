"""The notebooks under docs/ are committed with the outputs of an executed run (text and at least
one plot as image/png), so that they show something on the repository's page; none holds an
error, and each stays small. scripts/notebooks.sh executes them as python/tests/test_notebooks.py
does and writes them back."""

import json
import os

import pytest

from conftest import ROOT

MAX_BYTES = 1_000_000


def notebooks():
    found = []
    for d, dirs, files in os.walk(os.path.join(ROOT, "docs")):
        dirs.sort()
        found += sorted(os.path.relpath(os.path.join(d, f), ROOT) for f in files if f.endswith(".ipynb"))
    return found


NOTEBOOKS = notebooks()


def test_there_are_notebooks():
    assert NOTEBOOKS, "no notebook under docs/"


@pytest.mark.parametrize("path", NOTEBOOKS)
def test_notebook_holds_outputs(path):
    full = os.path.join(ROOT, path)
    size = os.path.getsize(full)
    assert size < MAX_BYTES, f"{path} is {size} bytes (keep it under {MAX_BYTES}: smaller figures)"
    with open(full, encoding="utf-8") as f:
        nb = json.load(f)
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    outputs = [o for c in code for o in c.get("outputs", [])]
    errors = [o for o in outputs if o.get("output_type") == "error"]
    assert not errors, f"{path} holds an error output: {errors[0].get('ename')}: {errors[0].get('evalue')}"
    assert outputs, f"{path} holds no outputs (run scripts/notebooks.sh)"
    pngs = [o for o in outputs if "image/png" in o.get("data", {})]
    assert pngs, f"{path} holds no plot (image/png output; run scripts/notebooks.sh)"
    unexecuted = [i for i, c in enumerate(code) if c.get("source") and c.get("execution_count") is None]
    assert not unexecuted, f"{path}: code cells {unexecuted} were not executed (run scripts/notebooks.sh)"
