#!/usr/bin/env bash
# libFuzzer harnesses (fuzz/, docs/reliability.md): configures the clang build (CMake preset
# "fuzz", folder build-fuzz/), builds only the harnesses and what they link, and runs each one.
#
#   scripts/fuzz.sh [SECONDS=20] [HARNESS...]   run each harness (default: all) for SECONDS
#   scripts/fuzz.sh build                        only configure and build
#
# New inputs go to build-fuzz/fuzz/corpus/NAME (the checked-in seeds in fuzz/corpus/NAME are only
# read); a crash, leak, timeout or out-of-memory input is saved in build-fuzz/fuzz/artifacts/NAME
# and fails the script. Replay one with build-fuzz/fuzz/fuzz_NAME FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=20
if [ "${1:-}" = build ] || [[ "${1:-}" =~ ^[0-9]+$ ]]; then
  seconds=$1
  shift
fi
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (./scripts/setup.sh installs it)" >&2; exit 1; }
cmake --preset fuzz >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_all
[ "$seconds" = build ] && exit 0

harnesses=("$@")
[ "${#harnesses[@]}" -gt 0 ] || harnesses=(image_loaders kitti_files euroc_yaml cli_options)
status=0
for name in "${harnesses[@]}"; do
  work=build-fuzz/fuzz/corpus/$name
  artifacts=build-fuzz/fuzz/artifacts/$name
  mkdir -p "$work" "$artifacts"
  dict=()
  [ -f "fuzz/$name.dict" ] && dict=(-dict="fuzz/$name.dict")
  log=build-fuzz/fuzz/$name.log
  echo "== fuzz_$name for ${seconds} s (log: $log)"
  if build-fuzz/fuzz/"fuzz_$name" "${dict[@]}" -max_total_time="$seconds" -rss_limit_mb=2560 \
      -timeout=10 -close_fd_mask=3 -print_final_stats=1 -artifact_prefix="$artifacts/" \
      "$work" "fuzz/corpus/$name" >"$log" 2>&1; then
    grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$log" | tr '\n' ' '
    echo "corpus $(ls "$work" | wc -l) files: ok"
  else
    status=1
    echo "FINDING (see $log and $artifacts/):"
    grep -E "ERROR|SUMMARY|fuzz:|Test unit written" "$log" | head -5
  fi
done
exit "$status"
