#!/bin/sh
# Both methods on the Middlebury 2003 pairs, one JSON line per pair, to
# docs/figures/avoidance/middlebury.jsonl. These pairs have no calibration, so the threshold is
# given in pixels: half the search range (T = ndisp / 2). Overlays go to $OUT (default /tmp).
# Usage: run_middlebury.sh [BUILD]
set -eu
build=${1:-build-robot}
data=${STEREO_DATA_DIR:-../shared/data}/middlebury2003
out=docs/figures/avoidance/middlebury.jsonl
: >"$out"
for scene in tsukuba:16 venus:20 teddy:60 cones:60; do
    name=${scene%%:*}
    ndisp=${scene##*:}
    "$build/app/stereo" avoid "$data/$name/left.png" "$data/$name/right.png" --ndisp "$ndisp" \
        --threshold $((ndisp / 2)) --method both --json \
        --overlay "${OUT:-/tmp}/middlebury_$name.png" | jq -c --arg s "$name" '. + {scene: $s}' >>"$out"
done
