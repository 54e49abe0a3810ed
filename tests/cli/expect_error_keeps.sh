#!/bin/sh
# Usage: expect_error_keeps.sh EXIT_CODE KEEP COMMAND [ARGS...]
#
# expect_error.sh's contract (exit code, empty stdout, one error line) for a command whose outputs
# name existing files, plus: every file in KEEP (':'-separated) has the same bytes afterwards.
set -u
expected=$1
keep=$2
shift 2
here=$(dirname "$0")
digests() {
    old_ifs=$IFS
    IFS=:
    for file in $keep; do sha256sum "$file"; done
    IFS=$old_ifs
}
before=$(digests) || { echo "FAIL: a KEEP file is missing"; exit 1; }
sh "$here/expect_error.sh" "$expected" - "$@" || exit 1
after=$(digests)
[ "$before" = "$after" ] || { echo "FAIL: a file the command must not touch changed"; exit 1; }
echo "ok: kept $keep"
