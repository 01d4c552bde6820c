"""docs/notebooks executed with `jupyter nbconvert --execute` (Debian's python3 kernel): they run
without error, and their key numbers are what formsim computes when asked again here.

With FORMSIM_NOTEBOOKS_WRITE=1 (scripts/notebooks.sh) a notebook that passes is written back
into docs/notebooks with the outputs of this run (the timing metadata left out), so that the
committed notebooks show what the tested run showed."""

import hashlib
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import formsim

NOTEBOOKS = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "notebooks")
WRITE_BACK = os.environ.get("FORMSIM_NOTEBOOKS_WRITE") == "1"


def execute(name, out_dir):
    """Executes docs/notebooks/NAME.ipynb into out_dir; returns its KEY_NUMBERS dict."""
    pytest.importorskip("nbconvert")
    nbformat = pytest.importorskip("nbformat")
    subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                    "--ExecutePreprocessor.timeout=120", "--output-dir", str(out_dir),
                    os.path.join(NOTEBOOKS, name + ".ipynb")], check=True, capture_output=True)
    nb = nbformat.read(os.path.join(out_dir, name + ".ipynb"), as_version=4)
    images = 0
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            assert out.get("output_type") != "error", out
            images += "image/png" in out.get("data", {})
            for line in out.get("text", "").splitlines():
                if line.startswith("KEY_NUMBERS "):
                    numbers = json.loads(line[len("KEY_NUMBERS "):])
    assert images >= 1, "the notebook drew no figure"
    return numbers


def write_back(name, out_dir):
    """With FORMSIM_NOTEBOOKS_WRITE=1: docs/notebooks/NAME.ipynb := the executed notebook."""
    if not WRITE_BACK:
        return
    import nbformat
    nb = nbformat.read(os.path.join(out_dir, name + ".ipynb"), as_version=4)
    for cell in nb.cells:
        cell.metadata.pop("execution", None)  # wall-clock times: a diff on every run
    nbformat.write(nb, os.path.join(NOTEBOOKS, name + ".ipynb"))


def test_tuning_notebook(tmp_path):
    k = execute("tuning", tmp_path)
    # The optimiser's best gain is at least as good as the shipped one, and its RMS is what a
    # run with that gain gives.
    assert k["rms_best_m"] <= k["rms_shipped_m"]
    sim = formsim.load("agv_fused", set={"duration": 20, "control.cross.kp": k["kp_best"]})
    sim.run()
    assert sim.summary()["results"]["cross_track"]["rms_m"] == k["rms_best_m"]
    assert k["kp_shipped"] == formsim.load("agv_fused").tunables["control.cross.kp"].value
    assert k["sweep_kp"] == pytest.approx(list(np.linspace(0.5, 4, 8)))
    assert all(0 < r < 0.05 for r in k["sweep_rms_mean_m"])
    write_back("tuning", tmp_path)


def test_teaching_notebook(tmp_path):
    k = execute("teaching", tmp_path)
    sim = formsim.load("formation_traj2_ukf")
    sim.run()
    assert k["status"] == "completed" and k["steps"] == sim.steps and k["time"] == sim.time
    assert k["robots"] == ["R1", "R2", "R3"]
    assert k["frames"] == math.ceil(sim.duration / 2.0)
    # The frames are formsim's world view at those times: the same pixels drawn again here.
    assert k["pictures"] == k["frames"] and k["picture_shape"] == [320, 480, 3]
    again = formsim.load("formation_traj2_ukf")
    again.run(until=k["picture_time"])
    assert again.time == k["picture_time"]
    px = again.render(480, 320)
    assert hashlib.sha256(px.tobytes()).hexdigest() == k["picture_sha256"]
    ts = sim.timeseries()
    after = ts["t"] >= 5.0
    assert k["rms_e_l_m"] == float(np.sqrt(np.mean(ts["R1-R2.e_l"][after] ** 2)))
    assert 0 < k["rms_e_l_m"] < 0.5
    write_back("teaching", tmp_path)
