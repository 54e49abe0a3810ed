#!/usr/bin/env bash
# Builds and runs the default test suite (everything except the long `bench`, `soak` and `docs`
# labels and the generated `hostile` suite).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE "bench|soak|hostile|docs|golden-full"
