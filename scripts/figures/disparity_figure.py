#!/usr/bin/python3
"""A disparity map as a figure people read without a caption (issue 23): the map with a colour
bar in pixels of disparity, axis labels and a title with its coverage; with --gt, the ground
truth beside it on the same colour scale and an error map with a legend and the bad-pixel
percentage.

    disparity_figure.py DISP.pfm --out FIG.png [--gt GT.png|GT.pfm] [--gt-scale S]
                        [--gt-downscale F] [--threshold T] [--title TEXT]

DISP: a PFM (what `stereo match -o disp.pfm` writes: pixels, +inf invalid) or a PNG holding
disparity x --scale (0 invalid); a PNG `stereo` wrote records its encoding and scale (its
"stereo-disparity" text chunk), which then applies. GT: a PFM or a PNG holding disparity x
--gt-scale (0 unknown). --gt-downscale F samples the GT as `stereo eval` does (the centre of each
F x F block, divided by F), so the bad-pixel percentage, printed as "bad_all P" after the figure's
path, is `stereo eval`'s bad_all (python/tests/test_figures.py).
Needs Debian's python3-matplotlib.
"""
import argparse
import sys
from pathlib import Path

import numpy as np


def read_pfm(path):
    data = Path(path).read_bytes()
    header, rest = data.split(b"\n", 1)
    if header.strip() != b"Pf":
        raise ValueError(f"{path}: not a grey PFM (header {header[:8]!r})")
    size, rest = rest.split(b"\n", 1)
    width, height = map(int, size.split())
    scale, rest = rest.split(b"\n", 1)
    dtype = "<f4" if float(scale) < 0 else ">f4"
    if len(rest) < width * height * 4:
        raise ValueError(f"{path}: truncated PFM")
    rows = np.frombuffer(rest[: width * height * 4], dtype=dtype).reshape(height, width)
    out = rows[::-1].astype(np.float32)
    out[~np.isfinite(out)] = np.nan
    return out


def read_disparity(path, scale):
    """Float disparities with NaN where invalid or unknown."""
    if Path(path).suffix.lower() == ".pfm":
        return read_pfm(path)
    from PIL import Image  # python3-pil, a dependency of python3-matplotlib

    image = Image.open(path)
    tag = getattr(image, "text", {}).get("stereo-disparity", "")
    values = np.array(image).astype(np.float32)
    if values.ndim != 2:
        raise ValueError(f"{path}: a disparity PNG must be single-channel")
    values[values == 0] = np.nan
    if tag == "encoding=offset16":  # stereo match --png16: 32768 + 16 d
        return (values - 32768.0) / 16.0
    if tag.startswith("encoding=scaled scale="):
        scale = float(tag.split("=")[-1])
    return values / scale


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("disparity")
    parser.add_argument("--out", required=True, help="figure file (.png, .svg, .pdf)")
    parser.add_argument("--scale", type=float, default=1.0, help="PNG disparity holds d x S")
    parser.add_argument("--gt", help="ground truth (PFM, or PNG with --gt-scale)")
    parser.add_argument("--gt-scale", type=float, default=1.0)
    parser.add_argument("--gt-downscale", type=int, default=1,
                        help="GT at F times the disparity's size: every F-th pixel, divided by F")
    parser.add_argument("--threshold", type=float, default=1.0, help="bad when |d - gt| > T")
    parser.add_argument("--title", default=None)
    args = parser.parse_args(argv)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    disp = read_disparity(args.disparity, args.scale)
    gt = read_disparity(args.gt, args.gt_scale) if args.gt else None
    if gt is not None and args.gt_downscale > 1:
        # As stereo eval (io::downscale_ground_truth): floor(W/F) x floor(H/F) samples, each the
        # centre (F x + F/2, F y + F/2) of its block, divided by F.
        f = args.gt_downscale
        rows, cols = gt.shape[0] // f, gt.shape[1] // f
        gt = gt[f // 2 :: f, f // 2 :: f][:rows, :cols] / f
    if gt is not None and gt.shape != disp.shape:
        raise ValueError(f"ground truth is {gt.shape[1]}x{gt.shape[0]}, the disparity "
                         f"{disp.shape[1]}x{disp.shape[0]}")
    finite = disp[np.isfinite(disp)]
    values = np.concatenate([finite, gt[np.isfinite(gt)]]) if gt is not None else finite
    vmin, vmax = (float(values.min()), float(values.max())) if values.size else (0.0, 1.0)
    if vmax - vmin < 1.0:  # a constant map: one pixel of range around it
        vmin, vmax = vmin - 0.5, vmax + 0.5
    cmap = matplotlib.colormaps["turbo"].copy()
    cmap.set_bad("0.35")  # invalid / unknown pixels: grey

    panels = 1 if gt is None else 3
    fig, axes = plt.subplots(1, panels, figsize=(4.6 * panels, 4.2), squeeze=False,
                             constrained_layout=True)
    axes = axes[0]
    coverage = 100.0 * finite.size / disp.size
    image = axes[0].imshow(disp, cmap=cmap, vmin=vmin, vmax=vmax, interpolation="nearest")
    axes[0].set_title(f"disparity ({coverage:.1f} % valid, grey: invalid)")
    if gt is not None:
        axes[1].imshow(gt, cmap=cmap, vmin=vmin, vmax=vmax, interpolation="nearest")
        axes[1].set_title("ground truth (grey: unknown)")
        known = np.isfinite(gt)
        valid = np.isfinite(disp)
        bad = known & (~valid | (np.abs(np.nan_to_num(disp) - np.nan_to_num(gt)) > args.threshold))
        classes = np.zeros(disp.shape, dtype=np.uint8)  # 0 unknown GT
        classes[known & ~bad] = 1
        classes[known & bad & valid] = 2
        classes[known & ~valid] = 3
        colours = matplotlib.colors.ListedColormap(["0.85", "0.55", "red", "blue"])
        axes[2].imshow(classes, cmap=colours, vmin=0, vmax=3, interpolation="nearest")
        percent = 100.0 * bad.sum() / max(int(known.sum()), 1)
        axes[2].set_title(f"bad pixels (|d - gt| > {args.threshold:g} px): {percent:.2f} %")
        axes[2].legend(handles=[Patch(color="0.55", label="good"),
                                Patch(color="red", label="wrong disparity"),
                                Patch(color="blue", label="invalid (no output)"),
                                Patch(color="0.85", label="unknown ground truth")],
                       loc="lower left", fontsize=7, framealpha=0.85)
    for ax in axes:
        ax.set_xlabel("x (pixels)")
        ax.set_ylabel("y (pixels)")
    fig.colorbar(image, ax=list(axes[:2]) if gt is not None else axes[0], shrink=0.85,
                 label="disparity (pixels)")
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.out, dpi=110)
    print(args.out)
    if gt is not None:
        print(f"bad_all {percent!r}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (OSError, ValueError) as error:
        print(f"disparity_figure.py: error: {error}", file=sys.stderr)
        sys.exit(1)
