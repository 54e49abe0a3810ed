#!/bin/sh
# install.consumer: `cmake --install` the build into a fresh prefix, configure and build
# examples/consumer against it with find_package(stereo), run it on the CLI fixtures, and
# require its PFM to equal `stereo match --no-validation`'s byte for byte (the installed headers
# and libraries compute what the tool does).
# usage: install_consumer.sh BUILD_DIR SOURCE_DIR LEFT RIGHT
set -eu
build=$1 source=$2 left=$3 right=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in lib/cmake/stereo/stereo-config.cmake lib/cmake/stereo/stereo-config-version.cmake \
         include/stereo/matcher.hpp include/stereo_io/io.hpp include/stereo_robot/decision.hpp \
         bin/stereo; do
  [ -e "$prefix/$f" ] || { echo "install.consumer: $f was not installed"; exit 1; }
done

cmake -S "$source/examples/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" 2>&1 \
  || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" -j2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }

"$work/consumer/disparity" "$left" "$right" "$work/consumer.pfm" 16
"$prefix/bin/stereo" match "$left" "$right" --ndisp 16 --no-validation -o "$work/tool.pfm"
cmp "$work/consumer.pfm" "$work/tool.pfm"
"$work/consumer/disparity" "$left" "$right" "$work/consumer2.pfm" 8 2
"$prefix/bin/stereo" match "$left" "$right" --ndisp 8 --downscale 2 --no-validation -o "$work/tool2.pfm"
cmp "$work/consumer2.pfm" "$work/tool2.pfm"
echo "install.consumer: installed, consumer built, its PFM equals stereo match's"
