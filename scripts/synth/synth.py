#!/usr/bin/python3
"""Synthesis reports for stereo_synth_top and stereo_axil_top (docs/synthesis.md).

Subcommands (each writes one JSON report; run with -h for the options):
  ice40     Yosys synth_ice40 + nextpnr-ice40 place and route: resources and Fmax.
  board     the iCEBreaker build of stereo_board_top: synth_ice40, nextpnr-ice40 on the UP5K
            with the board's pins (boards/icebreaker.pcf), icepack to a flashable .bin.
  estimate  Yosys synth_xilinx (7-series) or synth_ecp5 resource estimate, no place and route;
            --top axil: stereo_axil_top, the AXI4-Lite top with its run-time kernel.
  fit       the largest configuration that places and routes on an iCE40 device.
  sweep     estimates over a list of configurations, one JSON with every point; --jobs N at a
            time, or --emit-commands: one shell command per point for a job runner.
  merge     the point JSON of those commands into the sweep JSON.
  plot      SVG plots of a sweep (resources against each parameter, and per stage).
  table     markdown tables of sweeps and estimate reports (docs/synthesis.md).
  check     validates a report's fields (used by the ctest of label `synth`).

The plots need matplotlib (Debian package python3-matplotlib); everything else uses only the
Python standard library. Tools: yosys, nextpnr-ice40, and icepack for `board` (Debian packages
yosys, nextpnr-ice40, fpga-icestorm).
"""
import argparse
import io
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
RTL = Path(os.environ.get("STEREO_RTL_DIR", REPO / "rtl"))  # override: a snapshot
TOP = "stereo_synth_top"
# The tops `estimate` (and the sweeps) synthesize, `--top NAME` (the module or its short name):
# stereo_synth_top (the constant kernel, the configuration on ports) or stereo_axil_top (what
# integrators instantiate: the configuration and a run-time kernel in AXI4-Lite registers).
# "absent": the options that set a parameter the top does not have.
AXIL_TOP = "stereo_axil_top"
ESTIMATE_TOPS = {
    TOP: {"short": "synth", "absent": {"runtime_kernel": "--constant-kernel"}},
    AXIL_TOP: {"short": "axil", "absent": {"ring_block_min_fill": "--ring-min-fill",
                                           "asw": "--asw"}},
}


def resolve_top(name):
    """The module of an estimate top given by its name or short name."""
    for module, info in ESTIMATE_TOPS.items():
        if name in (module, info["short"]):
            return module
    raise ReportError(f"unknown top {name!r} (" + ", ".join(
        f"{module} or {info['short']}" for module, info in ESTIMATE_TOPS.items()) + ")")


def check_top_config(top, config, target):
    """Refuses the options that set a parameter `top` lacks, and the iCE40 for the AXI top (no
    RING_BLOCK_RAM: its group rings could not go to block RAM)."""
    for key, option in ESTIMATE_TOPS[top]["absent"].items():
        if key in config:
            raise ReportError(f"{top} has no parameter for {option}")
    if top == AXIL_TOP and target == "ice40":
        raise ReportError(f"{top} has no RING_BLOCK_RAM for the iCE40; estimate it for xilinx or "
                          "ecp5")
    if "shift_add" in config and config.get("runtime_kernel", 0 if top == TOP else 1):
        raise ReportError(f"--shift-add needs a constant kernel ({top}: add --constant-kernel)")


# Device capacities (vendor data sheets): logic cells, 4 Kib block RAMs, DSPs.
ICE40_DEVICES = {
    "up5k": {"package": "sg48", "luts": 5280, "brams": 30, "dsps": 8},
    "hx8k": {"package": "ct256", "luts": 7680, "brams": 32, "dsps": 0},
}


# Larger parts for the estimates (vendor data sheets: AMD DS180 7-series overview, Lattice ECP5
# family data sheet): LUTs, flip-flops, block RAM in Kib, DSP multipliers (DSP48E1 / 18x18).
ESTIMATE_DEVICES = {
    "xilinx": [("XC7A35T", 20800, 41600, 1800, 90), ("XC7A100T", 63400, 126800, 4860, 240),
               ("XC7A200T", 134600, 269200, 13140, 740), ("XC7K325T", 203800, 407600, 16020, 840),
               ("XC7K410T", 254200, 508400, 28620, 1540)],
    "ecp5": [("LFE5U-25F", 24288, 24288, 1008, 28), ("LFE5U-45F", 43848, 43848, 1944, 72),
             ("LFE5U-85F", 83640, 83640, 3744, 156)],
}


def smallest_device(target, resources):
    """The smallest listed part whose LUTs, FFs, block RAM and DSPs all hold the estimate (no
    allowance for packing or routing), or None."""
    for name, luts, ffs, kbits, dsps in ESTIMATE_DEVICES.get(target, []):
        if (resources["luts"] <= luts and resources["ffs"] <= ffs and
                resources.get("bram_kbits", 0) <= kbits and resources["dsps"] <= dsps):
            return name
    return None


class ReportError(Exception):
    pass


# Stages, sources and lint configurations, generated from model/include/stereo/stage_table.hpp.
STAGE_TABLE = json.loads((REPO / "scripts" / "stage_table.json").read_text())


def rtl_sources():
    names = [STAGE_TABLE["package"]] + [module + ".sv" for module in STAGE_TABLE["modules"]]
    return [str(RTL / name) for name in names]


def tool_version(command):
    try:
        out = subprocess.run(command, capture_output=True, text=True, check=False)
        return (out.stdout or out.stderr).strip().splitlines()[0]
    except (OSError, IndexError):
        return "unknown"


def config_from_args(args):
    config = {"width": args.width, "height": args.height, "ndisp": args.ndisp,
              "window": args.window}
    # stereo_top's LANES (labels per clock, NDISP / LANES clocks per pixel): recorded only when
    # given, so reports of the all-parallel core keep their shape.
    if getattr(args, "lanes", None) is not None:
        config["lanes"] = args.lanes
    # stereo_top's RING_BLOCK_MIN_FILL (which group rings go to block RAM on the iCE40), likewise.
    if getattr(args, "ring_min_fill", None) is not None:
        config["ring_block_min_fill"] = args.ring_min_fill
    # stereo_top's COST (ad, lcdm, census), likewise recorded only when given.
    if getattr(args, "cost", None) is not None:
        if getattr(args, "command", None) == "board":
            raise ReportError("the board top builds the AD cost only; --cost is for the core")
        config["cost"] = args.cost
    # stereo_top's SHIFT_ADD (constant tap products from shifts and adds), likewise.
    if getattr(args, "shift_add", None) is not None:
        if getattr(args, "command", None) == "board":
            raise ReportError("--shift-add is for the core, not the board top")
        config["shift_add"] = args.shift_add
    # stereo_top's RECOMPUTE_COSTS (the lean memory architecture; the catalogue's lean_core
    # costs), likewise.
    if getattr(args, "recompute", False):
        lean = [cost["name"] for cost in STAGE_TABLE["costs"] if cost["lean_core"]]
        if config.get("cost", "ad") not in lean:
            raise ReportError("--recompute (the lean memory architecture) is for the costs "
                              + ", ".join(lean))
        config["recompute_costs"] = 1
    # stereo_top's ASW (adaptive support weights of diameter --window, docs/asw.md), likewise.
    if getattr(args, "asw", False):
        # The ASW core recomputes its costs from image rows: the lean core's costs.
        recomputed = [cost["name"] for cost in STAGE_TABLE["costs"] if cost["lean_core"]]
        if config.get("cost", "ad") not in recomputed or config.get("recompute_costs"):
            raise ReportError("--asw (adaptive support weights) is for the costs "
                              + ", ".join(recomputed) + ", without --recompute")
        config["asw"] = 1
    # stereo_top's MAX_MIN_DISP, likewise recorded only when given.
    if getattr(args, "max_min_disp", None) is not None and getattr(args, "command", None) != "board":
        config["max_min_disp"] = args.max_min_disp
    # stereo_axil_top's RUNTIME_KERNEL 0 (the default kernel as constants), recorded when given.
    if getattr(args, "constant_kernel", False):
        config["runtime_kernel"] = 0
    if config["window"] % 2 != 1 or not 1 <= config["window"] <= 31:
        raise ReportError(f"window must be odd and in 1..31, got {config['window']}")
    if not 1 <= config["ndisp"] <= 256:
        raise ReportError(f"ndisp must be in 1..256, got {config['ndisp']}")
    if config["width"] < 1 or config["height"] < 1:
        raise ReportError("width and height must be positive")
    lanes = config.get("lanes", config["ndisp"])
    if lanes < 1 or config["ndisp"] % lanes != 0:
        raise ReportError(f"lanes must divide ndisp {config['ndisp']}, got {lanes}")
    return config


def clocks_per_step(config):
    """Clocks per pixel step, NDISP / LANES (stage_table.hpp clocks_per_step)."""
    return config["ndisp"] // config.get("lanes", config["ndisp"])


def chparam(config, ice40=False, top=TOP):
    """chparam of stereo_synth_top (or `top`, which takes the same parameters but those of
    check_top_config); ice40: the group rings in block RAM (RING_BLOCK_RAM, the iCE40 has no LUT
    RAM and its flip-flops are logic cells)."""
    lanes = config.get("lanes", config["ndisp"])
    extra = (f"-set MAX_MIN_DISP {config['max_min_disp']} " if "max_min_disp" in config else "")
    if "ring_block_min_fill" in config:
        extra += f"-set RING_BLOCK_MIN_FILL {config['ring_block_min_fill']} "
    if "cost" in config:
        extra += f"-set COST {COSTS[config['cost']]} "
    if "shift_add" in config:
        extra += f"-set SHIFT_ADD {SHIFT_ADD[config['shift_add']]} "
    if config.get("recompute_costs"):
        extra += "-set RECOMPUTE_COSTS 1 "
    if config.get("asw"):
        extra += "-set ASW 1 "
    if "runtime_kernel" in config:
        extra += f"-set RUNTIME_KERNEL {config['runtime_kernel']} "
    return (f"chparam -set WIDTH {config['width']} -set HEIGHT {config['height']} "
            f"-set NDISP {config['ndisp']} -set WINDOW {config['window']} "
            f"-set LANES {lanes} {extra}{'-set RING_BLOCK_RAM 1 ' if ice40 else ''}{top}")


def progress(message):
    """One progress line on stderr: synthesis and place and route take minutes."""
    print(f"synth.py: {message}", file=sys.stderr, flush=True)


# A Yosys log line that starts a pass: "2.3. Executing SYNTH_XILINX pass." -> ("2.3", "SYNTH_XILINX").
PASS_LINE = re.compile(r"^(\d+(?:\.\d+)*)\. Executing (\S+(?: \S+)*?)(?: pass)?[.(: ]")
# Progress lines during a Yosys run: at most one per this many seconds (0: one per pass).
PROGRESS_SECONDS = float(os.environ.get("STEREO_SYNTH_PROGRESS_SECONDS", "15"))
# The Yosys run in progress, for the partial report of an interrupted command.
RUNNING = {}


class Interrupted(Exception):
    """SIGINT or SIGTERM during a command: main() writes the partial report."""


def pass_of(line):
    """(number, name) of the pass a Yosys log line starts, or None."""
    match = PASS_LINE.match(line)
    return (match.group(1), match.group(2)) if match else None


def run_yosys(script, log_path):
    """Runs Yosys with its log in log_path; while it runs, a progress line (elapsed time, the
    pass it is in) at most every PROGRESS_SECONDS. Interrupted, it stops Yosys, keeps the log and
    raises Interrupted with the elapsed time and the last pass in RUNNING."""
    start = time.monotonic()
    progress(f"yosys running (log {log_path})")
    Path(log_path).unlink(missing_ok=True)
    errors = tempfile.TemporaryFile(mode="w+")  # a file, not a pipe: Yosys never blocks on it
    process = subprocess.Popen(["yosys", "-q", "-l", str(log_path), "-p", script],
                               stdout=subprocess.DEVNULL, stderr=errors, text=True)
    RUNNING.clear()
    RUNNING.update({"log": str(log_path), "last_pass": None, "passes": 0})
    offset, partial, last_print, outer = 0, "", start, ""
    try:
        while True:
            try:
                process.wait(timeout=1.0)
                finished = True
            except subprocess.TimeoutExpired:
                finished = False
            if Path(log_path).exists():
                with open(log_path, "r", errors="replace") as log:
                    log.seek(offset)
                    chunk = log.read()
                    offset = log.tell()
                lines = (partial + chunk).split("\n")
                partial = lines.pop()
                for line in lines:
                    found = pass_of(line)
                    if found:
                        # "46 SYNTH_XILINX / 46.2 Verilog-2005": the script's pass, the one in it.
                        top = found[0].split(".")[0]
                        if top == found[0]:
                            outer = f"{found[0]} {found[1]}"
                        RUNNING["last_pass"] = (outer if top == found[0] or not outer.startswith(
                            top + " ") else f"{outer} / {found[0]} {found[1]}")
                        RUNNING["passes"] += 1
            now = time.monotonic()
            RUNNING["seconds"] = round(now - start, 1)
            if not finished and RUNNING["last_pass"] and now - last_print >= PROGRESS_SECONDS:
                progress(f"yosys {now - start:.0f} s: pass {RUNNING['last_pass']} "
                         f"({RUNNING['passes']} passes so far)")
                last_print = now
            if finished:
                break
    except (KeyboardInterrupt, Interrupted):
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
        RUNNING["seconds"] = round(time.monotonic() - start, 1)
        raise Interrupted()
    errors.seek(0)
    stderr = errors.read()
    errors.close()
    if process.returncode != 0:
        tail = "\n".join(Path(log_path).read_text().splitlines()[-15:]) if Path(
            log_path).exists() else stderr
        raise ReportError(f"yosys failed (log {log_path}):\n{tail}")
    seconds = time.monotonic() - start
    progress(f"yosys done in {seconds:.0f} s ({RUNNING['passes']} passes)")
    RUNNING.clear()
    return seconds


