#!/usr/bin/env bash
# Fresh machine to first result: install dependencies, build the tool, and run the main job on
# the packaged default input, Debian opencv-doc's Middlebury Aloe pair, at half size.
# Writes out/aloe_disparity.png (disparity x 2, 0 = invalid), out/aloe_color.png and
# out/aloe_errors.png, and prints the Middlebury metrics against aloeGT.png.
#
# The first result comes from the tool built without the Verilated models (about 3 minutes of
# compiling on two cores; they take most of a full build). Then the same build folder is
# configured with the RTL and everything is built (the co-simulation models, the testbenches, the
# tests), so that ./scripts/test.sh afterwards only runs the tests. --no-rest stops after the
# first result.
set -euo pipefail
cd "$(dirname "$0")/.."
rest=1
for arg in "$@"; do
  case "$arg" in
    --no-rest) rest=0 ;;
    *) echo "quickstart: unknown option '$arg' (only --no-rest)" >&2; exit 2 ;;
  esac
done
start=$SECONDS
./scripts/setup.sh

# A build folder that already has the tool with the RTL is used as it is.
if [ -x build/app/stereo ] && grep -q '^STEREO_WITH_RTL:BOOL=ON' build/CMakeCache.txt 2>/dev/null; then
  cmake --build build -j"$(nproc)" --target stereo
else
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSTEREO_WITH_RTL=OFF
  cmake --build build -j"$(nproc)" --target stereo
fi
# The Python module too, so that the README's Python first step works right after this script
# (the target exists when pybind11 was found, python/CMakeLists.txt).
if cmake --build build --target help | grep -q stereo_python; then
  cmake --build build -j"$(nproc)" --target stereo_python
else
  echo "quickstart: pybind11 or Python 3 not found, the Python module is not built" >&2
fi

data=/usr/share/doc/opencv-doc/examples/data
mkdir -p out
# Aloe's disparities reach 211 px at full size (1282x1110); at half size 128 labels cover them.
./build/app/stereo match "$data/aloeL.jpg" "$data/aloeR.jpg" --downscale 2 --ndisp 128 \
  --scale 2 -o out/aloe_disparity.png --color out/aloe_color.png
./build/app/stereo eval out/aloe_disparity.png "$data/aloeGT.png" --scale 2 --gt-downscale 2 \
  --error-map out/aloe_errors.png
echo "quickstart: wrote out/aloe_disparity.png, out/aloe_color.png, out/aloe_errors.png" \
  "($((SECONDS - start)) s after the start)"

if [ "$rest" -eq 1 ]; then
  echo "quickstart: now building the rest (the Verilated co-simulation models, testbenches and" \
    "tests; stop with Ctrl-C at any time, ./scripts/test.sh continues it)"
  cmake -S . -B build -DSTEREO_WITH_RTL=ON
  cmake --build build -j"$(nproc)"
  echo "quickstart: everything built ($((SECONDS - start)) s); run the tests with ./scripts/test.sh"
fi
