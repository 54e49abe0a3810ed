#!/bin/sh
# Usage: cosim_localises.sh STAGE DEFINE STEREO LEFT RIGHT WORKDIR
#
# A deliberately broken RTL (the test hook DEFINE of stereo_ca_plane, which breaks one stage's
# rounding) co-simulated on demand: `stereo cosim` must exit 3, name STAGE as the first stage
# whose output differs (its stage probes against the model's stage values at the first
# mismatching pixels), in the JSON and in its error line, and write the --diff map.
# shellcheck disable=SC2154  # the arguments: named_args (common.sh) assigns them
set -u
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
named_args stage define stereo left right work -- "$@"
fresh_work "$work"
fail() {
    echo "FAIL: $*"
    for f in "$work/out.json" "$work/err"; do echo "--- $f:"; cat "$f"; done
    exit 1
}
STEREO_COSIM_DEFINES=$define "$stereo" cosim "$left" "$right" --size 64x48 --ndisp 16 --window 5 \
    --cost census --uniqueness 5 --lr-check 1 --subpixel --cache "$work/cache" \
    --diff "$work/diff.png" --json >"$work/out.json" 2>"$work/err"
status=$?
[ "$status" -eq 3 ] || fail "exit code $status, expected 3 (a mismatch)"
grep -q "\"localisation\":{[^}]*\"stage\":\"$stage\"" "$work/out.json" || fail "not localised to $stage"
tail -n 1 "$work/err" | grep -q "pixels differ from the golden model; the first stage that differs is $stage: at (" ||
    fail "the error line does not name $stage"
[ -s "$work/diff.png" ] || fail "no --diff map"
[ "$(head -c 4 "$work/diff.png" | tail -c 3)" = "PNG" ] || fail "--diff is not a PNG"
echo "localised to $stage"
