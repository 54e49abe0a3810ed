#!/bin/sh
# Usage: aloe_end_to_end.sh STEREO ALOE_DIR WORKDIR
#
# The README's main job at quarter size: match Debian opencv-doc's Aloe pair, write the colour
# view, and score it against aloeGT.png. Fails if the error among the output pixels or the
# coverage drifts from what was measured when the census cost became the default (bad_valid
# 4.31 %, coverage 0.760; 4.34 % at 0.760 with the calibrated sub-pixel table; with the AD defaults before it: 3.82 % at 0.663; before stage 6: bad_all
# 26.96 %, coverage 0.899 with every pixel output), so a regression on real input is caught. Exit 77 (skipped) when the package's data is
# not installed.
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
stereo=$1
aloe=$2
work=$3
files_or_skip "Aloe (Debian package opencv-doc)" "$aloe" aloeL.jpg aloeR.jpg aloeGT.png
mkdir -p "$work"
rm -f "$work/aloe.png" "$work/aloe_colour.png"
"$stereo" match "$aloe/aloeL.jpg" "$aloe/aloeR.jpg" --downscale 4 --ndisp 64 --scale 4 \
    -o "$work/aloe.png" --color "$work/aloe_colour.png"
[ -s "$work/aloe.png" ] && [ -s "$work/aloe_colour.png" ] || { echo "FAIL: outputs missing"; exit 1; }
scores=$("$stereo" eval "$work/aloe.png" "$aloe/aloeGT.png" --scale 4 --gt-downscale 4 --json)
echo "$scores"
# Pull two numbers out of the one-line JSON with sed (no jq on a fresh machine).
bad=$(printf '%s' "$scores" | sed -n 's/.*"bad_valid":\([0-9.]*\).*/\1/p')
coverage=$(printf '%s' "$scores" | sed -n 's/.*"coverage":\([0-9.]*\).*/\1/p')
awk -v bad="$bad" -v cov="$coverage" 'BEGIN {
    if (bad == "" || cov == "") { print "FAIL: scores missing"; exit 1 }
    if (bad > 4.7) { print "FAIL: bad_valid " bad " % > 4.7 %"; exit 1 }
    if (cov < 0.73) { print "FAIL: coverage " cov " < 0.73"; exit 1 }
    print "OK: bad_valid " bad " %, coverage " cov
}'
