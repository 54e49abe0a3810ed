#!/bin/sh
# install.consumer: `cmake --install` the build into a fresh prefix, configure and build
# examples/consumer against it with find_package(stereo), run it on the CLI fixtures and on a
# real scene (Debian opencv-doc's Aloe pair at quarter size), and require its PFM to equal
# `stereo match`'s default map byte for byte (census, stage 6, sub-pixel, speckle filter: the
# installed headers and libraries compute what the tool does by default). On Aloe the test first
# requires `stereo match --cost ad` and `--no-validation` to differ from the default map, so
# that an example that drifts to another cost or drops stage 6 fails. Exit 77 (skipped) after
# the fixture comparisons when Aloe is not installed.
# usage: install_consumer.sh BUILD_DIR SOURCE_DIR LEFT RIGHT [ALOE_DIR]
set -eu
build=$1 source=$2 left=$3 right=$4 aloe=${5:-/usr/share/doc/opencv-doc/examples/data}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in lib/cmake/stereo/stereo-config.cmake lib/cmake/stereo/stereo-config-version.cmake \
         include/stereo/matcher.hpp include/stereo_io/io.hpp include/stereo_robot/decision.hpp \
         bin/stereo; do
  [ -e "$prefix/$f" ] || { echo "install.consumer: $f was not installed"; exit 1; }
done

# No test helper among the installed headers, and every header the installed ones include
# ("stereo.../x.hpp") is installed too.
if find "$prefix/include" -name 'test_*.hpp' | grep -q .; then
  echo "install.consumer: test helpers were installed:"; find "$prefix/include" -name 'test_*.hpp'
  exit 1
fi
for included in $(grep -rhoE '#include "stereo[a-z_]*/[a-z_/]+\.hpp"' "$prefix/include" \
                  | sed 's/#include "\(.*\)"/\1/' | sort -u); do
  [ -f "$prefix/include/$included" ] || { echo "install.consumer: $included is included but not installed"; exit 1; }
done

cmake -S "$source/examples/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" 2>&1 \
  || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" -j2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }

"$work/consumer/disparity" "$left" "$right" "$work/consumer.pfm" 16
"$prefix/bin/stereo" match "$left" "$right" --ndisp 16 -o "$work/tool.pfm"
cmp "$work/consumer.pfm" "$work/tool.pfm"
"$work/consumer/disparity" "$left" "$right" "$work/consumer2.pfm" 8 2
"$prefix/bin/stereo" match "$left" "$right" --ndisp 8 --downscale 2 -o "$work/tool2.pfm"
cmp "$work/consumer2.pfm" "$work/tool2.pfm"

if [ ! -f "$aloe/aloeL.jpg" ] || [ ! -f "$aloe/aloeR.jpg" ]; then
  echo "SKIP: install.consumer: the fixtures agree; Aloe not found in $aloe (opencv-doc)"
  exit 77
fi
# Aloe at quarter size (320x277, disparities up to about 53 px): the real-scene comparison.
set -- "$aloe/aloeL.jpg" "$aloe/aloeR.jpg" --ndisp 64 --downscale 4
"$prefix/bin/stereo" match "$@" -o "$work/aloe.pfm" > /dev/null
for other in "--cost ad" "--no-validation"; do
  # shellcheck disable=SC2086 # $other is two words or one option
  "$prefix/bin/stereo" match "$@" $other -o "$work/aloe_other.pfm" > /dev/null
  if cmp -s "$work/aloe.pfm" "$work/aloe_other.pfm"; then
    echo "install.consumer: on Aloe 'stereo match $other' equals the default map; the scene cannot tell them apart"
    exit 1
  fi
done
"$work/consumer/disparity" "$aloe/aloeL.jpg" "$aloe/aloeR.jpg" "$work/consumer_aloe.pfm" 64 4
cmp "$work/consumer_aloe.pfm" "$work/aloe.pfm" || {
  echo "install.consumer: on Aloe the consumer's map differs from stereo match's default map"
  exit 1
}
echo "install.consumer: installed, consumer built, its PFM equals stereo match's default map (fixtures and Aloe)"
