"""scripts/figures/disparity_figure.py (matplotlib): figures from the CLI's own outputs."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "figures" / "disparity_figure.py"
CLI = os.environ.get("STEREO_CLI", "stereo")
FIXTURES = os.environ.get("STEREO_FIXTURES", "")

pytest.importorskip("matplotlib")


def run(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True)


@pytest.fixture
def pfm(tmp_path):
    left = Path(FIXTURES) / "left.png"
    if not left.exists():
        pytest.skip("the CLI fixtures are absent")
    out = tmp_path / "d.pfm"
    subprocess.run([CLI, "match", left, Path(FIXTURES) / "right.png", "--ndisp", "16", "-o", out],
                   check=True, capture_output=True)
    return out


def test_figure_with_ground_truth(pfm, tmp_path):
    from matplotlib.image import imread

    out = tmp_path / "fig.png"
    result = run(pfm, "--gt", Path(FIXTURES) / "gt.png", "--gt-scale", "4", "--out", out)
    assert result.returncode == 0, result.stderr
    figure = imread(out)
    # Three panels and a colour bar: much wider than tall, and not a blank canvas.
    assert figure.shape[1] > 2.5 * figure.shape[0]
    assert np.unique(figure.reshape(-1, figure.shape[2]), axis=0).shape[0] > 20


def test_refuses_other_sizes_and_formats(pfm, tmp_path):
    result = run(pfm, "--gt", Path(FIXTURES) / "gt_narrow.png", "--out", tmp_path / "x.png")
    assert result.returncode == 1 and "disparity_figure.py: error:" in result.stderr
    result = run(Path(FIXTURES) / "left.png", "--out", tmp_path / "y.png")
    assert result.returncode == 1
    assert not (tmp_path / "x.png").exists()


def test_bad_percentage_equals_stereo_eval(tmp_path):
    """The figure's bad % is stereo eval's bad_all, with --gt-downscale (block centres) and on a
    self-describing --png16 map (issue 47: the script sampled the top-left corner before)."""
    import json

    left = Path(FIXTURES) / "scene_left.png"
    if not left.exists():
        pytest.skip("the CLI fixtures are absent")
    gt = Path(FIXTURES) / "scene_gt.pfm"
    for name, options, gt_options in (
            ("half.pfm", ["--downscale", "2", "--ndisp", "8", "--min-disp", "-2"],
             ["--gt-downscale", "2"]),
            ("full.png", ["--ndisp", "16", "--min-disp", "-4", "--png16"], [])):
        disp = tmp_path / name
        subprocess.run([CLI, "match", left, Path(FIXTURES) / "scene_right.png", *options,
                        "-o", disp], check=True, capture_output=True)
        scores = json.loads(subprocess.run([CLI, "eval", disp, gt, *gt_options, "--json"],
                                           check=True, capture_output=True, text=True).stdout)
        result = run(disp, "--gt", gt, *gt_options, "--out", tmp_path / (name + ".fig.png"))
        assert result.returncode == 0, result.stderr
        line = [x for x in result.stdout.splitlines() if x.startswith("bad_all ")]
        assert line, result.stdout
        assert float(line[0].split()[1]) == pytest.approx(scores["bad_all"], abs=1e-9), name
