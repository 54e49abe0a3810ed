// gen_stage_table: writes every generated file of the hardware build from the model's
// hand-written definitions, model/include/stereo/constants.hpp (the arithmetic),
// model/include/stereo/stage_table.hpp (stages, interface, sources, configurations) and
// model/include/stereo/catalogue.hpp (the hardware costs and their codes):
//   rtl/fx_pkg.sv                 package fx_pkg: constants, typed interface and parameters,
//                                 agrees()
//   rtl/files.f                   the RTL sources in compile order
//   sim/verilated_configs.cmake   the Verilated configurations (sim/CMakeLists.txt)
//   scripts/stage_table.json      stages, sources and lint configurations for the scripts
//   hls/include/stereo/hls/lcdm_table.hpp   the LCDM cosine's quarter wave for the HLS kernels
//   hls/include/stereo/hls/asw_tables.hpp   the ASW response tables for the HLS kernels
//   stereo.core                   the FuseSoC core description
//   drivers/c/stereo_regs.h       stereo_axil_top's register map for C (kRegisters)
//   docs/integration.md           its register table, between two markers (the rest of the
//                                 page is read from the source tree, STEREO_SOURCE_DIR)
// Usage: gen_stage_table ROOT (writes ROOT/<each path>); gen_stage_table --list (the paths).
// `cmake --build build --target update_generated` rewrites the checked-in copies; the ctest
// rtl.generated_files_current regenerates into a temporary folder and names any stale file.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stereo/asw.hpp"
#include "stereo/constants.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages/lcdm.hpp"

