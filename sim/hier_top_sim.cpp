// The Verilated stereo_hier_top behind HierTopSim, and the host's loop (hier_top_sim.hpp).
#include "hier_top_sim.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_hier_top.h"
#include "axis_driver.hpp"
#include "hier_pass_ports.hpp"
#include "port_bits.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "verilated_harness.hpp"

namespace stereo::sim {
namespace {

namespace h = hierarchical;

template <class Port>
void put_kernel(Port& port, const h::LevelParams& level) {
    const auto taps = gaussian_kernel(level.window, level.sigma);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        put_bits(port, static_cast<int>(i) * table::kTapBits, table::kTapBits,
                 static_cast<std::uint64_t>(taps[i]));
    }
}

void put_setting(Vstereo_hier_top& m, const h::PlaneSetting& setting) {
    put_plane(m, setting.plane);
    m.tolerance = static_cast<std::uint32_t>(setting.tolerance);
}

h::PlaneStatistics read_statistics(Vstereo_hier_top& core) {
    h::PlaneStatistics s;
    s.count = static_cast<std::int64_t>(core.out_count);
    s.sum_x = static_cast<std::int64_t>(core.out_sum_x);
    s.sum_y = static_cast<std::int64_t>(core.out_sum_y);
    s.sum_xx = static_cast<std::int64_t>(core.out_sum_xx);
    s.sum_xy = static_cast<std::int64_t>(core.out_sum_xy);
    s.sum_yy = static_cast<std::int64_t>(core.out_sum_yy);
    s.sum_v = static_cast<std::int64_t>(core.out_sum_v);
    s.sum_xv = static_cast<std::int64_t>(core.out_sum_xv);
    s.sum_yv = static_cast<std::int64_t>(core.out_sum_yv);
    s.v_min = kHierTopLimits.v_min;
    for (int bin = 0; bin <= kHierTopLimits.v_max - kHierTopLimits.v_min; ++bin) {
        core.hist_index = static_cast<std::uint8_t>(bin);
        core.eval();
        s.histogram.push_back(static_cast<std::int64_t>(core.hist_count));
    }
    return s;
}

std::string pixels(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

}  // namespace

void check_hier_top(const h::Params& params) {
    constexpr HierTopLimits limits = kHierTopLimits;
    const std::string core = "the built stereo_hier_top (Vstereo_hier_top) ";
    const std::string_view census = catalogue::cost(catalogue::Cost::census).name;
    if (params.cost != census) {
        throw std::invalid_argument(core + "has the " + std::string(census) + " cost only, not " +
                                    params.cost);
    }
    // The pass takes fewer labels at run time, but the levels' horizontal range is the build's.
    if (params.ndisp != limits.ndisp) {
        throw std::invalid_argument(core + "searches D = " + std::to_string(limits.ndisp) +
                                    " labels (its levels' range is built in), not " +
                                    std::to_string(params.ndisp));
    }
    const int vrange = limits.v_max - limits.v_min + 1;
    if (params.vertical_range() != vrange) {
        throw std::invalid_argument(core + "searches V = " + std::to_string(vrange) +
                                    " vertical labels, not " +
                                    std::to_string(params.vertical_range()));
    }
    for (std::size_t l = 0; l < params.levels.size(); ++l) {
        if (params.levels[l].window != limits.level_windows[l]) {
            throw std::invalid_argument(core + "has level windows " +
                                        std::to_string(limits.level_windows[0]) + " / " +
                                        std::to_string(limits.level_windows[1]) + " / " +
                                        std::to_string(limits.level_windows[2]) + ", not " +
                                        std::to_string(params.levels[l].window) + " at the " +
                                        h::kLevelNames[l] + " level");
        }
    }
    if (params.field_level.window > limits.window) {
        throw std::invalid_argument(core + "has a pass window of at most " +
                                    std::to_string(limits.window) + ", not " +
                                    std::to_string(params.field_level.window));
    }
    if (params.neighbours != h::CaNeighbours::horizontal) {
        throw std::invalid_argument(core + "applies CA rule 1 along d only (horizontal)");
    }
}

void check_hier_top(const h::Params& params, int width, int height) {
    check_hier_top(params);
    constexpr HierTopLimits limits = kHierTopLimits;
    const std::string core = "the built stereo_hier_top (Vstereo_hier_top) ";
    if (width > limits.width || height > limits.height) {
        throw std::invalid_argument(core + "holds " + pixels(limits.width, limits.height) +
                                    ", the pair is " + pixels(width, height) +
                                    " (shrink it: --downscale, or cosim's --crop)");
    }
    h::validate(params, width, height);
}

struct HierTopSim::Model {
    VerilatedHarness<Vstereo_hier_top> harness{"hier_top"};
};

HierTopSim::HierTopSim() : model_(std::make_unique<Model>()) {
    reset();
}
HierTopSim::~HierTopSim() = default;

void HierTopSim::reset() {
    model_->harness.model().plane_commit = 0;
    reset_axis_core(model_->harness);
}

void HierTopSim::configure(int width, int height, const h::Params& params,
                           const h::PlaneSetting& setting) {
    check_hier_top(params, width, height);
    Vstereo_hier_top& m = model_->harness.model();
    put_pass_config(m, width, height, params, kHierTopLimits.window);
    put_kernel(m.cfg_kernel_q, params.levels[0]);
    put_kernel(m.cfg_kernel_h, params.levels[1]);
    put_kernel(m.cfg_kernel_f, params.levels[2]);
    m.cfg_wait_plane = 1;
    put_setting(m, setting);
}

void HierTopSim::set_host(Host host) {
    host_ = std::move(host);
}

void HierTopSim::serve_host() {
    // After every edge: the host's commit lasts one clock; at out_done it reads the registers
    // and writes the next setting.
    Vstereo_hier_top& core = model_->harness.model();
    core.plane_commit = 0;
    if (core.out_done == 0 || !host_) {
        return;
    }
    const h::PlaneSetting next = host_(read_statistics(core));
    ++statistics_read_;
    put_setting(core, next);
    core.plane_commit = 1;
}

StreamResult HierTopSim::stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                                const Traffic& traffic, std::uint64_t max_cycles) {
    return stream_axis(model_->harness, beats, expected_outputs, traffic, max_cycles,
                       [this](const Vstereo_hier_top&) { serve_host(); });
}

