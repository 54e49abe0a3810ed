#!/usr/bin/env bash
# Full-size SLAM runs behind the trajectory table of docs/results-slam.md (issue 20): for each
# clip the default (gated map merging) and the ungated merging of issue 9
# (--merge-significance 0 --merge-min-match 0); each run also reports the odometry alone.
# Usage: scripts/slam/run_gates.sh [BUILD_DIR=build] [OUT_DIR=out/slam-gates]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/slam-gates}
data=${STEREO_DATA_DIR:-$root/../shared/data}/sequence
stereo=$build/app/stereo
figures=$root/docs/figures/slam
mkdir -p "$out" "$figures"
ungated=(--merge-significance 0 --merge-min-match 0)
for n in 1 2; do
  seq=$data/kitti_sequence_$n
  "$stereo" slam "$seq" --json --map "$figures/kitti_sequence_${n}_full_map.png" \
    --trajectory "$out/kitti_sequence_${n}_trajectory.txt" > "$out/kitti_sequence_${n}.json"
  "$stereo" slam "$seq" --json "${ungated[@]}" \
    --map "$figures/kitti_sequence_${n}_full_map_ungated.png" \
    > "$out/kitti_sequence_${n}_ungated.json"
done
euroc=$data/euroc_v1_01_easy_micro
"$stereo" slam "$euroc" --layout euroc --ndisp 48 --json > "$out/euroc.json"
"$stereo" slam "$euroc" --layout euroc --ndisp 48 --json "${ungated[@]}" > "$out/euroc_ungated.json"
echo "wrote $out/*.json"
