"""Shared pieces of the documentation tests (ctest: docs.*; run them by hand with
`FORMSIM_BIN=build/formsim /usr/bin/python3 -m pytest -q tests/docs` from the repository root)."""

import os
import sys

import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))


def formsim_path():
    """The formsim program: FORMSIM_BIN (ctest sets it), else build/formsim of the repository."""
    return os.path.abspath(os.environ.get("FORMSIM_BIN") or os.path.join(ROOT, "build", "formsim"))


@pytest.fixture(scope="session")
def formsim_bin():
    path = formsim_path()
    if not os.access(path, os.X_OK):
        pytest.fail(f"no formsim program at {path} (build it, or set FORMSIM_BIN)")
    return path
