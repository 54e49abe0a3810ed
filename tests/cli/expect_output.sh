#!/bin/sh
# Usage: expect_output.sh REGEX COMMAND [ARGS...]
# Runs COMMAND and checks that it exits with 0, prints nothing on stderr, and that its stdout
# matches the extended regular expression REGEX (grep -E, any line).
set -u
regex=$1
shift
out=$(mktemp)
err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT

"$@" >"$out" 2>"$err"
status=$?
if [ "$status" -ne 0 ] || [ -s "$err" ] || ! grep -Eq -- "$regex" "$out"; then
    echo "FAIL: exit $status, expected 0 and stdout matching /$regex/ with an empty stderr"
    echo "--- stdout:"; cat "$out"
    echo "--- stderr:"; cat "$err"
    exit 1
fi
echo "ok"
