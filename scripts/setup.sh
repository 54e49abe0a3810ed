#!/usr/bin/env bash
# Installs every build and test dependency from Debian (idempotent, non-interactive).
# Run as root, or with sudo available.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ccache                           # compiler cache (CMakeLists.txt uses it when present)
  libopencv-dev opencv-doc          # image I/O, StereoBM/SGBM baselines; opencv-doc ships Aloe
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libeigen3-dev
  libyaml-cpp-dev                  # EuRoC rectification YAML (robot/src/slam/dataset.cpp)
  verilator zlib1g-dev yosys       # RTL co-simulation (FST traces need zlib), synthesis check
  nextpnr-ice40 python3            # place and route, synthesis reports (scripts/synth/synth.py)
  fpga-icestorm                    # icepack / iceprog: the iCEBreaker bitstream (docs/board.md)
  clang-format
  clang                            # libFuzzer harnesses (fuzz/, scripts/fuzz.sh)
  pybind11-dev python3-dev         # the Python module (python/)
  python3-numpy python3-pytest     # its arrays and tests (ctest label python)
  python3-matplotlib               # figures with colour bars (scripts/figures/)
  gtkwave                          # waveform viewer, fst2vcd (docs/gtkwave.md, cli.gtkw_layout_signals)
  doxygen                          # the API reference, target api_docs (docs/install.md, docs.api_reference)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
