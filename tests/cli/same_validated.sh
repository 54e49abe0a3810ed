#!/bin/sh
# same_validated.sh [--vertical] OUT CHECKER "REQUIREMENTS" STEREO ARGS_A... -- ARGS_B...: runs
# `STEREO ARGS_A` and `STEREO ARGS_B`, each writing stage 6's whole output (the disparity as PFM,
# so every 1/16 pixel counts, the reason codes and the certainty), and requires both runs to
# succeed and the three files to be identical bytes. Then CHECKER (map_exercises) must find that
# the map exercises the path: `CHECKER OUT.a.pfm --reasons OUT.a.reasons.png REQUIREMENTS`
# (e.g. "--min-valid 0.3 --fractional --negative --reason-codes 1,3,4"), so that the test fails
# when its fixture stops exercising what it claims (issue 52). With --vertical first, both runs
# also write the vertical offsets (--vertical, the 2-D methods) and those must be identical too.
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
parts="pfm reasons.png certainty.png"
if [ "${1:-}" = --vertical ]; then parts="$parts vertical.png"; shift; fi
out=$1
checker=$2
requirements=$3
stereo=$4
shift 4
split_args "same_validated.sh OUT CHECKER REQUIREMENTS STEREO ARGS_A -- ARGS_B" "$@"
shift "$a_count"
vertical_a=
vertical_b=
case $parts in
  *vertical*) vertical_a="--vertical $out.a.vertical.png"; vertical_b="--vertical $out.b.vertical.png" ;;
esac
for side in a b; do
  for part in $parts; do rm -f "$out.$side.$part"; done
done
# shellcheck disable=SC2086
"$stereo" $a -o "$out.a.pfm" --reasons "$out.a.reasons.png" --certainty "$out.a.certainty.png" $vertical_a
# shellcheck disable=SC2086
"$stereo" "$@" -o "$out.b.pfm" --reasons "$out.b.reasons.png" --certainty "$out.b.certainty.png" $vertical_b
for part in $parts; do
  if ! cmp -s "$out.a.$part" "$out.b.$part"; then
    echo "outputs differ ($part): $a  vs  $*"
    exit 1
  fi
done
echo "identical $parts: $a  vs  $*"
# shellcheck disable=SC2086
"$checker" "$out.a.pfm" --reasons "$out.a.reasons.png" $requirements
