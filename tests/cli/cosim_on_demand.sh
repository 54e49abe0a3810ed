#!/bin/sh
# Usage: cosim_on_demand.sh STEREO LEFT RIGHT WORKDIR
#
# `stereo cosim --size` on a configuration this build does not have (64x48, 8 labels 2 per clock,
# census, window 5): the first run Verilates it into an empty cache (one progress line on
# stderr) and co-simulates bit-exactly against the model with stalls, two frames and a
# mid-frame reset; the cache then holds exactly that runner and nothing half-written; the
# second run reuses it (no build line) with the same result; a --trace run builds the traced
# runner beside it and writes the FST.
set -u
stereo=$1
left=$2
right=$3
work=$4
cache=$work/cache

fail() {
    echo "FAIL: $*"
    for f in "$work"/*.json "$work"/*.err; do
        [ -f "$f" ] && { echo "--- $f:"; cat "$f"; }
    done
    exit 1
}

rm -rf "$work"
mkdir -p "$work"
run() {  # run NAME: the co-simulation, its JSON on NAME.json and stderr on NAME.err
    "$stereo" cosim "$left" "$right" --size 64x48 --ndisp 8 --window 5 --cost census --lanes 2 \
        --min-disp -3 --uniqueness 5 --lr-check 1 --subpixel --stall 0.2 --gap 0.2 --seed 3 \
        --frames 2 --reset-at 900 --cache "$cache" --json >"$work/$1.json" 2>"$work/$1.err" ||
        fail "$1 run exited with $?"
    grep -q '"mismatches":0,' "$work/$1.json" || fail "$1 run: mismatches"
    grep -q '"pixels_compared":6144,' "$work/$1.json" || fail "$1 run: not two whole frames"
    grep -q '"config":"on-demand 64x48-n8-w5-census-l2-m8"' "$work/$1.json" ||
        fail "$1 run: not the on-demand core"
}

run first
grep -q '^cosim: building the Verilated core 64x48, 8 labels, window 5, cost census, LANES 2' \
    "$work/first.err" || fail "no progress line"
[ "$(ls -A "$cache" | wc -l)" -eq 1 ] || fail "the cache holds $(ls -A "$cache")"
ls -A "$cache" | grep -q '^\.' && fail "a hidden (half-built) entry was left"
[ -x "$cache"/*/runner ] || fail "no runner in the cache"

run second
[ ! -s "$work/second.err" ] || fail "the second run built again"

# A trace needs FST tracing compiled in: a runner of its own, next to the plain one; built here
# through a relative cache path (Verilator's make runs in another folder).
(cd "$work" && "$stereo" cosim "$left" "$right" --size 64x48 --ndisp 8 --window 5 --cost census \
    --lanes 2 --cache cache --trace run.fst --json >trace.json 2>trace.err) ||
    fail "trace run exited with $?"
grep -q '"mismatches":0,' "$work/trace.json" || fail "trace run: mismatches"
[ -s "$work/run.fst" ] || fail "no FST trace written"
[ "$(ls -A "$cache" | wc -l)" -eq 2 ] || fail "the cache holds $(ls -A "$cache") after the trace run"
echo "on-demand core built once, reused, bit-exact; traced by its own runner"
