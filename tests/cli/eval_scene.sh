#!/bin/sh
# Usage: eval_scene.sh STEREO FIXTURES WORKDIR
#
# stereo eval on the scene fixture, whose true disparity varies (planes at 2, 7 and -2.5, a
# slanted plane, occlusions; scene_gt.pfm, written by make_cli_fixtures by forward warping):
# 1. the same map read as PFM and as an offset16 PNG scores identically at threshold 0, so every
#    1/16 pixel and the sign of the offset16 decoding count;
# 2. a map stored times 4 by another tool (no tag) scores like the PFM only when --scale 4 is
#    given (ignoring the scale makes nearly every pixel bad), and a GT stored times 4 likewise
#    needs --gt-scale 4: without it eval refuses (its range is far outside the map's);
# 3. the PNGs stereo writes record their encoding and scale (issue 47): the offset16 PNG scores
#    like the PFM without --encoding, the x 4 PNG like --scale 4 without --scale, and an option
#    that contradicts the record is refused.
set -eu
stereo=$1
fixtures=$2
work=$3
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
mkdir -p "$work"
rm -f "$work"/m.pfm "$work"/m0.pfm "$work"/m16.png "$work"/m4.png "$work"/m4_other.png
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

# The same x 4 map as another tool writes it: no record of its scale.
untag "$work/m4.png" "$work/m4_other.png"
scaled=$("$stereo" eval "$work/m4_other.png" "$gt" --scale 4 --json)
unscaled=$("$stereo" eval "$work/m4_other.png" "$gt" --json)
require "bad_valid with --scale 4" "$(field "$scaled" bad_valid)" "<" 25
require "bad_valid without --scale" "$(field "$unscaled" bad_valid)" ">" 90

# A GT stored times 4 (the Middlebury 2003 convention) needs --gt-scale 4: the sub-pixel map
# against its own rounded labels x 4 is within half a pixel everywhere only with it; without it
# the GT reaches 4x the map's largest disparity and eval refuses, unless --any-gt-range.
"$stereo" match "$left" "$right" --ndisp 16 -o "$work/m0.pfm" >/dev/null
gt4=$("$stereo" eval "$work/m0.pfm" "$work/m4_other.png" --gt-scale 4 --threshold 0.5 --json)
require "bad_valid against labels x 4 with --gt-scale 4" "$(field "$gt4" bad_valid)" "==" 0
# expect_refusal WHAT WORD ARGS...: stereo ARGS exits 2 with one error line that names WORD.
expect_refusal() {
    _what=$1 _word=$2
    shift 2
    if "$stereo" "$@" >"$work/out.txt" 2>"$work/err.txt"; then
        echo "FAIL: $_what: exit 0"; cat "$work/out.txt"; exit 1
    else
        _status=$?
    fi
    [ "$_status" -eq 2 ] || { echo "FAIL: $_what: exit $_status, expected 2"; exit 1; }
    [ "$(wc -l <"$work/err.txt")" -eq 1 ] || { echo "FAIL: $_what: not one line"; exit 1; }
    grep -q -e "$_word" "$work/err.txt" || { echo "FAIL: $_what: no $_word"; exit 1; }
    echo "ok: $_what: $(cat "$work/err.txt")"
}
expect_refusal "GT x 4 without --gt-scale" "--gt-scale" \
    eval "$work/m0.pfm" "$work/m4_other.png" --threshold 0.5 --json
forced=$("$stereo" eval "$work/m0.pfm" "$work/m4_other.png" --threshold 0.5 --any-gt-range --json)
require "bad_valid against labels x 4 with --any-gt-range" "$(field "$forced" bad_valid)" ">" 90

# 3. The PNGs stereo writes carry their encoding and scale.
png16_auto=$("$stereo" eval "$work/m16.png" "$gt" --threshold 0 --json)
[ "$png16_auto" = "$pfm" ] || { echo "FAIL: offset16 without --encoding: $png16_auto"; exit 1; }
echo "ok: the --png16 map scores like the PFM without --encoding"
scaled_auto=$("$stereo" eval "$work/m4.png" "$gt" --json)
[ "$scaled_auto" = "$scaled" ] || { echo "FAIL: x 4 PNG without --scale: $scaled_auto"; exit 1; }
echo "ok: the --scale 4 map scores like --scale 4 without --scale"
gt4_auto=$("$stereo" eval "$work/m0.pfm" "$work/m4.png" --threshold 0.5 --json)
[ "$gt4_auto" = "$gt4" ] || { echo "FAIL: x 4 GT without --gt-scale: $gt4_auto"; exit 1; }
echo "ok: a x 4 GT written by stereo reads right without --gt-scale"
expect_refusal "--encoding scaled on an offset16 PNG" "--encoding" \
    eval "$work/m16.png" "$gt" --encoding scaled
expect_refusal "--scale 1 on a x 4 PNG" "--scale" eval "$work/m4.png" "$gt" --scale 1
echo "ok"
