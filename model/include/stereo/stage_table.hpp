// The stage table: the one hand-written definition of the hardware pipeline's shape.
//
// constants.hpp holds the numbers of the arithmetic; this header holds everything else that the
// RTL (rtl/), its co-simulation (sim/, testbench/), the HLS kernels (hls/) and the scripts
// (scripts/) must agree on: the interface constants of stereo_top's ports, the five hardware
// stages in pipeline order with their widths and latencies (the pipeline latency formula lives
// here and nowhere else), the RTL source list in compile order, and the Verilated
// configurations. `gen_stage_table` (model/tools/gen_stage_table.cpp) writes rtl/fx_pkg.sv,
// rtl/files.f, sim/verilated_configs.cmake and scripts/stage_table.json from it:
//   cmake --build build --target update_generated
// and the ctest rtl.generated_files_current fails, naming the file, while one of them is stale.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "stereo/catalogue.hpp"
#include "stereo/constants.hpp"
#include "stereo/image.hpp"

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
// Stage 6's configuration ports: cfg_min_disp (signed, |value| <= the core's MAX_MIN_DISP, else
// clamped), cfg_uniqueness (U, 0 .. fx::kMaxUniqueness percent), cfg_lr_tolerance (T, 0 ..
// fx::kMaxLrTolerance labels), each beside an enable bit (cfg_uniqueness_en, cfg_lr_en,
// cfg_subpixel_en).
inline constexpr int kCfgMinDispBits = 12;
inline constexpr int kCfgUniquenessBits = 8;
inline constexpr int kCfgLrToleranceBits = 8;
static_assert((1 << (kCfgMinDispBits - 1)) > fx::kMaxMinDisparity);
static_assert((1 << kCfgUniquenessBits) > fx::kMaxUniqueness);
static_assert((1 << kCfgLrToleranceBits) > fx::kMaxLrTolerance);
// fx_pkg::config_t: the run-time configuration but the kernel, as stereo_top holds it (its cfg_*
// ports, clamped and latched) and hands it whole to the stages (their `cfg` port, docs/rtl.md).
// The fields from the most significant down, as the generated packed struct declares them;
// config_lsb gives a field's position for the testbenches that drive a stage's `cfg` port.
enum class ConfigField : unsigned char {
    width,
    height,
    ndisp,
    radius,
    use_ca,
    min_disp,
    uniqueness_en,
    uniqueness,
    lr_en,
    lr_tolerance,
    subpixel_en
};
struct ConfigFieldRow {
    ConfigField id;
    std::string_view name;     // the struct member; stereo_top's port is cfg_<name>
    std::string_view sv_type;  // its type in fx_pkg
    int bits;
};
inline constexpr std::array<ConfigFieldRow, 11> kConfigFields = {{
    {ConfigField::width, "width", "cfg_size_t", kCfgSizeBits},
    {ConfigField::height, "height", "cfg_size_t", kCfgSizeBits},
    {ConfigField::ndisp, "ndisp", "cfg_ndisp_t", kCfgNdispBits},
    {ConfigField::radius, "radius", "cfg_radius_t", kCfgRadiusBits},
    {ConfigField::use_ca, "use_ca", "logic", 1},
    {ConfigField::min_disp, "min_disp", "cfg_min_disp_t", kCfgMinDispBits},  // signed
    {ConfigField::uniqueness_en, "uniqueness_en", "logic", 1},
    {ConfigField::uniqueness, "uniqueness", "cfg_uniqueness_t", kCfgUniquenessBits},
    {ConfigField::lr_en, "lr_en", "logic", 1},
    {ConfigField::lr_tolerance, "lr_tolerance", "cfg_lr_tolerance_t", kCfgLrToleranceBits},
    {ConfigField::subpixel_en, "subpixel_en", "logic", 1},
}};
constexpr const ConfigFieldRow& config_field(ConfigField id) {
    return kConfigFields[static_cast<std::size_t>(id)];
}
// The least significant bit of `id` in config_t: the widths of the fields declared after it.
constexpr int config_lsb(ConfigField id) {
    int lsb = 0;
    for (std::size_t i = static_cast<std::size_t>(id) + 1; i < kConfigFields.size(); ++i) {
        lsb += kConfigFields[i].bits;
    }
    return lsb;
}
inline constexpr int kConfigBits = config_lsb(ConfigField::width) + kCfgSizeBits;
static_assert(
    [] {
        for (std::size_t i = 0; i < kConfigFields.size(); ++i) {
            if (static_cast<std::size_t>(kConfigFields[i].id) != i) {
                return false;
            }
        }
        return true;
    }(),
    "kConfigFields lists the fields in ConfigField order");

// The default of stereo_top's MAX_MIN_DISP, the largest |cfg_min_disp| the core takes: it sizes
// the cost stage's delay lines (MAX_MIN_DISP more right pixels, MAX_MIN_DISP left pixels).
inline constexpr int kDefaultMaxMinDisp = 8;
static_assert(kDefaultMaxMinDisp <= fx::kMaxMinDisparity);
static_assert((1 << kCfgNdispBits) > fx::kMaxDisparities);
static_assert((1 << kCfgRadiusBits) > fx::kMaxWindow / 2);
static_assert((1 << kCfgSizeBits) > kMaxFrameSide);
// Input beat: {right RGB, left RGB}, R in the high byte of each half.
inline constexpr int kRgbBits = fx::kChannels * fx::kPixelBits;  // 24
inline constexpr int kInBeatBits = 2 * kRgbBits;                 // 48
inline constexpr int kInLeftLsb = 0;
inline constexpr int kInRightLsb = kRgbBits;
// Output beat (stage 6, stereo::ValidatedDisparity of one pixel), 32 bits:
//   [15:0]  fixed disparity: signed, disparity x 16 (fx::kSubpixelScale), 0 where invalid
//   [18:16] reason: fx::kReasonValid, kReasonBorder, kReasonUniqueness, kReasonLeftRight
//   [23:19] zero
//   [31:24] certainty, 0 .. 255, every pixel (border pixels too)
inline constexpr int kOutBeatBits = 32;
inline constexpr int kOutFixedLsb = 0;
inline constexpr int kOutReasonLsb = kOutFixedLsb + fx::kFixedDisparityBits;  // 16
inline constexpr int kOutCertaintyBits = fx::kCertaintyBits;
inline constexpr int kOutCertaintyLsb = kOutBeatBits - kOutCertaintyBits;               // 24
inline constexpr int kOutPadBits = kOutCertaintyLsb - kOutReasonLsb - fx::kReasonBits;  // 5
static_assert(kOutPadBits >= 0);

