#!/usr/bin/env bash
# Synthesizability check of stereo_top with Yosys at the default configuration (or the
# parameters given as NAME=VALUE arguments): elaborates, fails on any error, on any latch and on
# the problems `check -assert` finds (undriven or multiply driven nets, combinational loops),
# then runs a generic `synth` and prints the cell statistics.
set -euo pipefail
rtl="$(cd "$(dirname "$0")/../../rtl" && pwd)"
# rtl/files.f (generated from the stage table): the sources in compile order after a // header.
sources=$(grep -v '^//' "$rtl/files.f" | sed "s|^|$rtl/|" | tr '\n' ' ')
chparams=""
for assignment in "$@"; do
    chparams="$chparams -set ${assignment%%=*} ${assignment#*=}"
done
script="read_verilog -sv $sources;"
[ -n "$chparams" ] && script="$script chparam $chparams stereo_top;"
script="$script hierarchy -check -top stereo_top; proc;"
script="$script select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$sr;"
script="$script check -assert; synth -top stereo_top; check -assert; stat"
yosys -q -p "$script" -l "${YOSYS_LOG:-/dev/null}"
echo "yosys: stereo_top ${*:-(default parameters)} synthesized without errors or latches"