std::uint64_t HierTopSim::wait_for_statistics(std::size_t count, std::uint64_t max_clocks) {
    Vstereo_hier_top& m = model_->harness.model();
    m.s_axis_tvalid = 0;
    m.m_axis_tready = 1;
    std::uint64_t clocks = 0;
    for (; clocks < max_clocks && statistics_read_ < count; ++clocks) {
        model_->harness.tick();
        serve_host();
    }
    return clocks;
}

HierTopRun run_hier_top(const Image& left, const Image& right, const h::Params& params,
                        const HierTopRunOptions& options) {
    const int width = left.width;
    const int height = left.height;
    const std::size_t pixels_per_frame = static_cast<std::size_t>(width) * height;
    const auto beats = frame_beats(left, right);
    if (options.reset_at >= static_cast<int>(beats.size()) ||
        options.stray_start >= static_cast<int>(beats.size())) {
        throw std::invalid_argument("--reset-at must be below the frame's " +
                                    std::to_string(beats.size()) + " beats");
    }
    HierTopSim core;
    h::PlaneTracker tracker;
    core.configure(width, height, params, tracker.setting());
    // Frame t runs with settings[t]: the core waits for the host's commit after each frame.
    std::vector<h::PlaneSetting> settings{tracker.setting()};
    std::vector<h::PlaneStatistics> statistics;
    core.set_host([&](const h::PlaneStatistics& frame) {
        statistics.push_back(frame);
        tracker.update(frame);
        settings.push_back(tracker.setting());
        return tracker.setting();
    });
    HierTopRun run;
    std::vector<StreamResult> streams;
    // The pass's last beat can leave before the levels' last winner: a frame's statistics come
    // during the next frame's stream (whose beats wait for the commit) or in a wait.
    constexpr std::uint64_t kStatisticsClocks = 100000;
    const auto wait_for = [&](std::size_t frames) {
        run.total_clocks += core.wait_for_statistics(frames, kStatisticsClocks);
        if (core.statistics_read() < frames) {
            throw std::runtime_error("the core gave no statistics for frame " +
                                     std::to_string(frames - 1));
        }
    };
    const auto finish_frames = [&] {
        for (std::size_t f = run.frames.size(); f < streams.size(); ++f) {
            run.frames.push_back({settings[f],
                                  hier_pass_assemble(streams[f].outputs, 0, width, height),
                                  statistics[f], settings[f + 1], streams[f].cycles});
        }
    };
    const bool wait_each_frame = options.reset_at >= 0 || static_cast<bool>(options.stop_after);
    for (int frame = 0; frame < options.frames; ++frame) {
        const Traffic traffic{options.traffic.input_gap, options.traffic.output_stall,
                              options.traffic.seed + static_cast<std::uint32_t>(frame)};
        if (options.reset_at >= 0) {
            const std::vector<InputBeat> part(beats.begin(), beats.begin() + options.reset_at);
            // Stop once a quarter of them came out (or the cycle budget ends): the reset then
            // lands with beats still inside the core. --reset-at 0: a reset before any beat.
            if (!part.empty()) {
                run.total_clocks += core.stream(part, std::max<std::size_t>(1, part.size() / 4),
                                                traffic, 10 * part.size() + 10000)
                                        .cycles;
            }
            core.reset();
            core.configure(width, height, params, tracker.setting());
        }
        std::vector<InputBeat> frame_input = beats;
        if (frame == 0 && options.stray_start >= 0) {
            frame_input[static_cast<std::size_t>(options.stray_start)].user = true;
        }
        StreamResult result =
            core.stream(frame_input, pixels_per_frame, traffic, 100 * pixels_per_frame + 100000);
        run.total_clocks += result.cycles;
        run.status = result.status;
        if (!result.completed) {
            throw std::runtime_error("the core stalled in frame " + std::to_string(frame) + ": " +
                                     std::to_string(result.outputs.size()) + " of " +
                                     std::to_string(pixels_per_frame) + " outputs arrived");
        }
        if (!result.protocol_error.empty()) {
            throw std::runtime_error("AXI4-Stream protocol error in frame " +
                                     std::to_string(frame) + ": " + result.protocol_error);
        }
        streams.push_back(std::move(result));
        if (wait_each_frame) {
            wait_for(streams.size());
            finish_frames();
            if (options.stop_after && options.stop_after(run.frames.back())) {
                return run;
            }
        }
    }
    wait_for(streams.size());
    finish_frames();
    return run;
}

std::vector<HierTopExpected> hier_top_expected(const Image& left, const Image& right,
                                               const h::Params& params, int frames) {
    h::PlaneTracker host;
    std::vector<HierTopExpected> expected;
    for (int f = 0; f < frames; ++f) {
        const h::PlaneSetting setting = host.setting();
        h::FrameResult frame = h::match_frame(left, right, params, setting);
        expected.push_back({setting, hier_pass_expected(left, right, setting.plane, params),
                            std::move(frame.statistics)});
        host.update(expected.back().statistics);
    }
    return expected;
}

std::vector<std::size_t> differing_pixels(const HierPassOutput& rtl, const HierPassOutput& model) {
    std::vector<std::size_t> differing;
    const ValidatedDisparity& got = rtl.validated;
    const ValidatedDisparity& want = model.validated;
    for (std::size_t p = 0; p < model.vertical.size(); ++p) {
        if (got.fixed[p] != want.fixed[p] || got.reason[p] != want.reason[p] ||
            got.certainty[p] != want.certainty[p] || rtl.vertical[p] != model.vertical[p]) {
            differing.push_back(p);
        }
    }
    return differing;
}

}  // namespace stereo::sim