// s_axis_tdata of the pixel pair at (x, y): {right RGB, left RGB}; a grey image is matched as
// (g, g, g). sim::frame_beats and the test vectors (stereo_io/test_vectors.hpp) pack with it.
inline std::uint64_t in_beat_data(const Image& left, const Image& right, int x, int y) {
    const auto rgb = [x, y](const Image& image) -> std::uint64_t {
        const int g = image.channels == 1 ? 0 : 1;
        const int b = image.channels == 1 ? 0 : 2;
        return (std::uint64_t{image.at(x, y, 0)} << (2 * fx::kPixelBits)) |
               (std::uint64_t{image.at(x, y, g)} << fx::kPixelBits) | image.at(x, y, b);
    };
    return (rgb(right) << kInRightLsb) | (rgb(left) << kInLeftLsb);
}
// m_axis_tdata of one pixel of stage 6 (fx_pkg::out_beat_t).
constexpr std::uint32_t out_beat_data(std::int16_t fixed, unsigned reason, unsigned certainty) {
    return (static_cast<std::uint32_t>(static_cast<std::uint16_t>(fixed)) << kOutFixedLsb) |
           ((reason & ((1U << fx::kReasonBits) - 1)) << kOutReasonLsb) |
           ((certainty & ((1U << kOutCertaintyBits) - 1)) << kOutCertaintyLsb);
}
// Sticky status bits (stereo_top's status port; stereo_hls_top's return value).
inline constexpr int kStatusEolMisplaced = 0;   // tlast not at the row end
inline constexpr int kStatusSofMisplaced = 1;   // tuser inside a frame
inline constexpr int kStatusConfigClamped = 2;  // configuration out of range (clamped)
inline constexpr int kStatusBits = 3;

