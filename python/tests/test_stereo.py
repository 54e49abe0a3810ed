"""Tests of the Python module `stereo` (ctest label "python"; python/CMakeLists.txt).

The expected values come from elsewhere: the `stereo` CLI run as a subprocess (its PFM parsed
here with numpy, not by the module), the naive reference engine, or arithmetic in numpy.
"""
import json
import os
import subprocess

import numpy as np
import pytest

import stereo

CLI = os.environ.get("STEREO_CLI", "stereo")
FIXTURES = os.environ.get("STEREO_FIXTURES", "")
SEED = int(os.environ.get("STEREO_SEED", "7"))


def read_pfm(path):
    """A grey PFM as float32 (H, W), top row first; independent of the module's decoder."""
    with open(path, "rb") as f:
        data = f.read()
    header, rest = data.split(b"\n", 1)
    assert header == b"Pf"
    size, rest = rest.split(b"\n", 1)
    width, height = map(int, size.split())
    scale, rest = rest.split(b"\n", 1)
    dtype = "<f4" if float(scale) < 0 else ">f4"
    rows = np.frombuffer(rest[: width * height * 4], dtype=dtype).reshape(height, width)
    return rows[::-1].astype(np.float32)


def shifted_pair(width=64, height=48, shift=4, seed=SEED):
    """A random RGB texture and its copy shifted left by `shift` pixels (printed seed)."""
    print(f"STEREO_SEED={seed}")
    rng = np.random.default_rng(seed)
    left = rng.integers(0, 256, size=(height, width, 3), dtype=np.uint8)
    right = np.empty_like(left)
    right[:, : width - shift] = left[:, shift:]
    right[:, width - shift :] = rng.integers(0, 256, size=(height, shift, 3), dtype=np.uint8)
    return left, right


@pytest.fixture
def fixture_pair():
    if not FIXTURES or not os.path.exists(os.path.join(FIXTURES, "left.png")):
        pytest.skip("the CLI fixtures (ctest fixture stereo_cli_images) are absent")
    return os.path.join(FIXTURES, "left.png"), os.path.join(FIXTURES, "right.png")


def test_version_matches_cli():
    out = subprocess.run([CLI, "--version"], capture_output=True, text=True, check=True)
    assert stereo.__version__ in out.stdout


def grey_png(path):
    """An 8-bit grey PNG (stereo match --reasons / --certainty) as uint8 (H, W)."""
    image = stereo.load_image(str(path))
    return image if image.ndim == 2 else image[:, :, 0]


@pytest.fixture
def scene_pair():
    """The equality-test scene of make_cli_fixtures: planes at 2, 7 and -2.5, a slanted plane,
    occlusions and speckle islands (issue 52)."""
    if not FIXTURES or not os.path.exists(os.path.join(FIXTURES, "scene_left.png")):
        pytest.skip("the CLI fixtures (ctest fixture stereo_cli_images) are absent")
    return os.path.join(FIXTURES, "scene_left.png"), os.path.join(FIXTURES, "scene_right.png")


# The CLI's defaults: the census cost, every stage-6 step on (uniqueness 0, left-right 1,
# sub-pixel; stereo/defaults.hpp), then the speckle filter (size 100, range 1). The binding keeps
# the library's defaults (AD, stage 6 off), so they are spelled out here.
CLI_DEFAULTS = dict(ndisp=16, min_disp=-4, cost="census", uniqueness=0, lr_check=1,
                    subpixel=True, speckle_size=100, speckle_range=1)


