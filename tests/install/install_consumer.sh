#!/bin/sh
# install.consumer: `cmake --install` the build into a fresh prefix, configure and build
# examples/consumer against it with find_package(stereo), run it on the CLI fixtures and on a
# real scene (Debian opencv-doc's Aloe pair at quarter size), and require its PFM to equal
# `stereo match`'s default map byte for byte (census, stage 6, sub-pixel, speckle filter: the
# installed headers and libraries compute what the tool does by default). On Aloe the test first
# requires `stereo match --cost ad` and `--no-validation` to differ from the default map, so
# that an example that drifts to another cost or drops stage 6 fails. Exit 77 (skipped) after
# the fixture comparisons when Aloe is not installed. Before that (issue 47 part 6): the build
# must be portable (no -march=native), and find_package(stereo COMPONENTS model) must configure,
# build and run where OpenCV and the other third-party packages cannot be found.
# usage: install_consumer.sh BUILD_DIR SOURCE_DIR LEFT RIGHT [ALOE_DIR]
set -eu
build=$1 source=$2 left=$3 right=$4 aloe=${5:-/usr/share/doc/opencv-doc/examples/data}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

# A portable build: no compile command of the build (the installed libraries, the tool and what
# it links) tuned to this CPU. A build configured with STEREO_NATIVE=ON refuses to install.
if grep -E -- '-m(arch|tune|cpu)=native|-mpopcnt' "$build/compile_commands.json" > "$work/native.txt"; then
  echo "install.consumer: the build uses CPU-specific flags; its installed files may not run elsewhere:"
  head -3 "$work/native.txt"
  exit 1
fi
cmake --install "$build" --prefix "$prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log"; exit 1; }
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

# Per-component dependencies: find_package(stereo COMPONENTS model) where OpenCV, nlohmann_json,
# ZLIB, Eigen3 and yaml-cpp cannot be found (CMAKE_DISABLE_FIND_PACKAGE_*) configures, loads
# stereo::model alone, and builds and runs a program on it. The same project asking for `io`
# must fail there, or the disabled packages prove nothing.
mkdir -p "$work/model_only"
cat > "$work/model_only/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(model_only LANGUAGES CXX)
set(STEREO_COMPONENT model CACHE STRING "")
find_package(stereo 0.1 REQUIRED COMPONENTS ${STEREO_COMPONENT})
foreach(package IN ITEMS OpenCV nlohmann_json ZLIB Eigen3 yaml-cpp)
  if(DEFINED ${package}_FOUND OR ${package}_DIR)
    message(FATAL_ERROR "find_package(stereo COMPONENTS ${STEREO_COMPONENT}) looked for ${package}")
  endif()
endforeach()
foreach(target IN ITEMS stereo::io stereo::robot)
  if(TARGET ${target})
    message(FATAL_ERROR "find_package(stereo COMPONENTS ${STEREO_COMPONENT}) loaded ${target}")
  endif()
endforeach()
add_executable(model_only main.cpp)
target_link_libraries(model_only PRIVATE stereo::model)
CMAKE
cat > "$work/model_only/main.cpp" <<'CPP'
#include <cstdio>
#include "stereo/defaults.hpp"
#include "stereo/version.hpp"
int main() {
    stereo::Image left(48, 16, 1), right(48, 16, 1);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 48; ++x) {
            left.at(x, y, 0) = static_cast<unsigned char>((x * 37 + y * 11) % 251);
            right.at(x, y, 0) = static_cast<unsigned char>(((x + 3) * 37 + y * 11) % 251);
        }
    stereo::MatchConfig config = stereo::defaults::match_config();
    config.pipeline.ndisp = 8;
    stereo::MatcherRegistry registry;
    stereo::register_model_matchers(registry);
    const auto result = registry.create("pipeline", "model", config)->compute(left, right);
    std::printf("stereo %s: %dx%d map\n", stereo::kVersion, result.disparity.width,
                result.disparity.height);
    return result.disparity.width == 48 ? 0 : 1;
}
CPP
no_third_party="-DCMAKE_DISABLE_FIND_PACKAGE_OpenCV=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_ZLIB=ON -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_yaml-cpp=ON"
# shellcheck disable=SC2086 # one option a word
cmake -S "$work/model_only" -B "$work/model_only/build" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release $no_third_party > "$work/model_only.log" 2>&1 || {
  cat "$work/model_only.log"
  echo "install.consumer: find_package(stereo COMPONENTS model) needs a third-party package"
  exit 1
}
cmake --build "$work/model_only/build" > "$work/model_only_build.log" 2>&1 \
  || { cat "$work/model_only_build.log"; exit 1; }
"$work/model_only/build/model_only"
# shellcheck disable=SC2086
if cmake -S "$work/model_only" -B "$work/io_only" -DCMAKE_PREFIX_PATH="$prefix" \
         -DSTEREO_COMPONENT=io $no_third_party > "$work/io_only.log" 2>&1; then
  echo "install.consumer: find_package(stereo COMPONENTS io) configured without OpenCV"
  exit 1
fi
grep -q OpenCV "$work/io_only.log" || { cat "$work/io_only.log"; echo "install.consumer: io failed, not on OpenCV"; exit 1; }

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
echo "install.consumer: portable install; COMPONENTS model needs no third-party package; consumer built, its PFM equals stereo match's default map (fixtures and Aloe)"
