#!/usr/bin/env bash
# cosim_soak.sh STEREO LEFT RIGHT FRAMES RESETS [SEED]: the co-simulation soak of docs/reliability.md.
#   1. FRAMES frames of the pair through the Verilated core, each under its own random input gaps
#      and output stalls (traffic seed SEED + frame), every pixel compared with the model;
#   2. RESETS runs, each resetting the core in the middle of a frame at a random beat (bash's
#      RANDOM seeded with SEED) with random traffic, then streaming 3 whole frames; each run
#      draws its own stage-6 configuration (minimum disparity -8..8, uniqueness 0..40 %,
#      left-right tolerance 0..2 or off, sub-pixel on or off) and cost stage (AD or LCDM).
# Fails on any mismatch, stall or protocol error (stereo cosim exits non-zero).
set -euo pipefail
stereo=$1 left=$2 right=$3 frames=$4 resets=$5 seed=${6:-1}
common=(--ndisp 16 --window 5 --json)
out=$("$stereo" cosim "$left" "$right" "${common[@]}" --frames "$frames" --stall 0.3 --gap 0.3 \
      --seed "$seed")
echo "$out" | grep -q '"mismatches":0,' || { echo "FAIL: $out"; exit 1; }
beats=$("$stereo" cosim "$left" "$right" "${common[@]}" | sed 's/.*"pixels":\([0-9]*\).*/\1/')
RANDOM=$seed
for ((r = 0; r < resets; ++r)); do
    at=$((RANDOM % beats))
    traffic_seed=$((seed * 1000 + r))
    stall=0.$((RANDOM % 6))
    gap=0.$((RANDOM % 6))
    stage6=(--min-disp $((RANDOM % 17 - 8)) --uniqueness $((RANDOM % 41)))
    lr=$((RANDOM % 4))
    [ "$lr" -lt 3 ] && stage6+=(--lr-check "$lr")
    [ $((RANDOM % 2)) -eq 0 ] && stage6+=(--subpixel)
    costs=(ad lcdm)
    stage6+=(--cost "${costs[$((RANDOM % 2))]}")
    out=$("$stereo" cosim "$left" "$right" "${common[@]}" "${stage6[@]}" --frames 3 \
          --reset-at "$at" --stall "$stall" --gap "$gap" --seed "$traffic_seed") ||
        { echo "FAIL: reset at $at, stall $stall, gap $gap, seed $traffic_seed, ${stage6[*]}: $out"
          exit 1; }
    echo "$out" | grep -q '"mismatches":0,' || { echo "FAIL: $out"; exit 1; }
done
echo "soak: $frames frames under stalls and $resets mid-frame resets (x3 frames each, random stage-6 settings and cost stage): 0 mismatches"