def partial_report(args, started):
    """What an interrupted command leaves in its --out file: the command and its options, the
    elapsed time, and the Yosys pass and log it was in."""
    options = {key: value for key, value in vars(args).items()
               if key not in ("handler", "command") and isinstance(value, (str, int, float, bool,
                                                                           type(None), list))}
    return {"partial": True, "command": args.command, "options": options,
            "interrupted_after_seconds": round(time.monotonic() - started, 1),
            "yosys": dict(RUNNING)}


def load_stat_json(path):
    """The JSON object of a `stat -json` file. Yosys 0.23 interleaves the text listing of the
    hierarchy into the JSON of a hierarchical design: lines that cannot be JSON are dropped."""
    lines = Path(path).read_text().splitlines()
    json_lines = [line for line in lines if line.strip()[:1] in ('"', "{", "}", "[", "]")]
    return json.loads("\n".join(json_lines))


def submodule(cell, modules):
    """The module a cell type names, or None for a leaf cell. Yosys lists a module without
    parameters as "\\name" but names its instances' type "name"."""
    if cell in modules:
        return cell
    return "\\" + cell if "\\" + cell in modules else None


def hierarchy_totals(modules):
    """Leaf cell counts of every module including its submodules (times their instances)."""
    own = {name: data.get("num_cells_by_type", {}) for name, data in modules.items()}
    totals = {}

    def total(name):
        if name not in totals:
            result = {}
            for cell, n in own[name].items():
                sub = submodule(cell, own)
                for leaf, m in (total(sub).items() if sub else [(cell, 1)]):
                    result[leaf] = result.get(leaf, 0) + n * m
            totals[name] = result
        return totals[name]

    for name in own:
        total(name)
    return totals


def read_stat_json(path, top=TOP):
    """Cell counts of the whole design: the one flattened module, or `top`'s hierarchy total."""
    data = load_stat_json(path)
    if "design" in data:
        return data["design"].get("num_cells_by_type", {})
    modules = data["modules"]
    if len(modules) == 1:
        return next(iter(modules.values())).get("num_cells_by_type", {})
    for key in (top, "\\" + top):
        if key in modules:
            return hierarchy_totals(modules)[key]
    raise ReportError(f"stat -json: no module {top} in {path}")


def count(cells, *patterns):
    return sum(n for name, n in cells.items() if any(re.fullmatch(p, name) for p in patterns))


def resources_ice40(cells):
    return {
        "luts": count(cells, r"SB_LUT4"),
        "ffs": count(cells, r"SB_DFF\w*"),
        "carries": count(cells, r"SB_CARRY"),
        "brams": count(cells, r"SB_RAM40_4K\w*"),
        "bram_kbits": 4 * count(cells, r"SB_RAM40_4K\w*"),
        "dsps": count(cells, r"SB_MAC16"),
    }


def resources_xilinx(cells):
    return {
        "luts": count(cells, r"LUT[1-6]"),
        "ffs": count(cells, r"FD[CPRSE]+"),
        "carries": count(cells, r"CARRY4"),
        "lutrams": count(cells, r"RAM\d+[SDM]\w*"),
        # RAMB36E1 = 36 Kib, RAMB18E1 = 18 Kib; brams counts 36 Kib equivalents.
        "ramb36": count(cells, r"RAMB36E1"),
        "ramb18": count(cells, r"RAMB18E1"),
        "brams": count(cells, r"RAMB36E1") + 0.5 * count(cells, r"RAMB18E1"),
        "bram_kbits": 36 * count(cells, r"RAMB36E1") + 18 * count(cells, r"RAMB18E1"),
        "dsps": count(cells, r"DSP48E1"),
        "srls": count(cells, r"SRL\w+"),
        # LUTs of the part that the design occupies: logic LUTs, shift registers (one LUT each)
        # and LUT RAM (UG474: RAM32M/RAM64M/RAM128X1D/RAM256X1S take four LUTs, RAM64X1D and
        # RAM128X1S two, RAM32X1S/RAM64X1S one).
        "lut_sites": count(cells, r"LUT[1-6]") + count(cells, r"SRL\w+") +
        4 * count(cells, r"RAM32M\w*", r"RAM64M\w*", r"RAM128X1D", r"RAM256X1S") +
        2 * count(cells, r"RAM32X1D", r"RAM64X1D", r"RAM128X1S") +
        count(cells, r"RAM32X1S", r"RAM64X1S"),
    }


def resources_ecp5(cells):
    return {
        "luts": count(cells, r"LUT4"),
        "ffs": count(cells, r"TRELLIS_FF"),
        "carries": count(cells, r"CCU2C"),
        "lutrams": count(cells, r"TRELLIS_DPR16X4"),
        "brams": count(cells, r"DP16KD"),  # 18 Kib each
        "bram_kbits": 18 * count(cells, r"DP16KD"),
        "dsps": count(cells, r"MULT18X18D", r"ALU54B"),
    }


def stage_latency(stage, config):
    """Pixel steps of one stage of the stage table (stage_table.hpp Latency::at)."""
    lat, r = stage["latency"], config["window"] // 2
    k = max(0, -config.get("min_disp", 0))
    return ((lat["radius_rows"] * r + lat["rows"]) * config["width"] + lat["radius_steps"] * r
            + lat["steps"] + lat["ndisp_steps"] * config["ndisp"] + lat["left_delay"] * k)


def pipeline_latency(config):
    """Pixel steps from a pixel entering stereo_top to its output beat (stage_table.hpp
    pipeline_latency): every stage of the table, and the census stage with the census cost."""
    steps = sum(stage_latency(stage, config) for stage in STAGE_TABLE["stages"])
    if config.get("cost") == "census":
        steps += stage_latency(STAGE_TABLE["census_stage"], config)
    return steps


def throughput(config, fmax_mhz):
    """Frames per second and million disparity evaluations per second at Fmax (no stalls)."""
    if fmax_mhz is None:
        return None, None
    steps = config["width"] * config["height"] + pipeline_latency(config)
    cycles = steps * clocks_per_step(config)
    fps = fmax_mhz * 1e6 / cycles
    mdes = fps * config["width"] * config["height"] * config["ndisp"] / 1e6
    return round(fps, 2), round(mdes, 1)


def run_nextpnr(report, work, netlist, seed, target_args):
    """Places and routes `netlist` with nextpnr-ice40 (`target_args`: device, package, pins,
    clock) into `work`. Sets report["nextpnr_seconds"] and, when it routes, report["placed"],
    "fmax_mhz", "critical_path" and "utilisation"; when it fails, report["pnr_error"] (its first
    ERROR line). Returns the log text."""
    start = time.monotonic()
    pnr_json, log_path = work / "nextpnr.json", work / "nextpnr.log"
    progress(f"nextpnr-ice40 running (log {log_path})")
    result = subprocess.run(
        ["nextpnr-ice40", *target_args, "--json", str(netlist), "--seed", str(seed),
         "--report", str(pnr_json), "--quiet", "--log", str(log_path)],
        capture_output=True, text=True)
    report["nextpnr_seconds"] = round(time.monotonic() - start, 1)
    log = log_path.read_text() if log_path.exists() else ""
    if result.returncode != 0:
        errors = [line for line in (log + result.stderr).splitlines() if "ERROR" in line]
        report["pnr_error"] = (errors or result.stderr.strip().splitlines() or ["failed"])[0]
    else:
        report["placed"] = True
        report["fmax_mhz"], report["critical_path"] = parse_nextpnr_log(log)
        report["utilisation"] = json.loads(pnr_json.read_text()).get("utilization", {})
    return log


def parse_nextpnr_log(text):
    fmax = None
    for match in re.finditer(r"Max frequency for clock\s+'([^']+)':\s+([\d.]+) MHz", text):
        fmax = float(match.group(2))  # the last one is after routing
    critical = []
    section = text.rfind("Critical path report for clock")
    if section >= 0:
        for line in text[section:].splitlines()[1:]:
            if (not line.startswith("Info:") or "Max frequency" in line or
                    "Critical path report" in line):
                break
            critical.append(line[5:].rstrip())
            if " ns logic, " in line:  # the path's summary closes it
                break
    return fmax, critical


def command_ice40(args):
    report = ice40_report(config_from_args(args), args, args.work)
    write_report(report, args.out)
    return report


def ice40_report(config, args, work):
    """synth_ice40 + nextpnr-ice40 of one configuration (args: device, freq, seed, dsp, no_pnr)."""
    device = ICE40_DEVICES[args.device]
    work = Path(work or tempfile.mkdtemp(prefix="stereo_ice40_"))
    work.mkdir(parents=True, exist_ok=True)
    netlist, stat = work / "netlist.json", work / "stat.json"
    script = (f"read_verilog -sv {' '.join(rtl_sources())}; {chparam(config, ice40=True)}; "
              f"synth_ice40 {'-dsp ' if args.dsp else ''}-top {TOP}; "
              f"chformal -remove; opt_clean; write_json {netlist}; tee -q -o {stat} stat -json")
    yosys_seconds = run_yosys(script, work / "yosys.log")
    cells = read_stat_json(stat)
    report = {
        "target": "ice40", "device": args.device, "package": device["package"],
        "top": TOP, "config": config, "resources": resources_ice40(cells),
        "capacity": {k: device[k] for k in ("luts", "brams", "dsps")},
        "yosys_seconds": round(yosys_seconds, 1),
        "logic_depth": logic_depth(netlist, "ice40"),
        "tools": {"yosys": tool_version(["yosys", "-V"]),
                  "nextpnr": tool_version(["nextpnr-ice40", "--version"])},
    }
    fits = (report["resources"]["luts"] <= device["luts"] and
            report["resources"]["brams"] <= device["brams"] and
            report["resources"]["dsps"] <= device["dsps"])
    report["fits_after_synthesis"] = fits
    report["placed"] = False
    report["fmax_mhz"] = None
    if fits and not args.no_pnr:
        run_nextpnr(report, work, netlist, args.seed,
                    [f"--{args.device}", "--package", device["package"], "--freq", str(args.freq),
                     "--timing-allow-fail"])
    fps, mdes = throughput(config, report["fmax_mhz"])
    report["frames_per_second"] = fps
    report["mde_per_second"] = mdes
    return report


BOARD_TOP = "stereo_board_top"
# The link test (UART echo, no core) with the same pins: `board --top stereo_uart_echo_top`.
ECHO_TOP = "stereo_uart_echo_top"
BOARD_PCF = Path(__file__).resolve().parent / "boards" / "icebreaker.pcf"
BOARD_CLOCK_MHZ = 12.0  # the iCEBreaker's oscillator
# Bytes on the UART per pixel (docs/board.md): 6 in (the pixel pair), 4 out (the beat); each
# byte is 10 bit times (8N1). Input and output overlap (full duplex), so the input sets the rate.
BOARD_BYTES_IN_PER_PIXEL = 6
BOARD_BYTES_OUT_PER_PIXEL = 4


def board_uart_fps(config, baud):
    """Frames per second the UART allows: the frame's input bytes at `baud` (8N1), plus its
    command (2 bytes) and the pipeline's tail of output beats after the last input pixel."""
    pixels = config["width"] * config["height"]
    r = config["window"] // 2
    tail = (r + 2) * config["width"] + r + 11 + config["ndisp"]
    bits = 10 * (2 + BOARD_BYTES_IN_PER_PIXEL * pixels + BOARD_BYTES_OUT_PER_PIXEL * min(tail,
                                                                                          pixels))
    return round(baud / bits, 3)


