#!/bin/sh
# same_output.sh [--differ] OUT STEREO ARGS_A... -- ARGS_B...: runs `STEREO ARGS_A -o OUT_A` and
# `STEREO ARGS_B -o OUT_B` and requires both to succeed and write identical bytes (two engines of
# one method must agree to the byte). OUT ending in .pfm writes PFM maps (OUT_A = OUT.a.pfm),
# otherwise PNGs (OUT.a.png). With --differ the maps must differ instead: the fixture tells the
# two settings apart, so an engine that ignored the option would fail an equality test on it
# (issue 52).
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
expect=same
if [ "${1:-}" = --differ ]; then expect=different; shift; fi
case $1 in
  *.pfm) base=${1%.pfm}; ext=pfm ;;
  *) base=$1; ext=png ;;
esac
stereo=$2
shift 2
split_args "same_output.sh [--differ] OUT STEREO ARGS_A -- ARGS_B" "$@"
shift "$a_count"
rm -f "$base.a.$ext" "$base.b.$ext"
# shellcheck disable=SC2086
"$stereo" $a -o "$base.a.$ext"
"$stereo" "$@" -o "$base.b.$ext"
if cmp -s "$base.a.$ext" "$base.b.$ext"; then
  [ "$expect" = same ] || { echo "the fixture does not tell these apart (identical maps): $a  vs  $*"; exit 1; }
  echo "identical: $a  vs  $*"
else
  [ "$expect" = different ] || { echo "outputs differ: $a  vs  $*"; exit 1; }
  echo "different maps: $a  vs  $*"
fi
