#!/usr/bin/env bash
# parameter_checks.sh [SOURCE_DIR]: the RTL's parameter checks (`STEREO_ASSERT, rtl/stereo_assert.svh,
# docs/rtl.md "Parameter checks") stop a bad configuration with their message, and let a good one
# through:
#   1. Verilator lint of stereo_top at NDISP 16 with LANES 3 (not a divisor) fails, naming the
#      check, its condition, its message and the instance; LANES 4 passes.
#   2. ... with COST_LCDM and RECOMPUTE_COSTS = 1 (the lean core has no LCDM form) fails with
#      "COST must be COST_CENSUS or COST_AD when RECOMPUTE_COSTS = 1"; COST_CENSUS passes.
#   3. A model verilated with -Wno-fatal (elaboration goes on) stops at the start of simulation
#      with the message and the instance path (%m): stereo_power_on_reset with POR_BITS 0.
#   4. Yosys (when installed): elaborating stereo_top with LANES 3 fails with the message.
# Exits non-zero, saying which, when a bad configuration passes or a good one fails.
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
rtl=$root/rtl
mapfile -t files < <(grep -v '^//' "$rtl/files.f" | sed "s|^|$rtl/|")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
fail() {
    echo "FAIL: $*"
    status=1
}

lint() {  # lint TOP [-G...]: verilator --lint-only -Wall, output on $work/lint.out
    local top=$1
    shift
    verilator --lint-only -Wall -Wno-ENUMVALUE -I"$rtl" "${files[@]}" --top-module "$top" "$@" \
        >"$work/lint.out" 2>&1
}

# expect_rejected WHAT TEXT...: the last lint failed and its output has every TEXT.
expect_rejected() {
    local what=$1 rc=$2 missing=0
    shift 2
    if [ "$rc" -eq 0 ]; then
        fail "$what: accepted"
        return
    fi
    for text in "$@"; do
        grep -qF -- "$text" "$work/lint.out" || {
            fail "$what: rejected, but no \"$text\" in the output"
            missing=1
        }
    done
    [ "$missing" -ne 0 ] ||
        echo "ok: $what rejected: $(grep -m1 -F -- "$1" "$work/lint.out" | sed 's/^%Warning-//')"
}

# 1. LANES must divide NDISP.
lint stereo_top -GNDISP=16 -GLANES=3
expect_rejected "stereo_top NDISP 16 LANES 3" $? \
    "lanes_divide_ndisp failed: (LANES >= 1 && LANES <= NDISP && NDISP" \
    "LANES must be 1 .. NDISP and divide NDISP" "In instance stereo_top"
lint stereo_top -GNDISP=16 -GLANES=4 || fail "stereo_top NDISP 16 LANES 4: rejected: $(cat "$work/lint.out")"

# 2. The lean memory core has no LCDM form.
lint stereo_top -GCOST=1 "-GRECOMPUTE_COSTS=1'b1"
expect_rejected "stereo_top COST_LCDM RECOMPUTE_COSTS 1" $? \
    "recompute_costs_cost failed" \
    "COST must be COST_CENSUS or COST_AD when RECOMPUTE_COSTS = 1" "In instance stereo_top"
lint stereo_top -GCOST=2 "-GRECOMPUTE_COSTS=1'b1" ||
    fail "stereo_top COST_CENSUS RECOMPUTE_COSTS 1: rejected: $(cat "$work/lint.out")"

# 3. -Wno-fatal lets elaboration go on; the simulation stops at its start.
if verilator --binary -Wno-fatal -Wno-lint -Wno-style -I"$rtl" "$rtl/fx_pkg.sv" \
    "$rtl/stereo_power_on_reset.sv" --top-module stereo_power_on_reset -GPOR_BITS=0 \
    --Mdir "$work/obj" -o por >"$work/build.out" 2>&1; then
    # A subshell, so that its "Aborted" goes to run.out too; without the check the model has no
    # $finish and runs until the timeout.
    (timeout 20 "$work/obj/por"; exit $?) >"$work/run.out" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -eq 124 ]; then
        fail "stereo_power_on_reset POR_BITS 0: the simulation ran"
    elif ! grep -qF "stereo_power_on_reset.por_bits_positive failed: (POR_BITS >= 1): POR_BITS must be at least 1" \
        "$work/run.out"; then
        fail "stereo_power_on_reset POR_BITS 0: no message at simulation start: $(cat "$work/run.out")"
    else
        echo "ok: stereo_power_on_reset POR_BITS 0 stopped at simulation start: $(grep -m1 failed "$work/run.out")"
    fi
else
    fail "stereo_power_on_reset POR_BITS 0: the -Wno-fatal build failed: $(tail -20 "$work/build.out")"
fi

# 4. Yosys: the same check at elaboration (read_verilog defines YOSYS).
if command -v yosys >/dev/null; then
    yosys -q -p "read_verilog -sv ${files[*]}; chparam -set NDISP 16 -set LANES 3 stereo_top;
                 hierarchy -check -top stereo_top" >"$work/lint.out" 2>&1
    expect_rejected "yosys stereo_top NDISP 16 LANES 3" $? \
        "ERROR: lanes_divide_ndisp failed: (LANES >= 1 && LANES <= NDISP && NDISP % LANES == 0)" \
        "LANES must be 1 .. NDISP and divide NDISP" "stereo_top.sv:"
    yosys -q -p "read_verilog -sv ${files[*]}; chparam -set NDISP 16 -set LANES 4 stereo_top;
                 hierarchy -check -top stereo_top" >"$work/lint.out" 2>&1 ||
        fail "yosys stereo_top NDISP 16 LANES 4: rejected: $(tail -5 "$work/lint.out")"
else
    echo "yosys not found: its part is skipped"
fi
[ "$status" -eq 0 ] && echo "every bad configuration was rejected with its message, the good ones passed"
exit $status
