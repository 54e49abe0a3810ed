#!/usr/bin/python3
"""How biased is stage 6's sub-pixel parabola, and what would a calibrated correction give?

Part 1 (calibration, no evaluation scene): fronto-parallel pairs with known sub-pixel shifts,
made the way a camera samples them. A KITTI frame is the "scene"; the left view is its area
average over FACTOR x FACTOR blocks, the right view the same after shifting the frame by
FACTOR * D + m pixels, so the true disparity is D + m / FACTOR with every pixel integrated over
its footprint. For each parabola offset o (1/16 px, -8 .. 8) it prints the mean true offset of
the pixels that got o, and the correction table that maps o to that mean (rounded, odd).

Part 2 (evaluation): `stereo match`'s defaults for the cost on the eight scenes with ground
truth, the sub-pixel output as it is and with the table applied to each pixel's offset, scored
among the output pixels with ground truth: bad > 0.5 and the RMS error (px).

Usage (docs/results.md, "Sub-pixel"):
    PYTHONPATH=build/python scripts/subpixel/calibrate.py [--cost census] [--factor 8]
        [--data ../shared/data]
Needs the project's Python module (cmake -DSTEREO_BUILD_PYTHON=ON, the default) and numpy.
"""
import argparse
import os
import sys

import numpy as np
import stereo

SCALE = 16  # fx::kSubpixelScale
HALF = SCALE // 2


