// The Verilated stereo_hier_top (the hierarchical search's whole streaming core, issue 45;
// docs/hierarchical.md "The whole core") behind a small interface, the host's loop around it
// (stereo::hierarchical::PlaneTracker reads each frame's statistics registers and writes the next
// frame's plane), and what the model says each frame computes: the pass along the frame's setting
// (hier_pass_expected) and match_frame's statistics. Used by `stereo cosim --method
// hierarchical`, `stereo match --method hierarchical --engine rtl` and tb_stereo_hier_top.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hier_pass_sim.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_plane.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::sim {

// A Verilated configuration's parameters (stage_table.hpp): its pass is stereo_hier_pass at
// these limits, its levels have D = ndisp, V = v_max - v_min + 1 and fixed windows.
struct HierTopLimits : HierPassLimits {
    std::array<int, hierarchical::kLevels> level_windows = {9, 15, 15};
    std::string_view config = "Vstereo_hier_top";
};
// Vstereo_hier_top, always built: stereo_hier_top's defaults (64x48, D = V = 16, pass 5x5).
inline constexpr HierTopLimits kHierTopLimits{};
// Vstereo_hier_top_full (-DSTEREO_COSIM_CONFIGS=hier_top_full): 640x480, D = 64, V = 16, the lean
// census pass 11x11.
inline constexpr HierTopLimits kHierTopFullLimits{
    {640, 480, 64, 11, -8, 7}, {9, 15, 15}, "Vstereo_hier_top_full"};
// The configurations this library was built with, smallest first.
std::vector<HierTopLimits> hier_top_configs();

// Throws std::invalid_argument (one line naming the limit) unless a built core can run the
// search `params`: census, its D and V = 16, the levels' windows 9 / 15 / 15, a pass window up
// to its own, CA rule 1 along d only; with a size also the pair within the configuration and
// hierarchical::validate. The sized form returns the smallest configuration that holds the pair.
void check_hier_top(const hierarchical::Params& params);
HierTopLimits check_hier_top(const hierarchical::Params& params, int width, int height);

class HierTopSim {
  public:
    // What the host does with a frame's statistics (read at out_done): the setting it writes
    // and commits for the next frame.
    using Host = std::function<hierarchical::PlaneSetting(const hierarchical::PlaneStatistics&)>;

    explicit HierTopSim(const HierTopLimits& limits = kHierTopLimits);
    ~HierTopSim();
    HierTopSim(const HierTopSim&) = delete;
    HierTopSim& operator=(const HierTopSim&) = delete;

    void reset();
    // Every configuration port (cfg_wait_plane = 1: each frame waits for the host's plane) and
    // the first frame's setting.
    void configure(int width, int height, const hierarchical::Params& params,
                   const hierarchical::PlaneSetting& setting);
    // Called at every out_done while streaming or waiting; none: the statistics are not read and
    // no plane is committed.
    void set_host(Host host);
    // Streams `beats` under `traffic` until `expected_outputs` output beats arrived or
    // `max_cycles` passed.
    StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                        const Traffic& traffic, std::uint64_t max_cycles);
    // Clocks with no input until the host has had `count` frames' statistics since construction
    // (the pass's last beat can leave before the levels' last winner), at most `max_clocks`;
    // returns the clocks run.
    std::uint64_t wait_for_statistics(std::size_t count, std::uint64_t max_clocks);
    std::size_t statistics_read() const { return statistics_read_; }

    struct Model;  // one Verilated configuration behind the interface (hier_top_sim.cpp)

  private:
    void serve_host();

    HierTopLimits limits_;
    std::unique_ptr<Model> model_;
    Host host_;
    std::size_t statistics_read_ = 0;
};

// One frame of a run: the setting it ran with, its output in the model's form, its statistics
// registers and the setting the host wrote after them.
struct HierTopFrame {
    hierarchical::PlaneSetting setting;
    HierPassOutput output;
    hierarchical::PlaneStatistics statistics;
    hierarchical::PlaneSetting next;
    std::uint64_t cycles = 0;  // from its first accepted beat to its last output beat
};

struct HierTopRunOptions {
    int frames = 1;
    Traffic traffic;       // frame f streams under seed traffic.seed + f
    int reset_at = -1;     // >= 0: before every frame, this many of its beats, then a reset
    int stray_start = -1;  // >= 0: this beat of the first frame carries tuser too
    // Ends the run after a frame when it returns true (the frame is kept).
    std::function<bool(const HierTopFrame&)> stop_after;
};

struct HierTopRun {
    std::vector<HierTopFrame> frames;
    std::uint64_t total_clocks = 0;  // the streams' cycles, the resets' and the waits
    unsigned status = 0;             // the pass's sticky status bits at the end
};

// Streams the pair `options.frames` times (a steady rig) through a fresh core configured for
// `params` (the smallest built configuration that holds the pair), with the host's PlaneTracker in
// the loop: after each frame's statistics it writes the next setting. A mid-frame reset (reset_at)
// abandons that part-frame: it has no statistics and counts as no frame; the host keeps its
// tracker, and the whole frame after the reset runs with the setting the part-frame had. Throws
// std::runtime_error when the core stalls, breaks the AXI4-Stream rules or gives no statistics for
// a frame.
HierTopRun run_hier_top(const Image& left, const Image& right, const hierarchical::Params& params,
                        const HierTopRunOptions& options);

// The model's frames of the same steady rig: frame t's setting from the model's own tracker, the
// pass along it (hier_pass_expected) and match_frame's statistics.
struct HierTopExpected {
    hierarchical::PlaneSetting setting;
    HierPassOutput output;
    hierarchical::PlaneStatistics statistics;
};
std::vector<HierTopExpected> hier_top_expected(const Image& left, const Image& right,
                                               const hierarchical::Params& params, int frames);

// The pixels (raster indices) whose fixed disparity, reason, certainty or vertical offset differ.
std::vector<std::size_t> differing_pixels(const HierPassOutput& rtl, const HierPassOutput& model);

}  // namespace stereo::sim
