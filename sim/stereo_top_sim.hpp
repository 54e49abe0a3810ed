// Co-simulation of the Verilated stereo_top: AXI4-Stream drivers with seeded random input gaps
// and output stalls, frame assembly, and the checks of the output protocol. Used by the
// testbenches (testbench/) and by `stereo cosim`.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "stereo/asw.hpp"
#include "stereo/image.hpp"
#include "stereo/matcher.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"

namespace stereo::sim {

// A Verilated configuration of stereo_top: the synthesis parameters it was built with.
struct TopConfig {
    std::string name;
    int width;         // largest frame width
    int height;        // largest frame height
    int ndisp;         // largest cfg_ndisp
    int window;        // largest window
    int max_min_disp;  // largest |cfg_min_disp| (MAX_MIN_DISP)
    int lanes;         // labels computed per clock (LANES): NDISP / lanes clocks per pixel step
    int cost = table::kCostAd;  // COST: table::kCostAd, kCostLcdm or kCostCensus
    // ASW = 1: adaptive support weights of diameter `window` (stereo::asw::match, separable)
    // instead of the Gaussian aggregation and the CA rules.
    bool asw = false;
    // FST tracing compiled in (sim/CMakeLists.txt STEREO_TRACE_CONFIGS): only then does
    // trace_to() work. Cores built on demand trace when asked.
    bool traced = true;
};

// The configurations built into this binary, smallest first.
const std::vector<TopConfig>& built_top_configs();

// stereo_top with the LCDM cost stage (COST = 1) at the small configuration's size; not one of
// built_top_configs(), which all have the AD cost.
const TopConfig& lcdm_top_config();

// The same with time-multiplexed lanes (LANES = 4): "lcdm-lanes4". Not among
// built_top_configs(), lanes_top_configs() or fpga_top_configs().
const TopConfig& lcdm_lanes_top_config();

// stereo_top with the census cost (COST = 2, stereo_census in front of the cost stage) at the
// small configuration's size: "small-census"; and with LANES = 4: "census-lanes4".
const TopConfig& census_top_config();
const TopConfig& census_lanes_top_config();
// The census core in the lean memory architecture (stereo_top RECOMPUTE_COSTS = 1: rows of census
// codes, every label's vertical window recomputed; docs/rtl.md "Lean memory") at the small size:
// "census-recompute" (all labels per clock) and "census-recompute-lanes4" (LANES = 4).
const std::vector<TopConfig>& census_recompute_top_configs();

// stereo_top with time-multiplexed lanes (LANES < NDISP), AD cost: "lanes4" (16 labels, 4 per
// clock), "lanes1" (16, 1), "ndisp8-lanes2" (8, 2), "ndisp2-lanes1" (2, 1), the one-label
// core "ndisp1", and "lean-lanes4" (16, 4, in the lean memory architecture, RECOMPUTE_COSTS = 1).
// Not among built_top_configs().
const std::vector<TopConfig>& lanes_top_configs();
// The FPGA builds (stereo_synth_top: constant default kernel, MAX_MIN_DISP = 0) that
// tb_stereo_synth_top co-simulates: "ice40-ndisp1", "ice40-ndisp4-lanes1".
const std::vector<TopConfig>& fpga_top_configs();

// The adaptive-support-weight cores (ASW = 1, docs/asw.md): "asw-census" (diameter 5, all labels
// per clock), "asw-census-lanes4" (4 per clock) and "asw-ad-lanes4" (the AD cost, diameter 31).
// Not among the other lists.
const std::vector<TopConfig>& asw_top_configs();
// The built ASW core that runs `weights` (the separable variant with the default responses) on a
// width x height pair with `params` (cost, ndisp, min_disp): one of the pair's cost whose
// diameter is weights.diameter and which covers the rest, the most labels per clock first.
// Throws std::invalid_argument naming what the hardware cannot do, or the built cores.
const TopConfig& asw_top_config(int width, int height, const MatchParams& params,
                                const asw::Params& weights);

// Any built stereo_top configuration by name (small, small-lcdm, lcdm-lanes4, small-census,
// census-lanes4, full, the lanes and
// FPGA ones); throws std::invalid_argument for an unknown name.
const TopConfig& top_config_named(const std::string& name);
// Every built configuration, of every cost and family.
std::vector<const TopConfig*> all_top_configs();

// The largest built configuration of a hardware cost (ad: the last of built_top_configs(), lcdm:
// lcdm_top_config(), census: census_top_config()), for error messages; throws
// std::invalid_argument for a cost without hardware (stereo/catalogue.hpp).
const TopConfig& largest_config(const std::string& cost);
// The smallest built configuration with the cost `cost` ("ad": built_top_configs(), "lcdm":
// lcdm_top_config(), "census": census_top_config()) that covers a request; nullptr when none does.
const TopConfig* covering_config(int width, int height, int ndisp, int window, int min_disp = 0,
                                 const std::string& cost = "ad");

// Traffic shaping: each cycle the input is withheld with probability `input_gap` and the
// output is not ready with probability `output_stall`, from a generator seeded with `seed`.
struct Traffic {
    double input_gap = 0.0;
    double output_stall = 0.0;
    std::uint32_t seed = 1;
};

struct InputBeat {
    std::uint64_t data;  // {right RGB, left RGB}
    bool last;
    bool user;
};

struct OutputBeat {
    // fx_pkg::out_beat_t: {certainty, 0, reason, fixed} (stage_table.hpp); stereo_hier_pass puts
    // the vertical offset above it (bits 39:32).
    std::uint64_t data;
    bool last;
    bool user;
};

// The beats of one frame: raster order, tuser on the first, tlast at each row end.
std::vector<InputBeat> frame_beats(const Image& left, const Image& right);

struct StreamResult {
    std::vector<OutputBeat> outputs;
    std::uint64_t cycles = 0;       // clock cycles from the first input beat to the last output
    std::uint64_t input_beats = 0;  // accepted
    unsigned status = 0;            // the core's sticky status bits at the end
    bool completed = false;         // all expected outputs arrived within the cycle limit
    std::string protocol_error;     // empty, or the first AXI4-Stream rule the core broke
};

// Frame and pipeline configuration, applied to the cfg_* ports.
struct CoreParams {
    int width = 0;
    int height = 0;
    MatchParams match;
};

// The cfg_* port values of stereo_top for a frame (port_values()): what set_params() drives,
// also sent to a co-simulation runner built on demand (cosim_protocol.hpp).
struct PortValues {
    std::uint16_t width = 0;
    std::uint16_t height = 0;
    std::uint16_t ndisp = 0;
    std::uint16_t min_disp = 0;  // two's complement in table::kCfgMinDispBits
    std::uint8_t use_ca = 0;
    std::uint8_t uniqueness_en = 0;
    std::uint8_t uniqueness = 0;
    std::uint8_t lr_en = 0;
    std::uint8_t lr_tolerance = 0;
    std::uint8_t subpixel_en = 0;
    std::uint8_t radius = 0;           // cfg_radius: the window's radius
    std::vector<std::int32_t> kernel;  // cfg_kernel: the model's taps centred in config.window
};
// Throws std::invalid_argument when the window exceeds the configuration's.
PortValues port_values(const TopConfig& config, const CoreParams& params);

class TopSim {
  public:
    virtual ~TopSim() = default;
    virtual const TopConfig& config() const = 0;
    // Holds reset for two cycles (inputs idle).
    virtual void reset() = 0;
    virtual void set_params(const CoreParams& params) = 0;
    // Streams `beats` (possibly several frames back to back) and collects `expected_outputs`
    // output beats, or stops after `max_cycles`.
    virtual StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                                const Traffic& traffic, std::uint64_t max_cycles) = 0;
    // Starts writing an FST waveform of everything that follows; check_trace_path(path) first.
    virtual void trace_to(const std::string& path) = 0;
};

// Throws std::invalid_argument unless `path` ends in .fst (any case): the models are verilated
// with FST tracing only (Verilator builds one trace format into a model), so a .vcd or any other
// name is refused instead of silently receiving FST bytes. docs/gtkwave.md: fst2vcd converts.
void check_trace_path(const std::string& path);

std::unique_ptr<TopSim> make_top_sim(const TopConfig& config);

// Output beats of one frame back into the validated result (fixed, reason, certainty of every
// pixel); throws std::runtime_error naming the first beat whose tuser/tlast framing is wrong.
ValidatedDisparity assemble_validated(const std::vector<OutputBeat>& beats, std::size_t first,
                                      int width, int height);
// Its 8-bit view, stereo::to_label_map(assemble_validated(...)).
DisparityMap assemble_frame(const std::vector<OutputBeat>& beats, std::size_t first, int width,
                            int height);

// The cfg_kernel taps for `params` in a core of `window` taps: the model's kernel, centred.
std::vector<std::int32_t> centred_kernel(const MatchParams& params, int window);

// Registers method "pipeline", engine "rtl" (rtl_matcher.cpp).
void register_matchers(MatcherRegistry& registry);

}  // namespace stereo::sim
