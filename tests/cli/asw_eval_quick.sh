#!/bin/sh
# Usage: asw_eval_quick.sh STEREO_EXPERIMENTS DATA_DIR WORKDIR
#
# `stereo_experiments asw-eval --quick` (Tsukuba and Venus, about 30 s on two cores) end to end:
# the tables, the JSON and the two figure strips are written, and every table is there. Exit 77
# (skipped) when the Middlebury 2003 data is not in DATA_DIR.
set -eu
experiments=$1
data=$2
work=$3
for scene in tsukuba venus; do
    if [ ! -d "$data/middlebury2003/$scene" ]; then
        echo "SKIP: $data/middlebury2003/$scene not found"
        exit 77
    fi
done
rm -rf "$work"
mkdir -p "$work/figures"
"$experiments" asw-eval --quick --data "$data" --markdown "$work/asw.md" --json "$work/asw.json" \
    --figures "$work/figures" > "$work/stdout.md"
for heading in "Table 3.6" "Table 3.7" "Table 3.8" "Lightness sweep" "Speed on venus"; do
    grep -q "### $heading" "$work/asw.md" || { echo "missing table: $heading"; exit 1; }
done
cmp -s "$work/asw.md" "$work/stdout.md" || { echo "stdout differs from --markdown"; exit 1; }
grep -q '"runs"' "$work/asw.json" || { echo "no runs in the JSON"; exit 1; }
for scene in tsukuba venus; do
    [ -s "$work/figures/$scene.png" ] || { echo "missing figure $scene.png"; exit 1; }
done
echo "asw-eval --quick: ok"
