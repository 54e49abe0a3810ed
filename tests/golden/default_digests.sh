#!/usr/bin/env bash
# The default path's golden outputs (issue 52): one line per `stereo match` run with a method's
# defaults, "<scene> <options...> <sha256 of each output>", where the outputs are the PFM
# disparity, the reason PNG and the certainty PNG for the methods with stage 6 (pipeline, its
# costs, asw, vertical, diagonal, hierarchical) and the label PNG for the others (edges, sparse,
# and the hierarchical search's thesis output, --field none).
#
#   tests/golden/default_digests.sh STEREO FIXTURES DATA_DIR ALOE_DIR record > default_digests.txt
#   tests/golden/default_digests.sh STEREO FIXTURES DATA_DIR ALOE_DIR check
#
# `record` runs every line's options again with `--engine naive` (where the method has one and
# the run is small enough) and refuses to record when the bytes differ, so no digest is written
# that only the model vouches for. `check` (ctest golden.default_digests) requires every line it
# computes to be a line of default_digests.txt beside this script. FIXTURES is make_cli_fixtures'
# folder (the scene pair, always present); scenes of DATA_DIR and ALOE_DIR whose files are absent
# are skipped.
set -euo pipefail
stereo=$1
fixtures=$2
data=$3
aloe=$4
mode=${5:-check}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source=tests/golden/untagged.sh
source "$(dirname "$0")/untagged.sh"
digest() { untagged "$1" | sha256sum | cut -c1-16; }

# One run: prints the line; in record mode compares with the naive engine when asked.
#   run SCENE STAGE6(yes|no) NAIVE(yes|no) LEFT RIGHT OPTIONS...
run() {
  local scene=$1 stage6=$2 naive=$3 left=$4 right=$5
  shift 5
  local line
  if [ "$stage6" = yes ]; then
    "$stereo" match "$left" "$right" "$@" -o "$work/d.pfm" --reasons "$work/r.png" \
      --certainty "$work/c.png" >/dev/null
    line="$scene $* $(digest "$work/d.pfm") $(digest "$work/r.png") $(digest "$work/c.png")"
    if [ "$mode" = record ] && [ "$naive" = yes ]; then
      "$stereo" match "$left" "$right" "$@" --engine naive -o "$work/n.pfm" \
        --reasons "$work/nr.png" --certainty "$work/nc.png" >/dev/null
      for part in d.pfm:n.pfm r.png:nr.png c.png:nc.png; do
        if ! cmp -s "$work/${part%%:*}" "$work/${part##*:}"; then
          echo "not recorded: the naive engine differs on $scene $*" >&2
          exit 1
        fi
      done
    fi
  else
    "$stereo" match "$left" "$right" "$@" -o "$work/d.png" >/dev/null
    line="$scene $* $(digest "$work/d.png")"
    if [ "$mode" = record ] && [ "$naive" = yes ]; then
      "$stereo" match "$left" "$right" "$@" --engine naive -o "$work/n.png" >/dev/null
      cmp -s "$work/d.png" "$work/n.png" || {
        echo "not recorded: the naive engine differs on $scene $*" >&2
        exit 1
      }
    fi
  fi
  echo "$line"
}

# The scene fixture: every method's defaults, naive-checked (ASW's naive reference too: the
# image is small).
f=$fixtures
{
run scene yes yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --min-disp -4
run scene yes yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --min-disp -4 --cost ad
run scene yes yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --min-disp -4 --cost lcdm
run scene yes yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --min-disp -4 \
  --method asw --window 15
run scene yes yes "$f/scene_left.png" "$f/scene_vertical.png" --ndisp 16 --min-disp -4 \
  --method vertical
run scene yes yes "$f/scene_left.png" "$f/scene_diagonal.png" --ndisp 16 --min-disp -4 \
  --method diagonal
run scene yes yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --method hierarchical
run scene no yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --method hierarchical \
  --field none
run scene no yes "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --method edges
run scene no no "$f/scene_left.png" "$f/scene_right.png" --ndisp 16 --method sparse
} >"$work/lines"

# Real scenes (ndisp from the data README; Aloe at half size): the pipeline's default and each
# cost's, ASW's default, and the methods without stage 6. The naive pipeline checks the
# pipeline lines; ASW's and the hierarchical search's naive references are too slow at these
# sizes with the census cost (codes rebuilt for every comparison: over 10 minutes on Teddy).
# Their equality with the model is the scene lines above, the AswMatch and
# VerticalFieldEqualsNaive tests and cli.hierarchical_end_to_end (Tsukuba at half size).
scenes=()
for s in tsukuba:16 venus:20 teddy:60 cones:60; do
  name=${s%%:*}
  dir=$data/middlebury2003/$name
  [ -f "$dir/left.png" ] && scenes+=("$name|$dir/left.png|$dir/right.png|--ndisp ${s##*:}")
done
[ -f "$aloe/aloeL.jpg" ] && scenes+=("aloe|$aloe/aloeL.jpg|$aloe/aloeR.jpg|--downscale 2 --ndisp 128")
for scene in "${scenes[@]+"${scenes[@]}"}"; do
  IFS='|' read -r name left right options <<<"$scene"
  # shellcheck disable=SC2086
  {
    run "$name" yes yes "$left" "$right" $options
    run "$name" yes yes "$left" "$right" $options --cost ad
    run "$name" yes no "$left" "$right" $options --method asw
    run "$name" yes no "$left" "$right" $options --method hierarchical
    run "$name" no no "$left" "$right" $options --method hierarchical --field none
    run "$name" no no "$left" "$right" $options --method edges
  }
done >>"$work/lines"

if [ "$mode" = record ]; then
  cat "$work/lines"
  exit 0
fi
"$here/lines_recorded.sh" "$work/lines" "$here/default_digests.txt" \
  "stereo match's default outputs"
