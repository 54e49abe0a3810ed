#!/bin/sh
# Usage: match_then_eval.sh STEREO FIXTURES WORKDIR
#
# End to end: match the generated pair (true disparity 4 everywhere), then evaluate the result
# against itself (must be perfect) and against the true disparity (every valid pixel exact).
set -eu
stereo=$1
fixtures=$2
work=$3
mkdir -p "$work"
rm -f "$work/disp.png" "$work/colour.png" "$work/errors.png"

check() {  # check TEXT REGEX WHAT
    if ! printf '%s\n' "$1" | grep -Eq -- "$2"; then
        echo "FAIL: $3: /$2/ not found in:"
        printf '%s\n' "$1"
        exit 1
    fi
}

summary=$("$stereo" match "$fixtures/left.png" "$fixtures/right.png" -o "$work/disp.png" \
    --ndisp 8 --scale 4 --color "$work/colour.png" --json)
echo "match: $summary"
check "$summary" '"width":64' "match width"
check "$summary" '"ndisp":8' "match ndisp"
check "$summary" '"valid_fraction":0\.[0-9]' "match valid_fraction"
[ -s "$work/disp.png" ] && [ -s "$work/colour.png" ] || { echo "FAIL: outputs missing"; exit 1; }

self=$("$stereo" eval "$work/disp.png" "$work/disp.png" --scale 4 --gt-scale 4 --json)
echo "self: $self"
check "$self" '"bad_all":0\.0[,}]' "self bad_all"
check "$self" '"nmse":0\.0[,}]' "self nmse"
check "$self" '"coverage":1\.0[,}]' "self coverage"
check "$self" '"bad_nonocc":null' "self bad_nonocc"
check "$self" '"bad_disc":null' "self bad_disc"

truth=$("$stereo" eval "$work/disp.png" "$fixtures/gt.png" --scale 4 --gt-scale 4 \
    --nonocc "$fixtures/mask.png" --error-map "$work/errors.png" --json)
echo "truth: $truth"
check "$truth" '"nmse":0\.0[,}]' "truth nmse"
[ -s "$work/errors.png" ] || { echo "FAIL: error map missing"; exit 1; }

text=$("$stereo" eval "$work/disp.png" "$work/disp.png" --scale 4 --gt-scale 4)
check "$text" '^bad_all +0\.00 %' "text bad_all"
check "$text" '^bad_nonocc +n/a' "text bad_nonocc"
echo "ok"
