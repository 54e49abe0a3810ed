#!/bin/sh
# Usage: teddy_gt_scale.sh STEREO DATA_DIR WORKDIR
#
# Issue 47's case: Middlebury 2003's teddy/gt.png holds 4 d (its maximum is 211, the map's about
# 50), so `stereo eval MAP teddy/gt.png` without --gt-scale 4 used to print 100 % bad and exit 0.
# It must now exit 2 with one line naming --gt-scale, and with --gt-scale 4 score normally.
# Half size to keep it short. Exit 77 (skipped) when the data is absent.
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
stereo=$1
teddy=$2/middlebury2003/teddy
work=$3
files_or_skip teddy "$teddy" left.png right.png gt.png
mkdir -p "$work"
rm -f "$work/teddy.pfm"
"$stereo" match "$teddy/left.png" "$teddy/right.png" --downscale 2 --ndisp 32 \
    -o "$work/teddy.pfm" >/dev/null
status=0
"$stereo" eval "$work/teddy.pfm" "$teddy/gt.png" --gt-downscale 2 >"$work/out.txt" \
    2>"$work/err.txt" || status=$?
cat "$work/err.txt"
[ "$status" -eq 2 ] || { echo "FAIL: exit $status without --gt-scale, expected 2"; cat "$work/out.txt"; exit 1; }
[ "$(wc -l <"$work/err.txt")" -eq 1 ] || { echo "FAIL: not one error line"; exit 1; }
grep -q -e "--gt-scale" "$work/err.txt" || { echo "FAIL: the error names no --gt-scale"; exit 1; }
scores=$("$stereo" eval "$work/teddy.pfm" "$teddy/gt.png" --gt-downscale 2 --gt-scale 4 --json)
bad=$(printf '%s' "$scores" | sed -n 's/.*"bad_all":\([0-9.]*\).*/\1/p')
awk -v bad="$bad" 'BEGIN {
    if (bad == "" || bad > 50) { print "FAIL: bad_all " bad " with --gt-scale 4"; exit 1 }
    print "ok: bad_all " bad " % with --gt-scale 4"
}'
