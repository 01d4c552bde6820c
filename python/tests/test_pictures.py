"""Sim.render and Sim.figure: the pictures of `formsim run --snapshot` and `--plots`, in memory."""

import io
import subprocess

import numpy as np
import pytest
from PIL import Image  # python3-pil (a dependency of python3-matplotlib)

import formsim

SCENARIO = "formation_traj2_ukf"
DURATION = 1


@pytest.fixture(scope="module")
def ended():
    """The scenario run to its end (DURATION s), as `formsim run --set duration=...` runs it."""
    sim = formsim.load(SCENARIO, set={"duration": DURATION})
    sim.run()
    return sim


def cli_run(formsim_bin, out, *args):
    cmd = [formsim_bin, "run", SCENARIO, "--set", f"duration={DURATION}", "--out", str(out),
           "--quiet", *args]
    subprocess.run(cmd, check=True, capture_output=True)


@pytest.mark.parametrize("size,theme,overlay,legend", [
    ((320, 200), "light", None, False),
    ((256, 384), "dark", "all", True),
])
def test_render_equals_the_snapshot(formsim_bin, tmp_path, ended, size, theme, overlay, legend):
    w, h = size
    args = ["--snapshot", str(tmp_path / "s.png"), "--size", f"{w}x{h}", "--theme", theme]
    if overlay:
        args += ["--overlay", overlay]
    if legend:
        args.append("--legend")
    cli_run(formsim_bin, tmp_path, *args)
    expected = np.asarray(Image.open(tmp_path / "s.png").convert("RGB"))
    px = ended.render(w, h, theme=theme, overlays=None if overlay is None else [overlay],
                      legend=legend)
    assert px.shape == (h, w, 3) and px.dtype == np.uint8
    assert np.array_equal(px, expected)
    assert len(np.unique(px.reshape(-1, 3), axis=0)) > 10  # a picture, not a blank frame


def test_render_follows_the_run():
    sim = formsim.load(SCENARIO, set={"duration": 2})
    first = sim.render(128, 96)
    assert np.array_equal(first, sim.render(128, 96))  # the same run, the same picture
    sim.run()
    assert not np.array_equal(first, sim.render(128, 96))
    assert not np.array_equal(sim.render(480, 320, overlays=["all"]),
                              sim.render(480, 320, overlays=["none"]))


@pytest.mark.parametrize("kwargs,words", [
    ({"width": 10, "height": 100}, "width 10"),
    ({"width": 100, "height": 9000}, "height 9000"),
    ({"width": 100.5, "height": 100}, "width"),
    ({"width": True, "height": 100}, "width"),
    ({"width": 100, "height": 100, "theme": "sepia"}, "theme 'sepia'"),
    ({"width": 100, "height": 100, "theme": 3}, "theme"),
    ({"width": 100, "height": 100, "overlays": ["links", "bogus"]}, "unknown overlay 'bogus'"),
    ({"width": 100, "height": 100, "overlays": [1]}, "overlays"),
    ({"width": 100, "height": 100, "legend": "yes"}, "legend"),
])
def test_render_refuses_bad_arguments(ended, kwargs, words):
    with pytest.raises(formsim.Error) as e:
        ended.render(**kwargs)
    assert words in str(e.value)


def test_figures_equal_the_cli_files(formsim_bin, tmp_path, ended):
    plots = tmp_path / "plots"
    cli_run(formsim_bin, tmp_path, "--plots", str(plots), "--plot-format", "png,svg,pdf")
    names = ended.figures()
    assert names and sorted(names) == sorted(p.stem for p in plots.glob("*.svg"))
    for name in names:
        for fmt in ("svg", "pdf", "png"):
            assert ended.figure(name, format=fmt) == (plots / f"{name}.{fmt}").read_bytes(), \
                (name, fmt)
    png = Image.open(io.BytesIO(ended.figure(names[0])))
    assert png.size == (960, 600)


def test_figure_refuses_bad_arguments(ended):
    names = ended.figures()
    with pytest.raises(formsim.Error) as e:
        ended.figure("no_such_figure")
    assert "no_such_figure" in str(e.value)
    assert all(n in str(e.value) for n in names)  # the valid names are listed
    with pytest.raises(formsim.Error) as e:
        ended.figure(names[0], format="jpg")
    assert "format 'jpg'" in str(e.value)
    with pytest.raises(formsim.Error) as e:
        ended.figure(names[0], theme="neon")
    assert "theme 'neon'" in str(e.value)
    with pytest.raises(formsim.Error):
        ended.figure(7)
