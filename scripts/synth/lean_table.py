#!/usr/bin/python3
"""The lean-memory tables of docs/synthesis.md from the reports of docs/figures/synthesis/boards
(or the folder given): python3 scripts/synth/lean_table.py [FOLDER]."""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import synth  # noqa: E402

D = sys.argv[1] if len(sys.argv) > 1 else str(synth.REPO / "docs" / "figures" / "synthesis" / "boards")
rows = [
 ("xilinx_640x480_64_11x11_lanes8_census_rows", "640x480, 64 labels, 11x11, `LANES = 8`, census, per-label rows (before)"),
 ("xilinx_640x480_64_11x11_lanes8_census_lean", "the same, **lean** (`--recompute`)"),
 ("xilinx_640x480_64_11x11_lanes16_census_lean", "640x480, 64 labels, `LANES = 16` (60 frames/s), lean"),
 ("xilinx_640x480_128_11x11_lanes16_census_lean", "640x480, 128 labels, `LANES = 16`, lean"),
 ("xilinx_640x480_32_11x11_lanes4_census_lean", "640x480, 32 labels, `LANES = 4`, lean"),
 ("xilinx_640x480_16_11x11_lanes2_census_lean", "640x480, 16 labels, `LANES = 2`, lean"),
 ("xilinx_320x240_64_11x11_lanes2_census_lean", "320x240, 64 labels, `LANES = 2`, lean"),
 ("ecp5_640x480_64_11x11_lanes8_census_lean", "ECP5: 640x480, 64 labels, `LANES = 8`, lean"),
 ("ecp5_640x480_32_11x11_lanes4_census_lean", "ECP5: 640x480, 32 labels, `LANES = 4`, lean"),
]
print("| configuration (all 11x11, census, `--shift-add narrow`, `MAX_MIN_DISP = 8`) | LUT (sites) | FF | block RAM | DSP | LUT levels | frames/s at 100 MHz | report |")
print("|---|---|---|---|---|---|---|---|")
for name, text in rows:
    try:
        r = json.load(open(f"{D}/{name}.json"))
    except OSError:
        print(f"| {text} | not measured | | | | | | |"); continue
    res = r["resources"]
    ecp5 = r["target"] == "ecp5"
    lut = f"{res['luts']:,} LUT4" if ecp5 else f"{res['luts']:,} LUT6 ({res['lut_sites']:,})"
    bram = f"{res['brams']:g} DP16KD ({res['bram_kbits']:,} Kib)" if ecp5 else f"{res['brams']:g} RAMB36 ({res['bram_kbits']:,} Kib)"
    fps, _ = synth.throughput(r["config"], 100.0)
    print(f"| {text} | {lut} | {res['ffs']:,} | {bram} | {res['dsps']} | {r['logic_depth']['lut_levels']} | {fps} | `{name}.json` |")
print()
print("Per stage, 7-series, 640x480 / 64 / `LANES = 8` (LUT sites / FF / RAMB36 / DSP):")
print()
print("| stage | " + " | ".join(["per-label rows", "lean"]) + " |")
print("|---|---|---|")
reps = {}
for n in ("xilinx_640x480_64_11x11_lanes8_census_rows", "xilinx_640x480_64_11x11_lanes8_census_lean"):
    try: reps[n] = json.load(open(f"{D}/{n}.json"))
    except OSError: reps[n] = None
for stage in ("cost", "aggregate", "ca_rule1", "ca_rule2", "wta", "validate", "lr_check", "glue"):
    cells = []
    for n, r in reps.items():
        if r is None: cells.append("not measured"); continue
        s = r["stages"][stage]
        cells.append(f"{s.get('lut_sites', s['luts']):,} / {s['ffs']:,} / {s['brams']:g} / {s['dsps']}")
    print(f"| {stage} | " + " | ".join(cells) + " |")
