#!/usr/bin/env bash
# Fresh machine to first result: install dependencies, build, and run the main job on the
# packaged default input, Debian opencv-doc's Middlebury Aloe pair, at half size.
# Writes out/aloe_disparity.png (disparity x 2, 0 = invalid), out/aloe_color.png and
# out/aloe_errors.png, and prints the Middlebury metrics against aloeGT.png.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
# Only the tool (the tests are built by scripts/test.sh).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target stereo

data=/usr/share/doc/opencv-doc/examples/data
mkdir -p out
# Aloe's disparities reach 211 px at full size (1282x1110); at half size 128 labels cover them.
./build/app/stereo match "$data/aloeL.jpg" "$data/aloeR.jpg" --downscale 2 --ndisp 128 \
  --scale 2 -o out/aloe_disparity.png --color out/aloe_color.png
./build/app/stereo eval out/aloe_disparity.png "$data/aloeGT.png" --scale 2 --gt-downscale 2 \
  --error-map out/aloe_errors.png
echo "quickstart: wrote out/aloe_disparity.png, out/aloe_color.png, out/aloe_errors.png"
