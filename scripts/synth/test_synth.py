#!/usr/bin/env python3
"""Unit tests of synth.py's report arithmetic, without Yosys (ctest synth.report_arithmetic).

Every expected value is worked out by hand in the test from the fabricated input."""
import contextlib
import importlib.util
import io
import json
import re
import shlex
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ElementTree
from pathlib import Path
from types import SimpleNamespace
from unittest import mock

sys.path.insert(0, str(Path(__file__).resolve().parent))
import synth  # noqa: E402

# A hierarchical `stat -json` as Yosys 0.23 writes it: the text listing of the hierarchy lands in
# the middle of the JSON. stereo_top holds one aggregate (which holds two line buffers) and one
# cost stage; the other stages are empty modules.
STAT_WITH_LISTING = """
{
   "creator": "Yosys 0.23",
   "modules": {
      "\\\\stereo_synth_top": {
         "num_cells_by_type": {
            "$paramod$aa\\\\stereo_top": 1,
            "IBUF": 5,
            "LUT2": 3
         }
      },
      "$paramod$aa\\\\stereo_top": {
         "num_cells_by_type": {
            "$paramod$bb\\\\stereo_aggregate": 1,
            "$paramod\\\\stereo_cost\\\\NDISP=s32'00000000000000000000000000000100": 1,
            "$paramod$dd\\\\stereo_ca_plane": 1,
            "$paramod$de\\\\stereo_ca_plane": 1,
            "$paramod$ee\\\\stereo_wta": 1,
            "$paramod$ef\\\\stereo_validate": 1,
            "$paramod$eg\\\\stereo_lr_check": 1,
            "FDRE": 7
         }
      },
      "$paramod$bb\\\\stereo_aggregate": {
         "num_cells_by_type": {
            "$paramod$cc\\\\stereo_line_buffer": 2,
            "LUT6": 10,
            "DSP48E1": 4
         }
      },
      "$paramod$cc\\\\stereo_line_buffer": {
         "num_cells_by_type": {"RAMB18E1": 3, "LUT3": 1}
      },
      "$paramod\\\\stereo_cost\\\\NDISP=s32'00000000000000000000000000000100": {
         "num_cells_by_type": {"LUT4": 20, "FDRE": 2}
      },
      "$paramod$dd\\\\stereo_ca_plane": {"num_cells_by_type": {"LUT1": 1}},
      "$paramod$de\\\\stereo_ca_plane": {"num_cells_by_type": {"LUT1": 1}},
      "$paramod$ee\\\\stereo_wta": {"num_cells_by_type": {"FDRE": 1}},
      "$paramod$ef\\\\stereo_validate": {"num_cells_by_type": {}},
      "$paramod$eg\\\\stereo_lr_check": {"num_cells_by_type": {}}
   },
       \\stereo_synth_top      1
         $paramod$aa\\stereo_top      1
      "design": {
         "num_cells": 71,
         "num_cells_by_type": {"LUT2": 3, "LUT6": 10, "LUT3": 2, "LUT4": 20, "LUT1": 2,
                               "FDRE": 10, "DSP48E1": 4, "RAMB18E1": 6, "IBUF": 5}
      }
}
"""

# The module of each stage, as stage_module_query lists it (the two CA rules are stereo_ca_plane
# with different parameters).
STAGE_LISTINGS = {
    "cost": "$paramod\\stereo_cost\\NDISP=s32'00000000000000000000000000000100/clk\n",
    "aggregate": "$paramod$bb\\stereo_aggregate/clk\n",
    "ca_rule1": "$paramod$dd\\stereo_ca_plane/clk\n",
    "ca_rule2": "$paramod$de\\stereo_ca_plane/clk\n",
    "wta": "$paramod$ee\\stereo_wta/clk\n",
    "validate": "$paramod$ef\\stereo_validate/clk\n",
    "lr_check": "$paramod$eg\\stereo_lr_check/clk\n",
}