def test_match_equals_cli_bit_for_bit(scene_pair, tmp_path):
    left_path, right_path = scene_pair
    pfm, reasons, certainty = (tmp_path / name for name in ("cli.pfm", "r.png", "c.png"))
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "16", "--min-disp", "-4",
                    "-o", str(pfm), "--reasons", str(reasons), "--certainty", str(certainty)],
                   check=True, capture_output=True)
    expected = read_pfm(pfm)
    expected_valid = np.isfinite(expected)
    # The scene exercises what the comparison claims: enough valid pixels, fractional and
    # negative disparities, pixels removed by the left-right check and the speckle filter.
    assert expected_valid.mean() >= 0.3
    values = expected[expected_valid]
    assert (values != np.floor(values)).any() and (values < 0).any()
    expected_reasons = grey_png(reasons)
    assert {1, 3, 4} <= set(np.unique(expected_reasons).tolist())

    left = stereo.load_image(left_path)
    right = stereo.load_image(right_path)
    result = stereo.match(left, right, **CLI_DEFAULTS)
    got = result["disparity_px"]
    assert got.shape == expected.shape
    assert np.array_equal(np.isfinite(got), expected_valid)
    assert np.array_equal(got[expected_valid], expected[expected_valid])
    # `valid` is the 8-bit label view's: stage 6's valid pixels whose nearest label (halves up)
    # is 0..255, so not the negative plane.
    labelled = expected_valid & (np.floor(np.nan_to_num(expected, nan=-1.0) + 0.5) >= 0)
    assert np.array_equal(result["valid"], labelled)
    assert np.array_equal(result["fixed"][expected_valid],
                          (expected[expected_valid] * 16).astype(np.int16))
    assert np.array_equal(result["reason"], expected_reasons)
    assert np.array_equal(result["certainty"], grey_png(certainty))

    # Every option the binding forwards changes the map when flipped, so a binding that dropped
    # one would fail the comparison above.
    for name, flipped in (("cost", "ad"), ("uniqueness", 10), ("lr_check", 3),
                          ("subpixel", False), ("speckle_size", 0), ("speckle_range", 3),
                          ("min_disp", -2)):
        options = dict(CLI_DEFAULTS, **{name: flipped})
        other = stereo.match(left, right, **options)
        assert not np.array_equal(np.nan_to_num(other["disparity_px"], nan=-99),
                                  np.nan_to_num(got, nan=-99)), name


def test_default_map_is_the_same_through_cli_python_and_cosim(scene_pair, tmp_path):
    """One definition of a default run (stereo/defaults.hpp, match_config): `stereo match` with no
    option but the label count, stereo.match with none, and stereo cosim's model and RTL (whose
    defaults are stereo match's but for the 5x5 window of the built cores and no speckle filter),
    bit for bit, on a scene that exercises stage 6 and the speckle filter (issue 44)."""
    left_path, right_path = scene_pair
    pfm, reasons, certainty = (tmp_path / name for name in ("cli.pfm", "r.png", "c.png"))
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "16", "-o", str(pfm),
                    "--reasons", str(reasons), "--certainty", str(certainty)],
                   check=True, capture_output=True)
    expected = read_pfm(pfm)
    valid = np.isfinite(expected)
    assert valid.mean() >= 0.3
    assert (expected[valid] != np.floor(expected[valid])).any()  # sub-pixel on by default
    assert {1, 3, 4} <= set(np.unique(grey_png(reasons)).tolist())  # border, left-right, speckle
    left = stereo.load_image(left_path)
    right = stereo.load_image(right_path)
    got = stereo.match(left, right, ndisp=16)
    assert np.array_equal(np.isfinite(got["disparity_px"]), valid)
    assert np.array_equal(got["disparity_px"][valid], expected[valid])
    assert np.array_equal(got["reason"], grey_png(reasons))
    assert np.array_equal(got["certainty"], grey_png(certainty))
    if not stereo.has_rtl:
        return
    core_pfm = tmp_path / "core.pfm"
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "16", "--window", "5",
                    "--speckle-size", "0", "-o", str(core_pfm)], check=True, capture_output=True)
    core_expected = read_pfm(core_pfm)
    core_valid = np.isfinite(core_expected)
    assert core_valid.mean() >= 0.3
    rtl = stereo.cosim(left, right)
    assert rtl["mismatches"] == 0
    assert np.array_equal(rtl["fixed"][core_valid],
                          (core_expected[core_valid] * 16).astype(np.int16))
    assert np.array_equal(rtl["reason"] == 0, core_valid)


