#!/usr/bin/env bash
# Lints every RTL module with `verilator --lint-only -Wall`, at the default parameters and at the
# extra configurations of the stage table (a module is linted as its own top, so unused ports and
# widths show up per module). The sources, the modules and the extra configurations come from
# scripts/stage_table.json, generated from model/include/stereo/stage_table.hpp.
# Exits non-zero on any warning. Waivers are inline, each with its reason, in the RTL itself.
set -euo pipefail
scripts="$(cd "$(dirname "$0")" && pwd)"
rtl="$(cd "$scripts/../rtl" && pwd)"
table="$scripts/stage_table.json"
mapfile -t files < <(python3 -c '
import json, sys
t = json.load(open(sys.argv[1]))
print(t["package"])
for m in t["modules"]:
    print(m + ".sv")' "$table" | sed "s|^|$rtl/|")
# One lint run per line: TOP [-Gparam=value ...]; every module at its defaults, then the extras.
# The values are Verilator's: integers, and 1'b0 / 1'b1 for `bit` parameters; the enum-typed
# parameters (COST, RULE, SHIFT_ADD) take their integer codes, hence -Wno-ENUMVALUE below.
mapfile -t runs < <(python3 -c '
import json, sys
t = json.load(open(sys.argv[1]))
for m in t["modules"]:
    print(m)
for run in t["lint"]:
    print(" ".join([run["top"]] + ["-G%s=%s" % kv for kv in run["parameters"].items()]))' "$table")
status=0
lint() {  # lint TOP [-Gparam=value ...]
    local top=$1
    shift
    local enum=()
    [ $# -eq 0 ] || enum=(-Wno-ENUMVALUE)
    if ! out=$(verilator --lint-only -Wall "${enum[@]}" -I"$rtl" "${files[@]}" --top-module "$top" "$@" 2>&1); then
        echo "lint FAILED: $top $*"
        echo "$out"
        status=1
    else
        echo "lint ok: $top $*"
    fi
}
for run in "${runs[@]}"; do
    # shellcheck disable=SC2086  # a run is TOP and its -G options, split on purpose
    lint $run
done
exit $status
