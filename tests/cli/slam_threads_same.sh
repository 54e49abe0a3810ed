#!/bin/sh
# slam_threads_same.sh OUT STEREO SEQUENCE ARGS...: `STEREO slam SEQUENCE ARGS` with --threads 1
# and with --threads 2 (the next frame read and matched while this one is integrated) must
# write the same trajectory and the same map, byte for byte.
# shellcheck disable=SC2154  # the arguments: named_args (common.sh) assigns them
set -eu
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
named_args out stereo sequence -- "$@"
shift 3
fresh_work "$out" one two
for run in one:1 two:2; do
  dir=${run%%:*}
  "$stereo" slam "$sequence" "$@" --threads "${run#*:}" \
    --trajectory "$out/$dir/trajectory.txt" --map "$out/$dir/map.png" > /dev/null
done
for file in trajectory.txt map.png; do
  cmp "$out/one/$file" "$out/two/$file" || { echo "--threads 1 and 2 differ in $file"; exit 1; }
done
echo "identical trajectory and map for 1 and 2 threads ($(wc -l < "$out/one/trajectory.txt") poses)"