def test_match_labels_equal_cli_without_validation(fixture_pair, tmp_path):
    left_path, right_path = fixture_pair
    pfm = tmp_path / "plain.pfm"
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "12", "--window", "3",
                    "--no-validation", "-o", str(pfm)], check=True, capture_output=True)
    expected = read_pfm(pfm)
    result = stereo.match(stereo.load_image(left_path), stereo.load_image(right_path),
                          ndisp=12, window=3, validation=False)
    labels = np.where(result["valid"], result["disparity"].astype(np.float32), np.nan)
    both = np.isfinite(expected)
    assert np.array_equal(np.isfinite(labels), both)
    assert np.array_equal(labels[both], expected[both])


def test_model_equals_naive_reference():
    left, right = shifted_pair()
    for options in ({}, {"uniqueness": 10, "lr_check": 1, "subpixel": True},
                    {"cost": "census"}, {"min_disp": -2, "ca": False}):
        model = stereo.match(left, right, ndisp=16, window=5, **options)
        naive = stereo.match(left, right, ndisp=16, window=5, engine="naive", **options)
        assert np.array_equal(model["disparity"], naive["disparity"]), options
        assert np.array_equal(model["fixed"], naive["fixed"]), options


def test_default_engine_fast_equals_model_on_every_thread_count():
    """The pipeline runs on engine fast by default (issue 49), bit for bit the model's output."""
    left, right = shifted_pair()
    for options in ({}, {"cost": "ad"}, {"min_disp": -3, "ca": False}):
        model = stereo.match(left, right, ndisp=16, window=5, engine="model", **options)
        for threads in (0, 1, 2, 3):
            fast = stereo.match(left, right, ndisp=16, window=5, threads=threads, **options)
            for key in ("disparity", "fixed", "reason", "certainty"):
                assert np.array_equal(model[key], fast[key]), (options, threads, key)
    for threads in (-1, 257):
        with pytest.raises(ValueError, match="threads"):
            stereo.match(left, right, ndisp=16, window=5, threads=threads)


def test_edge_options_reach_the_matcher():
    left, right = shifted_pair()
    options = {"method": "edges", "ndisp": 16, "window": 5, "log_window": 5, "log_sigma": 0.8,
               "edge_value": 200, "truncation": 120}
    model = stereo.match(left, right, **options)
    naive = stereo.match(left, right, engine="naive", **options)
    assert np.array_equal(model["disparity"], naive["disparity"])
    default = stereo.match(left, right, method="edges", ndisp=16, window=5)
    assert not np.array_equal(model["disparity"], default["disparity"])


def test_shift_is_found():
    left, right = shifted_pair(shift=5)
    result = stereo.match(left, right, ndisp=16, window=5)
    # Columns right of the search range: every left pixel has its match in the right image.
    valid = result["valid"][:, 20:]
    assert valid.sum() > 0.5 * valid.size
    assert np.mean(result["disparity"][:, 20:][valid] == 5) > 0.95


def test_every_registered_matcher_runs():
    left, right = shifted_pair()
    grey_l = left[:, :, 0].copy()
    grey_r = right[:, :, 0].copy()
    names = stereo.matchers()
    assert ("pipeline", "model") in [(m, e) for m, e, _ in names]
    for method, engine, _ in names:
        if engine == "rtl" and not stereo.has_rtl:
            with pytest.raises(ValueError):
                stereo.match(left, right, method=method, engine=engine, ndisp=16, window=5)
            continue
        # ASW's default circle (55) does not fit the 64 x 48 pair.
        extra = {"asw": {"diameter": 9}} if method == "asw" else {}
        for l, r in ((left, right), (grey_l, grey_r)):
            try:
                result = stereo.match(l, r, method=method, engine=engine, ndisp=16, window=5,
                                      **extra)
            except ValueError as error:  # a documented refusal (e.g. the lcdm cost needs colour)
                assert str(error), (method, engine)
                continue
            assert result["disparity"].shape == (48, 64), (method, engine)
            assert result["valid"].dtype == np.bool_


