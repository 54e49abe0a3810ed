#!/usr/bin/env bash
# Yosys estimate (synth_xilinx, 7-series, not placed) of the adaptive-support-weight core
# (stereo_synth_top ASW = 1: the census or AD cost, the separable ASW of diameter WINDOW, WTA and
# stage 6; MAX_MIN_DISP = 0), or of one of its parts (docs/asw.md "The hardware core",
# docs/results-asw.md "Hardware configuration").
#
#   scripts/asw/synth_asw.sh [PART WIDTH NDISP WINDOW LANES COST [LOG]]
#
# PART: core (stereo_synth_top, HEIGHT 480), passes (stereo_asw_aggregate: the three passes of
# LANES labels a clock, NDISP labels) or column (stereo_asw_column: the column stacks and the
# words). COST: census or ad. Defaults: core 640 64 11 8 census. Prints Yosys' statistics; the
# log goes to LOG (default /tmp/synth_asw_PART.log).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
part=${1:-core}
width=${2:-640}
ndisp=${3:-64}
window=${4:-11}
lanes=${5:-8}
cost=${6:-census}
log=${7:-/tmp/synth_asw_$part.log}
command -v yosys > /dev/null || { echo "synth_asw.sh: yosys not found" >&2; exit 1; }
case "$cost" in
  census) cost_code=2; codes=1 ;;
  ad) cost_code=0; codes=0 ;;
  *) echo "synth_asw.sh: COST must be census or ad, got '$cost'" >&2; exit 2 ;;
esac
case "$part" in
  core) top=stereo_synth_top
        params="-set WIDTH $width -set HEIGHT 480 -set NDISP $ndisp -set WINDOW $window -set LANES $lanes -set COST $cost_code -set ASW 1 -set MAX_MIN_DISP 0" ;;
  passes) top=stereo_asw_aggregate
        truncation=$([ "$cost" = ad ] && echo 40 || echo 0)
        params="-set NDISP $ndisp -set LANES $lanes -set DIAMETER $window -set CODES $codes -set TRUNCATION $truncation" ;;
  column) top=stereo_asw_column
        params="-set WIDTH $width -set DIAMETER $window -set CODES $codes" ;;
  *) echo "synth_asw.sh: PART must be core, passes or column, got '$part'" >&2; exit 2 ;;
esac
mapfile -t files < <(grep -v '^//' "$root/rtl/files.f" | sed "s|^|$root/rtl/|")
script=$(mktemp)
trap 'rm -f "$script"' EXIT
cat > "$script" << SCRIPT
read_verilog -sv -I$root/rtl ${files[*]}
chparam $params $top
synth_xilinx -family xc7 -top $top -flatten
stat
SCRIPT
yosys -q -l "$log" -s "$script" > /dev/null
sed -n '/^[0-9]*\. Printing statistics/,$p' "$log" | grep -E '^ +(Number of cells|[A-Z][A-Z0-9_]+ +[0-9]+)'
