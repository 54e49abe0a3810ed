#!/usr/bin/env bash
# Runs `stereo slam` on the two KITTI clips and the EuRoC clip of ../shared/data/sequence and
# writes the JSON summaries, trajectories and figures used by docs/results-slam.md.
# Usage: scripts/slam/run_kitti.sh [BUILD_DIR=build] [OUT_DIR=out/slam]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/slam}
data=${STEREO_DATA_DIR:-$root/../shared/data}/sequence
stereo=$build/app/stereo
figures=$root/docs/figures/slam
mkdir -p "$out" "$figures"

# KITTI: half size (613x185 / 620x188), 48 disparity labels (the clips' disparities reach
# about 65 px at full size, 33 at half size).
kitti=(--downscale 2 --ndisp 48)
for n in 1 2; do
  seq=$data/kitti_sequence_$n
  "$stereo" slam "$seq" "${kitti[@]}" --json \
    --map "$figures/kitti_sequence_${n}_map.png" \
    --trajectory "$out/kitti_sequence_${n}_trajectory.txt" \
    --vdisparity "$figures/kitti_sequence_${n}_vdisparity.png" --vdisparity-frame 10 \
    > "$out/kitti_sequence_${n}.json"
  # The same without the map-merging refinement (its map shows the odometry placement).
  "$stereo" slam "$seq" "${kitti[@]}" --json --no-merge \
    --map "$figures/kitti_sequence_${n}_map_no_merge.png" \
    > "$out/kitti_sequence_${n}_no_merge.json"
done

# EuRoC V1_01_easy, first 40 frames, camera at rest: raw images rectified on the fly.
"$stereo" slam "$data/euroc_v1_01_easy_micro" --layout euroc --ndisp 48 --json \
  --trajectory "$out/euroc_trajectory.txt" --map "$out/euroc_map.png" \
  > "$out/euroc.json"

echo "wrote $out/*.json and $figures/*.png"