class StatParsing(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.stat = Path(self.folder.name) / "stat.json"
        self.stat.write_text(STAT_WITH_LISTING)

    def tearDown(self):
        self.folder.cleanup()

    def test_interleaved_listing_is_dropped(self):
        data = synth.load_stat_json(self.stat)
        self.assertIn("design", data)
        self.assertEqual(len(data["modules"]), 10)

    def test_hierarchy_totals_multiply_instances(self):
        modules = synth.load_stat_json(self.stat)["modules"]
        totals = synth.hierarchy_totals(modules)
        # aggregate: 10 LUT6 + 4 DSP + 2 line buffers x (3 RAMB18 + 1 LUT3)
        self.assertEqual(totals["$paramod$bb\\stereo_aggregate"],
                         {"LUT6": 10, "DSP48E1": 4, "RAMB18E1": 6, "LUT3": 2})
        # the top: its own 5 IBUF + 3 LUT2 and everything below
        top = totals["\\stereo_synth_top"]
        self.assertEqual(top, synth.load_stat_json(self.stat)["design"]["num_cells_by_type"])

    def test_module_without_parameters_is_found_by_its_instances(self):
        # Yosys lists it as "\\stereo_coord_reg", its instances' type as "stereo_coord_reg".
        modules = {"$paramod$dd\\stereo_wta": {"num_cells_by_type": {"stereo_coord_reg": 2,
                                                                      "LUT4": 1}},
                   "\\stereo_coord_reg": {"num_cells_by_type": {"FF": 32}}}
        totals = synth.hierarchy_totals(modules)
        self.assertEqual(totals["$paramod$dd\\stereo_wta"], {"FF": 64, "LUT4": 1})

    def test_stage_modules_from_the_instance_listings(self):
        # What stage_module_query writes: `<module>/clk`, or a warning when nothing matched. A
        # module without parameters is listed with a leading backslash, which is dropped (as
        # stage_breakdown drops it from the `stat` names).
        listings = dict(STAGE_LISTINGS, wta="\\stereo_wta/clk\n")
        self.assertEqual(synth.stage_modules(listings), {
            "$paramod\\stereo_cost\\NDISP=s32'00000000000000000000000000000100": "cost",
            "$paramod$bb\\stereo_aggregate": "aggregate",
            "$paramod$dd\\stereo_ca_plane": "ca_rule1",
            "$paramod$de\\stereo_ca_plane": "ca_rule2",
            "stereo_wta": "wta",
            "$paramod$ef\\stereo_validate": "validate",
            "$paramod$eg\\stereo_lr_check": "lr_check"})
        listings["wta"] = 'Warning: Selection "*stereo_top/wta" did not match any object.\n'
        with self.assertRaises(synth.ReportError):
            synth.stage_modules(listings)

    def test_stage_breakdown_adds_up(self):
        stages = synth.stage_breakdown(self.stat, synth.stage_modules(STAGE_LISTINGS))
        xilinx = {name: synth.resources_xilinx(cells) for name, cells in stages.items()}
        self.assertEqual(xilinx["aggregate"]["luts"], 12)
        self.assertEqual(xilinx["aggregate"]["ramb18"], 6)
        self.assertEqual(xilinx["aggregate"]["brams"], 3.0)  # 36 Kib equivalents
        self.assertEqual(xilinx["aggregate"]["bram_kbits"], 108)
        self.assertEqual(xilinx["cost"]["luts"], 20)
        # glue = the two tops' own cells: 3 LUT2 + 5 IBUF + 7 FDRE
        self.assertEqual(xilinx["glue"]["luts"], 3)
        self.assertEqual(xilinx["glue"]["ffs"], 7)
        report = {"resources": synth.resources_xilinx(synth.read_stat_json(self.stat)),
                  "stages": xilinx}
        synth.check_stages(report)  # 3 + 12 + 20 + 1 + 1 + 0 = 37 LUTs both ways
        self.assertEqual(report["resources"]["luts"], 37)
        report["stages"]["wta"]["luts"] += 1
        with self.assertRaises(synth.ReportError):
            synth.check_stages(report)


class Throughput(unittest.TestCase):
    def test_cycles_per_frame(self):
        # 640x480, R = 5, N = 64: the pipeline latency (R + 2) W + R + 11 + N (stage_table.hpp)
        # is 7 * 640 + 5 + 11 + 64 = 4560 steps, so 307200 + 4560 = 311760 cycles; at 100 MHz
        # 320.76 fps, and 640 * 480 * 64 * 100e6 / 311760 / 1e6 = 6306.4 M disparity
        # evaluations/s.
        fps, mdes = synth.throughput({"width": 640, "height": 480, "ndisp": 64, "window": 11},
                                     100.0)
        self.assertEqual(fps, 320.76)
        self.assertEqual(mdes, 6306.4)
        self.assertEqual(synth.throughput({"width": 1, "height": 1, "ndisp": 1, "window": 1},
                                          None), (None, None))

    def test_lanes_divide_the_frame_rate(self):
        # LANES = 8 of 64 labels: 8 clocks per pixel step, 311760 * 8 cycles per frame.
        fps, mdes = synth.throughput({"width": 640, "height": 480, "ndisp": 64, "window": 11,
                                      "lanes": 8}, 100.0)
        self.assertEqual(fps, 40.09)
        self.assertEqual(mdes, 788.3)
        with self.assertRaises(synth.ReportError):
            synth.config_from_args(type("Args", (), {"width": 64, "height": 48, "ndisp": 6,
                                                     "window": 5, "lanes": 4})())

    def test_nextpnr_log(self):
        log = ("Info: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 20.00 MHz (PASS at 12 MHz)\n"
               "Info: Critical path report for clock 'clk$SB_IO_IN_$glb_clk' (posedge -> posedge):\n"
               "Info: curr total\n"
               "Info:  1.0  1.0  Source a.q\n"
               "Info: 0.5 ns logic, 0.5 ns routing\n"
               "Info: Critical path report for cross-domain path '<async>' -> '<async>':\n"
               "Info:  0.4  0.4  Source b.q\n"
               "Info: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 23.40 MHz (PASS at 12 MHz)\n")
        fmax, critical = synth.parse_nextpnr_log(log)
        self.assertEqual(fmax, 23.40)
        self.assertEqual(critical, [" curr total", "  1.0  1.0  Source a.q",
                                    " 0.5 ns logic, 0.5 ns routing"])


SVG = "{http://www.w3.org/2000/svg}"


# The plots need matplotlib; the rest of synth.py, and these tests of it, do not.
needs_matplotlib = unittest.skipUnless(importlib.util.find_spec("matplotlib"),
                                       "the plots need matplotlib (python3-matplotlib)")


def read_svg_texts(element):
    """The texts in an SVG element (one <text> a line of text)."""
    return ["".join(node.itertext()).strip() for node in element.iter(SVG + "text")]


def read_svg(path):
    """The root of an SVG that synth.py wrote, and its texts."""
    root = ElementTree.parse(path).getroot()
    return root, read_svg_texts(root)


def groups(root, pattern):
    """{id: <g>} of the groups whose id matches pattern: the gids synth.py gives its lines and
    bars."""
    return {g.get("id"): g for g in root.iter(SVG + "g") if re.fullmatch(pattern, g.get("id", ""))}


def markers(line):
    """The points of a line: one marker (a <use> of the marker shape) each."""
    return len(list(line.iter(SVG + "use")))


def path_top(bar):
    """The smallest y (the top, SVG y grows downwards) of a bar's outline."""
    d = next(bar.iter(SVG + "path")).get("d")
    return min(float(y) for y in re.findall(r"[ML] [-\d.]+ ([-\d.]+)", d))


def thousands(texts):
    """The texts that are numbers of four or more digits (with separators or without)."""
    return [t for t in texts if re.fullmatch(r"\d[\d,]{3,}", t)]


class Plots(unittest.TestCase):
    def sweep_point(self, target, ndisp, window, width, luts):
        # every stage (and the glue) an equal share, so the stacked total is the point's LUTs
        count = len(synth.STAGE_COLOURS)
        stages = {name: {"luts": luts / count, "ffs": 1, "bram_kbits": 18, "dsps": 0}
                  for name in synth.STAGE_COLOURS}
        return {"target": target, "use_dsp": True,
                "config": {"width": width, "height": width * 3 // 4, "ndisp": ndisp,
                           "window": window},
                "resources": {"luts": luts, "ffs": 6, "brams": 6, "dsps": 0}, "stages": stages}

    def plot(self, folder):
        points = [self.sweep_point(t, n, 11, 640, 1000 * n) for t in ("xilinx", "ecp5")
                  for n in (8, 16)]
        points.append(self.sweep_point("xilinx", 16, 3, 640, 500))
        sweep = Path(folder) / "sweep.json"
        sweep.write_text(json.dumps({"points": points}))
        synth.command_plot(SimpleNamespace(sweep=str(sweep), out_dir=folder))

    @needs_matplotlib
    def test_scaling_plot(self):
        with tempfile.TemporaryDirectory() as folder:
            self.plot(folder)
            svg, texts = read_svg(Path(folder) / "synth_scaling.svg")
        lines = groups(svg, r"(ndisp|window|width)-\w+-(xilinx|ecp5)")
        # One line per target and metric on each axis, all three axes holding both targets
        # (the window axis: xilinx at 3 and 11, ecp5 at 11 only): 3 x 2 x 4 lines.
        self.assertEqual(len(lines), 24)
        self.assertEqual(markers(lines["window-luts-xilinx"]), 2)
        self.assertEqual(markers(lines["window-luts-ecp5"]), 1)
        # points per metric: 2 + 2 on the disparity axis, 2 + 1 on the window's, 1 + 1 on width's
        self.assertEqual(sum(markers(line) for line in lines.values()), 9 * 4)
        self.assertIn("Yosys resource estimates of stereo_synth_top, one parameter at a time "
                      "around 640x480, 16 disparities, 11x11 window", texts)
        for text in ("7-series", "ECP5", "LUTs", "block RAM (Kib)", "DSPs",
                     "disparities (640x480, 11x11)"):
            self.assertIn(text, texts)
        # LUTs up to 16,000: tick labels with thousands separators
        self.assertTrue(thousands(texts))
        self.assertEqual([t for t in thousands(texts) if "," not in t], [])

    @needs_matplotlib
    def test_stage_plots(self):
        with tempfile.TemporaryDirectory() as folder:
            self.plot(folder)
            # every target with per-stage figures gets its stage plots
            for target in ("xilinx", "ecp5"):
                for metric in ("luts", "ffs", "bram_kbits", "dsps"):
                    read_svg(Path(folder) / f"synth_stages_{target}_{metric}.svg")
            svg, texts = read_svg(Path(folder) / "synth_stages_xilinx_luts.svg")
        stages = "|".join(synth.STAGE_COLOURS)
        bars = groups(svg, rf"({stages})-(8|16)")
        self.assertEqual(len(bars), 2 * len(synth.STAGE_COLOURS))
        # stacked in pipeline order: the first stage at the bottom
        first, second = list(synth.STAGE_COLOURS)[:2]
        self.assertGreater(path_top(bars[f"{first}-16"]), path_top(bars[f"{second}-16"]))
        self.assertIn("Xilinx 7-series: LUTs by pipeline stage, 640x480, 11x11 window", texts)
        for stage in synth.STAGE_COLOURS:
            self.assertIn(stage, texts)
        # the totals above the bars: the stages' equal shares of 16,000 LUTs at 16 disparities,
        # and of 8,000 at 8
        totals = groups(svg, r"total-\d+")
        self.assertEqual({key: read_svg_texts(group) for key, group in totals.items()},
                         {"total-8": ["8,000"], "total-16": ["16,000"]})

    @needs_matplotlib
    def test_same_sweep_same_file(self):
        with tempfile.TemporaryDirectory() as one, tempfile.TemporaryDirectory() as two:
            self.plot(one)
            self.plot(two)
            for name in ("synth_scaling.svg", "synth_stages_ecp5_luts.svg"):
                self.assertEqual((Path(one) / name).read_bytes(), (Path(two) / name).read_bytes())

    def test_missing_matplotlib_is_a_report_error(self):
        with mock.patch.dict(sys.modules, {"matplotlib": None}):  # None: import fails
            with self.assertRaisesRegex(synth.ReportError, "matplotlib"):
                synth.plot_scaling([])

    def test_bram_kbits_of_old_reports(self):
        # bram_kbits is filled in for reports written before it existed (18 Kib per ECP5 BRAM)
        self.assertEqual(synth.with_bram_kbits({"brams": 6}, "ecp5")["bram_kbits"], 108)

    def test_empty_sweep_is_an_error(self):
        with tempfile.TemporaryDirectory() as folder:
            sweep = Path(folder) / "sweep.json"
            sweep.write_text(json.dumps({"points": []}))
            with self.assertRaises(synth.ReportError):
                synth.command_plot(SimpleNamespace(sweep=str(sweep), out_dir=folder))


class LanePlots(unittest.TestCase):
    def test_lane_points(self):
        self.assertEqual(synth.parse_lane_points("16:1,64:8"), [(16, 1), (64, 8)])
        for bad in ("16:3", "16", "a:b", "0:1"):
            with self.assertRaises(synth.ReportError):
                synth.parse_lane_points(bad)

    @needs_matplotlib
    def test_one_line_per_lane_count_and_metric(self):
        def point(ndisp, lanes):
            return {"target": "xilinx",
                    "config": {"width": 640, "height": 480, "ndisp": ndisp, "window": 11,
                               "lanes": lanes},
                    "resources": {"luts": 100 * lanes + ndisp, "ffs": 1, "bram_kbits": 18,
                                  "dsps": 0}}
        # all parallel (16:16, 32:32), LANES 4 (16:4, 32:4), LANES 1 (16:1): three lines a metric
        points = [point(16, 16), point(32, 32), point(16, 4), point(32, 4), point(16, 1)]
        with tempfile.TemporaryDirectory() as folder:
            sweep = Path(folder) / "lanes.json"
            sweep.write_text(json.dumps({"points": points}))
            synth.command_plot_lanes(SimpleNamespace(sweep=str(sweep), out_dir=folder))
            svg, texts = read_svg(Path(folder) / "synth_lanes_xilinx.svg")
        lines = groups(svg, r"lanes-(all|\d+)-\w+")
        self.assertEqual(len(lines), 3 * len(synth.PLOT_METRICS))
        # the lines pass through the five points in all
        self.assertEqual(sum(markers(line) for line in lines.values()),
                         5 * len(synth.PLOT_METRICS))
        self.assertEqual(markers(lines["lanes-4-luts"]), 2)
        self.assertEqual(markers(lines["lanes-1-dsps"]), 1)
        for text in ("LANES = NDISP (1 clock per pixel)", "LANES = 4 (NDISP / 4 clocks per pixel)",
                     "LANES = 1 (NDISP clocks per pixel)", "LUTs", "disparities (NDISP)"):
            self.assertIn(text, texts)
        self.assertTrue(any("640x480, 11x11 window" in text for text in texts))
        # LUTs up to 3,232: separators in the tick labels
        self.assertIn("3,000", texts)


class Tables(unittest.TestCase):
    @staticmethod
    def point(ndisp, luts, dsps, use_dsp):
        resources = {"luts": luts, "ffs": 1000, "carries": 10, "bram_kbits": 10008, "dsps": dsps}
        return {"target": "xilinx", "use_dsp": use_dsp,
                "config": {"width": 640, "height": 480, "ndisp": ndisp, "window": 11},
                "resources": resources,
                "stages": {"aggregate": dict(resources)}}

    def test_sweep_and_single_estimate_report(self):
        with tempfile.TemporaryDirectory() as folder:
            sweep, single, out = (Path(folder) / n for n in ("s.json", "e.json", "t.md"))
            sweep.write_text(json.dumps({"points": [self.point(16, 23000, 224, True),
                                                     self.point(64, 88948, 896, True)]}))
            single.write_text(json.dumps(self.point(64, 182680, 0, False)))
            synth.command_table(SimpleNamespace(sweeps=[str(sweep), str(single)], clock=100,
                                                out=str(out)))
            text = out.read_text()
            rows = [line for line in text.splitlines() if line.startswith("| xilinx ")
                    and "stage" not in line and "W x H" not in line]
            self.assertEqual(len(rows), 3)
            # DSP points first; 182,680 LUTs and no DSP fit the XC7K325T (203,800 LUTs).
            self.assertTrue(rows[0].startswith("| xilinx | 640 x 480 | 16 |"))
            self.assertIn("| xilinx (no DSP) | 640 x 480 | 64 |", rows[2])
            self.assertIn("| XC7K325T |", rows[2])
            # By hand: 640*480 + 7*640 + 5 + 11 + 64 = 311,760 cycles; 1e8 / 311,760 = 320.76
            # fps; 320.76 * 640 * 480 * 64 / 1e6 = 6,306.4 M disparity evaluations/s.
            self.assertTrue(rows[2].endswith("| 321 | 6,306 |"))
            # The stage split is the DSP point's where both variants of a configuration exist.
            self.assertIn("| xilinx 640x480 / 64 / 11x11: stage |", text)
            self.assertIn("| aggregate | 88,948 (100 %) |", text)

    def test_other_json_is_an_error(self):
        with tempfile.TemporaryDirectory() as folder:
            report = Path(folder) / "ice40.json"
            report.write_text(json.dumps({"target": "ice40", "resources": {}}))
            with self.assertRaises(synth.ReportError):
                synth.estimate_points(str(report))


class Devices(unittest.TestCase):
    def test_smallest_device(self):
        fits_a35 = {"luts": 20800, "ffs": 100, "bram_kbits": 1800, "dsps": 90}
        self.assertEqual(synth.smallest_device("xilinx", fits_a35), "XC7A35T")
        # one DSP too many for the 35T and the 100T's 240: the 200T
        self.assertEqual(synth.smallest_device("xilinx", dict(fits_a35, dsps=241)), "XC7A200T")
        self.assertEqual(synth.smallest_device("ecp5", dict(fits_a35, bram_kbits=3745)), None)


class Configs(unittest.TestCase):
    def test_cost_and_shift_add_reach_chparam(self):
        args = SimpleNamespace(width=64, height=48, ndisp=8, window=7, lanes=2, cost="census",
                               shift_add="narrow", command="estimate")
        config = synth.config_from_args(args)
        self.assertEqual((config["cost"], config["shift_add"]), ("census", "narrow"))
        command = synth.chparam(config)
        self.assertIn("-set COST 2 ", command)  # fx_pkg COST_CENSUS
        self.assertIn("-set SHIFT_ADD 1 ", command)
        # Without them the report keeps its old shape and the RTL's defaults apply.
        plain = synth.config_from_args(SimpleNamespace(width=64, height=48, ndisp=8, window=7))
        self.assertNotIn("cost", plain)
        self.assertNotIn("COST", synth.chparam(plain))
        # The census stage adds 2W + 4 = 132 steps to (R + 2) W + R + 11 + N:
        # (3072 + 5 * 64 + 3 + 11 + 8 + 132) * 4 clocks.
        fps, _ = synth.throughput(dict(config, lanes=2), 100.0)
        self.assertEqual(fps, round(100e6 / ((3072 + 5 * 64 + 3 + 11 + 8 + 132) * 4), 2))

    def test_board_refuses_core_options(self):
        for extra in ({"cost": "census"}, {"shift_add": "all"}):
            args = SimpleNamespace(width=32, height=24, ndisp=1, window=3, command="board", **extra)
            with self.assertRaises(synth.ReportError, msg=str(extra)):
                synth.config_from_args(args)

    def test_impossible_configurations(self):
        for bad in ({"window": 4}, {"window": 33}, {"ndisp": 0}, {"ndisp": 257}, {"width": 0}):
            args = SimpleNamespace(**dict({"width": 64, "height": 48, "ndisp": 4, "window": 5},
                                          **bad))
            with self.assertRaises(synth.ReportError, msg=str(bad)):
                synth.config_from_args(args)


# An RTLIL `dump` of three $mul cells as Yosys writes it (the connections elided).
MUL_DUMP = """
  attribute \\src "rtl/a.sv:1"
  cell $mul $flatten\\core.$mul$a
    parameter \\A_SIGNED 0
    parameter \\A_WIDTH 14
    parameter \\B_SIGNED 0
    parameter \\B_WIDTH 17
    parameter \\Y_WIDTH 31
    connect \\A \\x
  end
  cell $mul $flatten\\core.$mul$b
    parameter \\A_WIDTH 20
    parameter \\B_WIDTH 4
    parameter \\Y_WIDTH 24
  end
  cell $mul $flatten\\core.$mul$c
    parameter \\A_WIDTH 8
    parameter \\B_WIDTH 2
    parameter \\Y_WIDTH 10
  end
"""


class Board(unittest.TestCase):
    def test_mul_dump(self):
        self.assertEqual(synth.parse_mul_dump(MUL_DUMP), [(14, 17, 31), (20, 4, 24), (8, 2, 10)])

    def test_dsp_selection(self):
        muls = synth.parse_mul_dump(MUL_DUMP)
        # 14x17 needs 1 * 2 blocks of 16x16, 20x4 needs 2 * 1; the 10-bit product stays in LUTs.
        self.assertEqual(synth.dsp_selection(muls, 4), 24)
        self.assertEqual(synth.dsp_selection(muls, 3), 31)
        self.assertEqual(synth.dsp_selection(muls, 2), 31)
        self.assertIsNone(synth.dsp_selection(muls, 1))

    def test_uart_frame_rate(self):
        # 8x4, window 3, 1 label: 32 pixels of 6 bytes, a 2-byte command, and the pipeline's
        # tail: (1 + 2) * 8 + 1 + 11 + 1 = 37 beats, more than the 32 pixels, so 32 of 4 bytes.
        # (2 + 192 + 128) bytes * 10 bits at 9600 baud: 9600 / 3220 frames per second.
        config = {"width": 8, "height": 4, "ndisp": 1, "window": 3}
        self.assertAlmostEqual(synth.board_uart_fps(config, 9600), round(9600 / 3220, 3))

    def board_report(self, **fields):
        report = {"target": "ice40_board", "board": "icebreaker", "device": "up5k",
                  "config": {"width": 16, "height": 8, "ndisp": 1, "window": 1},
                  "resources": {"luts": 4000, "ffs": 1500, "brams": 4, "dsps": 0},
                  "fits_after_synthesis": True, "placed": False, "fmax_mhz": None, "bin": None,
                  "bin_bytes": None, "baud": 115385, "uart_frames_per_second": 1.0,
                  "tools": {}, "pnr_error": "ERROR: Failed to expand region",
                  "logic_cells": 7000, "logic_cells_capacity": 5280}
        report.update(fields)
        return report

    def check(self, report, expect_placed=False):
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "board.json"
            path.write_text(json.dumps(report))
            synth.command_check(SimpleNamespace(report=str(path), expect_bram=False,
                                                expect_placed=expect_placed))

    def test_unplaced_report_must_say_why(self):
        self.check(self.board_report())
        with self.assertRaises(synth.ReportError):
            self.check(self.board_report(pnr_error=None))
        with self.assertRaises(synth.ReportError):
            self.check(self.board_report(logic_cells=5000))
        with self.assertRaises(synth.ReportError):
            self.check(self.board_report(fmax_mhz=20.0))
        with self.assertRaises(synth.ReportError):
            self.check(self.board_report(), expect_placed=True)

    def test_link_test_report_has_no_config(self):
        with tempfile.TemporaryDirectory() as folder:
            binary = Path(folder) / "echo.bin"
            binary.write_bytes(b"\xff" * 10)
            echo = self.board_report(top=synth.ECHO_TOP, config=None, placed=True, fmax_mhz=70.0,
                                     bin=str(binary), bin_bytes=10, pnr_error=None,
                                     uart_frames_per_second=None)
            self.check(echo, expect_placed=True)
            with self.assertRaises(synth.ReportError):
                self.check(dict(echo, config={"width": 1}), expect_placed=True)

    def test_placed_report_needs_its_bitstream(self):
        with tempfile.TemporaryDirectory() as folder:
            binary = Path(folder) / "board.bin"
            binary.write_bytes(b"\xff" * 100)
            config = {"width": 16, "height": 8, "ndisp": 1, "window": 1}
            placed = self.board_report(placed=True, fmax_mhz=25.0, bin=str(binary),
                                       bin_bytes=100, pnr_error=None, config=config,
                                       uart_frames_per_second=synth.board_uart_fps(config,
                                                                                   115385))
            self.check(placed, expect_placed=True)
            with self.assertRaises(synth.ReportError):
                self.check(dict(placed, bin_bytes=99), expect_placed=True)


# A Yosys JSON netlist (the fields logic_depth reads): a register feeds LUT a, which feeds a carry
# cell and LUT b; b and the carry feed LUT c, which feeds a register. Longest path by hand:
# a -> b -> c, three LUT levels, with one carry cell beside it on the path a -> carry -> c.
def _cell(kind, inputs, outputs):
    connections = {f"I{i}": [bit] for i, bit in enumerate(inputs)}
    connections.update({f"O{i}": [bit] for i, bit in enumerate(outputs)})
    directions = {f"I{i}": "input" for i in range(len(inputs))}
    directions.update({f"O{i}": "output" for i in range(len(outputs))})
    return {"type": kind, "connections": connections, "port_directions": directions}


NETLIST = {"modules": {"top": {"attributes": {"top": 1}, "cells": {
    "q0": _cell("FDRE", [10], [2]),
    "a": _cell("LUT2", [2, 3], [4]),
    "carry": _cell("CARRY4", [4], [5]),
    "b": _cell("LUT3", [4, 2, 3], [6]),
    "c": _cell("LUT4", [6, 5, 2, 3], [7]),
    "q1": _cell("FDRE", [7], [10]),
}}}}


class LogicDepth(unittest.TestCase):
    def test_longest_register_to_register_path(self):
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "netlist.json"
            path.write_text(json.dumps(NETLIST))
            self.assertEqual(synth.logic_depth(path, "xilinx"),
                             {"lut_levels": 3, "carry_cells": 0, "path": ["a", "b", "c"]})
            # Without LUT b the deepest path is a -> carry -> c: two levels and one carry.
            del NETLIST["modules"]["top"]["cells"]["b"]
            path.write_text(json.dumps(NETLIST))
            self.assertEqual(synth.logic_depth(path, "xilinx"),
                             {"lut_levels": 2, "carry_cells": 1, "path": ["a", "carry", "c"]})


class LogicDelay(unittest.TestCase):
    """synth.logic_delay: Yosys `sta` over the 7-series cell models, on two small netlists made
    here (a 16-bit addition and a 16 x 16 product between registers, no pipeline register in the
    multiplier), and the parser on a log excerpt written by hand."""
    # The result passes a LUT before its register, so the DSP block keeps no output register.
    DESIGN = """module t(input wire clk, input wire [15:0] a, input wire [15:0] b,
                       output reg [31:0] q, output reg [15:0] r);
  reg [15:0] ra, rb;
  always @(posedge clk) begin ra <= a; rb <= b; q <= (ra %s rb) ^ {rb, ra}; r <= ra ^ rb; end
endmodule"""

    def delay_of(self, operator, folder):
        design, netlist = Path(folder) / f"t{len(operator)}.v", Path(folder) / "t.json"
        design.write_text(self.DESIGN % operator)
        synth.run_yosys(f"read_verilog {design}; synth_xilinx -flatten -top t; "
                        f"write_json {netlist}", Path(folder) / "yosys.log")
        return synth.logic_delay(netlist, "xilinx", Path(folder) / "sta.log")

    def test_a_product_outlasts_an_addition_and_crosses_a_dsp_block(self):
        with tempfile.TemporaryDirectory() as folder, \
                contextlib.redirect_stderr(io.StringIO()):
            addition, product = self.delay_of("+", folder), self.delay_of("*", folder)
        self.assertIsNotNone(addition)
        self.assertIsNotNone(product)
        self.assertIn("CARRY4", addition["cells"])
        self.assertNotIn("DSP48E1", addition["cells"])
        self.assertIn("DSP48E1", product["cells"])
        # The models' DSP48E1 product takes about 3 ns; the 16-bit carry chain far less (2.0 and
        # 3.3 ns measured with Yosys 0.23).
        self.assertGreater(product["ns"], addition["ns"] + 1.0)
        self.assertEqual(sum(product["cells"].values()), len(product["path"]))

    def test_parse(self):
        text = """Latest arrival time in 'top' is 2134:
    2134 lut_b (LUT3.I0->O)
           net_c
    1727 carry (CARRY4.CI->O)
           net_b
     399 reg (FDRE.C->Q)
           clk

Arrival histogram:"""
        self.assertEqual(synth.parse_sta(text), {"ps": 2134, "cells": [
            (399, "FDRE", "C->Q"), (1727, "CARRY4", "CI->O"), (2134, "LUT3", "I0->O")]})
        self.assertIsNone(synth.parse_sta("no timing here"))
        self.assertIsNone(synth.logic_delay("unused.json", "ice40", "unused.log"))


class Boards(unittest.TestCase):
    """synth.py boards: the largest report within 85 % of every resource of a board."""

    @staticmethod
    def estimate(ndisp, luts, brams, dsps=0, ffs=1000, lanes=None):
        config = {"width": 640, "height": 480, "ndisp": ndisp, "window": 11}
        if lanes:
            config["lanes"] = lanes
        return {"target": "xilinx", "config": config,
                "resources": {"luts": luts, "lut_sites": luts, "ffs": ffs, "brams": brams,
                              "dsps": dsps},
                "logic_depth": {"lut_levels": 7, "carry_cells": 4}}

    def run_boards(self, reports, *arguments):
        with tempfile.TemporaryDirectory() as folder:
            for name, report in reports.items():
                (Path(folder) / name).write_text(json.dumps(report))
            out = Path(folder) / "boards.out"
            args = SimpleNamespace(board=list(arguments) or None, reports=[folder], min_fps=30.0,
                                   out=str(out), markdown=None)
            synth.command_boards(args)
            return json.loads(out.read_text())

    def test_largest_that_fits_85_percent(self):
        # XC7A35T: 85 % of 20,800 LUTs is 17,680, of 50 RAMB36 42.5. 64 labels at 17,000 LUTs and
        # 43 blocks is over (43 > 42.5); 32 labels at 17,680 LUTs and 42.5 blocks is exactly on
        # the budget, so it is the largest that fits. At 100 MHz and 4 clocks per step
        # (32 / 8) it runs 100e6 / (4 * (640*480 + 7*640 + 5 + 11 + 32)) = 80.20 frames/s.
        result = self.run_boards({"a.json": self.estimate(64, 17000, 43, lanes=8),
                                  "b.json": self.estimate(32, 17680, 42.5, lanes=8),
                                  "c.json": self.estimate(16, 9000, 20, lanes=4)}, "basys3")
        best = result["boards"]["basys3"]["largest"]
        self.assertEqual(best["report"], "b.json")
        self.assertEqual(best["frames_per_second"], round(100e6 / (4 * 311728), 2))
        self.assertEqual(best["usage"]["luts"]["percent"], 85.0)
        self.assertEqual(best["logic_depth"]["lut_levels"], 7)

    def test_too_slow_is_not_a_candidate(self):
        # 64 labels one per clock: 64 * 311,695 clocks a frame, 5.01 frames/s at 100 MHz, below 30.
        result = self.run_boards({"slow.json": self.estimate(64, 5000, 10, lanes=1),
                                  "ok.json": self.estimate(16, 5000, 10, lanes=4)}, "basys3")
        self.assertEqual(result["boards"]["basys3"]["largest"]["report"], "ok.json")

    def test_unknown_board_and_nothing_fits(self):
        with self.assertRaisesRegex(synth.ReportError, "unknown board 'zedboard'"):
            self.run_boards({"a.json": self.estimate(16, 5000, 10)}, "zedboard")
        with self.assertRaisesRegex(synth.ReportError, "no measured configuration fits basys3"):
            self.run_boards({"a.json": self.estimate(16, 20000, 10, lanes=4)}, "basys3")
        # An ECP5 report says nothing about a 7-series board.
        ecp5 = dict(self.estimate(16, 5000, 10, lanes=4), target="ecp5")
        with self.assertRaisesRegex(synth.ReportError, "no measured configuration fits"):
            self.run_boards({"a.json": ecp5}, "arty-a7-35t")


class LeanReport(unittest.TestCase):
    """The checked-in 7-series estimate of the lean VGA core (docs/synthesis.md "Lean memory"):
    its fields, and its block RAM against the memory formulas of docs/rtl.md."""
    REPORT = (Path(__file__).resolve().parents[2] / "docs" / "figures" / "synthesis" / "boards" /
              "xilinx_640x480_64_11x11_lanes8_census_lean.json")

    def test_block_ram_follows_the_formulas(self):
        report = json.loads(self.REPORT.read_text())
        config = report["config"]
        self.assertEqual((config["width"], config["ndisp"], config["window"], config["cost"],
                          config["recompute_costs"]), (640, 64, 11, "census", 1))
        for key in ("luts", "lut_sites", "ffs", "brams", "dsps"):
            self.assertGreater(report["resources"][key], 0, key)
        self.assertGreater(report["logic_depth"]["lut_levels"], 0)
        stages = report["stages"]
        # The aggregation keeps no rows: its per-label line buffer is gone.
        self.assertEqual(stages["aggregate"]["brams"], 0)
        # The cost stage's rows of codes: W (WINDOW - 1) 48 bits, a 480-bit word per column, 640
        # deep: one RAMB18 is 1024 x 18 deep enough, so ceil(480 / 18) = 27 of them.
        self.assertEqual(stages["cost"]["ramb18"], -(-10 * 48 // 18))
        # Each CA window: 2 W NDISP 14 bits = 1,120 Kib at least, whatever the packing.
        for rule in ("ca_rule1", "ca_rule2"):
            self.assertGreaterEqual(stages[rule]["bram_kbits"], 2 * 640 * 64 * 14 / 1024)


class Progress(unittest.TestCase):
    """The pass names of the progress lines, from Yosys log lines written by hand (Yosys 0.23's
    format: a section number, "Executing", the pass, "pass", a description)."""

    def test_pass_lines(self):
        self.assertEqual(synth.pass_of("3. Executing SYNTH_XILINX pass."), ("3", "SYNTH_XILINX"))
        self.assertEqual(synth.pass_of("3.47.2. Executing ABC pass (technology mapping using ABC)."),
                         ("3.47.2", "ABC"))
        self.assertEqual(synth.pass_of("1. Executing Verilog-2005 frontend: rtl/fx_pkg.sv"),
                         ("1", "Verilog-2005"))
        self.assertIsNone(synth.pass_of("Executing ABC pass."))  # no section number
        self.assertIsNone(synth.pass_of("  3.1. Executing HIERARCHY pass."))  # not at the start
        self.assertIsNone(synth.pass_of("Number of cells: 12"))



def fake_point(job):
    """What an estimate of `job` could report: numbers that differ from point to point."""
    c = job["config"]
    return {"target": job["target"], "top": job["top"], "config": c, "use_dsp": job["use_dsp"],
            "resources": {"luts": c["width"] * c["ndisp"] + 7 * c.get("lanes", 0),
                          "ffs": c["window"], "brams": 0.5, "dsps": 0},
            "yosys_seconds": 1.0}


class Tops(unittest.TestCase):
    """estimate --top: stereo_synth_top (synth) or stereo_axil_top (axil)."""

    def test_names(self):
        self.assertEqual(synth.resolve_top("axil"), "stereo_axil_top")
        self.assertEqual(synth.resolve_top("stereo_axil_top"), "stereo_axil_top")
        self.assertEqual(synth.resolve_top("synth"), "stereo_synth_top")
        for bad in ("stereo_top", "AXIL", "", "stereo_board_top"):
            with self.assertRaises(synth.ReportError, msg=bad):
                synth.resolve_top(bad)

    def test_chparam_names_the_top_and_its_kernel(self):
        config = synth.config_from_args(SimpleNamespace(width=64, height=48, ndisp=16, window=5,
                                                        lanes=4, cost="census",
                                                        constant_kernel=True))
        self.assertEqual(config["runtime_kernel"], 0)
        command = synth.chparam(config, top="stereo_axil_top")
        self.assertTrue(command.endswith(" stereo_axil_top"))
        self.assertIn("-set RUNTIME_KERNEL 0 ", command)
        self.assertIn("-set LANES 4 ", command)
        # Without --constant-kernel nothing is set: stereo_axil_top's default, the run-time one.
        del config["runtime_kernel"]
        self.assertNotIn("RUNTIME_KERNEL", synth.chparam(config, top="stereo_axil_top"))

    def test_parameters_a_top_lacks_are_refused(self):
        axil, top = "stereo_axil_top", "stereo_synth_top"
        for name, config, target in ((axil, {"ring_block_min_fill": 60}, "xilinx"),
                                     (axil, {"asw": 1}, "xilinx"),
                                     (axil, {}, "ice40"),
                                     (axil, {"shift_add": "all"}, "xilinx"),
                                     (top, {"runtime_kernel": 0}, "xilinx")):
            with self.assertRaises(synth.ReportError, msg=f"{name} {config} {target}"):
                synth.check_top_config(name, config, target)
        synth.check_top_config(axil, {"shift_add": "all", "runtime_kernel": 0}, "ecp5")
        synth.check_top_config(top, {"shift_add": "all", "asw": 1}, "ice40")

    def test_axi_registers_are_a_stage_of_their_own(self):
        with tempfile.TemporaryDirectory() as folder:
            stat = Path(folder) / "stat.json"
            stat.write_text(STAT_WITH_LISTING.replace("stereo_synth_top", "stereo_axil_top"))
            stages = synth.stage_breakdown(stat, synth.stage_modules(STAGE_LISTINGS),
                                           "stereo_axil_top")
        # the top's own cells (3 LUT2, 5 IBUF) apart from stereo_top's (7 FDRE, the glue)
        self.assertEqual(stages["axi_registers"], {"IBUF": 5, "LUT2": 3})
        self.assertEqual(stages["glue"], {"FDRE": 7})
        xilinx = {name: synth.resources_xilinx(cells) for name, cells in stages.items()}
        report = {"top": "stereo_axil_top", "stages": xilinx,
                  "resources": {"luts": 37, "ffs": 10, "brams": 3.0, "dsps": 4}}
        # 0 flip-flops of its own: the register file was optimized away (Yosys 0.23 and
        # `~ADDR_BITS'(3)`); 128 (three 32-bit counters and the read data) is the least.
        with self.assertRaisesRegex(synth.ReportError, "register file"):
            synth.check_stages(report)
        xilinx["axi_registers"]["ffs"] = 128
        report["resources"]["ffs"] = 10 + 128  # the stages must still add up
        synth.check_stages(report)
        del xilinx["axi_registers"]
        with self.assertRaisesRegex(synth.ReportError, "lack axi_registers"):
            synth.check_stages(report)

    def test_table_shows_both_tops(self):
        points = [dict(Tables.point(16, 9000, 20, True), top=top) for top in
                  ("stereo_axil_top", "stereo_synth_top")]
        points.append(dict(Tables.point(16, 8000, 10, True), top="stereo_axil_top"))
        points[2]["config"] = dict(points[2]["config"], runtime_kernel=0)
        with tempfile.TemporaryDirectory() as folder:
            sweep, out = Path(folder) / "s.json", Path(folder) / "t.md"
            sweep.write_text(json.dumps({"points": points}))
            synth.command_table(SimpleNamespace(sweeps=[str(sweep)], clock=100, out=str(out)))
            lines = out.read_text().splitlines()
        headers = [line for line in lines if "| W x H |" in line]
        # stereo_synth_top's table first, under the target's plain name (as before the AXI top).
        self.assertEqual([h.split(" | ")[0] for h in headers],
                         ["| xilinx", "| xilinx, stereo_axil_top"])
        axil_rows = [line for line in lines if line.startswith("| xilinx, stereo_axil_top")
                     and "W x H" not in line and "stage" not in line]
        self.assertEqual(len(axil_rows), 2)
        self.assertEqual(sum("(constant kernel)" in row for row in axil_rows), 1)
        self.assertIn("| xilinx, stereo_axil_top 640x480 / 16 / 11x11: stage |", "\n".join(lines))


class SweepPoints(unittest.TestCase):
    """--jobs N, --emit-commands and merge, with the estimates faked (no Yosys)."""

    CONFIGS = [{"width": 16, "height": 12, "ndisp": 2, "window": 3},
               {"width": 32, "height": 24, "ndisp": 4, "window": 5, "lanes": 2, "cost": "census",
                "max_min_disp": 0},
               {"width": 64, "height": 48, "ndisp": 8, "window": 7, "lanes": 1, "cost": "census",
                "recompute_costs": 1, "ring_block_min_fill": 60},
               {"width": 64, "height": 48, "ndisp": 8, "window": 7, "cost": "census", "asw": 1,
                "shift_add": "narrow"}]

    def jobs(self):
        jobs = [synth.sweep_job("xilinx", "synth", c) for c in self.CONFIGS]
        jobs.append(synth.sweep_job("ecp5", "axil", dict(self.CONFIGS[1], runtime_kernel=0,
                                                         shift_add="all"), use_dsp=False))
        return jobs

    @staticmethod
    def args(folder, name, jobs="1", emit=None):
        return SimpleNamespace(out=str(Path(folder) / f"{name}.json"), jobs=jobs,
                               emit_commands=emit, points_dir=str(Path(folder) / f"{name}_points"))

    def test_point_commands_reproduce_the_configuration(self):
        for job in self.jobs():
            command = shlex.split(synth.point_command(job, "p.json", "p"))
            self.assertEqual(command[1], str(Path(synth.__file__).resolve()))
            self.assertTrue(Path(command[0]).is_absolute() and Path(command[-1]).is_absolute())
            args = synth.build_parser().parse_args(command[2:])
            self.assertEqual(args.command, "estimate")
            self.assertEqual((args.target, synth.resolve_top(args.top), not args.no_dsp),
                             (job["target"], job["top"], job["use_dsp"]))
            self.assertEqual(synth.config_from_args(args), job["config"])
        # every configuration key an estimate records is covered by the jobs above
        covered = {key for job in self.jobs() for key in job["config"]}
        self.assertEqual(covered, set(synth.CONFIG_OPTIONS))

    def test_bad_configurations(self):
        for config in ({"width": 16, "height": 12, "ndisp": 2, "window": 4},
                       {"width": 16, "height": 12, "ndisp": 2, "window": 3, "cost": "sad"},
                       {"width": 16, "height": 12, "ndisp": 2, "window": 3, "colour": 1},
                       {"width": 16, "height": 12, "ndisp": 3, "window": 3, "lanes": 2}):
            with self.assertRaises(synth.ReportError, msg=str(config)):
                synth.sweep_job("xilinx", "synth", config)
        with self.assertRaises(synth.ReportError):
            synth.sweep_job("xilinx", "axil", dict(self.CONFIGS[0], asw=1))

    def run_in_process(self, folder, jobs):
        with mock.patch.object(synth, "estimate", lambda config, target, use_dsp, top: fake_point(
                {"target": target, "top": top, "config": config, "use_dsp": use_dsp})), \
                contextlib.redirect_stdout(io.StringIO()):
            return synth.run_sweep(jobs, self.args(folder, "in_process"))

    def test_jobs_give_the_same_json_in_the_same_order(self):
        jobs = self.jobs()

        def slow_fake(job, out, work=None):
            # The first point finishes last: the order of the file must not follow completion.
            delay = 0.15 * (len(jobs) - jobs.index(job))
            code = (f"import time; time.sleep({delay}); "
                    f"open({str(out)!r}, 'w').write({json.dumps(fake_point(job))!r})")
            return shlex.join([sys.executable, "-c", code])

        with tempfile.TemporaryDirectory() as folder:
            expected = self.run_in_process(folder, jobs)
            self.assertEqual([p["config"] for p in expected], [j["config"] for j in jobs])
            reference = Path(self.args(folder, "in_process").out).read_text()
            for n in ("2", "3", "8"):
                with mock.patch.object(synth, "point_command", slow_fake), \
                        mock.patch.object(synth, "progress", lambda message: None):
                    synth.run_sweep(jobs, self.args(folder, f"jobs{n}", jobs=n))
                self.assertEqual(Path(self.args(folder, f"jobs{n}").out).read_text(), reference,
                                 msg=f"--jobs {n}")

    def test_failed_point_fails_the_sweep(self):
        def failing(job, out, work=None):
            return shlex.join([sys.executable, "-c", "import sys; sys.exit('no yosys here')"])

        with tempfile.TemporaryDirectory() as folder, \
                mock.patch.object(synth, "point_command", failing), \
                mock.patch.object(synth, "progress", lambda message: None):
            with self.assertRaisesRegex(synth.ReportError, "point 1 failed .*no yosys here"):
                synth.run_sweep(self.jobs()[:2], self.args(folder, "failing", jobs="2"))

    def test_emitted_commands_and_merge_give_the_in_process_sweep(self):
        jobs = self.jobs()
        with tempfile.TemporaryDirectory() as folder:
            self.run_in_process(folder, jobs)
            reference = Path(self.args(folder, "in_process").out).read_text()
            args = self.args(folder, "emitted", emit=str(Path(folder) / "commands.txt"))
            with mock.patch.object(synth, "progress", lambda message: None):
                synth.run_sweep(jobs, args)
            lines = Path(args.emit_commands).read_text().splitlines()
            self.assertEqual(len(lines), len(jobs))
            self.assertFalse(Path(args.out).exists())
            # Run each "command" as a job runner would, in reverse order, faking the estimate.
            for line, job in reversed(list(zip(lines, jobs))):
                words = shlex.split(line)
                parsed = synth.build_parser().parse_args(words[2:])
                self.assertEqual(synth.config_from_args(parsed), job["config"])
                Path(parsed.out).write_text(json.dumps(fake_point(job), indent=2))
            self.assertEqual(sorted(p.name for p in Path(args.points_dir).glob("*.json")),
                             [f"point_{i:04d}.json" for i in range(1, len(jobs) + 1)])
            with mock.patch.object(synth, "progress", lambda message: None):
                synth.command_merge(SimpleNamespace(out=args.out, inputs=[args.points_dir]))
            self.assertEqual(Path(args.out).read_text(), reference)
            # Merging again adds nothing; a sweep resumed from the file emits nothing.
            with mock.patch.object(synth, "progress", lambda message: None):
                synth.command_merge(SimpleNamespace(out=args.out, inputs=[args.points_dir]))
                self.assertEqual(Path(args.out).read_text(), reference)
                synth.run_sweep(jobs, args)
            self.assertEqual(Path(args.emit_commands).read_text(), "")

    def test_merge_refuses_what_is_not_a_point_report(self):
        with tempfile.TemporaryDirectory() as folder:
            folder = Path(folder)
            good = folder / "good.json"
            good.write_text(json.dumps(fake_point(self.jobs()[0])))
            bad = {"text.json": "not json",
                   "partial.json": json.dumps({"partial": True, "command": "estimate"}),
                   "sweep.json": json.dumps({"points": [fake_point(self.jobs()[0])]}),
                   "board.json": json.dumps({"target": "ice40_board", "config": {},
                                             "resources": {}})}
            for name, text in bad.items():
                (folder / name).write_text(text)
                with self.assertRaises(synth.ReportError, msg=name):
                    synth.command_merge(SimpleNamespace(out=str(folder / "out.json"),
                                                        inputs=[str(good), str(folder / name)]))
                self.assertFalse((folder / "out.json").exists(), msg=name)
            (folder / "empty").mkdir()
            for missing in ("empty", "nothing.json"):
                with self.assertRaises(synth.ReportError, msg=missing):
                    synth.command_merge(SimpleNamespace(out=str(folder / "out.json"),
                                                        inputs=[str(folder / missing)]))

    def test_jobs_must_be_positive(self):
        for text in ("0", "-1", "two", "1.5", ""):
            with self.assertRaises(synth.ReportError, msg=text):
                synth.positive_jobs(text)
        self.assertEqual(synth.positive_jobs("3"), 3)

if __name__ == "__main__":
    unittest.main()
