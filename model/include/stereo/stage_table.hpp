// The stage table: the one hand-written definition of the hardware pipeline's shape.
//
// constants.hpp holds the numbers of the arithmetic; this header holds everything else that the
// RTL (rtl/), its co-simulation (sim/, testbench/), the HLS kernels (hls/) and the scripts
// (scripts/) must agree on: the interface constants of stereo_top's ports, the five hardware
// stages in pipeline order with their widths and latencies (the pipeline latency formula lives
// here and nowhere else), the RTL source list in compile order, and the Verilated
// configurations. `gen_stage_table` (model/src/gen_stage_table.cpp) writes rtl/fx_pkg.sv,
// rtl/files.f, sim/verilated_configs.cmake and scripts/stage_table.json from it:
//   cmake --build build --target update_generated
// and the ctest rtl.generated_files_current fails, naming the file, while one of them is stale.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "stereo/constants.hpp"

namespace stereo::fx {

// ---- The CA agreement test, for rules 1 and 2 ---------------------------------------------
// n "agrees" with c when it differs from c by less than half of c: 2|n - c| < c, in exact
// integers. The model, the HLS kernels and the testbenches call this; the RTL's
// fx_pkg::agrees (generated) computes the same as c < 2n < 3c.
constexpr bool agrees(int neighbour, int centre) {
    const int difference = neighbour >= centre ? neighbour - centre : centre - neighbour;
    return 2 * difference < centre;
}

}  // namespace stereo::fx