def test_asw_options_reach_the_matcher(fixture_pair, tmp_path):
    # The same pair through `stereo match --aggregation asw` (its default cost: census) and
    # stereo.match(method="asw", cost="census"): identical disparities, and a bad option is
    # refused.
    left_path, right_path = fixture_pair
    pfm = tmp_path / "asw.pfm"
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "8", "--aggregation", "asw",
                    "--window", "9", "--separable", "--no-validation", "-o", str(pfm)],
                   check=True, capture_output=True)
    expected = read_pfm(pfm)
    left = stereo.load_image(left_path)
    right = stereo.load_image(right_path)
    result = stereo.match(left, right, method="asw", ndisp=8, validation=False,
                          asw={"diameter": 9, "separable": True})
    got = result["disparity_px"]
    both = np.isfinite(expected)
    assert both.any()
    assert np.array_equal(np.isfinite(got), both)
    assert np.array_equal(got[both], expected[both])
    full = stereo.match(left, right, method="asw", ndisp=8, asw={"diameter": 9})
    assert full["disparity_px"].shape == expected.shape
    # The cost truncation: the CLI's --truncation and the dict key reach the same matcher.
    untruncated = tmp_path / "asw0.pfm"
    subprocess.run([CLI, "match", left_path, right_path, "--ndisp", "8", "--aggregation", "asw",
                    "--window", "9", "--cost", "ad", "--truncation", "0", "--no-validation", "-o",
                    str(untruncated)], check=True, capture_output=True)
    plain = stereo.match(left, right, method="asw", ndisp=8, cost="ad", validation=False,
                         asw={"diameter": 9, "truncation": 0})
    expected0 = read_pfm(untruncated)
    both0 = np.isfinite(expected0)
    assert np.array_equal(np.isfinite(plain["disparity_px"]), both0)
    assert np.array_equal(plain["disparity_px"][both0], expected0[both0])
    with pytest.raises(ValueError):
        stereo.match(left, right, method="asw", ndisp=8, asw={"diameter": 9, "truncation": 766})
    with pytest.raises(ValueError):
        stereo.match(left, right, method="asw", ndisp=8, asw={"diameter": 8})
    with pytest.raises(ValueError):
        stereo.match(left, right, method="asw", ndisp=8, asw={"radius": 4})


def test_speckle_filter_counts_what_it_removes():
    # Two unrelated random images: a map of islands. The filter's count is the pixels it marked
    # (reason 4), they were valid without it, and an impossible size is refused.
    rng = np.random.default_rng(SEED)
    left = rng.integers(0, 256, size=(48, 64, 3), dtype=np.uint8)
    right = rng.integers(0, 256, size=(48, 64, 3), dtype=np.uint8)
    options = dict(ndisp=8, window=5, uniqueness=8, lr_check=0, subpixel=True)
    plain = stereo.match(left, right, speckle_size=0, **options)
    filtered = stereo.match(left, right, speckle_size=30, speckle_range=1, **options)
    removed = filtered["reason"] == 4
    assert removed.any()
    assert filtered["counts"]["speckle"] == np.count_nonzero(removed)
    assert plain["valid"][removed].all()
    kept = filtered["valid"]
    assert np.array_equal(filtered["fixed"][kept], plain["fixed"][kept])
    with pytest.raises(ValueError):
        stereo.match(left, right, ndisp=8, speckle_size=-1)


def test_bad_inputs_raise():
    left, right = shifted_pair()
    with pytest.raises(ValueError):
        stereo.match(left.astype(np.float32), right, ndisp=16)
    with pytest.raises(ValueError):
        stereo.match(left, right[:, :32], ndisp=16)
    with pytest.raises(ValueError):
        stereo.match(left, right, ndisp=16, window=4)
    with pytest.raises(ValueError):
        stereo.match(left, right, method="nope")


def test_evaluate_counts_bad_pixels():
    rng = np.random.default_rng(SEED)
    gt = rng.uniform(1, 30, size=(20, 30)).astype(np.float32)
    disparity = gt.copy()
    wrong = rng.random(gt.shape) < 0.2
    disparity[wrong] += 3.0
    gt[0, :] = 0  # unknown
    known = gt > 0
    expected_bad = 100.0 * np.count_nonzero(wrong & known) / np.count_nonzero(known)
    scores = stereo.evaluate(disparity, gt, threshold=1.0)
    assert scores["bad_all"] == pytest.approx(expected_bad)


