// The options of `stereo cosim`, registered by the same function in a build with the RTL
// (cli_cosim.cpp) and without it (cli_cosim_absent.cpp): the command line parses alike in both,
// and the CLI fuzz harness (built without the RTL) covers them.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "cli_matcher_options.hpp"
#include "stereo/catalogue.hpp"
#include "stereo_io/io.hpp"

namespace stereo::cli {

// The pair and the matching options of a core: LEFT, RIGHT, the matcher options (stage 6, the
// hardware costs), --downscale and --crop; `stereo cosim` and `stereo vectors` share them.
struct CorePairOptions {
    std::string left;
    std::string right;
    MatcherOptions matcher;
    int downscale = 1;
    std::string crop;  // WxH+X+Y
};
void add_core_pair_options(CLI::App& command, CorePairOptions& options);
// The pair as the options ask: loaded, shrunk by --downscale, cropped by --crop (a bad geometry
// is a std::invalid_argument).
io::ImagePair load_core_pair(const CorePairOptions& options);

struct CosimOptions : CorePairOptions {
    // pipeline: stereo_top; hierarchical: the hierarchical search's whole core (stereo_hier_top)
    std::string method{catalogue::method(catalogue::Method::pipeline).name};
    std::uint32_t seed = 1;
    double stall = 0.0;  // probability that m_axis_tready is low in a cycle
    double gap = 0.0;    // probability that s_axis_tvalid is withheld in a cycle
    std::string output;  // the RTL's disparity PNG
    std::string trace;   // FST waveform
    bool json = false;
    int frames = 0;     // frames streamed, traffic seed + f for frame f; 0: the method's default
    int reset_at = -1;  // before every frame: this many beats of it, then a mid-frame reset
    // A core built on demand (sim/on_demand.hpp) instead of a configuration of this build:
    std::string size;       // WxH: the core's WIDTH x HEIGHT; given = on demand
    int lanes = 0;          // LANES (0: NDISP)
    int max_min_disp = -1;  // MAX_MIN_DISP (-1: 8, or |--min-disp| when larger)
    bool lean = false;      // RECOMPUTE_COSTS = 1
    std::string cache;      // the runners' folder (empty: sim::default_cache_folder())
    int sim_threads = 1;    // Verilator --threads of an on-demand core
    std::string diff;       // PNG: where RTL and model differ in the first mismatching frame
};

// --frames by default: one for stereo_top; for the hierarchical core enough for the host's
// tracker to settle on a steady rig (the start frame, the mode's, the fits).
inline constexpr int kPipelineFrames = 1;
inline constexpr int kHierarchicalFrames = 5;

// LEFT, RIGHT, the matcher options with stage 6 (ndisp 16 and window 5 by default: the smallest
// Verilated configuration covers them) and the co-simulation's own options.
void add_cosim_options(CLI::App& command, CosimOptions& options);

}  // namespace stereo::cli
