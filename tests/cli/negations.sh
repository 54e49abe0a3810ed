#!/bin/sh
# Usage: negations.sh STEREO FIXTURES WORKDIR
#
# Every switch of `stereo match` can be turned off explicitly (issue 47): sub-pixel output is on
# by default, and --no-subpixel and --subpixel=false both turn it off, in the JSON summary and
# in the map (on the scene fixture, whose slanted plane has fractional disparities); the
# positive forms of the negative switches (--validation, --ca) give the default map; --help
# names --no-subpixel with the default.
set -eu
stereo=$1
fixtures=$2
work=$3
mkdir -p "$work"
rm -f "$work"/*.pfm
set -- "$fixtures/scene_left.png" "$fixtures/scene_right.png" --ndisp 16 --min-disp -4

run() {  # run NAME OPTIONS...: the map NAME.pfm and its JSON summary in NAME.json
    _name=$1
    shift
    "$stereo" match "$@" -o "$work/$_name.pfm" --json >"$work/$_name.json"
}
subpixel_field() { sed -n 's/.*"subpixel":\([a-z]*\).*/\1/p' "$work/$1.json"; }

run default "$@"
run no_subpixel "$@" --no-subpixel
run subpixel_false "$@" --subpixel=false
run subpixel_again "$@" --no-subpixel --subpixel
run validation "$@" --validation
run ca "$@" --ca

[ "$(subpixel_field default)" = true ] || { echo "FAIL: default subpixel is not true"; exit 1; }
for name in no_subpixel subpixel_false; do
    [ "$(subpixel_field $name)" = false ] || { echo "FAIL: $name: JSON subpixel not false"; exit 1; }
    if cmp -s "$work/default.pfm" "$work/$name.pfm"; then
        echo "FAIL: $name: the map is the default (sub-pixel) one"
        exit 1
    fi
done
cmp "$work/no_subpixel.pfm" "$work/subpixel_false.pfm"
for name in subpixel_again validation ca; do
    cmp "$work/default.pfm" "$work/$name.pfm" || { echo "FAIL: $name differs from the default"; exit 1; }
done
echo "ok: --no-subpixel and --subpixel=false turn sub-pixel off; --subpixel, --validation, --ca are the defaults"

help=$("$stereo" match --help)
for word in "--no-subpixel" "--validation" "--ca" "--no-png16" "--both-weights" "--no-separable" \
            "--continuity"; do
    printf '%s\n' "$help" | grep -q -e "$word" || { echo "FAIL: --help does not name $word"; exit 1; }
done
printf '%s\n' "$help" | grep -A3 -e "--subpixel" | grep -q "default: on" \
    || { echo "FAIL: --help does not show sub-pixel's default"; exit 1; }
echo "ok: --help names every negation and sub-pixel's default"