def test_fuzzy_decision_equals_cli():
    for occupancy in ((0.0, 0.0, 0.0), (0.1, 0.9, 0.8), (0.9, 0.8, 0.05), (0.9, 0.95, 0.9)):
        out = subprocess.run([CLI, "fis", "--left", str(occupancy[0]), "--center",
                              str(occupancy[1]), "--right", str(occupancy[2]), "--json"],
                             capture_output=True, text=True, check=True)
        expected = json.loads(out.stdout)
        got = stereo.fuzzy_decision(*occupancy)
        assert got["decision"] == expected["decision"]
        assert got["angle_deg"] == pytest.approx(expected["angle_deg"])
        assert got["backwards"] == pytest.approx(expected["backwards"])


@pytest.mark.skipif(not stereo.has_rtl, reason="built with -DSTEREO_WITH_RTL=OFF")
def test_cosim_equals_model_under_stalls():
    left, right = shifted_pair()
    result = stereo.cosim(left, right, ndisp=16, window=5, uniqueness=10, lr_check=1,
                          stall=0.3, gap=0.2, seed=SEED)
    assert result["mismatches"] == 0
    model = stereo.match(left, right, ndisp=16, window=5, uniqueness=10, lr_check=1,
                         speckle_size=0)
    assert np.array_equal(result["fixed"], model["fixed"])
    assert np.array_equal(result["reason"], model["reason"])
    assert result["cycles"] >= 64 * 48
    assert result["config"] in stereo.cosim_configs()


def test_cosim_on_demand_core_equals_model(tmp_path):
    """size=: a core this build does not have (48x32, 8 labels 4 per clock, window 3), Verilated
    into an empty cache on first use, bit-exact with the model under stalls."""
    left, right = shifted_pair(width=48, height=32, shift=3)
    options = dict(ndisp=8, window=3, uniqueness=10, lr_check=1, subpixel=True)
    result = stereo.cosim(left, right, **options, stall=0.3, gap=0.2, seed=SEED, size=(48, 32),
                          lanes=4, cache=str(tmp_path))
    assert result["config"] == "on-demand 48x32-n8-w3-census-l4-m8"  # stereo cosim's default
    assert result["config"] not in stereo.cosim_configs()
    assert result["mismatches"] == 0
    model = stereo.match(left, right, speckle_size=0, **options)
    assert np.array_equal(result["fixed"], model["fixed"])
    assert np.array_equal(result["reason"], model["reason"])
    assert np.count_nonzero(result["reason"] == 0) > 48 * 32 // 2
    assert len([p for p in tmp_path.iterdir() if not p.name.startswith(".")]) == 1
    with pytest.raises(ValueError, match="LANES 3 must divide NDISP 8"):
        stereo.cosim(left, right, ndisp=8, window=3, size=(48, 32), lanes=3, cache=str(tmp_path))
    with pytest.raises(ValueError, match="give size"):
        stereo.cosim(left, right, ndisp=8, window=3, lanes=4)


# A ground truth stored as d * K (Middlebury 2003: 4) read without gt_scale scored every pixel
# bad and returned normally (issue 47): it is refused with a short hint, gt_scale reads it, and
# any_gt_range=True scores it anyway.
def _scaled_gt_case():
    rng = np.random.default_rng(SEED)
    disparity = rng.uniform(2, 40, size=(24, 32)).astype(np.float32)
    return disparity, np.round(disparity * 4).astype(np.uint8)


def test_evaluate_refuses_a_ground_truth_at_the_wrong_scale():
    disparity, gt = _scaled_gt_case()
    with pytest.raises(ValueError) as error:
        stereo.evaluate(disparity, gt)
    message = str(error.value)
    assert "gt_scale" in message and len(message) < 300


def test_evaluate_gt_scale_reads_a_scaled_ground_truth():
    disparity, gt = _scaled_gt_case()
    scores = stereo.evaluate(disparity, gt, gt_scale=4)
    # |d - round(4 d) / 4| <= 1/8: no pixel is bad.
    assert scores["bad_all"] == 0.0
    forced = stereo.evaluate(disparity, gt, any_gt_range=True)
    assert forced["bad_all"] == 100.0
    with pytest.raises(ValueError):
        stereo.evaluate(disparity, gt, gt_scale=0)


