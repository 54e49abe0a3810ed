#!/bin/sh
# gtkw_signals.sh STEREO LEFT RIGHT LAYOUT.gtkw: co-simulates LEFT/RIGHT with --trace, converts
# the FST to VCD with fst2vcd (Debian gtkwave) and requires every signal of the saved GTKWave
# layout to exist in the trace under the same hierarchical name, so that the layout documented in
# docs/gtkwave.md keeps opening with every trace.
set -eu
stereo=$1 left=$2 right=$3 layout=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$stereo" cosim "$left" "$right" --ndisp 8 --stall 0.2 --trace "$work/run.fst" > /dev/null
fst2vcd "$work/run.fst" > "$work/run.vcd" 2> /dev/null
# Every variable as scope.path.name[range], the form GTKWave writes into a .gtkw file.
awk '$1 == "$scope" { path = (path == "" ? $3 : path "." $3) }
     $1 == "$upscope" { sub(/\.?[^.]*$/, "", path) }
     $1 == "$var" { name = $5; if ($6 != "$end") name = name $6; print path "." name }
     $1 == "$enddefinitions" { exit }' "$work/run.vcd" | sort -u > "$work/names"
[ -s "$work/names" ] || { echo "no variables in the trace"; exit 1; }
grep -v '^[[@*-]' "$layout" | grep -v '^$' | sort -u > "$work/wanted"
[ -s "$work/wanted" ] || { echo "no signals in $layout"; exit 1; }
missing=$(comm -23 "$work/wanted" "$work/names")
if [ -n "$missing" ]; then
  echo "signals of $layout missing from the trace:"; echo "$missing"
  echo "(the trace has, e.g.:)"; head -20 "$work/names"
  exit 1
fi
echo "all $(wc -l < "$work/wanted") signals of $layout are in the trace"
