#!/bin/sh
# Usage: peak_memory.sh STEREO TABLE FIXTURES BOUND_KB WORK
#
# The peak memory of `stereo` on crafted images (issue 51): every row of TABLE (bad_inputs.txt)
# named hostile_* runs under /usr/bin/time -f %M (or Python's getrusage where that is missing) and
# must exit with the row's code, print one stderr line that names the hostile file, and peak below
# BOUND_KB kilobytes of resident memory. Its ARGS set --max-pixels 1048576 (2^20); the bound and
# why it is a function of the limit: docs/reliability.md, "Bounded inputs". Prints a table of
# the measured peaks.
# shellcheck disable=SC2154  # the arguments: named_args (common.sh) assigns them
set -u
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
named_args stereo table fixtures bound work -- "$@"

fresh_work "$work" out
stderr="$work/stderr"
measure="$work/peak"

peak() {  # peak COMMAND...: runs it, writes its peak RSS in kB to $measure, returns its status
    if [ -x /usr/bin/time ]; then
        /usr/bin/time -f %M -o "$measure" "$@"
    else
        python3 -c '
import resource, subprocess, sys
status = subprocess.call(sys.argv[2:])
open(sys.argv[1], "w").write("%d\n" % resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
sys.exit(status)' "$measure" "$@"
    fi
}

rows=0
failures=0
printf '%-28s %5s %10s\n' row exit peak_kB
while IFS='|' read -r name code args; do
    name=$(echo "$name" | tr -d ' ')
    case "$name" in hostile_*) ;; *) continue ;; esac
    code=$(echo "$code" | tr -d ' ')
    rows=$((rows + 1))
    args=$(echo "$args" | sed -e "s|@F@|$fixtures|g" -e "s|@O@|$work/out|g")
    file=$(echo "$args" | tr ' ' '\n' | grep '/hostile_\|huge_header' | head -n 1)
    set -f
    # shellcheck disable=SC2086  # ARGS is a list of words
    peak timeout 120 "$stereo" $args >/dev/null 2>"$stderr" </dev/null
    status=$?
    set +f
    kb=$(tail -n 1 "$measure")
    printf '%-28s %5s %10s\n' "$name" "$status" "$kb"
    problem=
    if [ "$status" -ne "$code" ]; then
        problem="exit code $status, expected $code"
    elif [ "$(wc -l <"$stderr")" -ne 1 ]; then
        problem="stderr has $(wc -l <"$stderr") lines, expected 1"
    elif ! grep -qF "'$file'" "$stderr"; then
        problem="the error does not name '$file'"
    elif [ "$kb" -ge "$bound" ]; then
        problem="peak memory $kb kB, bound $bound kB"
    fi
    if [ -n "$problem" ]; then
        failures=$((failures + 1))
        echo "FAIL: $name: $problem"
        sed 's/^/  stderr: /' "$stderr" | head -n 3
    fi
done <"$table"

echo "$rows rows, $failures failed"
[ "$rows" -gt 0 ] && [ "$failures" -eq 0 ]