# Bad input (issue 47): one short message each (under 300 characters) that names the argument,
# not pybind11's list of signatures with the repr of every argument (megabytes for a list).
@pytest.mark.parametrize("case", ["list", "none", "float", "float01", "int16", "shape", "tiny",
                                  "sizes"])
def test_bad_images_give_one_short_message(case):
    left, right = shifted_pair()
    wrong = {
        "list": (left.tolist(), right),
        "none": (None, right),
        "float": (left.astype(np.float32), right),
        "float01": (left / 255.0, right / 255.0),
        "int16": (left.astype(np.int16), right),
        "shape": (left[:, :, :2].copy(), right),
        "tiny": (left[:2, :2].copy(), right[:2, :2].copy()),
        "sizes": (left, right[:, :32].copy()),
    }[case]
    with pytest.raises((ValueError, TypeError)) as error:
        stereo.match(*wrong)
    message = str(error.value)
    print(message)
    assert 0 < len(message) < 300 and "\n" not in message
    if case in ("list", "none", "float", "float01", "int16", "shape"):
        assert "left" in message


def test_evaluate_bad_arguments_give_one_short_message():
    gt = np.ones((8, 8), np.float32)
    for disparity in (None, "map", np.array([["a"] * 8] * 8)):
        with pytest.raises((ValueError, TypeError)) as error:
            stereo.evaluate(disparity, gt)
        assert len(str(error.value)) < 300 and "disparity" in str(error.value)


def test_rgba_is_read_as_its_rgb():
    """The CLI drops alpha from an RGBA file; the module drops it from an (H, W, 4) array."""
    left, right = shifted_pair()
    alpha = np.full(left.shape[:2] + (1,), 77, np.uint8)
    rgb = stereo.match(left, right, ndisp=16)
    rgba = stereo.match(np.concatenate([left, alpha], axis=2),
                        np.concatenate([right, 255 - alpha], axis=2), ndisp=16)
    assert np.array_equal(rgb["fixed"], rgba["fixed"])
    assert np.array_equal(rgb["reason"], rgba["reason"])


def test_load_image_downscale_equals_the_cli(fixture_pair, tmp_path):
    """load_image(path, downscale=2) then match() writes what `stereo match --downscale 2` does
    (the README's CLI example, reproduced in Python)."""
    left_path, right_path = fixture_pair
    full = stereo.load_image(left_path)
    half = stereo.load_image(left_path, downscale=2)
    assert half.shape[:2] == (full.shape[0] // 2, full.shape[1] // 2)
    out = tmp_path / "half.pfm"
    subprocess.run([CLI, "match", left_path, right_path, "--downscale", "2", "--ndisp", "8",
                    "-o", str(out)], check=True, capture_output=True)
    result = stereo.match(half, stereo.load_image(right_path, downscale=2), ndisp=8)
    expected = read_pfm(out)
    assert np.array_equal(np.isnan(result["disparity_px"]), ~np.isfinite(expected))
    valid = np.isfinite(expected)
    assert np.array_equal(result["disparity_px"][valid], expected[valid])
    with pytest.raises(ValueError):
        stereo.load_image(left_path, downscale=0)


@pytest.mark.skipif(not stereo.has_rtl, reason="built with -DSTEREO_WITH_RTL=OFF")
def test_cosim_configs_lists_every_configuration_of_the_cli():
    """Every configuration `stereo cosim --help` lists as built is in cosim_configs()."""
    help_text = subprocess.run([CLI, "cosim", "--help"], capture_output=True, text=True,
                               check=True).stdout
    listed = help_text.split("Verilated configurations in this build", 1)[1]
    names = [line.split(":")[0].strip() for line in listed.splitlines()[1:]
             if line.startswith("  ") and ":" in line]
    assert len(names) >= 3, listed
    assert set(names) <= set(stereo.cosim_configs())
