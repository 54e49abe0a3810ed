#!/bin/sh
# Usage: cosim_vga.sh STEREO ALOE_DIR CACHE
#
# Co-simulation speed at VGA (issue 43): one 640x480 / 64-label / 11x11 census frame of the Aloe
# pair (half size, cropped) through two cores built on demand — all labels per clock (LANES = 64)
# and the board core (lean memory, LANES = 8) — each compared with the golden model. Prints the
# cycles, the simulated cycles per second and the co-simulation's time against the golden model's
# for the same frame (measured in the same run). Exit 77 (skipped) without the Aloe pair.
set -eu
stereo=$1
aloe=$2
cache=$3
[ -f "$aloe/aloeL.jpg" ] || { echo "no Aloe pair in $aloe"; exit 77; }
for core in "--lanes 64" "--lanes 8 --lean"; do
    # shellcheck disable=SC2086
    "$stereo" cosim "$aloe/aloeL.jpg" "$aloe/aloeR.jpg" --downscale 2 --crop 640x480+0+0 \
        --size 640x480 --ndisp 64 --window 11 --cost census $core --cache "$cache" --json |
        python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["mismatches"] == 0, "the RTL differs from the model"
print("%s: %d cycles, %.2f s, %.0f cycles/s; golden model %.2f s, co-simulation / model = %.1fx"
      % (d["config"], d["cycles"], d["sim_seconds"], d["sim_cycles_per_second"],
         d["model_seconds"], d["sim_to_model_time"]))'
done
