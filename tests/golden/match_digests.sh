#!/usr/bin/env bash
# Prints one line per `stereo match` run: "<scene> <options...> <sha256 of the disparity PNG>".
#
#   tests/golden/match_digests.sh STEREO_BINARY DATA_DIR ALOE_DIR [quick|full] > digests.txt
#
# The behaviour-preservation check of the matcher refactor: match_digests.txt beside this script
# was written by this script from the code *before* the refactor (commit "Record stereo match
# digests before the matcher refactor"), with
#   tests/golden/match_digests.sh build/app/stereo ../shared/data \
#       /usr/share/doc/opencv-doc/examples/data full > tests/golden/match_digests.txt
# and the ctest golden.match_digests[_full] re-runs it and compares the lines exactly.
# `quick` runs the fast engines only (model, hls, float, edges, no-CA; every scene); `full` adds
# the naive references. Scenes whose files are absent are skipped (the comparison then only
# covers what was run).
set -euo pipefail
stereo=$1
data=$2
aloe=$3
mode=${4:-quick}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source=tests/golden/untagged.sh
source "$(dirname "$0")/untagged.sh"

# scene name, left, right, extra options (ndisp from the data README; Aloe at half size)
scenes=()
for s in tsukuba:16 venus:20 teddy:60 cones:60; do
  name=${s%%:*}
  ndisp=${s##*:}
  dir=$data/middlebury2003/$name
  [ -f "$dir/left.png" ] && scenes+=("$name|$dir/left.png|$dir/right.png|--ndisp $ndisp")
done
[ -f "$aloe/aloeL.jpg" ] && scenes+=("aloe|$aloe/aloeL.jpg|$aloe/aloeR.jpg|--downscale 2 --ndisp 128")

variants=(
  "--engine model"
  "--engine model --no-ca"
  "--engine model --window 5 --sigma 1.5"
  "--engine hls"
  "--engine float"
  "--frontend edges"
  "--method hierarchical"
  "--method hierarchical --no-ca"
)
if [ "$mode" = full ]; then
  variants+=("--engine naive" "--method hierarchical --engine naive")
fi

for scene in "${scenes[@]}"; do
  IFS='|' read -r name left right options <<<"$scene"
  for variant in "${variants[@]}"; do
    # The maps of before stage 6: --no-validation keeps them reachable bit for bit, --cost ad
    # the cost every method had when the digests were recorded (the pipeline's default is now
    # census, stereo/defaults.hpp); neither is part of the printed line.
    # The hierarchical search's digests are the thesis' configuration (V = D, windows 9 / 15 /
    # 23, the full level's winners), which are no longer its defaults (docs/hierarchical.md,
    # issue 45); these options reach it bit for bit and are not part of the line either.
    thesis=()
    case $variant in
      *"--method hierarchical"*) thesis=(--field none --vrange 0 --level-windows 9 15 23) ;;
    esac
    # shellcheck disable=SC2086
    "$stereo" match "$left" "$right" $options $variant --no-validation --cost ad \
      "${thesis[@]+"${thesis[@]}"}" -o "$work/d.png" >/dev/null
    echo "$name $options $variant $(untagged "$work/d.png" | sha256sum | cut -c1-64)"
  done
done
