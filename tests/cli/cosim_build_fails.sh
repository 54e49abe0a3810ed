#!/bin/sh
# Usage: cosim_build_fails.sh STEREO LEFT RIGHT WORKDIR
#
# A Verilator build that fails (a stand-in `verilator` that reports a version, then fails the
# build with an %Error line): `stereo cosim --size` exits 1 with the progress line and one error
# line naming the failure, and leaves the cache empty (nothing half-built a later run would use).
# shellcheck disable=SC2154  # the arguments: named_args (common.sh) assigns them
set -u
# shellcheck source=tests/cli/common.sh
. "$(dirname "$0")/common.sh"
named_args stereo left right work -- "$@"
fresh_work "$work"
cat >"$work/verilator" <<'FAKE'
#!/bin/sh
if [ "$1" = "--version" ]; then echo "Verilator 5.006 (stand-in)"; exit 0; fi
echo "%Error: stand-in build failure"
exit 1
FAKE
chmod +x "$work/verilator"
STEREO_VERILATOR=$work/verilator "$stereo" cosim "$left" "$right" --size 64x32 --ndisp 8 \
    --window 5 --cache "$work/cache" >"$work/out" 2>"$work/err"
status=$?
fail() { echo "FAIL: $*"; echo "--- stderr:"; cat "$work/err"; exit 1; }
[ "$status" -eq 1 ] || fail "exit code $status, expected 1"
[ ! -s "$work/out" ] || fail "stdout is not empty"
[ "$(wc -l <"$work/err")" -eq 2 ] || fail "stderr is not the progress line and one error line"
tail -n 1 "$work/err" | grep -q '^stereo: error: cosim: building the core .* failed (.* exited with status 1): %Error: stand-in build failure$' ||
    fail "the error line does not name the failure"
[ -z "$(ls -A "$work/cache")" ] || fail "the cache holds $(ls -A "$work/cache")"
echo "failed build reported, cache left empty"
