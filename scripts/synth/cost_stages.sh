#!/usr/bin/env bash
# Resources of the cost stages alone (docs/synthesis.md, "Cost stages: AD, census and LCDM"):
# Yosys synth_ice40 and synth_xilinx (7-series) of stereo_cost with COST = 0 (AD), 1 (LCDM) and
# 2 (census), of the census stage stereo_census (at WIDTH 64, its default) and of one
# stereo_lcdm_convert, flattened, at NDISP disparities (default 16, the co-simulation
# point) and the default MAX_MIN_DISP.
# Usage: scripts/synth/cost_stages.sh [NDISP]. Prints one markdown table row per module and target.
set -euo pipefail
ndisp=${1:-16}
rtl="$(cd "$(dirname "$0")/../../rtl" && pwd)"
sources=$(grep -v '^//' "$rtl/files.f" | sed "s|^|$rtl/|" | tr '\n' ' ')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count() {  # count PATTERN FILE: sum of the cell counts whose type matches PATTERN
    awk -v p="$1" '$2 ~ "^"p"$" {n += $1} END {print n + 0}' "$2"
}
echo "| module | target | LUTs | FFs | carries | DSPs | block RAMs |"
echo "|---|---|---|---|---|---|---|"
for variant in stereo_cost:0 stereo_cost:1 stereo_cost:2 stereo_census: stereo_lcdm_convert:; do
    module=${variant%%:*}
    cost=${variant#*:}
    param=""
    label="$module"
    if [ -n "$cost" ]; then
        param="chparam -set NDISP $ndisp -set COST $cost $module;"
        label="$module COST=$cost (NDISP $ndisp)"
    fi
    for target in ice40 xilinx; do
        synth="synth_ice40 -top $module -flatten"
        [ "$target" = xilinx ] && synth="synth_xilinx -family xc7 -top $module -flatten"
        yosys -q -p "read_verilog -sv $sources; $param $synth; tee -o $work/stat.txt stat" \
            > /dev/null
        # stat lines: "     SB_LUT4      123"; keep "count type" pairs.
        awk '/^ +[A-Za-z_$][A-Za-z_0-9$]* +[0-9]+$/ {print $2, $1}' "$work/stat.txt" > "$work/cells.txt"
        if [ "$target" = ice40 ]; then
            luts=$(count 'SB_LUT4' "$work/cells.txt"); ffs=$(count 'SB_DFF[A-Z]*' "$work/cells.txt")
            carries=$(count 'SB_CARRY' "$work/cells.txt"); dsps=$(count 'SB_MAC16' "$work/cells.txt")
            brams=$(count 'SB_RAM40_4K[A-Z]*' "$work/cells.txt")
        else
            luts=$(count 'LUT[1-6]' "$work/cells.txt"); ffs=$(count 'FD[CPRSE]+' "$work/cells.txt")
            carries=$(count 'CARRY4' "$work/cells.txt"); dsps=$(count 'DSP48E1' "$work/cells.txt")
            brams=$(count 'RAMB(18|36)E1' "$work/cells.txt")
        fi
        echo "| $label | $target | $luts | $ffs | $carries | $dsps | $brams |"
    done
done