namespace {

// The LCDM cost (model/include/stereo/stages/lcdm.hpp, docs/fixed-point.md): its constants and
// the quarter wave of its cosine table.
std::string lcdm_section() {
    namespace lcdm = stereo::lcdm;
    std::ostringstream sv;
    sv << "\n  // ---- LCDM cost (model/include/stereo/stages/lcdm.hpp) ----\n";
    const std::pair<const char*, int> constants[] = {
        {"LCDM_RADIUS_BITS", lcdm::kRadiusBits}, {"LCDM_RADIUS", lcdm::kRadius},
        {"LCDM_HUE_STEPS", lcdm::kHueSteps},     {"LCDM_HUE_COUNT", lcdm::kHueCount},
        {"LCDM_HUE_QUARTER", lcdm::kHueQuarter}, {"LCDM_TRIG_BITS", lcdm::kTrigBits},
        {"LCDM_DARK_FLOOR", lcdm::kDarkFloor},   {"LCDM_LIGHT_SUM", lcdm::kLightSum},
        {"LCDM_COORD_BITS", lcdm::kCoordBits},   {"LCDM_DIST_SQ_BITS", lcdm::kDistSqBits},
        {"LCDM_DIST_BITS", lcdm::kDistBits}};
    for (const auto& [name, value] : constants) {
        sv << "  localparam int " << name << " = " << value << ";\n";
    }
    sv << "  // round(2^LCDM_TRIG_BITS cos(2 pi k / LCDM_HUE_COUNT)), k = 0 .. LCDM_HUE_QUARTER.\n"
          "  function automatic logic signed [LCDM_TRIG_BITS+1:0] lcdm_quarter_cos(\n"
          "      input logic [8:0] k);\n"
          "    case (k)";
    for (int k = 0; k <= lcdm::kHueQuarter; ++k) {
        sv << (k % 4 == 0 ? "\n      " : " ") << "9'd" << k
           << ": lcdm_quarter_cos = " << lcdm::kTrigBits + 2 << "'sd" << lcdm::quarter_cos(k)
           << ';';
    }
    sv << "\n      default: lcdm_quarter_cos = '0;\n    endcase\n  endfunction\n";
    return sv.str();
}

// One `typedef enum int` of the package: its items (name, value, comment) in value order.
struct EnumItem {
    std::string name;
    int value;
    std::string comment;
};
void write_enum(std::ostream& sv, std::vector<EnumItem> items, const char* type) {
    std::sort(items.begin(), items.end(),
              [](const EnumItem& a, const EnumItem& b) { return a.value < b.value; });
    sv << "  typedef enum int {\n";
    for (std::size_t i = 0; i < items.size(); ++i) {
        sv << "    " << items[i].name << " = " << items[i].value
           << (i + 1 < items.size() ? "," : "") << "  // " << items[i].comment << '\n';
    }
    sv << "  } " << type << ";\n";
}

// The typed parameters of the modules: stereo_top's COST from the catalogue's hardware costs
// (stereo/catalogue.hpp; rows without hardware are left out), stereo_ca_plane's RULE and
// stereo_top's SHIFT_ADD from the stage table. Their values are the old integer codes, so
// -GCOST=2 and `chparam -set COST 2` still select the census cost.
std::string parameter_types_section() {
    namespace t = stereo::table;
    std::ostringstream sv;
    sv << "\n  // ---- Typed parameters (catalogue.hpp, stage_table.hpp; docs/rtl.md) ----\n"
          "  // stereo_top's COST: the hardware costs of the catalogue, by their codes.\n";
    std::vector<EnumItem> costs;
    for (const stereo::catalogue::CostRow& row : stereo::catalogue::kCosts) {
        if (row.hardware_code == stereo::catalogue::kNoHardware) {
            continue;
        }
        std::string name = "COST_";
        for (const char c : row.name) {
            name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        }
        costs.push_back({name, row.hardware_code, std::string(row.summary)});
    }
    write_enum(sv, costs, "cost_e");
    sv << "  // stereo_ca_plane's RULE: which CA rule the plane applies (docs/fixed-point.md).\n";
    write_enum(
        sv,
        {{"CA_RULE1", t::kCaRule1, "the 3x3 mean where the d-1 or d+1 neighbour agrees"},
         {"CA_RULE2", t::kCaRule2, "c / 1.3 where RULE2_MIN_COUNT in-plane neighbours agree"}},
        "ca_rule_e");
    sv << "  // stereo_top's SHIFT_ADD (RUNTIME_KERNEL = 0): which constant tap products of the\n"
          "  // aggregation are shifts and adds instead of being left to the tools (DSP blocks).\n";
    std::vector<EnumItem> shift_add;
    for (const t::ShiftAddMode& mode : t::kShiftAddModes) {
        shift_add.push_back({std::string(mode.sv_name), mode.code, std::string(mode.summary)});
    }
    write_enum(sv, shift_add, "shift_add_e");
    return sv.str();
}

std::string asw_section();  // below, beside the other generated tables

// NAME_FIELD in upper case: "MATCH", "ndisp" -> "MATCH_NDISP".
std::string upper(std::string_view text) {
    std::string out;
    for (const char c : text) {
        out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return out;
}

std::string hex_text(std::uint64_t value, int digits) {
    std::ostringstream out;
    out << std::hex << std::uppercase << std::setw(digits) << std::setfill('0') << value;
    return out.str();
}

// The register map (stage_table.hpp kRegisters) as package constants: REG_<NAME> (byte offset),
// REG_<NAME>_<FIELD>_LSB and _BITS, REG_<NAME>_RESET where the reset value is a number.
std::string register_map_section() {
    namespace t = stereo::table;
    std::ostringstream sv;
    sv << "\n  // ---- stereo_axil_top's register map (stage_table.hpp kRegisters, "
          "docs/integration.md) ----\n";
    for (const t::Register& reg : t::kRegisters) {
        const std::string name = "REG_" + upper(reg.name);
        sv << "  localparam int " << name << " = 'h" << hex_text(reg.offset, 2) << ";";
        if (reg.count > 1) {
            sv << "  // + 4 i, i < " << reg.count;
        }
        sv << '\n';
        for (const t::RegField& field : reg.fields) {
            if (field.name.empty()) {
                continue;
            }
            const std::string prefix = name + "_" + upper(field.name);
            sv << "  localparam int " << prefix << "_LSB = " << field.lsb << ", " << prefix
               << "_BITS = " << field.bits << ";\n";
        }
        if (reg.reset >= 0) {
            sv << "  localparam int " << name << "_RESET = 'h" << hex_text(reg.reset, 8) << ";\n";
        }
    }
    return sv.str();
}

std::string package_text() {
    namespace fx = stereo::fx;
    std::ostringstream sv;
    sv << "// GENERATED by gen_stage_table from model/include/stereo/constants.hpp,\n"
          "// stage_table.hpp and catalogue.hpp: do not edit (cmake --build build --target\n"
          "// update_generated).\n"
          "// Every constant of the fixed-point pipeline; docs/fixed-point.md explains them.\n"
          "`default_nettype none\n\n"
          "package fx_pkg;\n"
          "  // Each module uses the constants of its own stage only.\n"
          "  /* verilator lint_off UNUSEDPARAM */\n";
    auto param = [&](const char* name, long long value, const char* comment) {
        sv << "  localparam int " << name << " = " << value << ';';
        if (*comment != '\0') {
            sv << "  // " << comment;
        }
        sv << '\n';
    };
    struct Param {
        const char* name;
        long long value;
        const char* comment;
    };
    // A run of constants, written in table order.
    auto params = [&](std::initializer_list<Param> table) {
        for (const Param& entry : table) {
            param(entry.name, entry.value, entry.comment);
        }
    };
    params({
        {"PIXEL_BITS", fx::kPixelBits, "one colour channel"},
        {"COST_BITS", fx::kCostBits, "AD cost over RGB"},
        {"COST_MAX", fx::kCostMax, "3 * 255"},
        {"COST_OUTSIDE", fx::kCostOutside, "cost where x - d < 0"},
        {"KERNEL_BITS", fx::kKernelBits, "1-D kernel taps sum to 2^KERNEL_BITS"},
        {"TAP_BITS", fx::kKernelBits + 1, "one tap, 0 .. 2^KERNEL_BITS"},
        {"VSUM_BITS", fx::kVerticalSumBits, "vertical pass, full precision"},
        {"WSUM_BITS", fx::kWindowSumBits, "window sum, full precision"},
        {"AGG_FRAC_BITS", fx::kAggFracBits, "fraction bits of the aggregate"},
        {"AGG_SHIFT", fx::kAggShift, "the single rounding shift"},
        {"AGG_BITS", fx::kAggBits, "aggregated cost, CA values"},
        {"AGG_MAX", fx::kAggMax, "largest aggregated cost"},
        {"CA_SUM_BITS", fx::kCaSumBits, "3x3 sum of rule 1"},
        {"MEAN9_MUL", fx::kMean9Mul, "round(sum / 9) = (sum * MUL + 2^(SHIFT-1)) >> SHIFT"},
        {"MEAN9_SHIFT", fx::kMean9Shift, ""},
        {"DIV13_MUL", fx::kDiv13Mul, "round(v / 1.3) = (v * MUL + 2^(SHIFT-1)) >> SHIFT"},
        {"DIV13_SHIFT", fx::kDiv13Shift, ""},
        {"RULE2_MIN_COUNT", fx::kRule2MinCount, "agreeing neighbours of 8 for rule 2"},
        {"DISP_BITS", fx::kDisparityBits, "output disparity"},
        {"MAX_WINDOW", fx::kMaxWindow, "largest aggregation window"},
        {"DEFAULT_WINDOW", fx::kDefaultWindow, "thesis Sec. 3.1"},
        // Stage 6 (docs/fixed-point.md): validation and sub-pixel output.
        {"MAX_MIN_DISPARITY", fx::kMaxMinDisparity, "largest |min_disp| of the model"},
        {"SUBPIXEL_BITS", fx::kSubpixelBits, "disparities are output x 2^SUBPIXEL_BITS"},
        {"FIXED_BITS", fx::kFixedDisparityBits, "signed disparity x 16"},
        {"UNIQUENESS_BASE", fx::kUniquenessBase, "invalid when C1 * (BASE + U) >= C2 * BASE"},
        {"MAX_UNIQUENESS", fx::kMaxUniqueness, "largest U"},
        {"MAX_LR_TOLERANCE", fx::kMaxLrTolerance, "largest left-right tolerance T"},
        {"CERTAINTY_BITS", fx::kCertaintyBits, "floor(((C2 - C1) << BITS) / (C2 + 1))"},
        {"NO_SECOND_COST", fx::kNoSecondCost, "C2 when no label lies away from the winner"},
        {"REASON_BITS", fx::kReasonBits, "why a pixel is invalid:"},
        {"REASON_VALID", fx::kReasonValid, ""},
        {"REASON_BORDER", fx::kReasonBorder, "window or match outside the images"},
        {"REASON_UNIQUENESS", fx::kReasonUniqueness, "a distant label costs almost as little"},
        {"REASON_LEFT_RIGHT", fx::kReasonLeftRight, "the right image's winner disagrees"},
    });

    // The interface of stereo_top and of the stage modules (stage_table.hpp).
    namespace t = stereo::table;
    sv << "\n  // ---- Interface (model/include/stereo/stage_table.hpp, docs/rtl.md) ----\n";
    param("COORD_BITS", t::kCoordBits, "signed pixel coordinates beside the data");
    sv << "  typedef logic signed [COORD_BITS-1:0] coord_t;\n"
          "  // Coordinates after a reset: far outside any frame.\n"
          "  localparam logic signed [COORD_BITS-1:0] NO_PIXEL = -"
       << t::kCoordBits << "'sd" << -t::kNoPixel << ";\n";
    params({
        {"MAX_FRAME_SIDE", t::kMaxFrameSide, "largest WIDTH and HEIGHT"},
        {"CFG_SIZE_BITS", t::kCfgSizeBits, "cfg_width, cfg_height"},
        {"CFG_NDISP_BITS", t::kCfgNdispBits, "cfg_ndisp"},
        {"CFG_RADIUS_BITS", t::kCfgRadiusBits, "cfg_radius"},
        {"CFG_MIN_DISP_BITS", t::kCfgMinDispBits, "cfg_min_disp, signed"},
        {"CFG_UNIQUENESS_BITS", t::kCfgUniquenessBits, "cfg_uniqueness"},
        {"CFG_LR_TOLERANCE_BITS", t::kCfgLrToleranceBits, "cfg_lr_tolerance"},
        {"DEFAULT_MAX_MIN_DISP", t::kDefaultMaxMinDisp, "stereo_top's MAX_MIN_DISP default"},
    });
    sv << "  typedef logic [CFG_SIZE_BITS-1:0] cfg_size_t;\n"
          "  typedef logic [CFG_NDISP_BITS-1:0] cfg_ndisp_t;\n"
          "  typedef logic [CFG_RADIUS_BITS-1:0] cfg_radius_t;\n"
          "  typedef logic signed [CFG_MIN_DISP_BITS-1:0] cfg_min_disp_t;\n"
          "  typedef logic [CFG_UNIQUENESS_BITS-1:0] cfg_uniqueness_t;\n"
          "  typedef logic [CFG_LR_TOLERANCE_BITS-1:0] cfg_lr_tolerance_t;\n"
          "  // The run-time configuration but the kernel, as stereo_top holds it (clamped to its\n"
          "  // parameters, latched at the start of a frame) and hands it to its stages (`cfg`).\n"
          "  typedef struct packed {\n";
    for (const t::ConfigFieldRow& field : t::kConfigFields) {
        sv << "    " << field.sv_type << ' ' << field.name << ";\n";
    }
    sv << "  } config_t;\n";
    params({
        {"RGB_BITS", t::kRgbBits, "one RGB pixel"},
        {"IN_BEAT_BITS", t::kInBeatBits, "s_axis_tdata = {right RGB, left RGB}"},
        {"IN_LEFT_LSB", t::kInLeftLsb, ""},
        {"IN_RIGHT_LSB", t::kInRightLsb, ""},
        {"OUT_BEAT_BITS", t::kOutBeatBits, "m_axis_tdata, the layout of out_beat_t"},
    });
    sv << "  typedef struct packed {\n"
          "    logic ["
       << t::kOutCertaintyBits - 1 << ":0] certainty;  // bits " << t::kOutBeatBits - 1 << ":"
       << t::kOutCertaintyLsb << ", every pixel\n    logic [" << t::kOutPadBits - 1
       << ":0] pad;  // zero\n    logic [REASON_BITS-1:0] reason;  // bits "
       << t::kOutReasonLsb + fx::kReasonBits - 1 << ":" << t::kOutReasonLsb
       << ", REASON_*\n    logic signed [FIXED_BITS-1:0] fixed;  // bits " << t::kOutReasonLsb - 1
       << ":" << t::kOutFixedLsb << ", disparity x 16, 0 where invalid\n  } out_beat_t;\n";
    static_assert(
        t::kOutFixedLsb == 0 && t::kOutCertaintyLsb + t::kOutCertaintyBits == t::kOutBeatBits,
        "out_beat_t lists the fields from the top bit down");
    params({
        {"STATUS_BITS", t::kStatusBits, "sticky status bits:"},
        {"STATUS_EOL_MISPLACED", t::kStatusEolMisplaced, "tlast not at the row end"},
        {"STATUS_SOF_MISPLACED", t::kStatusSofMisplaced, "tuser inside a frame"},
        {"STATUS_CONFIG_CLAMPED", t::kStatusConfigClamped, "configuration out of range"},
        {"REGMAP_ID", static_cast<std::int64_t>(t::kRegmapId), "stereo_axil_top's ID register"},
        {"REGMAP_VERSION", static_cast<std::int64_t>(t::kRegmapVersion),
         "stereo_axil_top's VERSION register"},
    });

    sv << register_map_section();

    // The CA agreement test (stereo::fx::agrees), shared by rules 1 and 2.
    sv << "\n  // CA rules: 2|n - c| < c  <=>  c < 2n < 3c, exactly in integers "
          "(stereo::fx::agrees):\n"
          "  // two comparisons instead of a subtraction, an absolute value and a comparison.\n"
          "  function automatic logic agrees(input logic [AGG_BITS-1:0] neighbour,\n"
          "                                  input logic [AGG_BITS-1:0] centre);\n"
          "    logic [AGG_BITS+1:0] twice_neighbour, centre_wide;\n"
          "    twice_neighbour = {1'b0, neighbour, 1'b0};\n"
          "    centre_wide = {2'b0, centre};\n"
          "    agrees = centre_wide < twice_neighbour &&\n"
          "             twice_neighbour < centre_wide + {1'b0, centre, 1'b0};\n"
          "  endfunction\n";

    // Constant kernels of every odd window, for synthesis tops that tie the kernel configuration
    // to constants: the 1-D default (sigma = kDefaultSigma) and the hierarchical levels'
    // (hierarchical::default_level: sigma keeps the default's ratio to the window). One table,
    // the default kernels from entry 0, the levels' from entry DEFAULT_TAP_ENTRIES; in each,
    // window w = 2k + 1 from entry k * k (the windows before it hold 1 + 3 + ... + (2k - 1) =
    // k * k taps), entry 0 in the low bits.
    static_assert(fx::kMinWindow == 1 && fx::kMaxWindow % 2 == 1, "the table starts at window 1");
    constexpr int kTapEntries = (fx::kMaxWindow / 2 + 1) * (fx::kMaxWindow / 2 + 1);
    std::ostringstream sigma;
    sigma << fx::kDefaultSigma;
    sv << "\n  // Tap i (0 .. window-1) of a constant kernel of every odd window 1 .. "
       << fx::kMaxWindow << ": the default kernels (sigma = " << sigma.str()
       << ") from entry 0, the\n"
          "  // hierarchical levels' (hierarchical::default_level: sigma = "
       << sigma.str() << " * window / " << fx::kDefaultWindow
       << ") from entry DEFAULT_TAP_ENTRIES;\n"
          "  // window 2k + 1 starts at entry k * k of its kernel; the last line holds entry 0.\n"
          "  localparam int DEFAULT_TAP_ENTRIES = "
       << kTapEntries
       << ";\n"
          "  localparam logic [2*DEFAULT_TAP_ENTRIES*TAP_BITS-1:0] CONSTANT_TAPS = {";
    const std::array<std::function<double(int)>, 2> sigma_of = {
        [](int window) { return stereo::hierarchical::default_level(window).sigma; },
        [](int) { return fx::kDefaultSigma; }};
    for (std::size_t kernel = 0; kernel < sigma_of.size(); ++kernel) {
        for (int window = fx::kMaxWindow; window >= fx::kMinWindow; window -= 2) {
            const auto taps = stereo::gaussian_kernel(window, sigma_of[kernel](window));
            sv << "\n      ";
            for (int i = window - 1; i >= 0; --i) {
                sv << fx::kKernelBits + 1 << "'d" << taps[static_cast<std::size_t>(i)]
                   << (i > 0 ? ", " : "");
            }
            const bool last = kernel + 1 == sigma_of.size() && window == fx::kMinWindow;
            sv << (last ? "" : ",") << "  // " << (kernel == 0 ? "level" : "default") << " window "
               << window;
        }
    }
    sv << "\n  };\n"
          "  // LEVEL = 1: the levels' kernel; 0: the default.\n"
          "  function automatic int constant_tap(input bit level, input int window, input int i);\n"
          "    if (window < 1 || window > "
       << fx::kMaxWindow
       << " || window % 2 == 0 || i < 0 || i >= window) constant_tap = 0;\n"
          "    else constant_tap = 32'(CONSTANT_TAPS[((level ? DEFAULT_TAP_ENTRIES : 0) +\n"
          "                                          (window / 2) * (window / 2) + i) * TAP_BITS "
          "+: "
          "TAP_BITS]);\n"
          "  endfunction\n"
          "  function automatic int default_tap(input int window, input int i);\n"
          "    default_tap = constant_tap(1'b0, window, i);\n"
          "  endfunction\n";
    sv << "  // Sub-pixel correction (constants.hpp kSubpixelCorrection): |offset| 0 .. "
       << fx::kSubpixelScale / 2
       << " of the parabola -> the refined |offset|.\n"
          "  function automatic logic [SUBPIXEL_BITS-1:0] subpixel_correction(\n"
          "      input logic [SUBPIXEL_BITS-1:0] steps);\n"
          "    case (steps)";
    for (std::size_t k = 0; k < fx::kSubpixelCorrection.size(); ++k) {
        sv << "\n      " << fx::kSubpixelBits << "'d" << k
           << ": subpixel_correction = " << fx::kSubpixelBits << "'d" << fx::kSubpixelCorrection[k]
           << ';';
    }
    sv << "\n      default: subpixel_correction = steps;  // above 8: not reached\n"
          "    endcase\n  endfunction\n";
    sv << parameter_types_section();
    sv << lcdm_section();
    sv << asw_section();
    sv << "\n  // ---- Census cost (constants.hpp, stages/census.hpp; COST = COST_CENSUS) ----\n";
    params({
        {"LUMA_R", fx::kLumaR, "luma = (R*LUMA_R + G*LUMA_G + B*LUMA_B"},
        {"LUMA_G", fx::kLumaG, "        + 2^(LUMA_SHIFT-1)) >> LUMA_SHIFT"},
        {"LUMA_B", fx::kLumaB, ""},
        {"LUMA_SHIFT", fx::kLumaShift, ""},
        {"CENSUS_RADIUS", fx::kCensusRadius, "(2r+1)^2 window"},
        {"CENSUS_BITS", fx::kCensusBits, "code bits, raster order, centre skipped"},
        {"CENSUS_WEIGHT", fx::kCensusWeight, "cost = Hamming distance * CENSUS_WEIGHT"},
        {"CENSUS_CODE_BITS", fx::kCensusCodeBits, "aggregation line buffer: the distance"},
        {"CENSUS_CODE_OUTSIDE", fx::kCensusCodeOutside, "... or this code: cost COST_OUTSIDE"},
    });
    sv << "  /* verilator lint_on UNUSEDPARAM */\n\nendpackage\n\n"
          "`default_nettype wire\n";
    return sv.str();
}

constexpr const char* kHeader =
    "generated by gen_stage_table from model/include/stereo/stage_table.hpp: do not edit";

std::string files_text() {
    std::ostringstream out;
    // Read by sim/CMakeLists.txt and scripts/synth/yosys_check.sh, which skip // lines.
    out << "// " << kHeader << ".\n" << stereo::table::kPackageFile << '\n';
    for (const auto module : stereo::table::kRtlModules) {
        out << module << ".sv\n";
    }
    return out.str();
}

// NAME=VALUE of every parameter that is set, in a fixed order, VALUE as Verilator's -G takes
// it: a decimal integer, or for a `bit` parameter 1'b0 / 1'b1 (a plain 1 would be a 32-bit value
// for a 1-bit parameter, a WIDTH warning under -Wall). The enum-typed parameters (COST, RULE,
// SHIFT_ADD) take their integer codes: the command lines pass -Wno-ENUMVALUE.
std::vector<std::pair<std::string, std::string>> assignments(const stereo::table::Params& params) {
    std::vector<std::pair<std::string, std::string>> out;
    struct Assignment {
        const char* name;
        int value;
        bool bit;
    };
    const Assignment all[] = {{"WIDTH", params.width, false},
                              {"HEIGHT", params.height, false},
                              {"NDISP", params.ndisp, false},
                              {"WINDOW", params.window, false},
                              {"RUNTIME_KERNEL", params.runtime_kernel, true},
                              {"RULE", params.rule, false},
                              {"MAX_MIN_DISP", params.max_min_disp, false},
                              {"COST", params.cost, false},
                              {"LANES", params.lanes, false},
                              {"CLKS_PER_BIT", params.clks_per_bit, false},
                              {"SHIFT_ADD", params.shift_add, false},
                              {"RECOMPUTE_COSTS", params.recompute_costs, true},
                              {"FACTOR", params.factor, false},
                              {"COLS", params.cols, false},
                              {"ROWS", params.rows, false},
                              {"V_MIN", params.v_min, false},
                              {"V_MAX", params.v_max, false},
                              {"REFINE", params.refine, true},
                              {"ASW", params.asw, true}};
    for (const auto& [name, value, bit] : all) {
        if (value != stereo::table::kUnset) {
            out.emplace_back(
                name, bit ? "1'b" + std::to_string(value != 0 ? 1 : 0) : std::to_string(value));
        }
    }
    return out;
}

std::string cmake_text() {
    std::ostringstream out;
    out << "# " << kHeader << ".\n"
        << "# stereo_verilated_config(PREFIX TOP OPTION PARAMETER=VALUE...) (sim/CMakeLists.txt)\n"
           "# records one configuration; OPTION names the CMake option that must be ON (empty:\n"
           "# always built).\n";
    for (const auto& config : stereo::table::kVerilatedConfigs) {
        out << "stereo_verilated_config(" << config.prefix << ' ' << config.top << " \""
            << config.option << '"';
        for (const auto& [name, value] : assignments(config.params)) {
            out << ' ' << name << '=' << value;
        }
        out << ")\n";
    }
    return out.str();
}

// The -G values as JSON: integers as numbers, the `bit` literals (1'b1) as strings.
std::string json_parameters(const std::vector<std::pair<std::string, std::string>>& list) {
    std::string out = "{";
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string& value = list[i].second;
        const bool literal = value.find('\'') != std::string::npos;
        out += (i == 0 ? "\"" : ", \"") + list[i].first +
               "\": " + (literal ? "\"" + value + "\"" : value);
    }
    return out + "}";
}

std::string json_text() {
    namespace t = stereo::table;
    std::ostringstream out;
    out << "{\n  \"_comment\": \"" << kHeader
        << " (cmake --build build --target update_generated)\",\n";
    out << "  \"package\": \"" << t::kPackageFile << "\",\n  \"modules\": [";
    for (std::size_t i = 0; i < t::kRtlModules.size(); ++i) {
        out << (i == 0 ? "" : ", ") << '"' << t::kRtlModules[i] << '"';
    }
    // The hardware costs of the catalogue (stereo/catalogue.hpp): name, COST code, summary.
    out << "],\n  \"costs\": [\n";
    std::vector<const stereo::catalogue::CostRow*> hardware;
    for (const auto& row : stereo::catalogue::kCosts) {
        if (row.hardware_code != stereo::catalogue::kNoHardware) {
            hardware.push_back(&row);
        }
    }
    for (std::size_t i = 0; i < hardware.size(); ++i) {
        out << "    {\"name\": \"" << hardware[i]->name
            << "\", \"code\": " << hardware[i]->hardware_code
            << ", \"lean_core\": " << (hardware[i]->lean_core ? "true" : "false")
            << ", \"summary\": \"" << hardware[i]->summary << "\"}"
            << (i + 1 < hardware.size() ? "," : "") << '\n';
    }
    // stereo_top's SHIFT_ADD values by name (synth.py's --shift-add).
    out << "  ],\n  \"shift_add\": {";
    for (std::size_t i = 0; i < t::kShiftAddModes.size(); ++i) {
        out << (i == 0 ? "" : ", ") << '"' << t::kShiftAddModes[i].name
            << "\": " << t::kShiftAddModes[i].code;
    }
    out << "}";
    const auto stage_json = [](const t::Stage& stage) {
        std::ostringstream text;
        text << "{\"name\": \"" << stage.name << "\", \"module\": \"" << stage.module
             << "\", \"in_lane_bits\": " << stage.in_lane_bits
             << ", \"out_lane_bits\": " << stage.out_lane_bits
             << ", \"latency\": {\"radius_rows\": " << stage.rtl.radius_rows
             << ", \"rows\": " << stage.rtl.rows << ", \"radius_steps\": " << stage.rtl.radius_steps
             << ", \"steps\": " << stage.rtl.steps << ", \"ndisp_steps\": " << stage.rtl.ndisp_steps
             << ", \"left_delay\": " << stage.rtl.left_delay << "}}";
        return text.str();
    };
    // The census stage runs in front of the cost stage with the census cost only
    // (stage_table.hpp pipeline_latency).
    out << ",\n  \"census_stage\": " << stage_json(t::kCensusStage) << ",\n  \"stages\": [\n";
    for (std::size_t i = 0; i < t::kStages.size(); ++i) {
        out << "    " << stage_json(t::kStages[i]) << (i + 1 < t::kStages.size() ? "," : "")
            << '\n';
    }
    out << "  ],\n  \"lint\": [\n";
    for (std::size_t i = 0; i < t::kExtraLintConfigs.size(); ++i) {
        const auto& lint = t::kExtraLintConfigs[i];
        out << "    {\"top\": \"" << lint.top
            << "\", \"parameters\": " << json_parameters(assignments(lint.params)) << '}'
            << (i + 1 < t::kExtraLintConfigs.size() ? "," : "") << '\n';
    }
    out << "  ],\n  \"verilated\": [\n";
    for (std::size_t i = 0; i < t::kVerilatedConfigs.size(); ++i) {
        const auto& config = t::kVerilatedConfigs[i];
        out << "    {\"prefix\": \"" << config.prefix << "\", \"top\": \"" << config.top
            << "\", \"parameters\": " << json_parameters(assignments(config.params))
            << ", \"option\": \"" << config.option << "\"}"
            << (i + 1 < t::kVerilatedConfigs.size() ? "," : "") << '\n';
    }
    out << "  ]\n}\n";
    return out.str();
}

// The adaptive-support-weight core's response tables (stereo_top ASW = 1, docs/asw.md): the
// model's stereo::asw::response_tables at the default responses for every diameter the hardware
// builds, each kind one packed constant (table t, diameter ASW_MIN_DIAMETER + 2 t, at
// [t * entries * 8 +: entries * 8], entry i at [i * 8 +: 8]), read by three functions.
std::string asw_section() {
    namespace asw = stereo::asw;
    namespace table = stereo::table;
    std::ostringstream sv;
    sv << "\n  // ---- Adaptive support weights (model/include/stereo/asw.hpp; stereo_top ASW = 1) "
          "----\n";
    const std::pair<const char*, int> constants[] = {
        {"ASW_MIN_DIAMETER", table::kAswMinDiameter},
        {"ASW_MAX_DIAMETER", table::kAswMaxDiameter},
        {"ASW_DIVIDE_STEPS", table::kAswDivideSteps},
        {"ASW_VERTICAL_STEPS", table::kAswVerticalSteps},
        {"ASW_WINNER_STEPS", table::kAswWinnerSteps},
        {"ASW_HORIZONTAL_STEPS", table::kAswHorizontalSteps},
        {"ASW_RESPONSE_BITS", asw::kResponseBits},
        {"ASW_COLOUR_ENTRIES", asw::kMaxColourDifference + 1},
        {"ASW_CONTINUITY_ENTRIES", 256},
        {"ASW_PROXIMITY_ENTRIES", table::kAswMaxDiameter / 2 + 1},
        {"ASW_TRUNCATION_AD", asw::truncation_for(asw::kTruncationByCost, "ad")},
        {"ASW_TRUNCATION_CENSUS", asw::truncation_for(asw::kTruncationByCost, "census")},
        // An excluded label (stereo::kNoCandidate): all ones, above every aggregated cost.
        {"ASW_NO_CANDIDATE", (1 << stereo::fx::kAggBits) - 1}};
    for (const auto& [name, value] : constants) {
        sv << "  localparam int " << name << " = " << value << ";\n";
    }
    const int tables = (table::kAswMaxDiameter - table::kAswMinDiameter) / 2 + 1;
    // One kind: entries(w) gives diameter w's table; written highest diameter first.
    auto packed = [&](const char* name, int entries, auto entries_of) {
        sv << "  localparam logic [" << tables << " * " << entries << " * 8 - 1:0] " << name
           << " = {";
        for (int w = table::kAswMaxDiameter; w >= table::kAswMinDiameter; w -= 2) {
            const std::vector<std::uint8_t> values = entries_of(w);
            sv << "\n      " << entries * 8 << "'h";
            for (int i = entries - 1; i >= 0; --i) {
                static constexpr char kHex[] = "0123456789abcdef";
                const int v = values[static_cast<std::size_t>(i)];
                sv << kHex[v >> 4] << kHex[v & 15];
            }
            sv << (w > table::kAswMinDiameter ? "," : "") << "  // w = " << w;
        }
        sv << "\n  };\n";
    };
    auto tables_of = [](int w) {
        asw::Params params;
        params.diameter = w;
        return asw::response_tables(params);
    };
    packed("ASW_COLOUR", asw::kMaxColourDifference + 1, [&](int w) { return tables_of(w).colour; });
    packed("ASW_CONTINUITY", 256, [&](int w) { return tables_of(w).continuity; });
    // Proximity along an axis: the response at distance |o| = 0 .. r (squared index o^2).
    packed("ASW_PROXIMITY", table::kAswMaxDiameter / 2 + 1, [&](int w) {
        const auto proximity = tables_of(w).proximity;
        std::vector<std::uint8_t> axis(table::kAswMaxDiameter / 2 + 1, 0);
        for (int o = 0; o <= w / 2; ++o) {
            axis[static_cast<std::size_t>(o)] = proximity[static_cast<std::size_t>(o * o)];
        }
        return axis;
    });
    sv << "  // The responses of a diameter ASW_MIN_DIAMETER .. ASW_MAX_DIAMETER (odd): colour by\n"
          "  // |dR| + |dG| + |dB|, continuity by the label difference, proximity by the "
          "distance.\n"
          "  function automatic logic [7:0] asw_colour(input int diameter, input int difference);\n"
          "    asw_colour = ASW_COLOUR[(((diameter - ASW_MIN_DIAMETER) / 2) * ASW_COLOUR_ENTRIES "
          "+\n"
          "                             difference) * 8 +: 8];\n"
          "  endfunction\n"
          "  function automatic logic [7:0] asw_continuity(input int diameter, input int "
          "difference);\n"
          "    asw_continuity = ASW_CONTINUITY[(((diameter - ASW_MIN_DIAMETER) / 2) *\n"
          "                                     ASW_CONTINUITY_ENTRIES + difference) * 8 +: 8];\n"
          "  endfunction\n"
          "  function automatic logic [7:0] asw_proximity(input int diameter, input int "
          "distance);\n"
          "    asw_proximity = ASW_PROXIMITY[(((diameter - ASW_MIN_DIAMETER) / 2) *\n"
          "                                   ASW_PROXIMITY_ENTRIES + distance) * 8 +: 8];\n"
          "  endfunction\n"
          "  // (a * b + 128) >> 8: two responses combined (stereo::asw::combine).\n"
          "  function automatic logic [7:0] asw_combine(input logic [7:0] a, input logic [7:0] "
          "b);\n"
          "    /* verilator lint_off UNUSEDSIGNAL */  // the rounded-off byte\n"
          "    logic [15:0] product;\n"
          "    /* verilator lint_on UNUSEDSIGNAL */\n"
          "    product = 16'(a) * 16'(b) + 16'd128;\n"
          "    asw_combine = product[15:8];\n"
          "  endfunction\n"
          "  // Two combines with a common factor in one multiplier (a DSP block): {b1, 8'd0, b0} "
          "* a\n"
          "  // holds b1 * a and b0 * a in its two 16-bit halves (b0 * a < 2^16 never carries "
          "into b1's);\n"
          "  // each half rounds as asw_combine.\n"
          "  // Returns {b1 (x) a, b0 (x) a}.\n"
          "  function automatic logic [15:0] asw_combine_pair(input logic [7:0] a, input logic "
          "[7:0] b0,\n"
          "                                                   input logic [7:0] b1);\n"
          "    logic [31:0] product;\n"
          "    /* verilator lint_off UNUSEDSIGNAL */  // the rounded-off bytes\n"
          "    logic [15:0] low, high;\n"
          "    /* verilator lint_on UNUSEDSIGNAL */\n"
          "    product = 32'({b1, 8'd0, b0}) * 32'(a);\n"
          "    low = product[15:0] + 16'd128;\n"
          "    high = product[31:16] + 16'd128;\n"
          "    asw_combine_pair = {high[15:8], low[15:8]};\n"
          "  endfunction\n"
          "  // asw_combine with a constant a, as shifts and adds (a multiplier by a constant "
          "would take\n"
          "  // a DSP block).\n"
          "  function automatic logic [7:0] asw_combine_constant(input int a, input logic [7:0] "
          "b);\n"
          "    /* verilator lint_off UNUSEDSIGNAL */  // the rounded-off byte\n"
          "    logic [15:0] product;\n"
          "    /* verilator lint_on UNUSEDSIGNAL */\n"
          "    product = 16'd128;\n"
          "    for (int k = 0; k < 8; k++) if (a[k]) product = product + (16'(b) << k);\n"
          "    asw_combine_constant = product[15:8];\n"
          "  endfunction\n";
    return sv.str();
}

// The LCDM quarter-wave cosine for the HLS kernels (hls/include/stereo/hls/cost_lcdm.hpp): a
// constexpr table, as the synthesis tool needs it.
std::string hls_lcdm_table_text() {
    namespace lcdm = stereo::lcdm;
    std::ostringstream out;
    out << "// GENERATED by gen_stage_table from model/include/stereo/stages/lcdm.hpp: do not "
           "edit\n"
           "// (cmake --build build --target update_generated).\n"
           "// round(2^kTrigBits cos(2 pi k / kHueCount)), k = 0 .. kHueQuarter: the LCDM "
           "cosine's\n"
           "// quarter wave, as rtl/fx_pkg.sv's lcdm_quarter_cos.\n"
           "#pragma once\n\n#include <cstdint>\n\n#include \"stereo/stages/lcdm.hpp\"\n\n"
           "namespace stereo::hls {\n\n"
           "// clang-format off\n"
           "inline constexpr std::int16_t kLcdmQuarterCos[lcdm::kHueQuarter + 1] = {";
    for (int k = 0; k <= lcdm::kHueQuarter; ++k) {
        out << (k % 12 == 0 ? "\n    " : " ") << lcdm::quarter_cos(k) << ',';
    }
    out << "\n};\n// clang-format on\n\n}  // namespace stereo::hls\n";
    return out.str();
}

// The adaptive-support-weight response tables for the HLS kernels (hls/include/stereo/hls/
// asw.hpp): stereo::asw::response_tables at the default responses for every diameter the
// hardware builds, as constexpr arrays (the synthesis tool needs them constant), the same values
// as rtl/fx_pkg.sv's ASW_COLOUR, ASW_CONTINUITY and ASW_PROXIMITY (asw_section).
std::string hls_asw_tables_text() {
    namespace asw = stereo::asw;
    namespace table = stereo::table;
    std::ostringstream out;
    out << "// GENERATED by gen_stage_table from model/src/asw.cpp (stereo::asw::response_tables): "
           "do not\n"
           "// edit (cmake --build build --target update_generated).\n"
           "// The ASW responses of every diameter table::kAswMinDiameter .. kAswMaxDiameter (odd) "
           "at the\n"
           "// default responses (log, normalisers 255), as rtl/fx_pkg.sv's ASW_COLOUR, "
           "ASW_CONTINUITY and\n"
           "// ASW_PROXIMITY: table t is diameter kAswMinDiameter + 2 t; colour by |dR| + |dG| + "
           "|dB|,\n"
           "// continuity by the label difference, proximity by the distance along an axis.\n"
           "#pragma once\n\n#include <cstdint>\n\n#include \"stereo/asw.hpp\"\n"
           "#include \"stereo/stage_table.hpp\"\n\n"
           "namespace stereo::hls {\n\n"
           "inline constexpr int kAswTables = (table::kAswMaxDiameter - table::kAswMinDiameter) / "
           "2 + 1;\n"
           "inline constexpr int kAswColourEntries = asw::kMaxColourDifference + 1;\n"
           "inline constexpr int kAswContinuityEntries = 256;\n"
           "inline constexpr int kAswProximityEntries = table::kAswMaxDiameter / 2 + 1;\n\n"
           "// clang-format off\n";
    auto tables_of = [](int w) {
        asw::Params params;
        params.diameter = w;
        return asw::response_tables(params);
    };
    auto write = [&](const char* name, const char* entries, auto values_of) {
        out << "inline constexpr std::uint8_t " << name << "[kAswTables][" << entries << "] = {";
        for (int w = table::kAswMinDiameter; w <= table::kAswMaxDiameter; w += 2) {
            const std::vector<std::uint8_t> values = values_of(w);
            out << "\n  {  // w = " << w;
            for (std::size_t i = 0; i < values.size(); ++i) {
                out << (i % 16 == 0 ? "\n    " : " ") << int{values[i]} << ',';
            }
            out << "\n  },";
        }
        out << "\n};\n";
    };
    write("kAswColour", "kAswColourEntries", [&](int w) { return tables_of(w).colour; });
    write("kAswContinuity", "kAswContinuityEntries",
          [&](int w) { return tables_of(w).continuity; });
    write("kAswProximity", "kAswProximityEntries", [&](int w) {
        const auto proximity = tables_of(w).proximity;
        std::vector<std::uint8_t> axis(table::kAswMaxDiameter / 2 + 1, 0);
        for (int o = 0; o <= w / 2; ++o) {
            axis[static_cast<std::size_t>(o)] = proximity[static_cast<std::size_t>(o * o)];
        }
        return axis;
    });
    out << "// clang-format on\n\n}  // namespace stereo::hls\n";
    return out.str();
}

// FuseSoC CAPI2 description of the core: the sources in compile order, the SystemVerilog
// testbench, every top-level parameter, and the lint, simulation and synthesis targets. FuseSoC
// is not in Debian, so nothing here runs it; generating the file keeps its file list equal to
// rtl/files.f, and test_fusesoc_core parses it and checks every parameter against the RTL
// (docs/integration.md). No YAML anchors: every target is written out in full.
struct CoreParameter {
    const char* name;
    const char* datatype;   // int or str
    const char* paramtype;  // vlogparam or plusarg
    const char* tops;       // whose parameter: a (stereo_axil_top), t (tb_stereo_top), x
                            // (tb_stereo_axil_top), b (stereo_arty_top)
    const char* description;
};
// The parameters of stereo_axil_top (the synthesis top) and of the testbenches, the RTL's defaults
// in the descriptions: no default is given here, so FuseSoC passes only what a user sets and
// the RTL's own defaults (LANES = NDISP, ...) hold otherwise.
constexpr CoreParameter kCoreParameters[] = {
    {"WIDTH", "int", "vlogparam", "atxb", "Largest frame width (64)"},
    {"HEIGHT", "int", "vlogparam", "atxb", "Largest frame height (48)"},
    {"NDISP", "int", "vlogparam", "atxb", "Labels in parallel, the largest ndisp (16)"},
    {"WINDOW", "int", "vlogparam", "atxb", "Largest aggregation window, odd (5)"},
    {"RUNTIME_KERNEL", "int", "vlogparam", "atx",
     "1: the kernel from the KERNEL registers; 0: the default kernel as constants (1)"},
    {"MAX_MIN_DISP", "int", "vlogparam", "atxb", "Largest |minimum disparity| (8)"},
    {"COST", "int", "vlogparam", "atx",
     "Matching cost, fx_pkg::cost_e code: 0 AD, 1 LCDM, 2 census (0)"},
    {"LANES", "int", "vlogparam", "atxb", "Labels per clock, divides NDISP (NDISP)"},
    {"SHIFT_ADD", "int", "vlogparam", "atx",
     "RUNTIME_KERNEL 0: tap products as shifts and adds, fx_pkg::shift_add_e code (0)"},
    {"RECOMPUTE_COSTS", "int", "vlogparam", "atx",
     "1: the lean memory architecture, census or AD (0)"},
    {"ADDR_BITS", "int", "vlogparam", "ax", "AXI4-Lite address width (8)"},
    {"CLKS_PER_BIT", "int", "vlogparam", "b", "Arty A7: clocks per UART bit (868: 115,200 baud)"},
    {"vectors", "str", "plusarg", "tx",
     "Testbench: folder of config.hex, input.hex, expected.hex (stereo vectors -o DIR)"},
    {"seed", "int", "plusarg", "tx", "Testbench: seed of the gap and stall generators (1)"},
    {"gap", "int", "plusarg", "tx", "Testbench: percent of cycles s_axis_tvalid is withheld (30)"},
    {"stall", "int", "plusarg", "tx", "Testbench: percent of cycles m_axis_tready is low (30)"},
    {"max_errors", "int", "plusarg", "tx", "Testbench: mismatching beats printed (10)"},
};

std::string fusesoc_text() {
    std::ostringstream out;
    out << "CAPI=2:\n# " << kHeader << ".\n"
        << "name: ::stereo-ca:" << stereo::table::kRegmapVersionText << "\n"
        << "description: CA-enhanced streaming stereo matcher (AXI4-Stream, AXI4-Lite registers)"
           "\n\nfilesets:\n  rtl:\n    files:\n"
        << "      - rtl/" << stereo::table::kPackageFile << "\n";
    for (const auto module : stereo::table::kRtlModules) {
        out << "      - rtl/" << module << ".sv\n";
    }
    for (const auto include : stereo::table::kRtlIncludes) {
        out << "      - rtl/" << include << ": {is_include_file: true}\n";
    }
    out << "    file_type: systemVerilogSource\n"
           "  tb:\n    files:\n      - testbench/sv/tb_stereo_vectors.sv\n"
           "      - testbench/sv/tb_stereo_top.sv\n      - testbench/sv/tb_stereo_axil_top.sv\n"
           "      - testbench/sv/tb_core_params.svh: {is_include_file: true}\n"
           "      - testbench/sv/tb_cfg_signals.svh: {is_include_file: true}\n"
           "      - testbench/sv/tb_xorshift.svh: {is_include_file: true}\n"
           "    file_type: systemVerilogSource\n"
           "  arty_a7:\n    files:\n      - scripts/synth/boards/arty_a7.xdc:\n"
           "          file_type: xdc\n\nparameters:\n";
    for (const CoreParameter& parameter : kCoreParameters) {
        out << "  " << parameter.name << ":\n    datatype: " << parameter.datatype
            << "\n    description: \"" << parameter.description
            << "\"\n    paramtype: " << parameter.paramtype << '\n';
    }
    // The parameter list of a top (its letter in CoreParameter::tops).
    const auto list = [](char top) {
        std::string names;
        for (const CoreParameter& parameter : kCoreParameters) {
            if (std::string_view(parameter.tops).find(top) != std::string_view::npos) {
                names += (names.empty() ? "" : ", ") + std::string(parameter.name);
            }
        }
        return "[" + names + "]";
    };
    const std::string core =
        "    filesets: [rtl]\n    toplevel: stereo_axil_top\n"
        "    parameters: " +
        list('a') + "\n";
    const auto simulation = [&list](const char* top, char key) {
        return std::string("    filesets: [rtl, tb]\n    toplevel: ") + top +
               "\n    parameters: " + list(key) +
               "\n    default_tool: verilator\n    tools:\n      verilator:\n"
               "        mode: binary\n        verilator_options: [--timing, -Wno-fatal]\n";
    };
    out << "\ntargets:\n  default:\n"
        << core << "  lint:\n"
        << core
        << "    default_tool: verilator\n    tools:\n      verilator:\n"
           "        mode: lint-only\n        verilator_options: [-Wall, -Wno-ENUMVALUE]\n"
           "  sim:\n"
        << simulation("tb_stereo_top", 't') << "  sim_axil:\n"
        << simulation("tb_stereo_axil_top", 'x') << "  synth:\n"
        << core
        << "    default_tool: yosys\n    tools:\n      yosys:\n        arch: xilinx\n"
           "  arty_a7:\n    filesets: [rtl, arty_a7]\n    toplevel: stereo_arty_top\n"
           "    parameters: "
        << list('b')
        << "\n    default_tool: vivado\n    tools:\n      vivado:\n"
           "        part: xc7a100tcsg324-1\n";
    return out.str();
}

// The C header of the register map (drivers/c/README.md): offsets, fields (LSB, width, mask),
// reset values, the ID and version, and the codes the BUILD register reports, for C99 and C++.
std::string c_header_text() {
    namespace t = stereo::table;
    std::ostringstream h;
    h << "/* GENERATED by gen_stage_table from model/include/stereo/stage_table.hpp (kRegisters):\n"
         " * do not edit (cmake --build build --target update_generated).\n"
         " * The AXI4-Lite register map of stereo_axil_top (docs/integration.md): byte offsets,\n"
         " * fields as STEREO_<REGISTER>_<FIELD>_{LSB,BITS,MASK}, reset values. */\n"
         "#ifndef STEREO_REGS_H\n#define STEREO_REGS_H\n\n"
         "#define STEREO_REGMAP_ID 0x"
      << hex_text(t::kRegmapId, 8) << "u\n#define STEREO_REGMAP_VERSION 0x"
      << hex_text(t::kRegmapVersion, 8)
      << "u\n#define STEREO_REGMAP_VERSION_MAJOR(version) ((version) >> 16)\n\n"
         "/* A field's value in a register word, and a register word's field. */\n"
         "#define STEREO_FIELD(field, value) ((((unsigned long)(value)) << field##_LSB) & "
         "field##_MASK)\n"
         "#define STEREO_GET(field, word) ((((unsigned long)(word)) & field##_MASK) >> "
         "field##_LSB)\n";
    for (const t::Register& reg : t::kRegisters) {
        const std::string name = "STEREO_" + upper(reg.name);
        h << "\n/* " << reg.name << " ("
          << (reg.access == t::RegAccess::ro   ? "read-only"
              : reg.access == t::RegAccess::rw ? "read-write"
                                               : "write-only")
          << ") */\n";
        if (reg.count > 1) {
            h << "#define STEREO_REG_" << upper(reg.name) << "(i) (0x" << hex_text(reg.offset, 2)
              << "u + 4u * (unsigned)(i))\n#define STEREO_REG_" << upper(reg.name) << "_COUNT_MAX "
              << reg.count << "\n";
        } else {
            h << "#define STEREO_REG_" << upper(reg.name) << " 0x" << hex_text(reg.offset, 2)
              << "u\n";
        }
        for (const t::RegField& field : reg.fields) {
            if (field.name.empty()) {
                continue;
            }
            const std::string prefix = name + "_" + upper(field.name);
            const std::uint64_t mask = ((std::uint64_t{1} << field.bits) - 1) << field.lsb;
            h << "#define " << prefix << "_LSB " << field.lsb << "\n#define " << prefix << "_BITS "
              << field.bits << "\n#define " << prefix << "_MASK 0x" << hex_text(mask, 8) << "ul\n";
        }
        if (reg.reset >= 0) {
            h << "#define " << name << "_RESET 0x" << hex_text(reg.reset, 8) << "ul\n";
        }
    }
    h << "\n/* BUILD.cost: stereo_top's COST codes. */\n";
    for (const stereo::catalogue::CostRow& row : stereo::catalogue::kCosts) {
        if (row.hardware_code != stereo::catalogue::kNoHardware) {
            h << "#define STEREO_COST_" << upper(row.name) << ' ' << row.hardware_code << '\n';
        }
    }
    h << "\n#endif /* STEREO_REGS_H */\n";
    return h.str();
}

// docs/integration.md with its register table regenerated between the markers kTableBegin and
// kTableEnd (the rest of the page is read from the source tree and kept as it is).
constexpr std::string_view kTableBegin =
    "<!-- generated by gen_stage_table from stage_table.hpp kRegisters: edit the table there -->\n";
constexpr std::string_view kTableEnd = "<!-- end of the generated table -->\n";

std::string register_table() {
    namespace t = stereo::table;
    std::ostringstream md;
    md << "| offset | name | access | fields | reset |\n|---|---|---|---|---|\n";
    for (const t::Register& reg : t::kRegisters) {
        md << "| 0x" << hex_text(reg.offset, 2) << (reg.count > 1 ? " + 4i" : "") << " | "
           << reg.name << (reg.count > 1 ? "[i]" : "") << " | "
           << (reg.access == t::RegAccess::ro   ? "RO"
               : reg.access == t::RegAccess::rw ? "RW"
                                                : "WO")
           << " | ";
        bool first = true;
        for (const t::RegField& field : reg.fields) {
            if (field.name.empty()) {
                continue;
            }
            md << (first ? "" : ", ");
            first = false;
            if (field.bits < 32) {
                md << "`[" << field.lsb + field.bits - 1;
                if (field.bits > 1) {
                    md << ':' << field.lsb;
                }
                md << "]` ";
            }
            md << "`" << field.name << "`" << (field.meaning.empty() ? "" : ": ") << field.meaning;
        }
        if (!reg.note.empty()) {
            md << (reg.name == "VERSION" ? " (" : "; ") << reg.note
               << (reg.name == "VERSION" ? ")" : "");
        }
        md << " |";
        if (!reg.reset_text.empty()) {
            md << ' ' << reg.reset_text;
        } else if (reg.reset >= 0) {
            md << " `0x" << hex_text(static_cast<std::uint64_t>(reg.reset), 8) << '`';
        }
        md << " |\n";
    }
    return md.str();
}

std::string integration_text() {
    const std::filesystem::path source =
        std::filesystem::path(STEREO_SOURCE_DIR) / "docs" / "integration.md";
    std::ifstream in(source, std::ios::binary);
    const std::string page{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::size_t begin = page.find(kTableBegin);
    const std::size_t end = page.find(kTableEnd);
    if (!in || begin == std::string::npos || end == std::string::npos || end < begin) {
        throw std::runtime_error(source.string() + " lacks the register table's markers");
    }
    return page.substr(0, begin + kTableBegin.size()) + register_table() + page.substr(end);
}

// Every generated file: its path under the source root and its text.
std::vector<std::pair<std::string, std::function<std::string()>>> generated_files() {
    return {{"rtl/fx_pkg.sv", package_text},
            {"rtl/files.f", files_text},
            {"sim/verilated_configs.cmake", cmake_text},
            {"scripts/stage_table.json", json_text},
            {"hls/include/stereo/hls/lcdm_table.hpp", hls_lcdm_table_text},
            {"hls/include/stereo/hls/asw_tables.hpp", hls_asw_tables_text},
            {"stereo.core", fusesoc_text},
            {"drivers/c/stereo_regs.h", c_header_text},
            {"docs/integration.md", integration_text}};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: gen_stage_table ROOT | --list\n";
        return 2;
    }
    const std::string root = argv[1];
    for (const auto& [path, text] : generated_files()) {
        if (root == "--list") {
            std::cout << path << '\n';
            continue;
        }
        const std::filesystem::path target = std::filesystem::path(root) / path;
        std::string content;
        try {
            content = text();
        } catch (const std::exception& error) {
            std::cerr << "gen_stage_table: error: " << error.what() << '\n';
            return 1;
        }
        {
            // An unchanged file keeps its time stamp, so the build does not redo its users.
            std::ifstream in(target, std::ios::binary);
            const std::string current{std::istreambuf_iterator<char>(in),
                                      std::istreambuf_iterator<char>()};
            if (in && current == content) {
                continue;
            }
        }
        std::filesystem::create_directories(target.parent_path());
        std::ofstream out(target, std::ios::binary);
        out << content;
        if (!out) {
            std::cerr << "gen_stage_table: error: cannot write " << target << '\n';
            return 1;
        }
    }
    return 0;
}
