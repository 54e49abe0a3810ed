// The catalogue: one row per matching cost and per method, with everything the rest of the
// project would otherwise work out again from a bare name — the hardware code, which engines and
// methods take a cost, stage 6's defaults for it, what a method produces, its default cost, and
// the one-line description that --help, Python and the docs show. The CLI's choices, Python's
// defaults, the RTL's cost codes (fx_pkg, generated), the simulation tables and the stage-table
// JSON that synth.py reads are derived from it; tests/test_catalogue.cpp checks every engine,
// binding and generated file against it. docs/architecture.md: how to add a cost or a method.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace stereo::catalogue {

// ---- costs ---------------------------------------------------------------------------------
enum class Cost : unsigned char { ad, census, lcdm, zncc };

// Stage 6's defaults of a cost: the uniqueness ratio U (percent) and the left-right tolerance T
// (labels), chosen by one rule on all eight scenes with ground truth (stereo/defaults.hpp).
struct Validation {
    int uniqueness;
    int lr_tolerance;
};

inline constexpr int kNoHardware = -1;

struct CostRow {
    Cost id;
    std::string_view name;
    // stereo_top's and stereo_cost's COST parameter (fx_pkg::COST_*), and the HLS kernel's cost
    // switch; kNoHardware: model engines only.
    int hardware_code;
    // The lean memory core (stereo_top RECOMPUTE_COSTS = 1) recomputes it from image rows.
    bool lean_core;
    // A cost of two pixels (not of two windows): the hierarchical search, the quad-camera pairs
    // and every direction of a partner take it.
    bool pixel_pair;
    // The double-precision engine (--engine float) has it.
    bool floating;
    Validation validation;
    // ASW's truncation T when asw::Params::truncation asks for the cost's (asw::truncation_for):
    // 0 = not truncated.
    int asw_truncation;
    std::string_view summary;  // one line for --help, Python and the docs
};

// One line per cost; the columns are CostRow's fields in order (summary on the next line). zncc
// is a window measure along rows, so not a pixel pair; lcdm and zncc keep AD's stage-6 defaults
// (the rule of stereo/defaults.hpp was not run for them).
// clang-format off
inline constexpr std::array<CostRow, 4> kCosts = {{
    //  id             name      hardware     lean   pixel  float  {U, T}  asw_truncation
    {Cost::ad,      "ad",     0,           true,  true,  true,  {6, 0}, 40,
     "absolute differences over RGB (thesis Sec. 3.1)"},
    {Cost::census,  "census", 2,           true,  true,  false, {0, 1}, 0,
     "5x5 census of the luma, Hamming distance x 31 (validated default)"},
    {Cost::lcdm,    "lcdm",   1,           false, true,  false, {6, 0}, 40,
     "hue-saturation distance, colour only (thesis Sec. 3.5)"},
    {Cost::zncc,    "zncc",   kNoHardware, false, false, false, {6, 0}, 40,
     "1 - ZNCC of 15x15 luma windows (use with --window 1 --no-ca)"},
}};
// clang-format on

// The row of `name`; throws std::invalid_argument naming the known costs when there is none.
const CostRow& cost(std::string_view name);
// The row of `id`.
constexpr const CostRow& cost(Cost id) {
    return kCosts[static_cast<std::size_t>(id)];
}
// True when `name` is a cost of the catalogue.
bool is_cost(std::string_view name);

// What a set of costs is asked for by.
enum class CostUse {
    any,         // the 1-D pipeline and ASW on the model engines
    hardware,    // the RTL and HLS engines, stereo cosim
    pixel_pair,  // the hierarchical search, the vertical and diagonal pairs
    floating,    // --engine float
};
bool usable(const CostRow& row, CostUse use);
// The names of the costs usable for `use`, in catalogue order.
std::vector<std::string> cost_names(CostUse use = CostUse::any);
// The names of the costs `keep` accepts (e.g. the lean core's), in catalogue order.
std::vector<std::string> cost_names_if(bool (*keep)(const CostRow&));
// "ad, census and lcdm": the names of cost_names(use) for an error message.
std::string cost_list(CostUse use);
// "ad (absolute differences ...), census (...)": the usable costs with their summaries, for --help.
std::string cost_help(CostUse use = CostUse::any);
// Throws std::invalid_argument ("<what> has the costs ..., not "x"") when `name` is not usable.
void require_cost(std::string_view name, CostUse use, std::string_view what);

// ---- methods -------------------------------------------------------------------------------
enum class Method : unsigned char {
    pipeline,
    edges,
    hierarchical,
    sparse,
    vertical,
    diagonal,
    asw
};

