#!/bin/sh
# Usage: cli_end_to_end.sh STEREO DATA_DIR WORKDIR
#
# `stereo match --method hierarchical` and `stereo distort` end to end on Middlebury Tsukuba:
# writes the disparity, vertical-offset and per-level maps, runs the thesis' output (--field none),
# checks that the golden model and the naive engine write the same bytes (at half size, to keep
# the naive run short; the vertical field and its validated 1-D pass included), distorts the
# pair by 10 % and matches and scores the distorted copy. Exit 77 (skipped) without the data.
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/../../tests/cli/common.sh"
stereo=$1
scene=$2/middlebury2003/tsukuba
work=$3
files_or_skip "Middlebury Tsukuba" "$scene" left.png right.png gt.png
rm -rf "$work"
mkdir -p "$work"

summary=$("$stereo" match "$scene/left.png" "$scene/right.png" -o "$work/disp.png" --ndisp 16 \
    --scale 16 --method hierarchical --vertical "$work/vertical.png" --dump-levels "$work/levels" \
    --json)
echo "$summary"
echo "$summary" | grep -q '"method":"hierarchical"'
# D = V = 16: the levels' (4 x 4) / 16 + 9 / 4 + 9 = 12.25 per pixel, and the 1-D pass 16 more.
echo "$summary" | grep -q '"cost_evaluations_per_pixel":28.25'
echo "$summary" | grep -q '"field":"radial-prior"'
# The thesis' output (--field none): the levels alone, no 1-D pass.
thesis=$("$stereo" match "$scene/left.png" "$scene/right.png" -o "$work/thesis.png" --ndisp 16 \
    --scale 16 --method hierarchical --field none --json)
echo "$thesis" | grep -q '"cost_evaluations_per_pixel":12.25'
echo "$thesis" | grep -q '"field":"none"'
for file in disp.png vertical.png levels/quarter_disparity.png levels/half_vertical.png \
    levels/full_color.png; do
    [ -s "$work/$file" ] || { echo "FAIL: $file not written"; exit 1; }
done
"$stereo" eval "$work/disp.png" "$scene/gt.png" --scale 16 --gt-scale 16 --json

"$stereo" match "$scene/left.png" "$scene/right.png" -o "$work/model.png" --ndisp 8 \
    --downscale 2 --method hierarchical --vertical "$work/model_v.png"
"$stereo" match "$scene/left.png" "$scene/right.png" -o "$work/naive.png" --ndisp 8 \
    --downscale 2 --method hierarchical --vertical "$work/naive_v.png" --engine naive
cmp "$work/model.png" "$work/naive.png"
cmp "$work/model_v.png" "$work/naive_v.png"

"$stereo" distort "$scene" "$work/tsukuba_10" --distortion 10 --gt-scale 16
"$stereo" match "$work/tsukuba_10/left.png" "$work/tsukuba_10/right.png" -o "$work/d10.png" \
    --ndisp 16 --scale 16 --method hierarchical
"$stereo" eval "$work/d10.png" "$work/tsukuba_10/gt.png" --scale 16 --gt-scale 16 \
    --nonocc "$work/tsukuba_10/nonocc.png" --all "$work/tsukuba_10/all.png" --json
echo "ok"
