"""Shared pieces of the formsim Python tests (run by ctest: python.pytest)."""

import csv
import os
import subprocess

import numpy as np
import pytest

import formsim


@pytest.fixture(scope="session")
def formsim_bin():
    """The formsim executable the build made (FORMSIM_BIN, set by ctest)."""
    path = os.environ.get("FORMSIM_BIN", "")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("FORMSIM_BIN does not name the formsim executable (FORMSIM_BUILD_APP=OFF)")
    return path


def run_cli(formsim_bin, scenario, out_dir, sets=(), seed=None):
    """`formsim run SCENARIO --out DIR --set ... [--seed S] --quiet`; returns its exit code."""
    cmd = [formsim_bin, "run", scenario, "--out", str(out_dir), "--quiet"]
    for key, value in sets:
        cmd += ["--set", f"{key}={value}"]
    if seed is not None:
        cmd += ["--seed", str(seed)]
    return subprocess.run(cmd, capture_output=True, text=True).returncode


def read_csv_bits(path):
    """timeseries.csv as {column: uint64 array of the bits}: an empty cell is the not-sampled
    mark, 'nan' a plain quiet NaN (the CSV keeps no payload)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    out = {}
    not_sampled = np.array([0x7FF800005E1F0001], dtype=np.uint64).view(np.float64)[0]
    for i, name in enumerate(header):
        vals = [not_sampled if r[i] == "" else float(r[i]) for r in body]
        out[name] = np.array(vals, dtype=np.float64).view(np.uint64)
    return header, out


def assert_same_bits(expected_bits, actual):
    """Bit-for-bit equality of a column, where a computed NaN only needs to be a NaN (not the
    not-sampled mark) since the CSV writes every NaN as 'nan'."""
    actual = np.ascontiguousarray(actual, dtype=np.float64)
    exp_f = expected_bits.view(np.float64)
    exp_ns = formsim.not_sampled(exp_f)
    act_ns = formsim.not_sampled(actual)
    assert np.array_equal(exp_ns, act_ns)
    plain_nan = np.isnan(exp_f) & ~exp_ns
    assert np.array_equal(plain_nan, np.isnan(actual) & ~act_ns)
    other = ~plain_nan
    assert np.array_equal(expected_bits[other], actual.view(np.uint64)[other])
