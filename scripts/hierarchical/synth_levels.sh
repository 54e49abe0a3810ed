#!/usr/bin/env bash
# Yosys estimate (synth_xilinx, 7-series, not placed) of the hierarchical core's three levels,
# stereo_hier_levels, with its pyramid, FIFOs and prediction rings (docs/hierarchical.md
# "Resources of the whole core"). The pass (stereo_hier_pass) is the lean census core, estimated
# by scripts/synth/synth.py; the two add up to the core.
#
#   scripts/hierarchical/synth_levels.sh [WIDTH NDISP VRANGE LANES_Q LANES_H LANES_F [LOG]]
#
# Defaults: the VGA build, 640 wide, D = 64, V = 16, one candidate row a clock at the quarter
# level's 16 x 4 grid / 4 (LANES_Q 4), the half level one label a clock (LANES_H 1), the full
# level one candidate row (LANES_F 3). Prints Yosys' statistics; the log goes to LOG
# (default /tmp/synth_levels.log). About 25 minutes and 7 GB of memory at the defaults.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
width=${1:-640}
ndisp=${2:-64}
vrange=${3:-16}
lanes_q=${4:-4}
lanes_h=${5:-1}
lanes_f=${6:-3}
log=${7:-/tmp/synth_levels.log}
command -v yosys > /dev/null || { echo "synth_levels.sh: yosys not found" >&2; exit 1; }
mapfile -t files < <(grep -v '^//' "$root/rtl/files.f" | sed "s|^|$root/rtl/|")
script=$(mktemp)
trap 'rm -f "$script"' EXIT
cat > "$script" << EOF
read_verilog -sv -I$root/rtl ${files[*]}
chparam -set WIDTH $width -set NDISP $ndisp -set VRANGE $vrange -set LANES_Q $lanes_q -set LANES_H $lanes_h -set LANES_F $lanes_f stereo_hier_levels
synth_xilinx -family xc7 -top stereo_hier_levels -flatten
stat
EOF
yosys -q -l "$log" "$script" > /dev/null
sed -n '/^[0-9]*\. Printing statistics/,$p' "$log" | grep -E '^ +(Number of cells|[A-Z][A-Z0-9_]+ +[0-9]+)'
