#!/bin/sh
# same_output.sh OUT STEREO ARGS_A... -- ARGS_B...: runs `STEREO ARGS_A -o OUT.a.png` and
# `STEREO ARGS_B -o OUT.b.png` and requires both to succeed and write identical bytes (two
# engines of one method must agree to the byte).
set -eu
out=$1
stereo=$2
shift 2
a=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do a="$a $1"; shift; done
[ "$#" -gt 0 ] || { echo "usage: same_output.sh OUT STEREO ARGS_A -- ARGS_B"; exit 2; }
shift
rm -f "$out.a.png" "$out.b.png"
# shellcheck disable=SC2086
"$stereo" $a -o "$out.a.png"
"$stereo" "$@" -o "$out.b.png"
if ! cmp -s "$out.a.png" "$out.b.png"; then
  echo "outputs differ: $a  vs  $*"
  exit 1
fi
echo "identical: $a  vs  $*"
