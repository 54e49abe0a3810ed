#!/bin/sh
# Usage: negations.sh STEREO FIXTURES WORKDIR
#
# Every switch of `stereo match` can be turned off explicitly (issue 47): sub-pixel output is on
# by default, and --no-subpixel and --subpixel=false both turn it off, in the JSON summary and
# in the map (on the scene fixture, whose slanted plane has fractional disparities); the
# positive forms of the negative switches (--validation, --ca) give the default map; --help
# names --no-subpixel with the default; --color and --error-map carry their key unless
# --no-color-bar / --no-legend.
set -eu
stereo=$1
fixtures=$2
work=$3
mkdir -p "$work"
rm -f "$work"/*.pfm "$work"/*.png
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
printf '%s\n' "$help" | grep -A3 -e "--subpixel" | grep -q "default: --subpixel\]" \
    || { echo "FAIL: --help does not show sub-pixel's default"; exit 1; }
echo "ok: --help names every negation and sub-pixel's default"

# --color carries a colour bar below the map unless --no-color-bar (issue 47); the same for
# eval's --error-map legend and --no-legend. Heights from the PNG header (IHDR).
png_height() { od -An -tu1 -j20 -N4 "$1" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4 }'; }
"$stereo" match "$@" -o "$work/map.pfm" --color "$work/keyed.png" >/dev/null
"$stereo" match "$@" -o "$work/map2.pfm" --color "$work/bare.png" --no-color-bar >/dev/null
"$stereo" eval "$work/default.pfm" "$fixtures/scene_gt.pfm" --error-map "$work/errors.png" >/dev/null
"$stereo" eval "$work/default.pfm" "$fixtures/scene_gt.pfm" --error-map "$work/errors_bare.png" \
    --no-legend >/dev/null
height=$(sed -n 2p "$work/map.pfm" | cut -d' ' -f2)  # PFM: "Pf", "W H", scale
[ "$(png_height "$work/bare.png")" -eq "$height" ] || { echo "FAIL: --no-color-bar changed the size"; exit 1; }
[ "$(png_height "$work/keyed.png")" -gt "$height" ] || { echo "FAIL: --color has no bar"; exit 1; }
[ "$(png_height "$work/errors_bare.png")" -eq "$height" ] || { echo "FAIL: --no-legend changed the size"; exit 1; }
[ "$(png_height "$work/errors.png")" -gt "$height" ] || { echo "FAIL: --error-map has no legend"; exit 1; }
echo "ok: --color has its bar and --error-map its legend unless --no-color-bar / --no-legend"