namespace stereo::table {

// ---- Interface constants of stereo_top (docs/rtl.md) ---------------------------------------
// Pixel coordinates travel with the data through every stage as signed kCoordBits integers.
inline constexpr int kCoordBits = 16;
// Coordinates of "no pixel": what a stage's coordinate registers hold after a reset. Far outside
// any frame, so nothing derived from them is ever taken for a frame pixel.
inline constexpr int kNoPixel = -(1 << (kCoordBits - 1));  // -32768
// Largest frame side: the coordinates of the priming and flush steps stay representable.
inline constexpr int kMaxFrameSide = (1 << (kCoordBits - 2)) - 1;  // 16383
// One aggregation-kernel tap, 0 .. 2^kKernelBits.
inline constexpr int kTapBits = fx::kKernelBits + 1;
// Configuration port widths.
inline constexpr int kCfgSizeBits = 16;   // cfg_width, cfg_height
inline constexpr int kCfgNdispBits = 9;   // cfg_ndisp, 1 .. 256
inline constexpr int kCfgRadiusBits = 5;  // cfg_radius, 0 .. kMaxWindow / 2
static_assert((1 << kCfgNdispBits) > fx::kMaxDisparities);
static_assert((1 << kCfgRadiusBits) > fx::kMaxWindow / 2);
static_assert((1 << kCfgSizeBits) > kMaxFrameSide);
// Input beat: {right RGB, left RGB}, R in the high byte of each half.
inline constexpr int kRgbBits = fx::kChannels * fx::kPixelBits;  // 24
inline constexpr int kInBeatBits = 2 * kRgbBits;                 // 48
inline constexpr int kInLeftLsb = 0;
inline constexpr int kInRightLsb = kRgbBits;
// Output beat: {padding, valid, disparity}.
inline constexpr int kOutBeatBits = 16;
inline constexpr int kOutDisparityLsb = 0;
inline constexpr int kOutValidBit = fx::kDisparityBits;  // 8
inline constexpr int kOutPadBits = kOutBeatBits - fx::kDisparityBits - 1;
static_assert(kOutPadBits >= 0);
// Sticky status bits (stereo_top's status port; stereo_hls_top's return value).
inline constexpr int kStatusEolMisplaced = 0;   // tlast not at the row end
inline constexpr int kStatusSofMisplaced = 1;   // tuser inside a frame
inline constexpr int kStatusConfigClamped = 2;  // configuration out of range (clamped)
inline constexpr int kStatusBits = 3;

// ---- The hardware stages, in pipeline order ------------------------------------------------
// Latency of one stage in pixel steps, R = WINDOW/2 of the synthesised window, W = frame width:
//   (radius_rows * R + rows) * W + radius_steps * R + steps
struct Latency {
    int radius_rows = 0;
    int rows = 0;
    int radius_steps = 0;
    int steps = 0;
    constexpr int at(int width, int window) const {
        const int radius = window / 2;
        return (radius_rows * radius + rows) * width + radius_steps * radius + steps;
    }
};

struct Stage {
    std::string_view name;    // ca_rule1, also the name of the stage's instance in stereo_top
    std::string_view module;  // stereo_ca_plane (file rtl/<module>.sv)
    int in_lane_bits;         // input bits per disparity lane (cost: the pixel pair, shared)
    int out_lane_bits;        // output bits per disparity lane (wta: one result, not per lane)
    Latency rtl;              // the RTL module
    // Steps the HLS kernel of the stage takes fewer than the RTL module (the RTL's CA windows
    // have an input register for Fmax, hls/README.md).
    int hls_fewer_steps;
};

inline constexpr std::array<Stage, 5> kStages = {{
    {"cost", "stereo_cost", kInBeatBits, fx::kCostBits, {0, 0, 0, 1}, 0},
    {"aggregate", "stereo_aggregate", fx::kCostBits, fx::kAggBits, {1, 0, 1, 2}, 0},
    // The two CA rules are one module, stereo_ca_plane, with RULE = 1 and 2.
    {"ca_rule1", "stereo_ca_plane", fx::kAggBits, fx::kAggBits, {0, 1, 0, 3}, 1},
    {"ca_rule2", "stereo_ca_plane", fx::kAggBits, fx::kAggBits, {0, 1, 0, 3}, 1},
    {"wta", "stereo_wta", fx::kAggBits, fx::kDisparityBits + 1, {0, 0, 0, 1}, 0},
}};

// Pixel steps from a pixel entering stereo_top's cost stage to its output beat:
// (R + 2) * W + R + 10. stereo_top streams one frame in W*H + this many cycles without stalls
// (checked by tb_stereo_top's Throughput test).
constexpr int pipeline_latency(int width, int window) {
    int steps = 0;
    for (const Stage& stage : kStages) {
        steps += stage.rtl.at(width, window);
    }
    return steps;
}

// The same for the HLS pipeline (stereo_hls_top): (R + 2) * W + R + 8.
constexpr int hls_pipeline_latency(int width, int window) {
    int steps = 0;
    for (const Stage& stage : kStages) {
        steps += stage.rtl.at(width, window) - stage.hls_fewer_steps;
    }
    return steps;
}

// ---- RTL sources in compile order (rtl/files.f) --------------------------------------------
// The package first, then every module before its first user. One module per file, named after
// it; the list of modules to lint is this list without the package.
inline constexpr std::string_view kPackageFile = "fx_pkg.sv";
inline constexpr std::array<std::string_view, 12> kRtlModules = {
    "stereo_coord_reg", "stereo_line_buffer",  "stereo_window3x3", "stereo_ca_plane",
    "stereo_cost",      "stereo_lcdm_convert", "stereo_cost_lcdm", "stereo_cost_select",
    "stereo_aggregate", "stereo_wta",          "stereo_top",       "stereo_synth_top",
};

// ---- Verilated configurations (sim/verilated_configs.cmake) --------------------------------
inline constexpr int kUnset = -1;

struct Params {
    int width = kUnset;
    int height = kUnset;
    int ndisp = kUnset;
    int window = kUnset;
    int runtime_kernel = kUnset;
    int rule = kUnset;  // stereo_ca_plane's RULE
    int cost = kUnset;  // stereo_top's COST: 0 AD (stereo_cost), 1 LCDM (stereo_cost_lcdm)
};

struct VerilatedConfig {
    std::string_view prefix;  // Verilator --prefix: the C++ class
    std::string_view top;     // top module
    Params params;            // the -G parameters that are set
    std::string_view option;  // CMake option that must be ON to build it; empty: always built
};

inline constexpr Params kSmall{64, 48, 16, 5, kUnset};  // the co-simulation point
inline constexpr Params kFull{640, 480, 64, 11, kUnset};
// The co-simulation point with the LCDM cost stage (stereo_top COST = 1).
inline constexpr Params kSmallLcdm{
    kSmall.width, kSmall.height, kSmall.ndisp, kSmall.window, kUnset, kUnset, 1};

inline constexpr std::array<VerilatedConfig, 10> kVerilatedConfigs = {{
    {"Vstereo_top_small", "stereo_top", kSmall, ""},
    {"Vstereo_cost", "stereo_cost", {kUnset, kUnset, kSmall.ndisp, kUnset, kUnset}, ""},
    {"Vstereo_top_lcdm", "stereo_top", kSmallLcdm, ""},
    {"Vstereo_cost_lcdm", "stereo_cost_lcdm", {kUnset, kUnset, kSmall.ndisp, kUnset, kUnset}, ""},
    {"Vstereo_aggregate",
     "stereo_aggregate",
     {kSmall.width, kUnset, kSmall.ndisp, kSmall.window, kUnset},
     ""},
    // The constant-kernel variant that the FPGA top (stereo_synth_top) synthesizes.
    {"Vstereo_aggregate_const",
     "stereo_aggregate",
     {kSmall.width, kUnset, kSmall.ndisp, kSmall.window, 0},
     ""},
    // The CA skeleton as rule 1 and as rule 2.
    {"Vstereo_ca_rule1",
     "stereo_ca_plane",
     {kSmall.width, kUnset, kSmall.ndisp, kUnset, kUnset, 1},
     ""},
    {"Vstereo_ca_rule2",
     "stereo_ca_plane",
     {kSmall.width, kUnset, kSmall.ndisp, kUnset, kUnset, 2},
     ""},
    {"Vstereo_wta", "stereo_wta", {kUnset, kUnset, kSmall.ndisp, kUnset, kUnset}, ""},
    // Its C++ takes minutes to compile: only with -DSTEREO_COSIM_FULL=ON.
    {"Vstereo_top_full", "stereo_top", kFull, "STEREO_COSIM_FULL"},
}};

// The configuration built under `prefix` (a compile-time error when there is none).
constexpr const VerilatedConfig& verilated(std::string_view prefix) {
    for (const VerilatedConfig& config : kVerilatedConfigs) {
        if (config.prefix == prefix) {
            return config;
        }
    }
    throw "no Verilated configuration with this prefix";
}

// ---- Lint configurations (scripts/lint_rtl.sh) ---------------------------------------------
// Every module of kRtlModules is linted as its own top at its default parameters; these are
// linted in addition.
struct LintConfig {
    std::string_view top;
    Params params;
};

inline constexpr std::array<LintConfig, 6> kExtraLintConfigs = {{
    // The top with the LCDM cost stage.
    {"stereo_top", kSmallLcdm},
    // The CA skeleton with the other rule.
    {"stereo_ca_plane", {kUnset, kUnset, kUnset, kUnset, kUnset, 2}},
    // The top at other shapes: a 3x3 window, odd label counts, and the full-size configuration.
    {"stereo_top", {kUnset, kUnset, 5, 3, kUnset}},
    {"stereo_top", {100, 75, 33, 7, kUnset}},
    {"stereo_top", kFull},
    // The FPGA build (constant kernel) at the full-size configuration.
    {"stereo_synth_top", kFull},
}};

}  // namespace stereo::table
