#!/usr/bin/python3
"""Re-runs every synthesis report of docs/figures/synthesis/boards (or FOLDER) with the
configuration it records, so that the board and lean-memory tables of docs/synthesis.md follow an
RTL change: python3 scripts/synth/regen_boards.py [--jobs N] [FOLDER].

Each report names its target (xilinx / ecp5 estimate, ice40 place and route, the iCEBreaker
board flow) and its stereo_top parameters; the command is rebuilt from them and the report is
replaced only when the run succeeds. Then regenerate the tables: scripts/synth/lean_table.py and
scripts/synth/synth.py boards --markdown FILE."""
import argparse
import concurrent.futures
import json
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
SYNTH = HERE / "synth.py"
# Debian's interpreter: a pyenv or venv python3 earlier on the PATH may lack what synth.py imports.
PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable

# report "config" key -> synth.py option (booleans are flags)
OPTIONS = {
    "width": "--width", "height": "--height", "ndisp": "--ndisp", "window": "--window",
    "lanes": "--lanes", "cost": "--cost", "shift_add": "--shift-add",
    "max_min_disp": "--max-min-disp", "ring_min_fill": "--ring-min-fill",
}


def command(report_path):
    report = json.loads(report_path.read_text())
    target = report["target"]
    config = report["config"]
    if target in ("xilinx", "ecp5"):
        args = ["estimate", "--target", target]
    elif target == "ice40":
        args = ["ice40", "--device", report.get("device", "hx8k")]
    elif target == "ice40_board":
        args = ["board"]
    else:
        raise ValueError(f"{report_path.name}: unknown target {target!r}")
    for key, value in config.items():
        if key == "recompute_costs":
            if value:
                args.append("--recompute")
        elif key in OPTIONS:
            args += [OPTIONS[key], str(value)]
        else:
            raise ValueError(f"{report_path.name}: config key {key!r} has no synth.py option")
    if report.get("use_dsp") is False and target in ("xilinx", "ecp5"):
        args.append("--no-dsp")
    return [PYTHON, str(SYNTH), *args]


def run(report_path):
    staged = report_path.with_suffix(".json.new")
    start = time.monotonic()
    result = subprocess.run(command(report_path) + ["--out", str(staged)],
                            capture_output=True, text=True)
    seconds = time.monotonic() - start
    if result.returncode != 0 or not staged.exists():
        staged.unlink(missing_ok=True)
        tail = (result.stderr or result.stdout).strip().splitlines()[-1:] or ["no output"]
        return f"FAILED {report_path.name} after {seconds:.0f} s: {tail[0]}"
    staged.replace(report_path)
    return f"ok {report_path.name} ({seconds:.0f} s)"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?",
                        default=str(HERE.parent.parent / "docs" / "figures" / "synthesis" / "boards"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--dry-run", action="store_true", help="print the commands only")
    args = parser.parse_args()
    reports = sorted(Path(args.folder).glob("*.json"))
    if not reports:
        sys.exit(f"regen_boards: no reports in {args.folder}")
    if args.dry_run:
        for report in reports:
            print(" ".join(command(report)))
        return
    # Longest first (the largest cores), so the two jobs end together.
    reports.sort(key=lambda p: -json.loads(p.read_text()).get("yosys_seconds", 0))
    failed = False
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for line in pool.map(run, reports):
            print(line, flush=True)
            failed |= line.startswith("FAILED")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
