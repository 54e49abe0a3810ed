#!/bin/sh
# Usage: expect_error.sh EXIT_CODE OUTPUTS COMMAND [ARGS...]
#
# Runs COMMAND and checks the error contract of `stereo` and `stereo_experiments`: the exit code
# is EXIT_CODE, stdout is empty, stderr is exactly one line starting with "NAME: error: " (NAME:
# the file name of COMMAND), and none of the files in OUTPUTS (':'-separated, '-' for none)
# exists afterwards.
set -u
expected=$1
outputs=$2
shift 2
prefix="$(basename "$1"): error: "

fail() {
    echo "FAIL: $*"
    echo "--- command: $*"
    echo "--- stdout:"; cat "$out"
    echo "--- stderr:"; cat "$err"
    exit 1
}

out=$(mktemp)
err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT

old_ifs=$IFS
IFS=:
for file in $outputs; do
    [ "$file" = "-" ] || rm -f "$file"
done
IFS=$old_ifs

"$@" >"$out" 2>"$err"
status=$?

[ "$status" -eq "$expected" ] || fail "exit code $status, expected $expected"
[ ! -s "$out" ] || fail "stdout is not empty"
[ "$(wc -l <"$err")" -eq 1 ] || fail "stderr is not exactly one line"
case "$(cat "$err")" in
    "$prefix"?*) ;;
    *) fail "stderr does not start with '$prefix'" ;;
esac

IFS=:
for file in $outputs; do
    if [ "$file" != "-" ] && [ -e "$file" ]; then
        IFS=$old_ifs
        fail "output file $file was created"
    fi
done
IFS=$old_ifs

echo "ok: exit $status: $(cat "$err")"