struct MethodRow {
    Method id;
    std::string_view name;
    // Stage 6 as the pipeline's validation options set it (uniqueness, left-right, sub-pixel,
    // reasons, certainty), followed by the speckle filter; the PFM, --reasons and --certainty
    // outputs.
    bool stage6;
    // Its result carries stage 6's full output (MatchResult::validated): the stage-6 methods, and
    // sparse, which runs a stage 6 of its own parameters (sparse::Params).
    bool validated_output;
    bool ca;          // the two CA rules run inside the method's volume
    bool two_d;       // a vertical offset per pixel (MatchResult::vertical)
    bool takes_cost;  // --cost chooses its cost (edges: its own truncated AD)
    CostUse costs;    // which costs it takes
    // Its default cost is the validated census (catalogue::kDefaultCost), else the thesis' AD.
    bool census_default;
    std::string_view summary;
};

// One line per method; the columns are MethodRow's fields in order (summary on the next line).
// clang-format off
inline constexpr std::array<MethodRow, 7> kMethods = {{
    //  id                    name            stage6 validated ca     two_d  takes  costs                census
    {Method::pipeline,     "pipeline",     true,  true,     true,  false, true,  CostUse::any,        true,
     "1-D, rectified pairs: cost, Gaussian window, CA rules, WTA, stage 6 (Sec. 3.1)"},
    {Method::edges,        "edges",        false, false,    false, false, false, CostUse::any,        false,
     "LoG edge front end with truncated AD, no CA (Sec. 4.1.1)"},
    {Method::hierarchical, "hierarchical", true,  true,     true,  true,  true,  CostUse::pixel_pair, true,
     "2-D search over three levels for the vertical field, then a 1-D pass with stage 6, for pairs nobody rectified (Sec. 3.3)"},
    {Method::sparse,       "sparse",       false, true,     false, false, true,  CostUse::any,        false,
     "validated sub-pixel disparities at features (SLAM front end)"},
    {Method::vertical,     "vertical",     true,  true,     true,  false, true,  CostUse::pixel_pair, true,
     "the quad rig's vertical pair, partner below (Sec. 3.2)"},
    {Method::diagonal,     "diagonal",     true,  true,     true,  false, true,  CostUse::pixel_pair, true,
     "the quad rig's diagonal pair, partner below-right (Sec. 3.2)"},
    {Method::asw,          "asw",          true,  true,     false, false, true,  CostUse::any,        true,
     "adaptive support weights (Sec. 3.4)"},
}};
// clang-format on

const MethodRow& method(std::string_view name);  // throws std::invalid_argument when unknown
constexpr const MethodRow& method(Method id) {
    return kMethods[static_cast<std::size_t>(id)];
}
// The names of the methods `keep` accepts (every method when it is null), in catalogue order.
std::vector<std::string> method_names(bool (*keep)(const MethodRow&) = nullptr);
// "pipeline (1-D ...), edges (...), ...": every method with its summary, for --help.
std::string method_help();

// ---- engines -------------------------------------------------------------------------------
// How a method runs. The registry (stereo/matcher.hpp) says which method has which engine; this
// row says which costs the engine computes.
struct EngineRow {
    std::string_view name;
    CostUse costs;
    bool stage6;  // runs stage 6 where the method has it (float: plain winners only)
    std::string_view summary;
};

// clang-format off
inline constexpr std::array<EngineRow, 7> kEngines = {{
    //  name           costs                stage6 summary
    {"model",       CostUse::any,        true,  "the bit-exact golden model"},
    {"fast",        CostUse::any,        true,  "the model's pipeline in row tiles on --threads cores, bit-exact (stereo match's default)"},
    {"naive",       CostUse::any,        true,  "the naive reference (direct sums), for tests"},
    {"float",       CostUse::floating,   false, "double precision, no stage 6"},
    {"hls",         CostUse::hardware,   true,  "the C-simulated HLS kernels"},
    {"rtl",         CostUse::hardware,   true,  "the Verilated RTL (built configurations)"},
    {"full-search", CostUse::pixel_pair, false, "every D x V displacement at full size"},
}};
// clang-format on

const EngineRow& engine(std::string_view name);  // throws std::invalid_argument when unknown
std::vector<std::string> engine_names();
std::string engine_help();  // "model (the bit-exact ...), naive (...), ..."

// "a, b<last_separator>c": names for a message ("a, b and c", "a, b or c").
std::string join(const std::vector<std::string>& names, std::string_view last_separator = ", ");

// ---- defaults ------------------------------------------------------------------------------
// The validated default cost (stereo/defaults.hpp says how it was chosen) and the thesis' cost,
// the default of the methods and engines that do not have census.
inline constexpr Cost kDefaultCost = Cost::census;
inline constexpr Cost kFallbackCost = Cost::ad;
// The engine `stereo match` runs a method on when it has it (the fast CPU engine of the
// pipeline, stereo/fast_engine.hpp), else the reference engine every method has.
inline constexpr std::string_view kDefaultEngine = "fast";
inline constexpr std::string_view kReferenceEngine = "model";

// The default cost of `method` on `engine`: census where the method defaults to it and the
// engine has it, else AD.
std::string_view default_cost(std::string_view method, std::string_view engine);

}  // namespace stereo::catalogue
