#!/bin/sh
# Runs `stereo avoid` (both methods) on the two KITTI clips at the given safety distances and
# writes one JSON line per frame to docs/figures/avoidance/kitti<N>_z<Z>.jsonl, plus an overlay
# contact sheet to OUT (default /tmp/avoid). Usage: run_kitti.sh [BUILD] [OUT] [Z...]
set -eu
build=${1:-build-robot}
out=${2:-/tmp/avoid}
shift 2 2>/dev/null || true
distances=${*:-10 7}
data=${STEREO_DATA_DIR:-../shared/data}/sequence
figures=docs/figures/avoidance
mkdir -p "$out" "$figures"
for z in $distances; do
    for n in 1 2; do
        clip=$data/kitti_sequence_$n
        "$build/app/stereo" avoid "$clip/image_l" "$clip/image_r" --calib "$clip/calib.txt" \
            --safe-distance "$z" --method both --overlay "$out/kitti${n}_z${z}.png" \
            >"$figures/kitti${n}_z${z}.jsonl"
    done
done
