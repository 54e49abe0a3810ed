// Co-simulation of any stereo_top configuration on demand: the first request of a configuration
// Verilates it, with a small runner (cosim_runner_main.cpp), into a cache folder; later requests
// reuse the runner. `stereo cosim --size` (app/src/cli_cosim.cpp) and Python's stereo.cosim(...,
// size=) use it; docs/gtkwave.md "Any configuration on demand".
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "stereo_top_sim.hpp"

namespace stereo::sim {

// stereo_top's synthesis parameters for one core.
struct CoreRequest {
    int width = 0;
    int height = 0;
    int ndisp = 0;
    int window = 0;
    std::string cost = "ad";  // ad, lcdm or census
    int lanes = 0;            // 0: NDISP (every label in one clock)
    int max_min_disp = 8;     // largest |cfg_min_disp|
    bool lean = false;        // RECOMPUTE_COSTS = 1 (ad and census only)
    // A probe build: the stage outputs readable (Verilator --public-flat-rw) for probe_stages();
    // needs LANES = NDISP. A separate cache entry from the plain runner.
    bool probes = false;
    bool trace = false;  // FST tracing compiled in (only then can the runner write a trace)
    int threads = 1;     // Verilator --threads of the model (1..kMaxCoreThreads)
};

// Limits of a request (the cache keeps one runner per configuration; these bound its size).
inline constexpr int kMaxCoreSide = 4096;
inline constexpr int kMaxCoreNdisp = 256;
inline constexpr int kMaxCoreMinDisp = 1024;
inline constexpr int kMaxCoreThreads = 16;

// Throws std::invalid_argument naming the first impossible parameter.
void check_request(const CoreRequest& request);

// Throws std::invalid_argument unless a pair of width x height with minimum disparity
// `min_disp` can stream through the core of `request` (the frame within its size, |min_disp|
// within its MAX_MIN_DISP).
void check_fits(const CoreRequest& request, int width, int height, int min_disp);

// The configuration a request builds (its name starts with "on-demand").
TopConfig on_demand_config(const CoreRequest& request);

// $STEREO_COSIM_CACHE, else $XDG_CACHE_HOME/stereo/cosim, else ~/.cache/stereo/cosim.
std::filesystem::path default_cache_folder();

// The runner of `request` in `cache`, built first (a progress line on `progress`) when the cache
// does not hold it. The build goes to a hidden folder renamed into place when complete, so a
// failed or interrupted build leaves nothing a later run would use; it throws std::runtime_error
// with the failing step (Verilator absent, the cache not writable, the build failing).
// $STEREO_VERILATOR names the verilator program (default: verilator on the PATH).
// $STEREO_COSIM_DEFINES (macro names, space-separated) are defined for the RTL: the test hooks
// STEREO_TEST_BREAK_RULE1_ROUNDING / _RULE2_ROUNDING of stereo_ca_plane break one stage on
// purpose (tests of the localisation); they are part of the cache key.
std::filesystem::path ensure_runner(const CoreRequest& request, const std::filesystem::path& cache,
                                    std::ostream& progress);

// What the probed stages gave the watched pixels: the probe build of `request` streams `beats`
// (one frame, configured by `params`) without stalls. Throws std::invalid_argument unless
// LANES = NDISP.
struct PixelStages {
    int x = 0;
    int y = 0;
    std::vector<bool> seen;                          // per probed stage
    std::vector<std::vector<std::uint16_t>> values;  // per probed stage, per label
};
std::vector<std::string> probed_stages();  // aggregate, ca_rule1, ca_rule2
std::vector<PixelStages> probe_stages(CoreRequest request, const std::filesystem::path& cache,
                                      const CoreParams& params, const std::vector<InputBeat>& beats,
                                      const std::vector<std::pair<int, int>>& pixels,
                                      std::ostream& progress);

// A TopSim that drives a runner process (ensure_runner's path) over pipes.
std::unique_ptr<TopSim> make_runner_sim(const TopConfig& config,
                                        const std::filesystem::path& runner);

}  // namespace stereo::sim
