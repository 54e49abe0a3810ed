#!/bin/sh
# differs.sh OUT STEREO ARGS_A... -- ARGS_B...: runs `STEREO ARGS_A -o OUT.a.pfm` and
# `STEREO ARGS_B -o OUT.b.pfm` and requires both to succeed and the maps to differ: the fixture
# tells the two settings apart, so an engine that ignored the option would fail an equality test
# on it (issue 52).
set -eu
out=$1
stereo=$2
shift 2
a=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do a="$a $1"; shift; done
[ "$#" -gt 0 ] || { echo "usage: differs.sh OUT STEREO ARGS_A -- ARGS_B"; exit 2; }
shift
rm -f "$out.a.pfm" "$out.b.pfm"
# shellcheck disable=SC2086
"$stereo" $a -o "$out.a.pfm"
"$stereo" "$@" -o "$out.b.pfm"
if cmp -s "$out.a.pfm" "$out.b.pfm"; then
  echo "the fixture does not tell these apart (identical maps): $a  vs  $*"
  exit 1
fi
echo "different maps: $a  vs  $*"
