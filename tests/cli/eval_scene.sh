#!/bin/sh
# Usage: eval_scene.sh STEREO FIXTURES WORKDIR
#
# stereo eval on the scene fixture, whose true disparity varies (planes at 2, 7 and -2.5, a
# slanted plane, occlusions; scene_gt.pfm, written by make_cli_fixtures by forward warping):
# 1. the same map read as PFM and as an offset16 PNG scores identically at threshold 0, so every
#    1/16 pixel and the sign of the offset16 decoding count;
# 2. a map stored times 4 scores like the PFM only when --scale 4 is given (ignoring the scale
#    makes nearly every pixel bad), and a GT stored times 4 likewise needs --gt-scale 4.
set -eu
stereo=$1
fixtures=$2
work=$3
mkdir -p "$work"
rm -f "$work"/m.pfm "$work"/m0.pfm "$work"/m16.png "$work"/m4.png
left=$fixtures/scene_left.png
right=$fixtures/scene_right.png
gt=$fixtures/scene_gt.pfm

# The value of a numeric JSON field.
field() { printf '%s\n' "$1" | sed -n "s/.*\"$2\":\([-0-9.e+]*\).*/\1/p"; }
# require WHAT VALUE OP LIMIT: awk numeric comparison.
require() {
    if ! awk -v v="$2" -v l="$4" "BEGIN { exit !(v $3 l) }"; then
        echo "FAIL: $1: $2 is not $3 $4"
        exit 1
    fi
    echo "ok: $1: $2 $3 $4"
}

"$stereo" match "$left" "$right" --ndisp 16 --min-disp -4 -o "$work/m.pfm" >/dev/null
"$stereo" match "$left" "$right" --ndisp 16 --min-disp -4 -o "$work/m16.png" --png16 >/dev/null
"$stereo" match "$left" "$right" --ndisp 16 -o "$work/m4.png" --scale 4 >/dev/null

pfm=$("$stereo" eval "$work/m.pfm" "$gt" --threshold 0 --json)
png16=$("$stereo" eval "$work/m16.png" "$gt" --encoding offset16 --threshold 0 --json)
# The "ms"-free JSON of both runs: identical.
if [ "$pfm" != "$png16" ]; then
    echo "FAIL: PFM and offset16 score differently:"
    echo "$pfm"
    echo "$png16"
    exit 1
fi
echo "ok: PFM and offset16 identical at threshold 0: $pfm"
# The scene exercises the comparison: most known pixels are scored, and at threshold 0 the
# fractional disparities make a difference between exact and rounded decoding.
require "coverage" "$(field "$pfm" coverage)" ">=" 0.4
exact=$(field "$pfm" bad_valid)
require "bad_valid at threshold 0 (sub-pixel values not all exact)" "$exact" ">" 0

scaled=$("$stereo" eval "$work/m4.png" "$gt" --scale 4 --json)
unscaled=$("$stereo" eval "$work/m4.png" "$gt" --json)
require "bad_valid with --scale 4" "$(field "$scaled" bad_valid)" "<" 25
require "bad_valid without --scale" "$(field "$unscaled" bad_valid)" ">" 90

# A GT stored times 4 (the Middlebury 2003 convention) needs --gt-scale 4: the sub-pixel map
# against its own rounded labels x 4 is within half a pixel everywhere only with it.
"$stereo" match "$left" "$right" --ndisp 16 -o "$work/m0.pfm" >/dev/null
gt4=$("$stereo" eval "$work/m0.pfm" "$work/m4.png" --gt-scale 4 --threshold 0.5 --json)
nogt4=$("$stereo" eval "$work/m0.pfm" "$work/m4.png" --threshold 0.5 --json)
require "bad_valid against labels x 4 with --gt-scale 4" "$(field "$gt4" bad_valid)" "==" 0
require "bad_valid against labels x 4 without --gt-scale" "$(field "$nogt4" bad_valid)" ">" 90
echo "ok"
