#!/bin/sh
# test_sweep_points.sh SYNTH_PY PYTHON MODE: a two-point tiny sweep (ECP5, 16x12, 3x3) two ways,
# which must give the same sweep JSON apart from the Yosys run times (ctest label synth):
#   jobs        `sweep --jobs 2`: two `synth.py estimate` processes at a time (the reference,
#               sweep_ref.json)
#   emit        `sweep --emit-commands`: each line run by sh from another folder, then `merge`
# The in-process sweep (no --jobs) writes the same JSON by test_synth.py's unit tests (no Yosys);
# a third pair of Yosys runs here cost about a minute of CI for no other code.
set -u
synth=$1 python=$2 mode=$3
folder=sweep_points_test
mkdir -p $folder && cd $folder || exit 1
cat > configs.json <<'JSON'
[{"width": 16, "height": 12, "ndisp": 2, "window": 3},
 {"width": 16, "height": 12, "ndisp": 2, "window": 3, "lanes": 1, "cost": "census"}]
JSON
sweep() { "$python" "$synth" sweep --targets ecp5 --configs configs.json "$@"; }
same() {  # same A B: equal sweep JSON, but for the Yosys seconds; both hold the two points
    "$python" - "$1" "$2" <<'PY'
import json, sys
def points(path):
    found = json.load(open(path))["points"]
    for point in found:
        point.pop("yosys_seconds")
    return found
a, b = points(sys.argv[1]), points(sys.argv[2])
if len(a) != 2 or a != b:
    sys.exit(f"{sys.argv[1]} and {sys.argv[2]} differ (or do not hold 2 points)")
print(f"{sys.argv[2]}: the same {len(a)} points as {sys.argv[1]}")
PY
}
case $mode in
jobs)
    rm -rf sweep_ref.json sweep_ref_points
    sweep --jobs 2 --out sweep_ref.json || exit 1
    test -s sweep_ref_points/point_0001.log || { echo "no point log"; exit 1; }
    grep -q '"cost": "census"' sweep_ref.json || { echo "no census point"; exit 1; } ;;
emit)
    rm -rf sweep_emit.json sweep_emit_points commands.txt
    sweep --out sweep_emit.json --emit-commands commands.txt || exit 1
    test "$(wc -l < commands.txt)" -eq 2 || { echo "not 2 commands:"; cat commands.txt; exit 1; }
    test ! -e sweep_emit.json || { echo "--emit-commands estimated"; exit 1; }
    # Self-contained: run from another folder, the second command first.
    (cd / && tac "$OLDPWD/commands.txt" | while read -r command; do sh -c "$command" || exit 1; done) \
        || exit 1
    # Each point report is complete, its stages (the census stage of the second) adding up.
    for point in sweep_emit_points/point_0001.json sweep_emit_points/point_0002.json; do
        "$python" "$synth" check "$point" || exit 1
    done
    grep -q '"census": {' sweep_emit_points/point_0002.json || { echo "no census stage"; exit 1; }
    "$python" "$synth" merge sweep_emit.json sweep_emit_points || exit 1
    same sweep_ref.json sweep_emit.json ;;
*)
    echo "unknown mode $mode"; exit 1 ;;
esac
