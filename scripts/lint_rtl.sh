#!/usr/bin/env bash
# Lints every RTL module with `verilator --lint-only -Wall`, at the default parameters and at a
# few others (a module is linted as its own top, so unused ports and widths show up per module).
# Exits non-zero on any warning. Waivers are inline, each with its reason, in the RTL itself.
set -euo pipefail
rtl="$(cd "$(dirname "$0")/../rtl" && pwd)"
mapfile -t files < <(sed "s|^|$rtl/|" "$rtl/files.f")
status=0
lint() {  # lint TOP [-Gparam=value ...]
    local top=$1
    shift
    if ! out=$(verilator --lint-only -Wall -I"$rtl" "${files[@]}" --top-module "$top" "$@" 2>&1); then
        echo "lint FAILED: $top $*"
        echo "$out"
        status=1
    else
        echo "lint ok: $top $*"
    fi
}
for module in stereo_line_buffer stereo_window3x3 stereo_cost stereo_aggregate stereo_ca_rule1 \
              stereo_ca_rule2 stereo_wta stereo_top stereo_synth_top; do
    lint "$module"
done
# The top at other shapes: a 3x3 window, odd label counts, and the full-size configuration.
lint stereo_top -GNDISP=5 -GWINDOW=3
lint stereo_top -GNDISP=33 -GWINDOW=7 -GWIDTH=100 -GHEIGHT=75
lint stereo_top -GNDISP=64 -GWINDOW=11 -GWIDTH=640 -GHEIGHT=480
# The FPGA build (constant kernel) at the full-size configuration.
lint stereo_synth_top -GNDISP=64 -GWINDOW=11 -GWIDTH=640 -GHEIGHT=480
exit $status