def board_report(config, args, work):
    """stereo_board_top (or the link test, args.top) through synth_ice40, nextpnr-ice40 (UP5K
    sg48, the board's pins) and icepack: resources, Fmax, and the .bin. The link test has no
    core: its config is None and it has no frame rates."""
    top = args.top
    if top == ECHO_TOP:
        config = None
    device = ICE40_DEVICES["up5k"]
    work = Path(work or tempfile.mkdtemp(prefix="stereo_board_"))
    work.mkdir(parents=True, exist_ok=True)
    netlist, stat = work / "netlist.json", work / "stat.json"
    clks_per_bit = round(BOARD_CLOCK_MHZ * 1e6 / args.baud)
    settings = [("CLKS_PER_BIT", clks_per_bit)]
    if config is not None:
        settings += [("WIDTH", config["width"]), ("HEIGHT", config["height"]),
                     ("NDISP", config["ndisp"]), ("WINDOW", config["window"]),
                     ("MAX_MIN_DISP", args.max_min_disp),
                     ("LANES", config.get("lanes", config["ndisp"]))]
        if "ring_block_min_fill" in config:
            settings.append(("RING_BLOCK_MIN_FILL", config["ring_block_min_fill"]))
        config = config | {"max_min_disp": args.max_min_disp}
    params = " ".join(f"-set {name} {value}" for name, value in settings)
    read = f"read_verilog -sv {' '.join(rtl_sources())}; chparam {params} {top}"
    finish = f"chformal -remove; opt_clean; write_json {netlist}; tee -q -o {stat} stat -json"
    spram = "-spram " if args.spram else ""
    dsp_threshold = None
    if args.dsp:
        # synth_ice40 -dsp maps every multiplier; the UP5K has 8 SB_MAC16. Map the widest
        # products only, as many as fit (dsp_selection), the rest stay LUT logic.
        yosys_seconds, dsp_threshold, script = board_dsp_script(read, finish, spram, work,
                                                                args.dsp_limit, top)
        yosys_seconds += run_yosys(script, work / "yosys.log")
    else:
        yosys_seconds = run_yosys(f"{read}; synth_ice40 {spram}-top {top}; {finish}",
                                  work / "yosys.log")
    cells = read_stat_json(stat, top)
    resources = resources_ice40(cells)
    resources["sprams"] = count(cells, r"SB_SPRAM256KA")
    report = {
        "target": "ice40_board", "board": "icebreaker", "device": "up5k",
        "package": device["package"], "top": top, "config": config,
        "clock_mhz": BOARD_CLOCK_MHZ, "baud": round(BOARD_CLOCK_MHZ * 1e6 / clks_per_bit),
        "clks_per_bit": clks_per_bit, "pcf": str(BOARD_PCF), "resources": resources,
        "dsp_min_product_width": dsp_threshold,
        "capacity": {k: device[k] for k in ("luts", "brams", "dsps")} | {"sprams": 4},
        "yosys_seconds": round(yosys_seconds, 1),
        "logic_depth": logic_depth(netlist, "ice40"),
        "tools": {"yosys": tool_version(["yosys", "-V"]),
                  "nextpnr": tool_version(["nextpnr-ice40", "--version"]),
                  "icepack": "icepack (fpga-icestorm)"},
    }
    fits = (resources["luts"] <= device["luts"] and resources["brams"] <= device["brams"] and
            resources["dsps"] <= device["dsps"] and resources["sprams"] <= 4)
    report["fits_after_synthesis"] = fits
    report["placed"] = False
    report["fmax_mhz"] = None
    report["bin"] = None
    report["bin_bytes"] = None
    if fits:
        asc = work / "board.asc"
        log = run_nextpnr(report, work, netlist, args.seed,
                          ["--up5k", "--package", device["package"], "--pcf", str(BOARD_PCF),
                           "--asc", str(asc), "--freq", str(BOARD_CLOCK_MHZ)])
        demand = re.search(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
        report["logic_cells"] = int(demand.group(1)) if demand else None
        report["logic_cells_capacity"] = int(demand.group(2)) if demand else None
        if report["placed"]:
            fmax = report["fmax_mhz"]
            report["meets_12mhz"] = fmax is not None and fmax >= BOARD_CLOCK_MHZ
            binary = Path(args.bin) if args.bin else work / "stereo_board.bin"
            packed = subprocess.run(["icepack", str(asc), str(binary)], capture_output=True,
                                    text=True)
            if packed.returncode != 0:
                raise ReportError(f"icepack failed: {packed.stderr.strip()}")
            report["bin"] = str(binary.resolve())
            report["bin_bytes"] = binary.stat().st_size
    # The core's own rate at 12 MHz (one pixel per clock) and the UART's (the real limit).
    if config is None:
        report["core_frames_per_second_at_12mhz"] = None
        report["uart_frames_per_second"] = None
    else:
        report["core_frames_per_second_at_12mhz"] = throughput(config, BOARD_CLOCK_MHZ)[0]
        report["uart_frames_per_second"] = board_uart_fps(config, report["baud"])
    return report


# synth_ice40's coarse step up to its DSP mapping (Yosys 0.23, `help synth_ice40`), and after it.
ICE40_COARSE_BEFORE_DSP = ("opt_expr; opt_clean; check; opt -nodffe -nosdff; fsm; opt; wreduce; "
                           "peepopt; opt_clean; share; techmap -map +/cmp2lut.v -D LUT_WIDTH=4; "
                           "opt_expr; opt_clean; memory_dff; wreduce t:$mul")
ICE40_DSP_MAP = ("techmap -map +/mul2dsp.v -map +/ice40/dsp_map.v -D DSP_A_MAXWIDTH=16 "
                 "-D DSP_B_MAXWIDTH=16 -D DSP_A_MINWIDTH=2 -D DSP_B_MINWIDTH=2 "
                 "-D DSP_Y_MINWIDTH=11 -D DSP_NAME=$__MUL16X16")
# The products left out stay $__soft_mul through ice40_dsp (which would map any $mul).
ICE40_COARSE_AFTER_DSP = ("select a:mul2dsp; setattr -unset mul2dsp; opt_expr -fine; wreduce; "
                          "select -clear; chtype -set $__soft_mul t:$mul; ice40_dsp; "
                          "chtype -set $mul t:$__soft_mul; alumacc; opt; memory -nomap; opt_clean")


def parse_mul_dump(text):
    """(A_WIDTH, B_WIDTH, Y_WIDTH) of every $mul cell in an RTLIL `dump`."""
    cells, current = [], None
    for line in text.splitlines():
        words = line.split()
        if words[:2] == ["cell", "$mul"]:
            current = {}
        elif current is not None and words[:1] == ["parameter"] and len(words) == 3:
            current[words[1].lstrip("\\")] = int(words[2])
        elif current is not None and words[:1] == ["end"]:
            cells.append((current.get("A_WIDTH", 0), current.get("B_WIDTH", 0),
                          current.get("Y_WIDTH", 0)))
            current = None
    return cells


def dsp_selection(muls, limit):
    """The smallest Y width w such that the multipliers with Y_WIDTH >= w need at most `limit`
    SB_MAC16 (a 16x16 block each: ceil(A/16) * ceil(B/16); products under 11 bits stay in LUTs
    as with synth_ice40 -dsp), or None when not even the widest fits."""
    def blocks(a, b):
        return -(-a // 16) * -(-b // 16)
    eligible = [m for m in muls if m[2] >= 11 and m[0] >= 2 and m[1] >= 2]
    for width in sorted({m[2] for m in eligible}):
        if sum(blocks(a, b) for a, b, y in eligible if y >= width) <= limit:
            return width
    return None


def board_dsp_script(read, finish, spram, work, limit, top=BOARD_TOP):
    """Runs synth_ice40 up to its DSP mapping, lists the multipliers, and returns (seconds, the
    Y width from which products go to SB_MAC16, the script that finishes the synthesis)."""
    dump, saved = work / "muls.il", work / "pre_dsp.il"
    seconds = run_yosys(f"{read}; synth_ice40 {spram}-top {top} -run begin:coarse; "
                        f"{ICE40_COARSE_BEFORE_DSP}; tee -q -o {dump} dump t:$mul; "
                        f"write_rtlil {saved}", work / "yosys_coarse.log")
    threshold = dsp_selection(parse_mul_dump(dump.read_text()), limit)
    mapped = f"{ICE40_DSP_MAP} t:$mul r:Y_WIDTH>={threshold} %i; " if threshold else ""
    script = (f"read_rtlil {saved}; {mapped}{ICE40_COARSE_AFTER_DSP}; "
              f"synth_ice40 {spram}-top {top} -run map_ram:; {finish}")
    return seconds, threshold, script


def command_board(args):
    report = board_report(config_from_args(args), args, args.work)
    write_report(report, args.out)
    if not report["placed"]:
        reason = report.get("pnr_error") or "over the UP5K's capacity after synthesis"
        message = f"{report['config'] or report['top']} does not fit the iCEBreaker: {reason}"
        if not args.allow_no_fit:
            raise ReportError(message)
        progress(message)
    return report


def command_fit(args):
    """The most disparities that place and route on the device at the given image and window:
    one more label at a time until nextpnr (or the synthesized size) says no."""
    base = config_from_args(args)
    work = Path(args.work or tempfile.mkdtemp(prefix="stereo_fit_"))
    attempts, largest = [], None
    for ndisp in range(1, args.max_ndisp + 1):
        config = dict(base, ndisp=ndisp)
        if "lanes" in base:  # --lanes L: the label counts that L divides, L per clock
            if ndisp % base["lanes"] != 0:
                continue
        print(f"ice40 {args.device} {config}", file=sys.stderr, flush=True)
        report = ice40_report(config, args, work / f"ndisp{ndisp}")
        attempts.append({"ndisp": ndisp, "placed": report["placed"],
                         "luts": report["resources"]["luts"],
                         "fits_after_synthesis": report["fits_after_synthesis"],
                         "fmax_mhz": report["fmax_mhz"],
                         "pnr_error": report.get("pnr_error")})
        if not report["placed"]:
            break
        largest = report
    result = {"target": "ice40", "device": args.device, "search": "ndisp",
              "image": {"width": base["width"], "height": base["height"]},
              "window": base["window"], "largest": largest, "attempts": attempts}
    write_report(result, args.out)
    if largest is None:
        raise ReportError(f"not even one disparity fits the {args.device} at {base}")
    return result


def command_estimate(args):
    config = config_from_args(args)
    top = resolve_top(args.top)
    check_top_config(top, config, args.target)
    report = estimate(config, args.target, args.work, use_dsp=not args.no_dsp, top=top)
    write_report(report, args.out)
    return report


def estimate(config, target, work=None, use_dsp=True, top=TOP):
    """Resource estimate of one configuration of `top` (ESTIMATE_TOPS); the hierarchy is kept
    (no flattening), so that every stage is synthesized once and reported on its own
    (`stages`)."""
    work = Path(work or tempfile.mkdtemp(prefix=f"stereo_{target}_"))
    work.mkdir(parents=True, exist_ok=True)
    stat = work / "stat.json"
    nodsp = "" if use_dsp else " -nodsp"
    synth = {"xilinx": f"synth_xilinx -family xc7{nodsp} -top {top}",
             "ecp5": f"synth_ecp5 -noflatten{nodsp} -top {top}",
             "ice40": f"synth_ice40 -noflatten -top {top}"}[target]  # no DSPs: the HX parts have none
    # Each stage's module, found through its instance in stereo_top (two stages can share a
    # module with different parameters: the CA rules are both stereo_ca_plane).
    # The census stage in front of the cost stage (g_census.census) with the census cost.
    # The ASW core's column stacks and words (g_asw.asw_column), a stage of their own.
    names = (STAGES + ((CENSUS_STAGE,) if config.get("cost") == "census" else ()) +
             (ASW_EXTRA_STAGES if config.get("asw") else ()))
    instances = {name: work / f"stage_{name}.txt" for name in names}
    # chparam leaves the top as a derived "$paramod...<top>": name it back for stat.
    netlist = work / "netlist.json"
    script = (f"read_verilog -sv {' '.join(rtl_sources())}; "
              f"{chparam(config, ice40=target == 'ice40', top=top)}; "
              f"{synth}; chformal -remove; opt_clean; rename -top {top}; "
              f"tee -q -o {stat} stat -json; " +
              "; ".join(f"tee -q -o {path} {stage_module_query(name)}"
                        for name, path in instances.items()) +
              f"; flatten; opt_clean; write_json {netlist}")
    seconds = run_yosys(script, work / "yosys.log")
    resources_of = {"xilinx": resources_xilinx, "ecp5": resources_ecp5,
                    "ice40": resources_ice40}[target]
    cells = read_stat_json(stat, top)
    modules = stage_modules({name: path.read_text() for name, path in instances.items()},
                            ASW_ABSENT_STAGES if config.get("asw") else ())
    stages = {name: resources_of(stage_cells) for name, stage_cells in
              stage_breakdown(stat, modules, top).items()}
    depth = logic_depth(netlist, target)
    delay = logic_delay(netlist, target, work / "sta.log")
    netlist.unlink()  # hundreds of MB at the VGA size; the depth is what was needed of it
    report = {"target": target, "top": top, "config": config, "use_dsp": use_dsp,
              "resources": resources_of(cells), "stages": stages, "logic_depth": depth,
              "yosys_seconds": round(seconds, 1),
              "tools": {"yosys": tool_version(["yosys", "-V"])},
              "note": "Yosys resource estimate before place and route; no Fmax"}
    if delay is not None:
        report["logic_delay"] = delay
    return report


# Yosys' timing models of the target's cells (specify blocks of its cells_sim.v), read beside a
# netlist so that `sta` can time it: the 7-series models give each LUT input, carry, LUT RAM,
# block RAM and DSP48E1 path its delay (the DSP's depend on its pipeline registers), no routing.
STA_MODELS = {"xilinx": "+/xilinx/cells_sim.v"}


def parse_sta(text):
    """The longest path of a Yosys `sta` log: {"ps": arrival, "cells": [(ps, cell type, pins)]},
    first to last, or None when the log holds no path."""
    match = re.search(r"Latest arrival time in '[^']*' is (\d+):\n(.*?)(?:\n\s*\n|\Z)", text, re.S)
    if not match:
        return None
    cells = []
    for line in match.group(2).splitlines():
        step = re.match(r"\s*(\d+)\s+\S+\s+\((\w+)\.([^)]*)\)\s*$", line)
        if step:
            cells.append((int(step.group(1)), step.group(2), step.group(3)))
    return {"ps": int(match.group(1)), "cells": cells[::-1]}


def logic_delay(netlist_path, target, log_path):
    """The longest register-to-register path of a flattened netlist by the cells' delays alone
    (Yosys `sta` over STA_MODELS; routing is not in it): {"ns", "cells" (how many of each cell
    type lie on it), "path" (type and pins, first to last)}; None for a target without models or
    when `sta` fails."""
    if target not in STA_MODELS:
        return None
    try:
        subprocess.run(["yosys", "-q", "-l", str(log_path), "-p",
                        f"read_json {netlist_path}; read_verilog -lib -specify "
                        f"{STA_MODELS[target]}; sta"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        parsed = parse_sta(Path(log_path).read_text())
    except (OSError, subprocess.CalledProcessError):
        return None
    if parsed is None:
        return None
    counts = {}
    for _, kind, _ in parsed["cells"]:
        counts[kind] = counts.get(kind, 0) + 1
    return {"ns": round(parsed["ps"] / 1000, 3), "cells": counts,
            "path": [f"{kind}.{pins}" for _, kind, pins in parsed["cells"]]}


# What each cell counts on a register-to-register path: "level" cells are one level of logic
# (a LUT, or a LUT RAM read), "free" cells are combinational but add no LUT level (carry chains,
# the slice's wide multiplexers); every other cell type (flip-flops, block RAM, DSP blocks, shift
# registers, I/O) starts and ends paths.
DEPTH_CELLS = {
    "xilinx": {"level": r"LUT[1-6]|RAM(32|64|128|256)(X1[SD]|M)\w*",
               "free": r"CARRY4|MUXF[78]"},
    # A CCU2C is two LUT4s and their carry: counted as carry, like the 7-series CARRY4 (the LUT
    # in front of a chain is the level there; on the ECP5 it sits inside the CCU2C).
    "ecp5": {"level": r"LUT4|TRELLIS_DPR16X4", "free": r"CCU2C|PFUMX|L6MUX21"},
    "ice40": {"level": r"SB_LUT4", "free": r"SB_CARRY"},
}


def logic_depth(netlist_path, target):
    """The most LUT levels between two registers (or ports) in a flattened Yosys JSON netlist, how
    many carry cells lie on that path, and its cells: {"lut_levels", "carry_cells", "path"}."""
    kinds = DEPTH_CELLS[target]
    modules = json.loads(Path(netlist_path).read_text())["modules"]
    top = next((m for name, m in modules.items() if m.get("attributes", {}).get("top")),
               None) or next(iter(modules.values()))
    driver = {}  # net bit -> index of the combinational cell that drives it
    cells = []   # (weight (lut levels, carries), input bits)
    names = []   # the cells' (flattened, hierarchical) names
    for cell_name, cell in top["cells"].items():
        kind = cell["type"].lstrip("\\$")
        if re.fullmatch(kinds["level"], kind):
            weight = (1, 0)
        elif re.fullmatch(kinds["free"], kind):
            weight = (0, 1 if "CARRY" in kind or "CCU2" in kind else 0)
        else:
            continue
        directions = cell.get("port_directions", {})
        inputs, index = [], len(cells)
        for port, bits in cell["connections"].items():
            for bit in bits:
                if isinstance(bit, int):
                    (inputs if directions.get(port) == "input" else []).append(bit)
                    if directions.get(port) == "output":
                        driver[bit] = index
        cells.append((weight, inputs))
        names.append(cell_name)
    depth = [None] * len(cells)
    before = [None] * len(cells)  # the predecessor on the deepest path into each cell
    on_stack = [False] * len(cells)  # a combinational loop (none expected) is cut, not followed
    for start in range(len(cells)):  # iterative depth-first, memoised
        stack = [start]
        while stack:
            node = stack[-1]
            if depth[node] is not None:
                on_stack[node] = False
                stack.pop()
                continue
            on_stack[node] = True
            pending = [driver[b] for b in cells[node][1]
                       if b in driver and depth[driver[b]] is None and not on_stack[driver[b]]]
            if pending:
                stack.extend(pending)
                continue
            best = (0, 0)
            for b in cells[node][1]:
                d = driver.get(b)
                if d is not None and d != node and depth[d] is not None and depth[d] > best:
                    best, before[node] = depth[d], d
            weight = cells[node][0]
            depth[node] = (best[0] + weight[0], best[1] + weight[1])
            on_stack[node] = False
            stack.pop()
    if not depth:
        return {"lut_levels": 0, "carry_cells": 0, "path": []}
    end = max(range(len(depth)), key=lambda i: depth[i])
    path = []
    while end is not None:
        path.append(names[end])
        end = before[end]
    levels, carries = max(depth)
    # The cells of that path, first to last: their names say which stages it crosses.
    return {"lut_levels": levels, "carry_cells": carries, "path": path[::-1]}


# Stage names in pipeline order; each is also the name of the stage's instance in stereo_top.
STAGES = tuple(stage["name"] for stage in STAGE_TABLE["stages"])
# The census stage (COST_CENSUS only), instance g_census.census of stereo_top.
CENSUS_STAGE = STAGE_TABLE["census_stage"]["name"]
# stereo_top's MAX_MIN_DISP default, read from the generated package (one definition).
DEFAULT_MAX_MIN_DISP = int(re.search(r"DEFAULT_MAX_MIN_DISP\s*=\s*(\d+)",
                                     (REPO / "rtl" / "fx_pkg.sv").read_text()).group(1))


# stereo_top's SHIFT_ADD values by name (stage_table.hpp kShiftAddModes).
SHIFT_ADD = STAGE_TABLE["shift_add"]
# stereo_top's COST values by name, read from the generated package.
# The hardware costs of the catalogue (model/include/stereo/catalogue.hpp), by name.
COSTS = {cost["name"]: cost["code"] for cost in STAGE_TABLE["costs"]}


def module_kind(name):
    """'stereo_aggregate' from a derived module name such as '$paramod$3f..\\stereo_aggregate'."""
    match = re.search(r"(stereo_[a-z0-9_]+)", name)
    return match.group(1) if match else name


# The ASW core's instance of a stage where its name differs (stereo_top ASW = 1, block g_asw):
# the aggregation is stereo_asw_aggregate `asw`; it has no CA rules.
ASW_INSTANCES = {"aggregate": "asw"}
ASW_ABSENT_STAGES = ("ca_rule1", "ca_rule2")
# ... and a stage the Gaussian core does not have: stereo_asw_column `asw_column`.
ASW_EXTRA_STAGES = ("asw_column",)


def stage_module_query(stage):
    """Yosys command listing `<module>/clk` of the module that implements stereo_top's instance
    `stage` (every stage module has a clk port): at the top, or inside the generate block of the
    Gaussian aggregation and CA rules (g_gaussian_ca: cost, aggregate, ca_rule1, ca_rule2) or of
    the ASW core (g_asw: cost, asw), or the census stage (g_census: census)."""
    asw = ASW_INSTANCES.get(stage, stage)
    return (f"select -list *stereo_top/{stage} *stereo_top/g_gaussian_ca.{stage} %u "
            f"*stereo_top/g_asw.{asw} %u *stereo_top/g_census.{stage} %u %M w:clk %i")


def stage_modules(listings, absent=()):
    """{module name: stage} from the output of stage_module_query for every stage; the stages in
    `absent` may have no module (the ASW core's CA rules)."""
    modules = {}
    for stage, text in listings.items():
        found = [line.rsplit("/", 1)[0].lstrip("\\") for line in text.splitlines()
                 if line.endswith("/clk")]
        if not found and stage in absent:
            continue
        if len(found) != 1:
            raise ReportError(f"no single module implements stage {stage}: {found}")
        modules[found[0]] = stage
    return modules


# The stage of stereo_axil_top's own cells: the AXI4-Lite register file, the counters, the I/O.
AXI_REGISTERS = "axi_registers"
# Flip-flops it cannot have fewer of (rtl/stereo_axil_top.sv): the FRAMES_IN, FRAMES_OUT and
# STALLS counters and the read data register, 32 bits each, all of them read over AXI4-Lite.
AXI_REGISTERS_MIN_FFS = 4 * 32


def stage_breakdown(stat_path, modules_of_stages, top=TOP):
    """Cells of each pipeline stage including its line buffers, and of the glue around them
    (stereo_top's own logic and stereo_synth_top's I/O), from a hierarchical `stat -json`.
    modules_of_stages maps each stage's module name (stage_modules) to the stage. The cells of
    another top (stereo_axil_top) are its own stage, AXI_REGISTERS."""
    modules = load_stat_json(stat_path)["modules"]
    totals = hierarchy_totals(modules)
    stages = {}
    for name, data in modules.items():
        stage = modules_of_stages.get(name.lstrip("\\"))
        cells = (totals[name] if stage else
                 {cell: n for cell, n in data.get("num_cells_by_type", {}).items()
                  if submodule(cell, modules) is None}
                 if module_kind(name) in ("stereo_top", top) else {})
        key = stage or (AXI_REGISTERS if top != TOP and module_kind(name) == top else "glue")
        if stage:  # a stage that synthesized to nothing is reported, with no cells
            stages.setdefault(key, {})
        for cell, n in cells.items():
            stages.setdefault(key, {})
            stages[key][cell] = stages[key].get(cell, 0) + n
    return stages


# The sweep of docs/synthesis.md: one parameter at a time around 640x480 / 16 labels / 11x11,
# up to the full configuration 640x480 / 64 / 11x11.
SWEEP = ([{"width": 640, "height": 480, "ndisp": n, "window": 11} for n in (8, 16, 32, 64)] +
         [{"width": 640, "height": 480, "ndisp": 16, "window": w} for w in (3, 5, 7, 9)] +
         [{"width": w, "height": w * 3 // 4, "ndisp": 16, "window": 11} for w in (160, 320)])


def point_key(point):
    """What makes two estimate points the same point of a sweep (resuming, merging)."""
    return (point["target"], point.get("top", TOP), json.dumps(point["config"], sort_keys=True),
            point.get("use_dsp", True))


def read_sweep(out):
    """The points already in a sweep file (none when it does not exist)."""
    out = Path(out)
    return json.loads(out.read_text()).get("points", []) if out.exists() else []


def write_sweep(points, out):
    Path(out).write_text(json.dumps({"points": points}, indent=2) + "\n")


# A config key of an estimate and the `estimate` option that sets it (FLAG_OPTIONS: set when the
# value is true; "--constant-kernel" is set for runtime_kernel 0).
CONFIG_OPTIONS = {"width": "--width", "height": "--height", "ndisp": "--ndisp",
                  "window": "--window", "lanes": "--lanes",
                  "ring_block_min_fill": "--ring-min-fill",
                  "cost": "--cost", "shift_add": "--shift-add", "max_min_disp": "--max-min-disp",
                  "recompute_costs": "--recompute", "asw": "--asw",
                  "runtime_kernel": "--constant-kernel"}
FLAG_OPTIONS = ("recompute_costs", "asw")


def estimate_arguments(job):
    """The `synth.py estimate` arguments of one sweep point {target, top, config, use_dsp}."""
    words = ["estimate", "--target", job["target"], "--top", job["top"]]
    for key, value in job["config"].items():
        if key not in CONFIG_OPTIONS:
            raise ReportError(f"configuration key {key!r} is not an estimate option (known: "
                              + ", ".join(CONFIG_OPTIONS) + ")")
        if key == "runtime_kernel":
            if value not in (0, 1):
                raise ReportError(f"runtime_kernel must be 0 or 1, got {value!r}")
            words += [] if value else ["--constant-kernel"]
        elif key in FLAG_OPTIONS:
            words += [CONFIG_OPTIONS[key]] if value else []
        else:
            words += [CONFIG_OPTIONS[key], str(value)]
    if not job.get("use_dsp", True):
        words.append("--no-dsp")
    return words


class ArgumentError(ReportError):
    """A parse error of build_parser(raising=True): one line, no usage text, no exit."""


class RaisingParser(argparse.ArgumentParser):
    def error(self, message):
        raise ArgumentError(message)


def sweep_job(target, top, config, use_dsp=True):
    """One sweep point, checked and normalised as `synth.py estimate` would take it: its
    arguments are parsed by estimate's own parser, so that a point command (point_command)
    reproduces exactly this configuration."""
    job = {"target": target, "top": resolve_top(top), "config": dict(config), "use_dsp": use_dsp}
    try:
        args = build_parser(raising=True).parse_args(estimate_arguments(job))
        job["config"] = config_from_args(args)
        check_top_config(job["top"], job["config"], target)
    except ReportError as error:
        raise ReportError(f"configuration {json.dumps(config)}: {error}") from None
    return job


def point_command(job, out, work=None):
    """One self-contained shell command that estimates a sweep point into the JSON file `out`
    (absolute paths: it runs from any folder, on any node that sees them)."""
    words = [sys.executable, str(Path(__file__).resolve()), *estimate_arguments(job),
             "--out", str(Path(out).resolve())]
    if work:
        words += ["--work", str(Path(work).resolve())]
    if "STEREO_RTL_DIR" in os.environ:
        words = ["env", f"STEREO_RTL_DIR={os.environ['STEREO_RTL_DIR']}"] + words
    return shlex.join(words)


def point_name(index, count):
    """point_0001 ...: numbered from 1 in the sweep's order, so that file names sort as it."""
    return f"point_{index + 1:0{max(4, len(str(count)))}d}"


def positive_jobs(text):
    try:
        jobs = int(text)
    except ValueError:
        raise ReportError(f"--jobs must be a positive integer, got {text!r}") from None
    if jobs < 1:
        raise ReportError(f"--jobs must be a positive integer, got {jobs}")
    return jobs


def run_sweep(jobs, args):
    """The sweep points `jobs` not yet in args.out, in their order: estimated in this process
    (--jobs 1), as --jobs N parallel `synth.py estimate` processes, or written as one shell
    command per point (--emit-commands FILE) for a job runner, whose JSON files `synth.py merge`
    gathers. Either way the points land in args.out in the order of `jobs`."""
    parallel = positive_jobs(args.jobs)
    out = Path(args.out)
    points = read_sweep(out)
    done = {point_key(p) for p in points}
    todo = [(index, job) for index, job in enumerate(jobs) if point_key(job) not in done]
    folder = Path(args.points_dir or out.with_name(out.stem + "_points"))
    if args.emit_commands:
        folder.mkdir(parents=True, exist_ok=True)
        lines = [point_command(job, folder / f"{point_name(i, len(jobs))}.json",
                               folder / point_name(i, len(jobs))) for i, job in todo]
        Path(args.emit_commands).write_text("".join(line + "\n" for line in lines))
        progress(f"{len(lines)} point commands in {args.emit_commands} ({len(jobs) - len(todo)} "
                 f"already in {out}); then: {Path(__file__).name} merge {out} {folder}")
        return points
    if parallel == 1:
        for _, job in todo:
            print(f"{job['target']} {job['config']}{'' if job['use_dsp'] else ' no DSP'}"
                  f"{'' if job['top'] == TOP else ' ' + job['top']}", flush=True)
            points.append(estimate(job["config"], job["target"], use_dsp=job["use_dsp"],
                                   top=job["top"]))
            write_sweep(points, out)
        return points
    folder.mkdir(parents=True, exist_ok=True)
    before = list(points)
    finished = {}

    def record(position, point):
        finished[position] = point
        write_sweep(before + [finished[k] for k in sorted(finished)], out)

    run_parallel([(position, job, folder / point_name(i, len(jobs)))
                  for position, (i, job) in enumerate(todo)], parallel, record)
    return before + [finished[k] for k in sorted(finished)]


# The point processes of a parallel sweep that are running, stopped when the sweep is.
CHILDREN = {}


def run_parallel(tasks, parallel, record):
    """Runs `synth.py estimate` for each (position, job, base) task, `parallel` at a time; each
    writes base.json, its Yosys files in base/ and its stderr in base.log. record(position,
    point) is called as each finishes. A failed point stops the launching of more; the sweep
    fails once the running ones finish. Interrupted, it stops them and raises Interrupted."""
    pending = list(tasks)
    count = len(tasks)
    failures = []
    last_print = time.monotonic()
    try:
        while pending or CHILDREN:
            while pending and len(CHILDREN) < parallel and not failures:
                position, job, base = pending.pop(0)
                Path(f"{base}.json").unlink(missing_ok=True)
                log = open(f"{base}.log", "w")
                command = point_command(job, f"{base}.json", base)
                process = subprocess.Popen(shlex.split(command), stdout=log, stderr=log,
                                           stdin=subprocess.DEVNULL)
                CHILDREN[position] = (process, log, base, time.monotonic())
                progress(f"point {position + 1}/{count} started: {job['target']} {job['top']} "
                         f"{job['config']} (log {base}.log)")
            time.sleep(0.2)
            for position, (process, log, base, started) in list(CHILDREN.items()):
                if process.poll() is None:
                    continue
                log.close()
                del CHILDREN[position]
                seconds = time.monotonic() - started
                if process.returncode != 0:
                    lines = Path(f"{base}.log").read_text(errors="replace").strip().splitlines()
                    failures.append(f"point {position + 1} failed (log {base}.log): "
                                    + (lines[-1] if lines else f"exit {process.returncode}"))
                    progress(failures[-1])
                    continue
                record(position, json.loads(Path(f"{base}.json").read_text()))
                progress(f"point {position + 1}/{count} done in {seconds:.0f} s")
            now = time.monotonic()
            if CHILDREN and now - last_print >= PROGRESS_SECONDS:
                last_print = now
                running = ", ".join(f"{position + 1} ({now - started:.0f} s)" for position,
                                    (_, _, _, started) in sorted(CHILDREN.items()))
                progress(f"{count - len(pending) - len(CHILDREN)} of {count} points finished; "
                         f"running: {running}")
    except (Interrupted, KeyboardInterrupt):
        for process, log, base, _ in CHILDREN.values():
            process.terminate()
        for process, log, base, _ in CHILDREN.values():
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
            log.close()
        CHILDREN.clear()
        raise Interrupted()
    if failures:
        raise ReportError(failures[0] + (f" (and {len(failures) - 1} more)"
                                         if len(failures) > 1 else ""))


def sweep_configs(args):
    """The configurations of `sweep`: --configs FILE (a JSON list of configuration objects, the
    `config` of estimate reports, in the order given), else SWEEP up to --max-ndisp."""
    if args.configs:
        configs = json.loads(Path(args.configs).read_text())
        if not isinstance(configs, list) or not all(isinstance(c, dict) for c in configs):
            raise ReportError(f"{args.configs} is not a JSON list of configuration objects")
        return configs
    return [config for config in sorted(SWEEP, key=lambda c: (c["ndisp"], c["window"], c["width"]))
            if config["ndisp"] <= args.max_ndisp]


def command_sweep(args):
    """Estimates of every sweep point not yet in the output file (it resumes after a stop)."""
    use_dsp = not args.no_dsp
    jobs = []
    for target in args.targets.split(","):
        if target not in ("xilinx", "ecp5"):
            raise ReportError(f"unknown target {target!r} (xilinx or ecp5)")
        jobs += [sweep_job(target, args.top, config | kernel_option(args), use_dsp)
                 for config in sweep_configs(args)]
    return run_sweep(jobs, args)


def kernel_option(args):
    """The configuration key of --constant-kernel, for the sweeps."""
    return {"runtime_kernel": 0} if args.constant_kernel else {}


def point_report(path):
    """The estimate report in `path`, or a ReportError saying why it is not one."""
    try:
        report = json.loads(Path(path).read_text())
    except json.JSONDecodeError:
        raise ReportError(f"{path} is not JSON, not a point report of `synth.py estimate`"
                          ) from None
    if isinstance(report, dict) and report.get("partial"):
        raise ReportError(f"{path} is the partial report of an interrupted point: run its command "
                          "again")
    if not (isinstance(report, dict) and report.get("target") in ("xilinx", "ecp5", "ice40") and
            isinstance(report.get("config"), dict) and isinstance(report.get("resources"), dict)
            and "use_dsp" in report):
        raise ReportError(f"{path} is not a point report of `synth.py estimate` (a target, config, "
                          "use_dsp and resources)")
    return report


def command_merge(args):
    """The sweep JSON that the in-process sweep writes, from the point files of its
    --emit-commands (in file-name order within a folder)."""
    paths = []
    for name in args.inputs:
        path = Path(name)
        if path.is_dir():
            found = sorted(path.glob("*.json"))
            if not found:
                raise ReportError(f"{path} holds no .json files")
            paths += found
        elif path.is_file():
            paths.append(path)
        else:
            raise ReportError(f"{path}: no such file or folder")
    points = read_sweep(args.out)
    done = {point_key(p) for p in points}
    added = 0
    for report in map(point_report, paths):
        if point_key(report) not in done:
            points.append(report)
            done.add(point_key(report))
            added += 1
    write_sweep(points, args.out)
    progress(f"{added} points added to {args.out} ({len(points)} in all)")
    return points


def parse_lane_points(text):
    """[(ndisp, lanes)] from "16:1,16:4,64:8" (each lanes must divide its ndisp)."""
    points = []
    for item in text.split(","):
        try:
            ndisp, lanes = (int(v) for v in item.split(":"))
        except ValueError:
            raise ReportError(f"lane point {item!r} is not NDISP:LANES") from None
        if ndisp < 1 or lanes < 1 or ndisp % lanes:
            raise ReportError(f"lane point {item!r}: LANES must divide NDISP")
        points.append((ndisp, lanes))
    return points


def command_lanes_sweep(args):
    """Estimates over (NDISP, LANES) at one frame size and window (resumable, like `sweep`)."""
    jobs = [sweep_job(args.target, args.top, {"width": args.width, "height": args.height,
                                              "ndisp": ndisp, "window": args.window,
                                              "lanes": lanes} | kernel_option(args))
            for ndisp, lanes in parse_lane_points(args.points)]
    return run_sweep(jobs, args)


def plot_lanes(points, target):
    """Resources against NDISP: one line for the all-parallel core (LANES = NDISP) and one per
    fixed LANES below NDISP (its slope is what a label costs at that many lanes)."""
    plt = pyplot()
    chosen = [p for p in points if p["target"] == target]
    series = {}
    for point in chosen:
        config = point["config"]
        lanes = config.get("lanes", config["ndisp"])
        key = 0 if lanes == config["ndisp"] else lanes  # 0: all parallel
        series.setdefault(key, []).append((config["ndisp"], point))
    colours = {key: LANE_COLOURS[i % len(LANE_COLOURS)] for i, key in enumerate(sorted(series))}
    ndisps = sorted({n for values in series.values() for n, _ in values})
    figure, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for axis, (metric, metric_name) in zip(axes.flat, PLOT_METRICS):
        for key, values in sorted(series.items()):
            values = sorted(values, key=lambda v: v[0])
            label = ("LANES = NDISP (1 clock per pixel)" if key == 0 else
                     "LANES = 1 (NDISP clocks per pixel)" if key == 1 else
                     f"LANES = {key} (NDISP / {key} clocks per pixel)")
            axis.plot([n for n, _ in values], [p["resources"][metric] for _, p in values],
                      color=colours[key], marker="o", linewidth=2, label=label,
                      gid=f"lanes-{key or 'all'}-{metric}")
        value_axis(axis, ndisps, "disparities (NDISP)", log2=True)
        count_axis(axis, metric_name)
    config = chosen[0]["config"] if chosen else {"width": 0, "height": 0, "window": 0}
    handles, labels = axes.flat[0].get_legend_handles_labels()
    figure_header(figure, f"{TARGET_NAMES.get(target, target)}: Yosys estimates of "
                  f"stereo_synth_top at {config['width']}x{config['height']}, "
                  f"{config['window']}x{config['window']} window,\nby disparities and labels "
                  "computed per clock (LANES)", handles, labels, columns=min(len(labels), 3) or 1)
    return figure_svg(figure)


def command_plot_lanes(args):
    points = json.loads(Path(args.sweep).read_text()).get("points", [])
    targets = sorted({p["target"] for p in points})
    if not targets:
        raise ReportError(f"{args.sweep} holds no points")
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    for target in targets:
        path = out / f"synth_lanes_{target}.svg"
        path.write_text(plot_lanes(points, target))
        print(path)


# ---- plots (SVG, matplotlib) ------------------------------------------------------------------
PLOT_METRICS = [("luts", "LUTs"), ("ffs", "flip-flops"), ("bram_kbits", "block RAM (Kib)"),
                ("dsps", "DSPs")]
# The swept parameters, their axis labels, and whether the sweep doubles (a log2 axis).
PLOT_PARAMETERS = [("ndisp", "disparities (640x480, 11x11)", True),
                   ("window", "window side in pixels (640x480, 16 disparities)", False),
                   ("width", "image width in pixels (4:3, 16 disparities, 11x11)", True)]
TARGET_STYLE = {("xilinx", True): ("#1f77b4", "7-series"),
                ("xilinx", False): ("#17becf", "7-series, no DSP"),
                ("ecp5", True): ("#d62728", "ECP5"), ("ecp5", False): ("#ff9896", "ECP5, no DSP")}
# ECP5's wider line lies under 7-series', so that where both targets need the same (block RAM,
# DSPs) both colours show.
TARGET_LINES = {"xilinx": {"marker": "o", "linewidth": 2, "zorder": 3},
                "ecp5": {"marker": "s", "markersize": 7, "linewidth": 4, "zorder": 2}}
TARGET_NAMES = {"xilinx": "Xilinx 7-series", "ecp5": "Lattice ECP5", "ice40": "Lattice iCE40"}
# In pipeline order (STAGES, from the stage table), then the glue.
# One colour per stage: a stage without one would drop out of the plots and the per-stage table.
STAGE_PALETTE = ("#8c564b", "#1f77b4", "#2ca02c", "#98df8a", "#9467bd", "#e377c2", "#bcbd22",
                 "#17becf", "#ff7f0e")
assert len(STAGES) <= len(STAGE_PALETTE), "add colours to STAGE_PALETTE for the new stages"
STAGE_COLOURS = dict(zip(STAGES, STAGE_PALETTE),
                     glue="#7f7f7f")
LANE_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2")


def sweep_series(points, parameter):
    """{(target, use_dsp): [(x, point)]} of the points on the axis of `parameter`."""
    base = {"ndisp": lambda c: c["width"] == 640 and c["window"] == 11,
            "window": lambda c: c["width"] == 640 and c["ndisp"] == 16,
            "width": lambda c: c["ndisp"] == 16 and c["window"] == 11}[parameter]
    series = {}
    for point in points:
        if base(point["config"]):
            key = (point["target"], point.get("use_dsp", True))
            series.setdefault(key, []).append((point["config"][parameter], point))
    return {key: sorted(values, key=lambda v: v[0]) for key, values in series.items()}


def pyplot():
    """matplotlib.pyplot on the Agg backend. Imported here, not at the top, so that the
    subcommands without plots run where matplotlib is missing."""
    try:
        import matplotlib
    except ImportError:
        raise ReportError("the plots need matplotlib (Debian: python3-matplotlib)") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # The SVG's element ids hash a random salt unless this is set; with it (and no date in
    # figure_svg) the same sweep gives the same file, so a regenerated figure diffs cleanly.
    matplotlib.rcParams["svg.hashsalt"] = "stereo synth.py"
    # Text as <text> (with a list of fallback fonts ending in sans-serif), not as glyph
    # outlines: half the size, and the numbers in a figure can be searched for.
    matplotlib.rcParams["svg.fonttype"] = "none"
    return plt


def figure_svg(figure):
    """The figure as SVG text (closed afterwards)."""
    import matplotlib.pyplot as plt

    text = io.StringIO()
    figure.savefig(text, format="svg", metadata={"Date": None})
    plt.close(figure)
    return text.getvalue()


def figure_header(figure, title, handles, labels, columns):
    """The title, the legend under it, and the panels fitted below both by tight_layout
    (constrained layout leaves no room for a figure legend before matplotlib 3.7)."""
    inch = 1 / figure.get_figheight()  # in figure fractions
    renderer = figure.canvas.get_renderer()

    def bottom(artist):
        return artist.get_window_extent(renderer).transformed(figure.transFigure.inverted()).y0

    heading = figure.suptitle(title, y=1 - 0.1 * inch, va="top", fontsize="large")
    heading.set_in_layout(False)  # else tight_layout reserves its height a second time
    legend = figure.legend(handles, labels, loc="upper center", ncol=columns, frameon=False,
                           bbox_to_anchor=(0.5, bottom(heading) - 0.05 * inch), borderaxespad=0)
    figure.tight_layout(rect=(0, 0, 1, bottom(legend) - 0.05 * inch))


def value_axis(axis, values, label, log2):
    """An x axis with a tick at every swept value, on a log2 scale where the sweep doubles."""
    from matplotlib.ticker import NullLocator, StrMethodFormatter

    if log2:
        axis.set_xscale("log", base=2)
        axis.xaxis.set_minor_locator(NullLocator())
    axis.set_xticks(values)
    axis.xaxis.set_major_formatter(StrMethodFormatter("{x:,.0f}"))
    axis.set_xlabel(label)


def count_axis(axis, label, headroom=1.06):
    """A y axis of resource counts from 0 to `headroom` times the largest: whole-number ticks
    with thousands separators, and a grid."""
    from matplotlib.ticker import MaxNLocator, StrMethodFormatter

    axis.set_ylim(0, max(1, axis.dataLim.y1 * headroom))  # 1: all zero, or no data
    axis.yaxis.set_major_locator(MaxNLocator(integer=True, steps=[1, 2, 2.5, 5, 10]))
    axis.yaxis.set_major_formatter(StrMethodFormatter("{x:,.0f}"))
    axis.set_ylabel(label)
    axis.grid(True, color="#dddddd")
    axis.set_axisbelow(True)


def plot_scaling(points):
    """Resources (rows) against each swept parameter (columns), one line per target."""
    plt = pyplot()
    figure, axes = plt.subplots(len(PLOT_METRICS), len(PLOT_PARAMETERS), figsize=(13, 13),
                                squeeze=False)
    handles = {}
    for column, (parameter, x_label, log2) in enumerate(PLOT_PARAMETERS):
        series = sweep_series(points, parameter)
        xs = sorted({x for values in series.values() for x, _ in values})
        for row, (metric, metric_name) in enumerate(PLOT_METRICS):
            axis = axes[row][column]
            for key, values in sorted(series.items()):
                colour, name = TARGET_STYLE[key]
                handles[key], = axis.plot(
                    [x for x, _ in values], [p["resources"][metric] for _, p in values],
                    color=colour, label=name, **TARGET_LINES.get(key[0], {}),
                    gid=f"{parameter}-{metric}-{key[0]}{'' if key[1] else '-nodsp'}")
            value_axis(axis, xs, x_label, log2)
            count_axis(axis, metric_name)
    keys = [key for key in TARGET_STYLE if key in handles]
    figure_header(figure, "Yosys resource estimates of stereo_synth_top, one parameter at a "
                  "time around 640x480, 16 disparities, 11x11 window",
                  [handles[key] for key in keys], [TARGET_STYLE[key][1] for key in keys],
                  columns=max(1, len(keys)))
    return figure_svg(figure)


def plot_stages(points, target, metric="luts"):
    """Stacked bars: each stage's share of `metric` at every disparity count of the sweep."""
    plt = pyplot()
    series = sweep_series(points, "ndisp").get((target, True), [])
    metric_name = dict(PLOT_METRICS)[metric]
    figure, axis = plt.subplots(figsize=(8, 5))
    positions = list(range(len(series)))  # evenly spaced: the disparity counts double
    totals = [0] * len(series)
    for stage, colour in STAGE_COLOURS.items():
        heights = [p.get("stages", {}).get(stage, {}).get(metric, 0) for _, p in series]
        bars = axis.bar(positions, heights, 0.6, bottom=totals, color=colour, label=stage)
        for bar, (ndisp, _) in zip(bars, series):
            bar.set_gid(f"{stage}-{ndisp}")
        totals = [t + h for t, h in zip(totals, heights)]
    for x, (ndisp, _), total in zip(positions, series, totals):
        axis.annotate(f"{total:,.0f}", (x, total), xytext=(0, 3), textcoords="offset points",
                      ha="center", va="bottom", gid=f"total-{ndisp}")
    axis.set_xticks(positions, [f"{ndisp:,}" for ndisp, _ in series])
    axis.set_xlabel("disparities (NDISP)")
    count_axis(axis, metric_name, headroom=1.1)  # room for the totals
    axis.grid(False, axis="x")
    handles, labels = axis.get_legend_handles_labels()
    # Top to bottom, as the stages stack.
    axis.legend(handles[::-1], labels[::-1], title="stage", loc="upper left",
                bbox_to_anchor=(1.02, 1))
    axis.set_title(f"{TARGET_NAMES.get(target, target)}: {metric_name} by pipeline stage, "
                   "640x480, 11x11 window\n(Yosys estimate; total above each bar)")
    figure.tight_layout()
    return figure_svg(figure)


def with_bram_kbits(resources, target):
    """Adds bram_kbits to reports written before it existed."""
    if "bram_kbits" not in resources:
        resources["bram_kbits"] = (36 * resources.get("ramb36", 0) + 18 * resources.get("ramb18", 0)
                                   if target == "xilinx" else 18 * resources.get("brams", 0))
    return resources


def estimate_points(path):
    """The estimate points a file holds: a sweep's `points`, or one `estimate` report."""
    data = json.loads(Path(path).read_text())
    if "points" in data:
        return data["points"]
    if data.get("target") in ("xilinx", "ecp5") and "resources" in data:
        return [data]
    raise ReportError(f"{path} is neither a sweep nor a 7-series / ECP5 estimate report")


def command_table(args):
    """Markdown tables of sweep points: one per target (and top, stereo_synth_top's first), then
    each stage's share at the largest configuration. fps and M disparity evaluations/s at --clock
    MHz (an assumed clock: Yosys gives no Fmax for these targets)."""
    points = [point for path in args.sweeps for point in estimate_points(path)]
    if not points:
        raise ReportError("no sweep points")
    lines = []
    for target, top in sorted({(p["target"], p.get("top", TOP)) for p in points},
                              key=lambda group: (group[0], group[1] != TOP, group[1])):
        name = target if top == TOP else f"{target}, {top}"
        rows = sorted((p for p in points if p["target"] == target and p.get("top", TOP) == top),
                      key=lambda p: (not p.get("use_dsp", True), p["config"]["width"],
                                     p["config"]["ndisp"], p["config"]["window"]))
        lines += [f"| {name} | W x H | labels | window | LUT | FF | carry | BRAM (Kib) | DSP | "
                  f"smallest listed part | fps at {args.clock:g} MHz | M disp. eval./s |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for p in rows:
            c, r = p["config"], with_bram_kbits(p["resources"], target)
            fps, mdes = throughput(c, args.clock)
            dsp = "" if p.get("use_dsp", True) else " (no DSP)"
            if top != TOP and c.get("runtime_kernel") == 0:
                dsp = " (constant kernel)" + dsp
            lines.append(f"| {name}{dsp} | {c['width']} x {c['height']} | {c['ndisp']} | "
                         f"{c['window']}x{c['window']} | {r['luts']:,} | {r['ffs']:,} | "
                         f"{r['carries']:,} | {r['bram_kbits']:,} | {r['dsps']:,} | "
                         f"{smallest_device(target, r) or 'none listed'} | {fps:,.0f} | "
                         f"{mdes:,.0f} |")
        lines.append("")
        # rows list DSP points first and max keeps the first of equals, so where a configuration
        # has both variants the stage split is the DSP one's.
        largest = max((p for p in rows if "stages" in p),
                      key=lambda p: (p["config"]["ndisp"] * p["config"]["window"] ** 2
                                     * p["config"]["width"]), default=None)
        if largest:
            c = largest["config"]
            lines += [f"| {name} {c['width']}x{c['height']} / {c['ndisp']} / "
                      f"{c['window']}x{c['window']}: stage | LUT | FF | BRAM (Kib) | DSP |",
                      "|---|---|---|---|---|"]
            names = [CENSUS_STAGE] * (CENSUS_STAGE in largest["stages"]) + list(
                STAGE_COLOURS) + [AXI_REGISTERS] * (AXI_REGISTERS in largest["stages"])
            for name in names:
                r = with_bram_kbits(dict(largest["stages"].get(name, {})), target)
                total = largest["resources"]
                share = 100 * r.get("luts", 0) / total["luts"] if total["luts"] else 0
                lines.append(f"| {name} | {r.get('luts', 0):,} "
                             f"({share:.0f} %) | {r.get('ffs', 0):,} | {r.get('bram_kbits', 0):,}"
                             f" | {r.get('dsps', 0):,} |")
            lines.append("")
    text = "\n".join(lines)
    if args.out:
        Path(args.out).write_text(text)
    else:
        print(text)


def command_plot(args):
    points = json.loads(Path(args.sweep).read_text()).get("points", [])
    if not points:
        raise ReportError(f"{args.sweep} holds no sweep points")
    for point in points:
        with_bram_kbits(point["resources"], point["target"])
        for stage in point.get("stages", {}).values():
            with_bram_kbits(stage, point["target"])
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "synth_scaling.svg"]
    written[0].write_text(plot_scaling(points))
    for target in sorted({p["target"] for p in points if "stages" in p}):
        for metric in ("luts", "ffs", "bram_kbits", "dsps"):
            path = out / f"synth_stages_{target}_{metric}.svg"
            path.write_text(plot_stages(points, target, metric))
            written.append(path)
    for path in written:
        print(path)


def write_report(report, out):
    text = json.dumps(report, indent=2) + "\n"
    if out:
        Path(out).write_text(text)
    else:
        sys.stdout.write(text)


REQUIRED = {
    "ice40_board": ["target", "board", "device", "config", "resources", "fits_after_synthesis",
                    "placed", "fmax_mhz", "bin", "bin_bytes", "baud", "uart_frames_per_second",
                    "tools"],
    "ice40": ["target", "device", "config", "resources", "fits_after_synthesis", "placed",
              "fmax_mhz", "frames_per_second", "mde_per_second", "tools"],
    "xilinx": ["target", "config", "resources", "tools"],
    "ecp5": ["target", "config", "resources", "tools"],
}


def command_check(args):
    report = json.loads(Path(args.report).read_text())
    target = report.get("target")
    if target not in REQUIRED:
        raise ReportError(f"unknown target {target!r}")
    missing = [key for key in REQUIRED[target] if key not in report]
    if missing:
        raise ReportError(f"report lacks {', '.join(missing)}")
    link_test = target == "ice40_board" and report.get("top") == ECHO_TOP
    if link_test and report["config"] is not None:
        raise ReportError("the link test has no core, but the report has a config")
    for key in () if link_test else ("width", "height", "ndisp", "window"):
        if not isinstance(report["config"].get(key), int):
            raise ReportError(f"config.{key} is not an integer")
    resources = report["resources"]
    for key in ("luts", "ffs", "brams", "dsps"):
        if not isinstance(resources.get(key), (int, float)) or resources[key] < 0:
            raise ReportError(f"resources.{key} missing or negative")
    if resources["luts"] == 0 or resources["ffs"] == 0:
        raise ReportError("no logic was synthesized")
    if args.expect_bram and resources["brams"] == 0:
        raise ReportError("the line buffers were not mapped to block RAM")
    check_stages(report)
    if target == "ice40_board" and not report["placed"]:
        over = not report["fits_after_synthesis"] or (
            isinstance(report.get("logic_cells"), int) and
            report["logic_cells"] > report.get("logic_cells_capacity", 0))
        if not report.get("pnr_error") and report["fits_after_synthesis"]:
            raise ReportError("the board did not place, and the report does not say why")
        if report["fits_after_synthesis"] and not over:
            raise ReportError("the board did not place but the logic cells are under capacity")
        if report["bin"] is not None or report["fmax_mhz"] is not None:
            raise ReportError("an unplaced board report has a bitstream or an Fmax")
    if target == "ice40_board" and args.expect_placed:
        if not report.get("placed") or not isinstance(report.get("fmax_mhz"), (int, float)):
            raise ReportError("the board was not placed and routed, or has no Fmax")
        binary = Path(report["bin"] or "")
        if not binary.is_file() or binary.stat().st_size != report["bin_bytes"]:
            raise ReportError(f"the bitstream {binary} is missing or not {report['bin_bytes']} "
                              "bytes")
        if report["bin_bytes"] == 0:
            raise ReportError("the bitstream is empty")
        if not link_test and abs(board_uart_fps(report["config"], report["baud"]) -
                                 report["uart_frames_per_second"]) > 1e-3:
            raise ReportError("uart_frames_per_second does not follow from the baud and config")
    elif args.expect_placed:
        if not report.get("placed") or not isinstance(report.get("fmax_mhz"), (int, float)):
            raise ReportError("the design was not placed and routed, or has no Fmax")
        fps, _ = throughput(report["config"], report["fmax_mhz"])
        if abs(fps - report["frames_per_second"]) > 0.01:
            raise ReportError("frames_per_second does not follow from fmax and the config")
    print(f"report ok: {args.report}")


def check_stages(report):
    """A hierarchical estimate's stages must add up to its totals, and every stage be there."""
    stages = report.get("stages")
    if stages is None:
        return
    absent = ASW_ABSENT_STAGES if (report.get("config") or {}).get("asw") else ()
    missing = [name for name in STAGES if name not in stages and name not in absent]
    if report.get("top", TOP) != TOP:
        missing += [name for name in [AXI_REGISTERS] if name not in stages]
    if missing:
        raise ReportError(f"stages lack {', '.join(missing)}")
    own = stages.get(AXI_REGISTERS, {}).get("ffs", 0)
    if AXI_REGISTERS in stages and own < AXI_REGISTERS_MIN_FFS:
        raise ReportError(f"{report['top']} has {own} flip-flops of its own, fewer than its "
                          f"counters and read data ({AXI_REGISTERS_MIN_FFS}): its register file "
                          "was optimized away")
    for key in ("luts", "ffs", "brams", "dsps"):
        total = sum(stage.get(key, 0) for stage in stages.values())
        if abs(total - report["resources"][key]) > 1e-9:
            raise ReportError(f"stages add up to {total} {key}, the design has "
                              f"{report['resources'][key]}")

# ---- boards: the largest measured configuration each board holds -------------------------------
# The boards a user can buy, their FPGA's resources (vendor data sheets: AMD DS180/DS190, Lattice
# FPGA-DS-02012 and iCE40 family data sheets) and the report family that estimates them. "clock_mhz"
# is the clock assumed for the frame rate where nothing is placed and routed (the 7-series and
# ECP5 estimates); iCE40 reports carry their routed Fmax, which is used instead. Block RAM is
# counted in the report's own unit: RAMB36 equivalents (7-series), DP16KD (ECP5), SB_RAM40_4K.
BOARDS = {
    "icebreaker": {"name": "iCEBreaker", "fpga": "iCE40 UP5K", "family": "ice40", "device": "up5k",
                   "luts": 5280, "ffs": 5280, "brams": 30, "dsps": 8},
    "hx8k-breakout": {"name": "iCE40-HX8K breakout", "fpga": "iCE40 HX8K", "family": "ice40",
                      "device": "hx8k", "luts": 7680, "ffs": 7680, "brams": 32, "dsps": 0},
    "basys3": {"name": "Basys 3", "fpga": "XC7A35T", "family": "xilinx", "luts": 20800,
               "ffs": 41600, "brams": 50, "dsps": 90, "clock_mhz": 100.0},
    "arty-a7-35t": {"name": "Arty A7-35T", "fpga": "XC7A35T", "family": "xilinx", "luts": 20800,
                    "ffs": 41600, "brams": 50, "dsps": 90, "clock_mhz": 100.0},
    "arty-a7-100t": {"name": "Arty A7-100T", "fpga": "XC7A100T", "family": "xilinx",
                     "luts": 63400, "ffs": 126800, "brams": 135, "dsps": 240, "clock_mhz": 100.0},
    "pynq-z2": {"name": "PYNQ-Z2", "fpga": "XC7Z020 (fabric)", "family": "xilinx", "luts": 53200,
                "ffs": 106400, "brams": 140, "dsps": 220, "clock_mhz": 100.0},
    "nexys-video": {"name": "Nexys Video", "fpga": "XC7A200T", "family": "xilinx",
                    "luts": 134600, "ffs": 269200, "brams": 365, "dsps": 740, "clock_mhz": 100.0},
    "ulx3s-85f": {"name": "ULX3S 85F", "fpga": "LFE5U-85F", "family": "ecp5", "luts": 83640,
                  "ffs": 83640, "brams": 208, "dsps": 156, "clock_mhz": 100.0},
}
BOARD_BUDGET = 0.85  # of every resource: headroom for packing, routing and the board's own logic


def report_luts(report):
    """The LUTs a report occupies: logic cells where it was placed (iCE40), the LUT sites of a
    7-series estimate (logic, shift registers, LUT RAM), else its LUT count."""
    utilisation = report.get("utilisation", {}).get("ICESTORM_LC")
    if utilisation:
        return utilisation["used"]
    resources = report["resources"]
    return resources.get("lut_sites", resources["luts"])


def board_usage(report, board):
    """{resource: (used, available)} of a report on a board."""
    resources = report["resources"]
    return {"luts": (report_luts(report), board["luts"]), "ffs": (resources["ffs"], board["ffs"]),
            "brams": (resources["brams"], board["brams"]), "dsps": (resources["dsps"], board["dsps"])}


def board_candidate(report, board):
    """A report's figures on a board, or None when it is not evidence for that board (another
    family, another iCE40 device, an iCE40 report that was not placed and routed)."""
    # An iCEBreaker build (synth.py board: the core with its UART top) is evidence for the UP5K.
    target = "ice40" if report.get("target") == "ice40_board" else report.get("target")
    if target != board["family"] or not isinstance(report.get("config"), dict):
        return None
    if board["family"] == "ice40" and (report.get("device") != board["device"] or
                                       not report.get("placed")):
        return None
    usage = board_usage(report, board)
    fits = all(used <= BOARD_BUDGET * available for used, available in usage.values())
    clock = report.get("fmax_mhz") if board["family"] == "ice40" else board["clock_mhz"]
    if report.get("target") == "ice40_board" and clock is not None:
        clock = min(clock, 12.0)  # the iCEBreaker top runs on the board's 12 MHz oscillator
    fps, _ = throughput(report["config"], clock)
    return {"fits": fits, "usage": {k: {"used": u, "available": a,
                                        "percent": round(100.0 * u / a, 1) if a else None}
                                    for k, (u, a) in usage.items()},
            "clock_mhz": clock, "frames_per_second": fps}


def config_size(config):
    """What "largest" means: pixels times labels, then the window."""
    return (config["width"] * config["height"] * config["ndisp"], config["window"])


def command_boards(args):
    names = args.board or list(BOARDS)
    for name in names:
        if name not in BOARDS:
            raise ReportError(f"unknown board {name!r}; known: {', '.join(sorted(BOARDS))}")
    paths = []
    for folder in args.reports:
        folder = Path(folder)
        paths += sorted(folder.glob("*.json")) if folder.is_dir() else [folder]
    reports = []
    for path in paths:
        try:
            report = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError):
            continue
        if isinstance(report, dict) and "resources" in report and "config" in report:
            reports.append((path, report))
    result = {"budget": BOARD_BUDGET, "min_frames_per_second": args.min_fps, "boards": {}}
    for name in names:
        board = BOARDS[name]
        best = None
        for path, report in reports:
            candidate = board_candidate(report, board)
            if candidate is None or not candidate["fits"]:
                continue
            if (candidate["frames_per_second"] or 0) < args.min_fps:
                continue
            key = config_size(report["config"]) + (candidate["frames_per_second"] or 0,)
            if best is None or key > best[0]:
                best = (key, path, report, candidate)
        entry = {"board": board["name"], "fpga": board["fpga"], "family": board["family"]}
        if best is None:
            entry["largest"] = None
        else:
            _, path, report, candidate = best
            entry["largest"] = {"report": path.name, "config": report["config"],
                                "placed": bool(report.get("placed")),
                                "logic_depth": report.get("logic_depth"),
                                **candidate}
        result["boards"][name] = entry
    fitting = [n for n in names if result["boards"][n]["largest"] is not None]
    if not fitting:
        raise ReportError(f"no measured configuration fits {', '.join(names)} within "
                          f"{BOARD_BUDGET:.0%} of every resource at >= {args.min_fps:g} frames/s "
                          f"(reports: {', '.join(map(str, args.reports))})")
    write_report(result, args.out)
    if args.markdown:
        Path(args.markdown).write_text(boards_markdown(result))
    return result


def boards_markdown(result):
    """The table of docs/synthesis.md "Boards"."""
    lines = ["| board | FPGA | largest configuration | LUT | FF | block RAM | DSP | clock | "
             "frames/s | LUT levels | report |", "|" + "---|" * 11]
    for entry in result["boards"].values():
        best = entry["largest"]
        if best is None:
            lines.append(f"| {entry['board']} | {entry['fpga']} | none measured fits | | | | | | "
                         "| | |")
            continue
        c = best["config"]
        text = (f"{c['width']}x{c['height']}, {c['ndisp']} label{'s' if c['ndisp'] > 1 else ''}, "
                f"{c['window']}x{c['window']}")
        for key, label in (("cost", "cost"), ("lanes", "LANES"), ("max_min_disp", "MAX_MIN_DISP")):
            if key in c:
                text += f", {label} {c[key]}"
        if c.get("recompute_costs"):
            text += ", lean memory"
        usage = best["usage"]
        cells = [f"{usage[k]['used']:,} ({usage[k]['percent']} %)" if usage[k]["available"]
                 else f"{usage[k]['used']:,} (none on the part)" for k in
                 ("luts", "ffs", "brams", "dsps")]
        clock = f"{best['clock_mhz']} MHz" + (" (routed)" if best["placed"] else " (assumed)")
        depth = (best["logic_depth"] or {}).get("lut_levels", "not measured")
        lines.append(f"| {entry['board']} | {entry['fpga']} | {text} | " + " | ".join(cells) +
                     f" | {clock} | {best['frames_per_second']} | {depth} | `{best['report']}` |")
    return "\n".join(lines) + "\n"



def add_config_arguments(parser, width=64, height=48, ndisp=4, window=5):
    parser.add_argument("--width", type=int, default=width)
    parser.add_argument("--height", type=int, default=height)
    parser.add_argument("--ndisp", type=int, default=ndisp)
    parser.add_argument("--window", type=int, default=window)
    parser.add_argument("--lanes", type=int, default=None,
                        help="stereo_top LANES: labels computed per clock, divides ndisp "
                             "(default: ndisp, all in parallel; `fit`: every ndisp it divides)")
    parser.add_argument("--ring-min-fill", type=int, default=None,
                        help="stereo_top RING_BLOCK_MIN_FILL (iCE40): a group ring goes to block "
                             "RAM when it fills each 16-bit block column with at least this many "
                             "bits (default: the RTL's, 50)")
    parser.add_argument("--cost", choices=list(COSTS), default=None,
                        help="stereo_top COST (default: the RTL's, AD); census keeps 5-bit codes "
                             "in the aggregation's line buffer")
    parser.add_argument("--shift-add", choices=sorted(SHIFT_ADD), default=None,
                        help="stereo_top SHIFT_ADD: which constant tap products of the aggregation "
                             "are shifts and adds instead of multipliers (DSP blocks): none, "
                             "narrow (the census codes' vertical pass) or all (default: none)")
    parser.add_argument("--asw", action="store_true",
                        help="stereo_top ASW (census or AD): adaptive support weights, the "
                             "separable two-pass core of diameter --window instead of the "
                             "Gaussian window and the CA rules (docs/asw.md)")
    parser.add_argument("--recompute", action="store_true",
                        help="stereo_top RECOMPUTE_COSTS (census or AD): the lean memory "
                             "architecture, rows of census codes (RGB) instead of per-label rows "
                             "(docs/rtl.md \"Lean memory\")")
    parser.add_argument("--work", help="folder for netlists and logs (default: a temp folder)")
    parser.add_argument("--out", help="JSON report file (default: stdout)")


def add_top_arguments(parser):
    """--top and --constant-kernel of `estimate` and the sweeps."""
    parser.add_argument("--top", default=TOP, metavar="TOP",
                        help=f"the top synthesized: {TOP} (synth, the default: constant kernel, "
                        f"configuration on ports) or {AXIL_TOP} (axil: AXI4-Lite registers and a "
                        "run-time kernel, what integrators instantiate)")
    parser.add_argument("--constant-kernel", action="store_true",
                        help=f"{AXIL_TOP} RUNTIME_KERNEL 0: the default kernel as constants, as "
                        f"in {TOP}")


def add_ice40_arguments(parser, device):
    """The place-and-route options of the ice40 and fit commands."""
    parser.add_argument("--device", choices=sorted(ICE40_DEVICES), default=device)
    parser.add_argument("--freq", type=float, default=30.0, help="target MHz for nextpnr")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--dsp", action="store_true", help="map multipliers to SB_MAC16")
    parser.add_argument("--max-min-disp", type=int, default=None,
                        help="stereo_top MAX_MIN_DISP (default: the RTL's default)")


def add_sweep_arguments(parser):
    """The options of `sweep` and `lanes-sweep` about how the points run."""
    add_top_arguments(parser)
    parser.add_argument("--jobs", default="1", metavar="N",
                        help="run N `synth.py estimate` processes at a time (one Yosys each); "
                        "the JSON is the same for every N, points in the sweep's order")
    parser.add_argument("--emit-commands", metavar="FILE",
                        help="estimate nothing: write one self-contained shell command per point "
                        "not yet in --out to FILE (for GNU parallel, xargs -P, make -j or a Slurm "
                        "array), each writing its JSON to --points-dir; then `merge`")
    parser.add_argument("--points-dir", metavar="DIR",
                        help="the points' JSON files, logs and Yosys folders with --jobs N > 1 "
                        "or --emit-commands (default: <out>_points beside --out)")


def build_parser(raising=False):
    """The command line; raising: errors raise ArgumentError instead of printing the usage and
    exiting (sweep_job parses estimate arguments with it)."""
    parser = (RaisingParser if raising else argparse.ArgumentParser)(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    ice40 = sub.add_parser("ice40", help="synth_ice40 + nextpnr-ice40")
    add_config_arguments(ice40)
    add_ice40_arguments(ice40, device="up5k")
    ice40.add_argument("--no-pnr", action="store_true", help="synthesis only")
    ice40.set_defaults(handler=command_ice40)
    board = sub.add_parser("board", help="iCEBreaker: stereo_board_top to a flashable .bin")
    add_config_arguments(board, width=32, height=24, ndisp=1, window=3)
    board.add_argument("--baud", type=float, default=115200.0,
                       help="UART baud rate (CLKS_PER_BIT = 12 MHz / baud, rounded)")
    board.add_argument("--seed", type=int, default=1)
    board.add_argument("--top", choices=[BOARD_TOP, ECHO_TOP], default=BOARD_TOP,
                       help=f"{ECHO_TOP}: the link test (UART echo, no core; the size options "
                       "are ignored)")
    board.add_argument("--dsp", action="store_true",
                       help="map the widest multipliers to SB_MAC16, at most --dsp-limit blocks")
    board.add_argument("--dsp-limit", type=int, default=ICE40_DEVICES["up5k"]["dsps"])
    board.add_argument("--spram", action="store_true",
                       help="let synth_ice40 map memories to SB_SPRAM256KA")
    board.add_argument("--max-min-disp", type=int, default=DEFAULT_MAX_MIN_DISP,
                       help="largest |min_disp| the core supports (MAX_MIN_DISP); 0: the range "
                       "0..ndisp-1 only, about 760 LUT4 smaller at one label")
    board.add_argument("--bin", help="bitstream path (default: <work>/stereo_board.bin)")
    board.add_argument("--allow-no-fit", action="store_true",
                       help="exit 0 with the report when the design does not place")
    board.set_defaults(handler=command_board)
    fit = sub.add_parser("fit", help="most disparities that place and route on an iCE40")
    add_config_arguments(fit, ndisp=1)
    add_ice40_arguments(fit, device="hx8k")
    fit.add_argument("--max-ndisp", type=int, default=16)
    fit.set_defaults(handler=command_fit, no_pnr=False)
    est = sub.add_parser("estimate", help="synth_xilinx / synth_ecp5 resource estimate")
    add_config_arguments(est)
    est.add_argument("--target", choices=["xilinx", "ecp5", "ice40"], required=True,
                     help="ice40: synth_ice40 with the hierarchy kept, for the per-stage split "
                     "(use `ice40` or `board` for place and route)")
    est.add_argument("--no-dsp", action="store_true", help="multipliers in LUTs, not DSPs")
    est.add_argument("--max-min-disp", type=int, default=None,
                     help="stereo_top MAX_MIN_DISP (default: the RTL's default)")
    add_top_arguments(est)
    est.set_defaults(handler=command_estimate)
    lanes_sweep = sub.add_parser("lanes-sweep", help="estimates over (NDISP, LANES) points")
    lanes_sweep.add_argument("--target", choices=["xilinx", "ecp5", "ice40"], default="xilinx")
    lanes_sweep.add_argument("--width", type=int, default=640)
    lanes_sweep.add_argument("--height", type=int, default=480)
    lanes_sweep.add_argument("--window", type=int, default=11)
    lanes_sweep.add_argument("--points", default="16:16,16:4,16:1,32:32,32:4,64:8,64:4",
                             help="NDISP:LANES,... (LANES divides NDISP)")
    lanes_sweep.add_argument("--out", required=True, help="JSON (points are appended; resumes)")
    add_sweep_arguments(lanes_sweep)
    lanes_sweep.set_defaults(handler=command_lanes_sweep)
    plot_lanes_parser = sub.add_parser("plot-lanes", help="SVG of a lanes-sweep JSON")
    plot_lanes_parser.add_argument("sweep")
    plot_lanes_parser.add_argument("--out-dir", required=True)
    plot_lanes_parser.set_defaults(handler=command_plot_lanes)
    sweep = sub.add_parser("sweep", help="estimates over the docs' configurations")
    sweep.add_argument("--targets", default="xilinx,ecp5")
    sweep.add_argument("--max-ndisp", type=int, default=64)
    sweep.add_argument("--no-dsp", action="store_true", help="multipliers in LUTs, not DSPs")
    sweep.add_argument("--out", required=True, help="sweep JSON (points are appended; resumes)")
    sweep.add_argument("--configs", metavar="FILE",
                       help="a JSON list of configurations to sweep instead of this document's "
                       "(objects as the `config` of an estimate report, e.g. {\"width\": 64, "
                       "\"height\": 48, \"ndisp\": 16, \"window\": 5, \"lanes\": 4})")
    add_sweep_arguments(sweep)
    sweep.set_defaults(handler=command_sweep)
    merge = sub.add_parser("merge", help="gather the point JSON of --emit-commands into a sweep")
    merge.add_argument("out", help="sweep JSON (its points are kept; points already there are "
                       "not added twice)")
    merge.add_argument("inputs", nargs="+", metavar="POINT",
                       help="point JSON files (in this order) or folders (their *.json in name "
                       "order)")
    merge.set_defaults(handler=command_merge)
    plot = sub.add_parser("plot", help="SVG plots of sweep JSON files")
    plot.add_argument("sweep", help="sweep JSON (merge targets with `sweep --out` on one file)")
    plot.add_argument("--out-dir", required=True)
    plot.set_defaults(handler=command_plot)
    table = sub.add_parser("table", help="markdown tables of sweep JSON files")
    table.add_argument("sweeps", nargs="+")
    table.add_argument("--clock", type=float, default=100.0, help="assumed clock in MHz")
    table.add_argument("--out")
    table.set_defaults(handler=command_table)
    boards = sub.add_parser("boards", help="the largest measured configuration each board holds")
    boards.add_argument("--board", action="append", metavar="NAME",
                        help=f"a board (repeatable; default: all): {', '.join(sorted(BOARDS))}")
    boards.add_argument("--reports", nargs="+",
                        default=[str(REPO / "docs" / "figures" / "synthesis" / "boards")],
                        help="report files or folders of them (default: docs/figures/synthesis/"
                        "boards, measured at the current RTL)")
    boards.add_argument("--min-fps", type=float, default=30.0,
                        help="only configurations at least this fast (default 30, a robot's camera)")
    boards.add_argument("--out", help="JSON file (default: stdout)")
    boards.add_argument("--markdown", help="also write the table as markdown to this file")
    boards.set_defaults(handler=command_boards)
    check = sub.add_parser("check", help="validate a JSON report")
    check.add_argument("report")
    check.add_argument("--expect-bram", action="store_true")
    check.add_argument("--expect-placed", action="store_true")
    check.set_defaults(handler=command_check)
    return parser


def main():
    args = build_parser().parse_args()
    started = time.monotonic()

    def stop(signum, frame):
        raise Interrupted()
    signal.signal(signal.SIGTERM, stop)
    try:
        args.handler(args)
    except (Interrupted, KeyboardInterrupt):
        report = partial_report(args, started)
        where = ""
        if args.command in ("sweep", "lanes-sweep"):
            # The points finished so far stay in the file, so that the sweep resumes from them.
            try:
                report["points"] = read_sweep(args.out)
            except (OSError, json.JSONDecodeError):
                report["points"] = []
        if getattr(args, "out", None):
            write_report(report, args.out)
            where = f"; partial report in {args.out}"
        last = report["yosys"].get("last_pass")
        print(f"synth.py: error: interrupted after {report['interrupted_after_seconds']:.0f} s"
              + (f" in yosys pass {last} (log {report['yosys']['log']})" if last else "") + where,
              file=sys.stderr)
        return 130
    except (ReportError, OSError, json.JSONDecodeError) as error:
        print(f"synth.py: error: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
