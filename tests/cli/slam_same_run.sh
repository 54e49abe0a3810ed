#!/bin/sh
# slam_same_run.sh OUT STEREO SEQUENCE "OPTIONS_A" "OPTIONS_B" ARGS...: `STEREO slam SEQUENCE ARGS
# OPTIONS_A` and the same with OPTIONS_B (each a space-separated list) must write the same
# trajectory and the same map, byte for byte: e.g. --threads 1 against --threads 2 (the next
# frame read and matched while this one is integrated).
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
out=$1
stereo=$2
sequence=$3
options_a=$4
options_b=$5
shift 5
fresh_work "$out" a b
for run in a b; do
  if [ "$run" = a ]; then options=$options_a; else options=$options_b; fi
  # shellcheck disable=SC2086  # OPTIONS is a list of words
  "$stereo" slam "$sequence" "$@" $options \
    --trajectory "$out/$run/trajectory.txt" --map "$out/$run/map.png" > /dev/null
done
for file in trajectory.txt map.png; do
  cmp "$out/a/$file" "$out/b/$file" || { echo "'$options_a' and '$options_b' differ in $file"; exit 1; }
done
echo "identical trajectory and map for '$options_a' and '$options_b' ($(wc -l < "$out/a/trajectory.txt") poses)"