def area_down(image, factor):
    h = image.shape[0] // factor * factor
    w = image.shape[1] // factor * factor
    blocks = image[:h, :w].astype(np.float64)
    blocks = blocks.reshape(h // factor, factor, w // factor, factor, -1).mean(axis=(1, 3))
    return np.clip(np.floor(blocks + 0.5), 0, 255).astype(np.uint8)


def as_colour(image):
    return image if image.ndim == 3 else np.repeat(image[:, :, None], 3, axis=2)


def match_defaults(left, right, cost, ndisp):
    """stereo match's defaults for the cost (stereo/defaults.hpp, stereo/speckle.hpp)."""
    uniqueness, lr_check = (0, 1) if cost == "census" else (8, 0)
    return stereo.match(left, right, ndisp=ndisp, cost=cost, subpixel=True,
                        uniqueness=uniqueness, lr_check=lr_check, speckle_size=100,
                        speckle_range=1)


def split(fixed):
    """The integer winner and the offset o in [-8, 8) of a fixed-point disparity."""
    winner = np.floor((fixed.astype(np.int64) + HALF) / SCALE).astype(np.int64)
    return winner, fixed.astype(np.int64) - SCALE * winner


def calibrate(data, cost, factor):
    frames = [os.path.join(data, "sequence", f"kitti_sequence_{s}", "image_l", f"{i:06d}.png")
              for s in (1, 2) for i in range(0, 51, 5)]
    offsets, truths = [], []
    for path in frames:
        scene = as_colour(stereo.load_image(path))
        width = (scene.shape[1] - 64 * factor) // factor
        left = area_down(scene[:, :width * factor], factor)
        for whole in (3, 6):
            for m in range(factor):
                shift = whole * factor + m
                right = area_down(scene[:, shift:shift + width * factor], factor)
                result = match_defaults(left, right, cost, 16)
                fixed = result["fixed"]
                winner, offset = split(fixed)
                true16 = SCALE * shift / factor
                ok = result["valid"] & (np.abs(fixed - true16) < SCALE)
                ok[:, :40] = False  # the left border: no partner
                offsets.append(offset[ok])
                truths.append((true16 - SCALE * winner)[ok])
    offsets = np.concatenate(offsets)
    truths = np.concatenate(truths)
    print(f"calibration: {cost}, factor {factor}, {len(offsets)} pixels from {len(frames)} "
          "KITTI frames")
    print("| parabola offset (1/16) | pixels | mean true offset | median |")
    print("|---|---|---|---|")
    means = {}
    for o in range(-HALF, HALF + 1):
        sel = offsets == o
        if sel.sum() == 0:
            continue
        means[o] = truths[sel].mean()
        print(f"| {o} | {sel.sum()} | {means[o]:.2f} | {np.median(truths[sel]):.1f} |")
    # Odd and monotone by construction: the mean of o and -o folded together, clamped to 8.
    table = [0]
    for o in range(1, HALF + 1):
        pos = [means[k] * np.sign(k) for k in (o, -o) if k in means]
        value = int(min(HALF, max(table[-1], np.floor(np.mean(pos) + 0.5)))) if pos else o
        table.append(value)
    table[HALF] = HALF  # a half-pixel offset stays half a pixel (either winner gives the same)
    fracs = []
    for m in range(factor):
        t = SCALE * m / factor
        sel = np.isclose(np.mod(truths - t, SCALE), 0) | np.isclose(np.mod(truths - t, SCALE), SCALE)
        corrected = np.sign(offsets[sel]) * np.array(table)[np.abs(offsets[sel])]
        fracs.append((m, np.abs(truths[sel]).mean() / SCALE,
                      np.abs(truths[sel] - offsets[sel]).mean() / SCALE,
                      np.abs(truths[sel] - corrected).mean() / SCALE))
    print("\n| true fraction | mean abs error: integer | parabola | corrected |")
    print("|---|---|---|---|")
    for m, e_int, e_par, e_cor in fracs:
        print(f"| {m}/{factor} | {e_int:.3f} | {e_par:.3f} | {e_cor:.3f} |")
    print(f"\ncorrection table |o| = 0..8: {table}")
    return table


def load_scenes(data):
    """The eight scenes of stereo_experiments validation-eval (experiments/src/scenes.cpp)."""
    scenes = []
    for name, ndisp, scale in (("tsukuba", 16, 16.0), ("venus", 20, 8.0), ("teddy", 60, 4.0),
                               ("cones", 60, 4.0)):
        d = os.path.join(data, "middlebury2003", name)
        if os.path.exists(os.path.join(d, "gt.png")):
            scenes.append((name, os.path.join(d, "left.png"), os.path.join(d, "right.png"),
                           os.path.join(d, "gt.png"), ndisp, scale, 1))
    for folder, name in (("middlebury2005", "Reindeer"), ("middlebury2006", "Cloth3"),
                         ("middlebury2006", "Wood2")):
        d = os.path.join(data, folder, name)
        if os.path.exists(os.path.join(d, "disp1.png")):
            scenes.append((name, os.path.join(d, "view1.png"), os.path.join(d, "view5.png"),
                           os.path.join(d, "disp1.png"), 128, 2.0, 1))
    d = os.path.join(data, "aloe")
    if os.path.exists(os.path.join(d, "aloeGT.png")):
        scenes.append(("Aloe (half)", os.path.join(d, "aloeL.jpg"), os.path.join(d, "aloeR.jpg"),
                       os.path.join(d, "aloeGT.png"), 112, 1.0, 2))
    return scenes


def evaluate(data, cost, table):
    print(f"\nevaluation: stereo match's defaults for {cost}, output pixels with ground truth")
    print("| scene | bad > 0.5 %: integer | parabola | corrected | RMS px: integer | parabola "
          "| corrected |")
    print("|---|---|---|---|---|---|---|")
    lut = np.array(table)
    for name, left_path, right_path, gt_path, ndisp, scale, down in load_scenes(data):
        left = as_colour(stereo.load_image(left_path))
        right = as_colour(stereo.load_image(right_path))
        gt = stereo.load_image(gt_path).astype(np.float64)
        if gt.ndim == 3:
            gt = gt[:, :, 0]
        gt = gt / scale
        if down > 1:  # Aloe at half size: area-averaged views, the ground truth's block centres
            left, right = area_down(left, down), area_down(right, down)
            gt = gt[down // 2::down, down // 2::down][:left.shape[0], :left.shape[1]] / down
        result = match_defaults(left, right, cost, ndisp)
        fixed = result["fixed"]
        winner, offset = split(fixed)
        corrected = SCALE * winner + np.sign(offset) * lut[np.abs(offset)]
        mask = result["valid"] & (gt > 0)
        rows = []
        for estimate in (SCALE * winner, fixed.astype(np.int64), corrected):
            error = estimate[mask] / SCALE - gt[mask]
            rows.append((100.0 * (np.abs(error) > 0.5).mean(), np.sqrt((error ** 2).mean())))
        print(f"| {name} | {rows[0][0]:.2f} | {rows[1][0]:.2f} | {rows[2][0]:.2f} | "
              f"{rows[0][1]:.3f} | {rows[1][1]:.3f} | {rows[2][1]:.3f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cost", default="census", choices=["census", "ad"])
    parser.add_argument("--factor", type=int, default=8, help="area-downsampling factor")
    parser.add_argument("--data", default=os.environ.get(
        "STEREO_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared",
                                        "data")))
    args = parser.parse_args()
    if args.factor < 2 or args.factor > 16:
        sys.exit("calibrate.py: --factor must be 2 .. 16")
    if not os.path.isdir(os.path.join(args.data, "sequence")):
        sys.exit(f"calibrate.py: no sequence/ folder under {args.data}")
    table = calibrate(args.data, args.cost, args.factor)
    evaluate(args.data, args.cost, table)


if __name__ == "__main__":
    main()
