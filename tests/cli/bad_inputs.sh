#!/bin/sh
# Usage: bad_inputs.sh STEREO TABLE FIXTURES SLAM_FIXTURES WORK
#
# The bad-input table of docs/reliability.md: every row of TABLE ("NAME | EXIT | ARGS", '#'
# comments) runs `STEREO ARGS` and must exit with EXIT, print nothing on stdout, print exactly one
# stderr line starting with "stereo: error: ", and leave every file it could reach unchanged
# (SHA-256 of every file under FIXTURES, SLAM_FIXTURES and WORK, before and after, so also no file
# created or removed). In ARGS, @F@, @S@, @O@ and @K@ stand for FIXTURES, SLAM_FIXTURES, WORK/out
# (outputs) and WORK/keep (copies of left.png, right.png, gt.png and a link left_link.png that
# rows name as outputs). Rows named unreadable_* are skipped as root, who can read any file.
# shellcheck disable=SC2154  # the arguments: named_args (common.sh) assigns them
set -u
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
named_args stereo table fixtures slam_fixtures work -- "$@"

fresh_work "$work" out keep
cp "$fixtures/left.png" "$fixtures/right.png" "$fixtures/gt.png" "$work/keep/"
ln -s "$work/keep/left.png" "$work/keep/left_link.png"
stdout=$(mktemp)
stderr=$(mktemp)
trap 'rm -f "$stdout" "$stderr"' EXIT

snapshot() {
    find "$fixtures" "$slam_fixtures" "$work" -type f -readable -print0 | sort -z |
        xargs -0 sha256sum
}

rows=0
failures=0
skipped=0
# A build without the RTL (-DSTEREO_WITH_RTL=OFF, e.g. the ASan preset) has a cosim that only
# says so (exit 2): its rows are skipped there.
has_rtl=1
"$stereo" cosim --help 2>/dev/null | grep -q "not in this build" && has_rtl=0
while IFS='|' read -r name code args; do
    name=$(echo "$name" | tr -d ' ')
    case "$name" in '' | '#'*) continue ;; esac
    code=$(echo "$code" | tr -d ' ')
    if [ "${name#unreadable_}" != "$name" ] && [ "$(id -u)" -eq 0 ]; then
        skipped=$((skipped + 1))
        echo "skip: $name (root reads any file)"
        continue
    fi
    case "$args" in
    *' cosim '* | 'cosim '*)
        if [ "$has_rtl" -eq 0 ]; then
            skipped=$((skipped + 1))
            echo "skip: $name (built without the RTL)"
            continue
        fi
        ;;
    esac
    rows=$((rows + 1))
    args=$(echo "$args" | sed -e "s|@F@|$fixtures|g" -e "s|@S@|$slam_fixtures|g" \
        -e "s|@O@|$work/out|g" -e "s|@K@|$work/keep|g")
    before=$(snapshot)
    set -f
    # shellcheck disable=SC2086  # ARGS is a list of words
    timeout 60 "$stereo" $args >"$stdout" 2>"$stderr" </dev/null
    status=$?
    set +f
    after=$(snapshot)
    problem=
    if [ "$status" -ne "$code" ]; then
        problem="exit code $status, expected $code"
    elif [ -s "$stdout" ]; then
        problem="stdout is not empty"
    elif [ "$(wc -l <"$stderr")" -ne 1 ]; then
        problem="stderr has $(wc -l <"$stderr") lines, expected 1"
    elif ! head -n 1 "$stderr" | grep -q '^stereo: error: .'; then
        problem="stderr does not start with 'stereo: error: '"
    elif [ "$before" != "$after" ]; then
        problem="a file changed, appeared or disappeared: $(printf '%s\n%s\n' "$before" "$after" |
            sort | uniq -u | head -n 2 | tr '\n' ' ')"
    fi
    if [ -n "$problem" ]; then
        failures=$((failures + 1))
        echo "FAIL: $name: $problem"
        echo "  command: stereo $args"
        sed 's/^/  stdout: /' "$stdout" | head -n 5
        sed 's/^/  stderr: /' "$stderr" | head -n 5
    else
        echo "ok: $name: exit $status: $(cat "$stderr")"
    fi
done <"$table"

echo "$rows rows, $failures failed, $skipped skipped"
[ "$rows" -gt 0 ] && [ "$failures" -eq 0 ]
