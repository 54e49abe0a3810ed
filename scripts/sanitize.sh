#!/usr/bin/env bash
# ASan + UBSan build (CMake preset "sanitize", folder build-sanitize/) of the model, io, robot and
# CLI with their tests, then those tests: any memory error or undefined behaviour fails the run.
# The fuzz harnesses are built here too with a replay main (fuzz/replay_main.cpp) and run once on
# every checked-in seed (label fuzz-replay): the seeds under the sanitizers without the clang
# build of scripts/fuzz.sh.
# The RTL testbenches, the synthesis checks and the long golden digests are left to the normal
# build (./scripts/test.sh), which covers the same code paths without the sanitizers' cost. The
# preset builds without the RTL (STEREO_WITH_RTL=OFF): compiling the 24 Verilated configurations
# under ASan took longer than the rest of this script together and pushed CI past its budget;
# `cosim`'s options still parse here (and its rows of the bad-input table are skipped), the
# co-simulation itself is checked by the normal build's testbenches, soak and cosim CLI tests.
# The two FST-trace tests are left out: Verilator's own FST writer (fstapi.c, from GTKWave) does a
# misaligned 32-bit store that UBSan reports; it is not our code and the normal build runs them.
# experiments.asw_eval_quick (the full ASW on two whole Middlebury pairs, many minutes under ASan)
# is left to the normal build too; test_asw runs the same ASW code on small inputs here. So are
# the two slowest model checks under ASan, experiments.subpixel_calibration_matches_constants
# (100 s: the same parabola code runs in every stage-6 test here) and
# VerticalFieldEqualsNaive.EveryFieldModel (46 s: the hierarchical search's naive reference; the
# other hierarchical tests run its code here), to keep CI within its budget.
# test_fast_engine (the fast CPU engine against the model) runs here too, but for its test of the
# eight Middlebury scenes on 1-4 threads (most of its 57 s under the sanitizers; the random pairs,
# the tile seams and the sequence test run the same code on every option here, and the normal
# build runs the scenes): the stop of 2026-12-07 added build time (the HLS ASW variants) to a CI
# run already at 2,629 of its 2,700 s.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(stereo stereo_experiments test_model test_matcher test_io test_output test_cli_run test_metrics test_middlebury
         test_edge_frontend test_hierarchical test_hierarchical_radial test_robot test_slam test_constants test_validation
         test_costs_lcdm test_speckle test_quad test_point_cloud test_obstacles test_bands test_asw test_board
         test_catalogue test_fast_engine test_self_calibration test_mjpeg_avi make_cli_fixtures map_exercises make_slam_fixtures fuzz_replay_all)
cmake --preset sanitize
cmake --build build-sanitize -j"$(nproc)" --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)" -L "model|app|robot|cli|fuzz-replay" \
  -E "golden|NOT_BUILT|hls|hierarchical_end_to_end|cosim_trace|gtkw_layout|asw_eval_quick|subpixel_calibration_matches_constants|VerticalFieldEqualsNaive|FastEngine.EveryScene"