// ---- The hardware stages, in pipeline order ------------------------------------------------
// Latency of one stage in pixel steps, R = WINDOW/2 of the synthesised window, W = frame width,
// N = NDISP of the synthesised core, K = max(0, -min_disp) (the cost stage delays the left pixel
// by K steps for a negative minimum disparity):
//   (radius_rows * R + rows) * W + radius_steps * R + steps + ndisp_steps * N + left_delay * K
struct Latency {
    int radius_rows = 0;
    int rows = 0;
    int radius_steps = 0;
    int steps = 0;
    int ndisp_steps = 0;
    int left_delay = 0;
    constexpr int at(int width, int window, int ndisp, int min_disp) const {
        const int radius = window / 2;
        const int k = min_disp < 0 ? -min_disp : 0;
        return (radius_rows * radius + rows) * width + radius_steps * radius + steps +
               ndisp_steps * ndisp + left_delay * k;
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

inline constexpr std::array<Stage, 7> kStages = {{
    {"cost", "stereo_cost", kInBeatBits, fx::kCostBits, {0, 0, 0, 1, 0, 1}, 0},
    {"aggregate", "stereo_aggregate", fx::kCostBits, fx::kAggBits, {1, 0, 1, 2}, 0},
    // The two CA rules are one module, stereo_ca_plane, with RULE = 1 and 2.
    {"ca_rule1", "stereo_ca_plane", fx::kAggBits, fx::kAggBits, {0, 1, 0, 3}, 1},
    {"ca_rule2", "stereo_ca_plane", fx::kAggBits, fx::kAggBits, {0, 1, 0, 3}, 1},
    // The winner (k1, C1, its neighbours' costs, the border rule with d = min_disp + k1) and
    // the final cost vector, registered for the stages after it.
    {"wta", "stereo_wta", fx::kAggBits, fx::kAggBits, {0, 0, 0, 1}, 0},
    // Stage 6: the second cost C2 (a masked comparator tree) and the sub-pixel offset.
    {"validate", "stereo_validate", fx::kAggBits, fx::kAggBits, {0, 0, 0, 1}, 0},
    // Stage 6: certainty (divider), uniqueness, the left-right check along the DSI diagonal
    // (NDISP - 1 steps of delay line) and the output register: N steps.
    {"lr_check", "stereo_lr_check", fx::kAggBits, kOutBeatBits, {0, 0, 0, 0, 1}, 0},
}};

// The matching costs of the hardware: stereo_top's COST parameter, the HLS pipeline's measure
// (the catalogue's hardware codes, stereo/catalogue.hpp).
inline constexpr int kCostAd = catalogue::cost(catalogue::Cost::ad).hardware_code;
inline constexpr int kCostLcdm = catalogue::cost(catalogue::Cost::lcdm).hardware_code;
inline constexpr int kCostCensus = catalogue::cost(catalogue::Cost::census).hardware_code;
inline constexpr int kCostCount = [] {
    int count = 0;
    for (const catalogue::CostRow& row : catalogue::kCosts) {
        count += row.hardware_code != catalogue::kNoHardware;
    }
    return count;
}();

// The two CA rules of stereo_ca_plane (its RULE parameter, fx_pkg::ca_rule_e): rule 1 (model
// stereo::ca_rule1) and rule 2 (stereo::ca_rule2), docs/fixed-point.md stages 3 and 4.
inline constexpr int kCaRule1 = 1;
inline constexpr int kCaRule2 = 2;
// stereo_top's SHIFT_ADD (fx_pkg::shift_add_e): which constant tap products of the aggregation
// (RUNTIME_KERNEL = 0) are built from shifts and adds instead of being left to the tools.
inline constexpr int kShiftAddNone = 0;    // none
inline constexpr int kShiftAddNarrow = 1;  // the census codes' narrow vertical products
inline constexpr int kShiftAddAll = 2;     // every product

// The SHIFT_ADD values by name: the SV enum (fx_pkg::shift_add_e) and synth.py's --shift-add
// choices (stage_table.json "shift_add") are generated from this one list.
struct ShiftAddMode {
    std::string_view name;     // synth.py's --shift-add choice
    std::string_view sv_name;  // the fx_pkg::shift_add_e item
    int code;
    std::string_view summary;
};
inline constexpr std::array<ShiftAddMode, 3> kShiftAddModes = {{
    {"none", "SHIFT_ADD_NONE", kShiftAddNone, "none"},
    {"narrow", "SHIFT_ADD_NARROW", kShiftAddNarrow, "the census codes' vertical products"},
    {"all", "SHIFT_ADD_ALL", kShiftAddAll, "every product"},
}};

// The census transform (COST = kCostCensus only), in front of the cost stage: it turns each
// image's RGB stream into a stream of census codes, which the cost stage's delay lines carry in
// place of the RGB pixels. An input register, a window reaching r rows and r columns past its
// centre (r = fx::kCensusRadius), and the output register: r * W + r + 2 steps.
inline constexpr Stage kCensusStage = {"census",
                                       "stereo_census",
                                       kInBeatBits,
                                       2 * fx::kCensusBits,
                                       {0, fx::kCensusRadius, 0, fx::kCensusRadius + 2},
                                       1};

// Pixel steps from a pixel entering stereo_top's first stage to its output beat:
// (R + 2) * W + R + 11 + N + K (N = NDISP, K = max(0, -min_disp)), and 2 * W + 4 more with the
// census cost. With LANES = NDISP stereo_top streams one frame in W*H + this many cycles + 1 (the
// input register slice) without stalls (frame_cycles; checked by tb_stereo_top's Throughput
// test and the census testbench's).
constexpr int pipeline_latency(int width, int window, int ndisp, int min_disp = 0,
                               int cost = kCostAd) {
    int steps = 0;
    for (const Stage& stage : kStages) {
        steps += stage.rtl.at(width, window, ndisp, min_disp);
    }
    if (cost == kCostCensus) {
        steps += kCensusStage.rtl.at(width, window, ndisp, min_disp);
    }
    return steps;
}

// Clocks per pixel step of stereo_top with LANES labels computed per clock (LANES divides NDISP):
// G = NDISP / LANES (docs/rtl.md, "Time-multiplexed lanes").
constexpr int clocks_per_step(int ndisp, int lanes) {
    return ndisp / lanes;
}

// Clock cycles from a frame's first input beat to its last output beat without stalls:
// S = W*H + pipeline_latency steps, a step every G clocks, the first beat taken into the input
// register slice at the first clock of the count and stepped on one clock later, the last
// output visible the clock after its step:
//   G * S - 2 * (G - 1) + 1   (G = 1: W*H + latency + 1).
// Back to back, frames follow each other every G * S clocks (the slice takes the next frame's
// first beat during the flush).
constexpr long long frame_cycles(int width, int height, int window, int ndisp, int lanes,
                                 int min_disp = 0, int cost = kCostAd) {
    const long long g = clocks_per_step(ndisp, lanes);
    const long long steps = static_cast<long long>(width) * height +
                            pipeline_latency(width, window, ndisp, min_disp, cost);
    return g * steps - 2 * (g - 1) + 1;
}

// Steps between a pass' weighted sums and its mean in stereo_asw_aggregate: the 14-row restoring
// division is cut into this many parts, one step each, through rings of one word per label group
// (fx_pkg::ASW_DIVIDE_STEPS; docs/asw.md "Pipelined divisions"): 5 parts of ceil(14 / 5) = 3 rows,
// about 10 LUT levels each. Each step moves the passes one column back and adds 3 steps of
// latency; the arithmetic is unchanged.
inline constexpr int kAswDivideSteps = 5;
// Steps between the vertical pass' weights (with the costs they weigh) and its weighted sums: the
// weights wait in a ring (fx_pkg::ASW_VERTICAL_STEPS, 0 or 1), so no clock holds the response
// products and the sums' adder tree together. One step moves both passes one column back.
inline constexpr int kAswVerticalSteps = 1;
// Steps between pass 1's means and its winner over the labels (fx_pkg::ASW_WINNER_STEPS, 0 or 1):
// the means wait in a ring, so no clock holds a division step and the winner. One step moves
// pass 2 one column back.
inline constexpr int kAswWinnerSteps = 1;
// Steps between a horizontal pass' factors and its weighted sums (fx_pkg::ASW_HORIZONTAL_STEPS,
// 0 .. 3): the factors (pass 2's with the continuity look-up and its product), the response
// products, and the weight x mean products each wait one step in a ring, so no clock holds two
// multipliers in a row, nor a multiplier and the sums' adder tree (Yosys chains the eleven
// products of a sum through the DSP blocks' cascade otherwise). Each step moves pass 2 one
// column back.
inline constexpr int kAswHorizontalSteps = 3;

// stereo_asw_aggregate's positions, in steps behind the vertical pass' pixel x (r = w / 2,
// S = kAswDivideSteps, V = kAswVerticalSteps, W = kAswWinnerSteps, H = kAswHorizontalSteps):
// pass 1's centre x1 = x - asw_near_steps(r), pass 2's x2 = x - asw_far_steps(r).
constexpr int asw_near_steps(int r) {
    return r + 1 + kAswDivideSteps + kAswVerticalSteps;
}
constexpr int asw_far_steps(int r) {
    return asw_near_steps(r) + r + 1 + kAswHorizontalSteps + kAswDivideSteps + kAswWinnerSteps;
}

// The adaptive-support-weight core (stereo_top ASW = 1, WINDOW = the diameter w, r = w / 2):
// the census stage (COST = census), r rows of the column stack (stereo_asw_column: a pixel's
// vertical pass waits for row y + r), the cost stage (1 + K), stereo_asw_aggregate's pass 2
// position, the H steps to its sums, the S of its division and its output register, the WTA and
// stage 6 (1 + 1 + N) steps.
constexpr int asw_pipeline_latency(int width, int diameter, int ndisp, int min_disp = 0,
                                   int cost = kCostCensus) {
    const int r = diameter / 2;
    int steps = r * width + asw_far_steps(r) + kAswHorizontalSteps + kAswDivideSteps + 1;
    for (const std::size_t stage :
         {std::size_t{0}, std::size_t{4}, std::size_t{5}, std::size_t{6}}) {
        steps += kStages.at(stage).rtl.at(width, diameter, ndisp, min_disp);
    }
    if (cost == kCostCensus) {
        steps += kCensusStage.rtl.at(width, diameter, ndisp, min_disp);
    }
    return steps;
}

// frame_cycles of the adaptive-support-weight core.
constexpr long long asw_frame_cycles(int width, int height, int diameter, int ndisp, int lanes,
                                     int min_disp = 0, int cost = kCostCensus) {
    const long long g = clocks_per_step(ndisp, lanes);
    const long long steps = static_cast<long long>(width) * height +
                            asw_pipeline_latency(width, diameter, ndisp, min_disp, cost);
    return g * steps - 2 * (g - 1) + 1;
}

// The same for the HLS pipeline (stereo_hls_top): (R + 2) * W + R + 9 + N + K, and 2 * W + 3
// more with the census cost.
constexpr int hls_pipeline_latency(int width, int window, int ndisp, int min_disp = 0,
                                   int cost = kCostAd) {
    int steps = 0;
    for (const Stage& stage : kStages) {
        steps += stage.rtl.at(width, window, ndisp, min_disp) - stage.hls_fewer_steps;
    }
    if (cost == kCostCensus) {
        steps += kCensusStage.rtl.at(width, window, ndisp, min_disp) - kCensusStage.hls_fewer_steps;
    }
    return steps;
}

// ---- Adaptive support weights in hardware (stereo_top ASW = 1, docs/asw.md) ---------------
// The separable ASW replaces the aggregation and both CA rules: WINDOW is the support diameter
// w, whose response tables fx_pkg holds for every odd w in this range (generated from
// stereo::asw::response_tables).
inline constexpr int kAswMinDiameter = 3;
inline constexpr int kAswMaxDiameter = 31;

// ---- RTL sources in compile order (rtl/files.f) --------------------------------------------
// The package first, then every module before its first user. One module per file, named after
// it; the list of modules to lint is this list without the package.
inline constexpr std::string_view kPackageFile = "fx_pkg.sv";
// One module a line: the compile order reads from top to bottom.
// clang-format off
inline constexpr std::array<std::string_view, 48> kRtlModules = {
    "stereo_coord_reg",
    "stereo_stage_output",
    "stereo_shift_reg",
    "stereo_border_flags",
    "stereo_window_centre",
    "stereo_line_buffer",
    "stereo_row_stack",
    "stereo_group_ring",
    "stereo_group_delay",
    "stereo_window3x3",
    "stereo_ca_plane",
    "stereo_lcdm_convert",
    "stereo_lcdm_distance",
    "stereo_census",
    "stereo_cost",
    "stereo_weighted_sum",
    "stereo_aggregate",
    "stereo_wta",
    "stereo_divider",
    "stereo_validate",
    "stereo_lr_check",
    "stereo_asw_column",
    "stereo_asw_weights",
    "stereo_asw_aggregate",
    "stereo_top",
    "stereo_axil_top",
    "stereo_synth_top",
    "stereo_uart_rx",
    "stereo_uart_tx",
    "stereo_power_on_reset",
    "stereo_board_link",
    "stereo_board_top",
    "stereo_uart_echo_top",
    "stereo_arty_top",
    "stereo_downscale",
    "stereo_plane_stats",
    "stereo_plane_offset",
    "stereo_row_warp",
    "stereo_field_border",
    "stereo_hier_pass",
    "stereo_level_cost",
    "stereo_level_wta",
    "stereo_hier_level",
    "stereo_fifo",
    "stereo_level_stepper",
    "stereo_prediction_ring",
    "stereo_hier_levels",
    "stereo_hier_top",
};
// clang-format on
// Port-list fragments and the parameter-check macro (`STEREO_ASSERT) the modules `include (found
// in rtl/: tools need rtl/ on the include path).
inline constexpr std::array<std::string_view, 7> kRtlIncludes = {
    "stereo_stage_ports.svh",      "stereo_core_ports.svh",     "stereo_stream_ports.svh",
    "stereo_assert.svh",           "stereo_hier_out_ports.svh", "stereo_pass_cfg_ports.svh",
    "stereo_plane_stats_ports.svh"};

// ---- SoC wrapper (rtl/stereo_axil_top.sv, docs/integration.md) -------------------------------
// The register map's version (VERSION register, 0xMMMMmmmm) and the FuseSoC core's version.
inline constexpr std::uint32_t kRegmapId = 0x5354'4552;  // "STER"
inline constexpr std::uint32_t kRegmapVersion = 0x0001'0001;
inline constexpr std::string_view kRegmapVersionText = "1.1.0";

// The register map of stereo_axil_top: the one definition. gen_stage_table writes from it the
// REG_* constants of rtl/fx_pkg.sv (stereo_axil_top decodes its registers with them), the C
// header drivers/c/stereo_regs.h (offsets, fields, masks, reset values; the C driver and the
// testbenches use it) and the table of docs/integration.md. 32-bit registers, byte offsets.
enum class RegAccess : unsigned char { ro, rw, wo };
struct RegField {
    std::string_view name;  // lower case: REG_MATCH_NDISP_LSB, STEREO_MATCH_NDISP_MASK
    int lsb;
    int bits;
    std::string_view meaning;  // for the documentation
};
inline constexpr int kRegMaxFields = 5;
struct Register {
    std::string_view name;  // upper case: REG_MATCH, STEREO_REG_MATCH
    std::uint32_t offset;
    RegAccess access;
    std::array<RegField, kRegMaxFields> fields;  // from bit 0 up; unused entries have no name
    // The value after reset (ID, VERSION: the constant): a number, shown as reset_text when
    // that is not empty; kRegResetParameters when it depends on the core's parameters
    // (reset_text says how); kRegNoReset for MAX_SIZE, BUILD (parameters) and CONTROL.
    std::int64_t reset;
    std::string_view reset_text;
    std::string_view note;  // after the fields in the documentation
    int count = 1;          // KERNEL: an array of WINDOW registers, stride 4
};
inline constexpr std::int64_t kRegNoReset = -1;
inline constexpr std::int64_t kRegResetParameters = -2;
// The model's default uniqueness ratio (ValidationParams), THRESHOLDS' reset value.
inline constexpr int kResetUniquenessRatio = 20;
// clang-format off
inline constexpr std::array<Register, 14> kRegisters = {{
    {"ID", 0x00, RegAccess::ro, {{{"id", 0, 32, "\"STER\""}}}, kRegmapId, "", ""},
    {"VERSION", 0x04, RegAccess::ro, {{{"version", 0, 32, "register-map version `0xMMMMmmmm`"}}},
     kRegmapVersion, "", "1.1: BUILD's COST field widened to two bits for the census cost"},
    {"MAX_SIZE", 0x08, RegAccess::ro,
     {{{"width", 0, kCfgSizeBits, "WIDTH"}, {"height", 16, kCfgSizeBits, "HEIGHT"}}},
     kRegNoReset, "", "the parameters: the largest frame"},
    {"BUILD", 0x0C, RegAccess::ro,
     {{{"ndisp", 0, kCfgNdispBits, "NDISP"},
       {"radius", 9, kCfgRadiusBits, "WINDOW/2"},
       {"max_min_disp", 14, kCfgMinDispBits, "MAX_MIN_DISP"},
       {"runtime_kernel", 26, 1, "RUNTIME_KERNEL"},
       {"cost", 27, 2, "COST (its `fx_pkg::cost_e` code: 0 AD, 1 LCDM, 2 census)"}}},
     kRegNoReset, "", ""},
    {"FRAME", 0x10, RegAccess::rw,
     {{{"width", 0, kCfgSizeBits, ""}, {"height", 16, kCfgSizeBits, ""}}},
     kRegResetParameters, "WIDTH, HEIGHT", "of the frames"},
    {"MATCH", 0x14, RegAccess::rw,
     {{{"ndisp", 0, kCfgNdispBits, "labels searched"},
       {"radius", 16, kCfgRadiusBits, "window = 2 radius + 1"},
       {"use_ca", 24, 1, "CA rules on"}}},
     kRegResetParameters, "NDISP, WINDOW/2, 1", ""},
    {"STAGE6", 0x18, RegAccess::rw,
     {{{"min_disp", 0, kCfgMinDispBits, "minimum disparity (two's complement)"},
       {"uniqueness_en", 12, 1, "uniqueness on"},
       {"lr_en", 13, 1, "left-right check on"},
       {"subpixel_en", 14, 1, "sub-pixel on"}}},
     0, "0", ""},
    {"THRESHOLDS", 0x1C, RegAccess::rw,
     {{{"uniqueness", 0, kCfgUniquenessBits, "uniqueness ratio U (percent)"},
       {"lr_tolerance", 8, kCfgLrToleranceBits, "left-right tolerance T (labels)"}}},
     kResetUniquenessRatio, "20, 0", ""},
    {"STATUS", 0x20, RegAccess::ro,
     {{{"eol_misplaced", kStatusEolMisplaced, 1, "tlast not at a row end"},
       {"sof_misplaced", kStatusSofMisplaced, 1, "tuser inside a frame"},
       {"config_clamped", kStatusConfigClamped, 1, "configuration out of range (clamped)"}}},
     0, "0", "sticky until a reset"},
    {"CONTROL", 0x24, RegAccess::wo,
     {{{"soft_reset", 0, 1, "one cycle of reset for the core and the counters (registers "
                            "keep their values)"}}},
     kRegNoReset, "", ""},
    {"FRAMES_IN", 0x28, RegAccess::ro, {{{"count", 0, 32, "input start-of-frame beats accepted"}}},
     0, "0", ""},
    {"FRAMES_OUT", 0x2C, RegAccess::ro,
     {{{"count", 0, 32, "output start-of-frame beats delivered"}}}, 0, "0", ""},
    {"STALLS", 0x30, RegAccess::ro,
     {{{"count", 0, 32, "cycles with `m_axis_tvalid` high and `m_axis_tready` low"}}}, 0, "0", ""},
    {"KERNEL", 0x40, RegAccess::rw,
     {{{"tap", 0, fx::kKernelBits + 1, "tap i of the 1-D Gaussian kernel"}}},
     kRegResetParameters, "the model's default kernel for WINDOW",
     "i = 0 .. WINDOW-1, taps summing to 256; a smaller window is written centred, zeros outside "
     "(only with `RUNTIME_KERNEL = 1`)", fx::kMaxWindow},
}};
// clang-format on
// The register of a name (a compile-time lookup for the checks below and the generator).
constexpr const Register& reg(std::string_view name) {
    for (const Register& r : kRegisters) {
        if (r.name == name) {
            return r;
        }
    }
    throw "no such register";  // not a constant expression: a compile error where it is used
}
static_assert(reg("FRAME").fields[1].lsb == reg("FRAME").fields[0].bits, "FRAME: width, height");
static_assert(
    [] {
        // Fields inside 32 bits, in ascending order, not overlapping; offsets word-aligned and
        // ascending; the array register last.
        std::uint32_t previous = 0;
        for (std::size_t r = 0; r < kRegisters.size(); ++r) {
            const Register& reg = kRegisters[r];
            if (reg.offset % 4 != 0 || (r > 0 && reg.offset <= previous)) {
                return false;
            }
            previous = reg.offset;
            int next = 0;
            for (const RegField& field : reg.fields) {
                if (field.name.empty()) {
                    continue;
                }
                if (field.lsb < next || field.bits < 1 || field.lsb + field.bits > 32) {
                    return false;
                }
                next = field.lsb + field.bits;
            }
        }
        return true;
    }(),
    "kRegisters: aligned ascending offsets, fields in order inside 32 bits");

// ---- Verilated configurations (sim/verilated_configs.cmake) --------------------------------
// Below every parameter value (V_MIN may be negative).
inline constexpr int kUnset = -(1 << 30);

struct Params {
    int width = kUnset;
    int height = kUnset;
    int ndisp = kUnset;
    int window = kUnset;
    int runtime_kernel = kUnset;
    int rule = kUnset;          // stereo_ca_plane's RULE
    int max_min_disp = kUnset;  // stereo_top's and stereo_cost's MAX_MIN_DISP
    int cost = kUnset;   // stereo_top's and stereo_cost's COST: kCostAd, kCostLcdm, kCostCensus
    int lanes = kUnset;  // stereo_top's and stereo_cost's LANES (unset: NDISP)
    int clks_per_bit = kUnset;  // the UART's CLKS_PER_BIT (stereo_board_top)
    int shift_add = kUnset;     // stereo_top's SHIFT_ADD: tap products from shifts and adds (0-2)
    // stereo_top's RECOMPUTE_COSTS (census): the lean memory architecture, rows of census codes
    // instead of per-label rows (docs/rtl.md "Lean memory")
    int recompute_costs = kUnset;
    int factor = kUnset;  // stereo_downscale's FACTOR (the hierarchical search's pyramid)
    // stereo_hier_level's candidate grid (COLS x ROWS), vertical offsets V_MIN .. V_MAX, REFINE
    int cols = kUnset;
    int rows = kUnset;
    int v_min = kUnset;
    int v_max = kUnset;
    int refine = kUnset;
    int asw = kUnset;  // stereo_top's ASW: adaptive support weights of diameter WINDOW

    // These parameters with those that `over` sets put in their place.
    [[nodiscard]] constexpr Params with(const Params& over) const {
        Params merged = *this;
        for (int Params::*field :
             {&Params::width, &Params::height, &Params::ndisp, &Params::window,
              &Params::runtime_kernel, &Params::rule, &Params::max_min_disp, &Params::cost,
              &Params::lanes, &Params::clks_per_bit, &Params::shift_add, &Params::recompute_costs,
              &Params::factor, &Params::cols, &Params::rows, &Params::v_min, &Params::v_max,
              &Params::refine, &Params::asw}) {
            if (over.*field != kUnset) {
                merged.*field = over.*field;
            }
        }
        return merged;
    }
};

struct VerilatedConfig {
    std::string_view prefix;  // Verilator --prefix: the C++ class
    std::string_view top;     // top module
    Params params;            // the -G parameters that are set
    std::string_view option;  // CMake option that must be ON to build it; empty: always built
    // The name `stereo cosim --config` and the testbenches give a stereo_top or stereo_synth_top
    // build (sim/sim_configs.hpp TopConfig); empty for the other modules.
    std::string_view cosim_name = "";
};

inline constexpr Params kSmall{
    .width = 64, .height = 48, .ndisp = 16, .window = 5};  // the co-simulation point
inline constexpr Params kFull{.width = 640, .height = 480, .ndisp = 64, .window = 11};
// The co-simulation point with the LCDM cost stage (stereo_top COST = 1).
inline constexpr Params kSmallLcdm = kSmall.with({.cost = kCostLcdm});

// ... and with the census cost (COST = 2: the census stage in front of the cost stage).
inline constexpr Params kSmallCensus = kSmall.with({.cost = kCostCensus});

// The iCEBreaker top (rtl/stereo_board_top.sv, docs/board.md) at the co-simulation point, with
// a UART of 4 clocks per bit so that a frame simulates in a few seconds.
inline constexpr Params kSmallBoard = kSmall.with({.clks_per_bit = 4});

// Time-multiplexed lanes (stereo_top LANES < NDISP): NDISP / LANES clocks per pixel step.
// tb_stereo_top runs all its checks on each of these as well as on the small configuration.
inline constexpr Params kSmallLanes4 = kSmall.with({.lanes = 4});
inline constexpr Params kSmallLanes1 = kSmall.with({.lanes = 1});
// The LCDM cost stage with lanes: its G:1 right-pixel multiplexers and LANES LCDM distance units.
inline constexpr Params kSmallLcdmLanes4 = kSmall.with({.cost = kCostLcdm, .lanes = 4});
// The census cost with lanes (the census stage steps once per pixel step, G clocks).
inline constexpr Params kSmallCensusLanes4 = kSmall.with({.cost = kCostCensus, .lanes = 4});
// The lean memory architecture (RECOMPUTE_COSTS = 1): the census core whose cost stage keeps rows
// of census codes and recomputes every label's vertical window, all labels in parallel and 4 per
// clock; tb_stereo_top_cost runs every census check on both.
inline constexpr Params kSmallCensusRecompute =
    kSmall.with({.cost = kCostCensus, .recompute_costs = 1});
inline constexpr Params kSmallCensusRecomputeLanes4 =
    kSmall.with({.cost = kCostCensus, .lanes = 4, .recompute_costs = 1});
// ... and the AD core in the lean memory architecture, 4 labels per clock (tb_stereo_top).
inline constexpr Params kSmallLeanLanes4 = kSmall.with({.lanes = 4, .recompute_costs = 1});
// The iCE40 cores: one label (no delay line, C2 a constant, the certainty divider folded away)
// and two labels one per clock (C2 a constant in the lanes mode too).
inline constexpr Params kNdisp1 = kSmall.with({.ndisp = 1});
inline constexpr Params kNdisp2Lanes1 = kSmall.with({.ndisp = 2, .lanes = 1});
inline constexpr Params kNdisp8Lanes2 = kSmall.with({.ndisp = 8, .lanes = 2});

// The FPGA builds as synthesised (stereo_synth_top: the constant default kernel, the radius
// WINDOW/2, MAX_MIN_DISP = 0): the HX8K's one-label 3x3 core and its 4-label 5x5 core at one
// label per clock (docs/synthesis.md). tb_stereo_synth_top co-simulates both.
inline constexpr Params kIce40Ndisp1 = kSmall.with({.ndisp = 1, .window = 3, .max_min_disp = 0});
inline constexpr Params kIce40Ndisp4Lanes1 =
    kSmall.with({.ndisp = 4, .window = 5, .max_min_disp = 0, .lanes = 1});
// The census build as synthesised: the aggregation's line buffer keeps census codes (5 bits, not
// 10-bit costs), at a 7x7 window (radius 3) and two labels per clock, with every tap product
// built from shifts and adds (SHIFT_ADD = 2).
inline constexpr Params kFpgaCensusNdisp8Lanes2 = kSmall.with({.ndisp = 8,
                                                               .window = 7,
                                                               .max_min_disp = 0,
                                                               .cost = kCostCensus,
                                                               .lanes = 2,
                                                               .shift_add = kShiftAddAll});

// The adaptive-support-weight core (ASW = 1; the window is the support diameter): the census
// cost at diameter 5, all labels per clock and 4 per clock (its vertical products from shifts
// and adds, SHIFT_ADD narrow), and the AD cost (truncated) at
// diameter 31, 4 per clock, where the continuity factor bites: label jumps above 255 / 31 (8)
// (tb_stereo_asw_top).
inline constexpr Params kSmallAswCensus = kSmall.with({.cost = kCostCensus, .asw = 1});
inline constexpr Params kSmallAswCensusLanes4 =
    kSmall.with({.cost = kCostCensus, .lanes = 4, .shift_add = kShiftAddNarrow, .asw = 1});
inline constexpr Params kSmallAswAdLanes4 = kSmall.with({.window = 31, .lanes = 4, .asw = 1});

// The VGA ASW core as an FPGA runs it (docs/results-asw.md "Hardware configuration"): census,
// diameter 11, 64 labels 8 per clock.
inline constexpr Params kFullAsw = kFull.with({.cost = kCostCensus, .lanes = 8, .asw = 1});

// The VGA census core in the lean memory architecture as an FPGA runs it: 64 labels 8 per clock.
inline constexpr Params kFullCensusLean =
    kFull.with({.cost = kCostCensus, .lanes = 8, .recompute_costs = 1});

// The whole hierarchical core at that size: the lean census pass (64 labels, 8 a clock, 11x11)
// and the levels (V = 16, windows 9 / 15 / 15, one candidate row a clock).
inline constexpr Params kFullHier = {
    .width = 640, .height = 480, .ndisp = 64, .window = 11, .lanes = 8, .recompute_costs = 1};

inline constexpr std::array<VerilatedConfig, 46> kVerilatedConfigs = {{
    {"Vstereo_top_small", "stereo_top", kSmall, "", "small"},
    {"Vstereo_top_lanes4", "stereo_top", kSmallLanes4, "", "lanes4"},
    {"Vstereo_top_lanes1", "stereo_top", kSmallLanes1, "", "lanes1"},
    {"Vstereo_top_ndisp8_lanes2", "stereo_top", kNdisp8Lanes2, "", "ndisp8-lanes2"},
    {"Vstereo_top_ndisp2_lanes1", "stereo_top", kNdisp2Lanes1, "", "ndisp2-lanes1"},
    {"Vstereo_top_ndisp1", "stereo_top", kNdisp1, "", "ndisp1"},
    {"Vstereo_top_lean_lanes4", "stereo_top", kSmallLeanLanes4, "", "lean-lanes4"},
    {"Vstereo_top_asw_census", "stereo_top", kSmallAswCensus, "", "asw-census"},
    {"Vstereo_top_asw_census_lanes4", "stereo_top", kSmallAswCensusLanes4, "", "asw-census-lanes4"},
    {"Vstereo_top_asw_ad_lanes4", "stereo_top", kSmallAswAdLanes4, "", "asw-ad-lanes4"},
    // The frame-border test of every window stage, at its default offsets (-2 .. 2).
    {"Vstereo_border_flags", "stereo_border_flags", {}, ""},
    {"Vstereo_cost", "stereo_cost", {.ndisp = kSmall.ndisp}, ""},
    {"Vstereo_top_lcdm", "stereo_top", kSmallLcdm, "", "small-lcdm"},
    {"Vstereo_top_lcdm_lanes4", "stereo_top", kSmallLcdmLanes4, "", "lcdm-lanes4"},
    {"Vstereo_cost_lcdm", "stereo_cost", {.ndisp = kSmall.ndisp, .cost = kCostLcdm}, ""},
    {"Vstereo_top_census", "stereo_top", kSmallCensus, "", "small-census"},
    {"Vstereo_top_census_lanes4", "stereo_top", kSmallCensusLanes4, "", "census-lanes4"},
    {"Vstereo_top_census_recompute", "stereo_top", kSmallCensusRecompute, "", "census-recompute"},
    {"Vstereo_top_census_recompute_lanes4", "stereo_top", kSmallCensusRecomputeLanes4, "",
     "census-recompute-lanes4"},
    {"Vstereo_aggregate",
     "stereo_aggregate",
     {.width = kSmall.width, .ndisp = kSmall.ndisp, .window = kSmall.window},
     ""},
    // The constant-kernel variant that the FPGA top (stereo_synth_top) synthesizes.
    {"Vstereo_aggregate_const",
     "stereo_aggregate",
     {.width = kSmall.width, .ndisp = kSmall.ndisp, .window = kSmall.window, .runtime_kernel = 0},
     ""},
    // The CA skeleton as rule 1 and as rule 2.
    {"Vstereo_ca_rule1",
     "stereo_ca_plane",
     {.width = kSmall.width, .ndisp = kSmall.ndisp, .rule = kCaRule1},
     ""},
    {"Vstereo_ca_rule2",
     "stereo_ca_plane",
     {.width = kSmall.width, .ndisp = kSmall.ndisp, .rule = kCaRule2},
     ""},
    {"Vstereo_wta", "stereo_wta", {.ndisp = kSmall.ndisp}, ""},
    {"Vstereo_validate", "stereo_validate", {.ndisp = kSmall.ndisp}, ""},
    {"Vstereo_lr_check", "stereo_lr_check", {.ndisp = kSmall.ndisp}, ""},
    {"Vstereo_synth_top_ice40_ndisp1", "stereo_synth_top", kIce40Ndisp1, "", "ice40-ndisp1"},
    {"Vstereo_synth_top_ice40_ndisp4_lanes1", "stereo_synth_top", kIce40Ndisp4Lanes1, "",
     "ice40-ndisp4-lanes1"},
    {"Vstereo_synth_top_census_ndisp8_lanes2", "stereo_synth_top", kFpgaCensusNdisp8Lanes2, "",
     "fpga-census-ndisp8-lanes2"},
    // The SoC wrapper (AXI4-Lite registers around stereo_top) at the co-simulation point, and
    // its census build as an FPGA would take it: the constant kernel, 4 labels per clock, the
    // census codes' vertical products as shifts and adds.
    {"Vstereo_axil_top", "stereo_axil_top", kSmall, ""},
    {"Vstereo_axil_top_census", "stereo_axil_top",
     kSmall.with(
         {.runtime_kernel = 0, .cost = kCostCensus, .lanes = 4, .shift_add = kShiftAddNarrow}),
     ""},
    // The iCEBreaker top: UART protocol, configuration registers and stereo_top.
    {"Vstereo_board_top", "stereo_board_top", kSmallBoard, ""},
    // The same board design on the Arty A7 (rtl/stereo_arty_top.sv, issue 48), same size and UART.
    {"Vstereo_arty_top", "stereo_arty_top", kSmallBoard, ""},
    // Its link test (UART echo, no core) with the same UART speed.
    {"Vstereo_uart_echo_top",
     "stereo_uart_echo_top",
     {.clks_per_bit = kSmallBoard.clks_per_bit},
     ""},
    // The hierarchical search's pyramid (issue 45): the half and the quarter image.
    {"Vstereo_downscale2", "stereo_downscale", {.width = kSmall.width, .factor = 2}, ""},
    {"Vstereo_downscale4", "stereo_downscale", {.width = kSmall.width, .factor = 4}, ""},
    // ... and the statistics of its vertical plane (default VRANGE 16, offsets -8 .. 7).
    {"Vstereo_plane_stats", "stereo_plane_stats", {}, ""},
    // ... and its 1-D pass along the plane (64x48, 16 labels, 5x5, census, offsets -8 .. 7).
    {"Vstereo_hier_pass", "stereo_hier_pass", {}, ""},
    // ... and its levels for a 128x96 frame, D = V = 16: the quarter level (32 wide, the whole
    // 4 x 4 range, offsets -2 .. 1, 9x9) and the half level (64 wide, 3x3, offsets -4 .. 3, 15x15).
    {"Vstereo_hier_level_quarter",
     "stereo_hier_level",
     {.width = 32,
      .window = 9,
      .lanes = 2,
      .cols = 4,
      .rows = 4,
      .v_min = -2,
      .v_max = 1,
      .refine = 0},
     ""},
    {"Vstereo_hier_level_refine",
     "stereo_hier_level",
     {.width = 64,
      .window = 15,
      .runtime_kernel = 0,
      .lanes = 1,
      .cols = 3,
      .rows = 3,
      .v_min = -4,
      .v_max = 3,
      .refine = 1},
     ""},
    // ... and the three levels chained with their predictions (the module's defaults: 128 wide,
    // D = V = 16, windows 9 / 15 / 15).
    {"Vstereo_hier_levels", "stereo_hier_levels", {}, ""},
    // ... and the whole core: the pass (64x48, 16 labels, 5x5), the levels and the statistics.
    {"Vstereo_hier_top", "stereo_hier_top", {}, ""},
    // Its C++ takes minutes to compile: only with -DSTEREO_COSIM_FULL=ON.
    {"Vstereo_top_full", "stereo_top", kFull, "STEREO_COSIM_FULL", "full"},
    // ... and the lean census core at that size: -DSTEREO_COSIM_CONFIGS=full_census_lean.
    {"Vstereo_top_full_census_lean", "stereo_top", kFullCensusLean, "STEREO_COSIM_FULL_CENSUS",
     "full-census-lean"},
    // ... the ASW core at that size: -DSTEREO_COSIM_CONFIGS=full_asw.
    {"Vstereo_top_full_asw", "stereo_top", kFullAsw, "STEREO_COSIM_FULL_ASW", "full-asw"},
    // ... and the whole hierarchical core at that size: -DSTEREO_COSIM_CONFIGS=hier_top_full.
    {"Vstereo_hier_top_full", "stereo_hier_top", kFullHier, "STEREO_COSIM_FULL_HIER",
     "hier-top-full"},
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

inline constexpr std::array<LintConfig, 25> kExtraLintConfigs = {{
    // The lean memory architecture (RECOMPUTE_COSTS): the VGA build (64 labels, 8 per clock), a
    // 3x3 window with one label, and the FPGA top at the VGA size.
    {"stereo_top", kFull.with({.cost = kCostCensus, .lanes = 8, .recompute_costs = 1})},
    {"stereo_top",
     {.ndisp = 1, .window = 3, .max_min_disp = 0, .cost = kCostCensus, .recompute_costs = 1}},
    {"stereo_synth_top",
     kFull.with(
         {.cost = kCostCensus, .lanes = 8, .shift_add = kShiftAddNarrow, .recompute_costs = 1})},
    // Time-multiplexed lanes: one label per clock, an odd group count, the FPGA build at full size.
    {"stereo_top", {.ndisp = 3, .window = 3, .lanes = 1}},
    {"stereo_top", {.width = 100, .height = 75, .ndisp = 12, .window = 7, .lanes = 4}},
    {"stereo_synth_top", kFull.with({.lanes = 8})},
    // Stage 6 with one label (no delay line, no neighbours) and with odd label counts.
    {"stereo_lr_check", {.ndisp = 1}},
    {"stereo_validate", {.ndisp = 3}},
    {"stereo_top", {.ndisp = 1, .window = 3}},
    // The LCDM cost stage, alone with one label and in the top.
    {"stereo_cost", {.ndisp = 1, .cost = kCostLcdm}},
    // The LCDM cost stage alone with lanes (LANES < NDISP: the group port, G:1 multiplexers).
    {"stereo_cost", {.cost = kCostLcdm, .lanes = 4}},
    {"stereo_top", kSmallLcdm},
    // The census stage alone, and the census cost: the cost stage alone (one label, and lanes) and
    // the top at the full size.
    {"stereo_census", {}},
    {"stereo_cost", {.ndisp = 1, .cost = kCostCensus}},
    {"stereo_cost", {.cost = kCostCensus, .lanes = 4}},
    {"stereo_top", kFull.with({.cost = kCostCensus})},
    // The CA skeleton with the other rule.
    {"stereo_ca_plane", {.rule = kCaRule2}},
    // The top at other shapes: a 3x3 window, odd label counts, and the full-size configuration.
    {"stereo_top", {.ndisp = 5, .window = 3}},
    {"stereo_top", {.width = 100, .height = 75, .ndisp = 33, .window = 7}},
    {"stereo_top", kFull},
    // The FPGA build (constant kernel) at the full-size configuration.
    {"stereo_synth_top", kFull},
    // ... with the census cost and its narrow vertical products as shifts and adds (SHIFT_ADD =
    // 1), and with the AD cost and every product as shifts and adds (SHIFT_ADD = 2).
    {"stereo_synth_top",
     kFull.with({.cost = kCostCensus, .lanes = 32, .shift_add = kShiftAddNarrow})},
    {"stereo_synth_top", kFull.with({.lanes = 8, .shift_add = kShiftAddAll})},
    // The board top at its co-simulation point (the defaults are the UP5K build).
    {"stereo_board_top", kSmallBoard},
    // The pyramid at the VGA size: the quarter image.
    {"stereo_downscale", {.width = kFull.width, .factor = 4}},
}};

}  // namespace stereo::table
