// The Verilated stereo_hier_top behind HierTopSim, and the host's loop (hier_top_sim.hpp).
#include "hier_top_sim.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_hier_top.h"
#ifdef STEREO_COSIM_FULL_HIER
#include "Vstereo_hier_top_full.h"
#endif
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

template <class Core>
void put_setting(Core& m, const h::PlaneSetting& setting) {
    put_plane(m, setting.plane);
    m.tolerance = static_cast<std::uint32_t>(setting.tolerance);
}

template <class Core>
h::PlaneStatistics read_statistics(Core& core, const HierTopLimits& limits) {
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
    s.v_min = limits.v_min;
    for (int bin = 0; bin <= limits.v_max - limits.v_min; ++bin) {
        core.hist_index = static_cast<std::uint8_t>(bin);
        core.eval();
        s.histogram.push_back(static_cast<std::int64_t>(core.hist_count));
    }
    return s;
}

std::string pixels(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// The search checks of one configuration (no size).
void check_config(const h::Params& params, const HierTopLimits& limits) {
    const std::string core = "the built stereo_hier_top (" + std::string(limits.config) + ") ";
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

// The size checks of one configuration.
void check_size(const h::Params& params, int width, int height, const HierTopLimits& limits) {
    check_config(params, limits);
    const std::string core = "the built stereo_hier_top (" + std::string(limits.config) + ") ";
    if (width > limits.width || height > limits.height) {
        throw std::invalid_argument(core + "holds " + pixels(limits.width, limits.height) +
                                    ", the pair is " + pixels(width, height) +
                                    " (shrink it: --downscale, or cosim's --crop)");
    }
}

// The first configuration `accepts` takes; none: the error of the last one tried.
template <class Check>
HierTopLimits first_accepting(const Check& accepts) {
    const std::vector<HierTopLimits> configs = hier_top_configs();
    std::string error;
    for (const HierTopLimits& limits : configs) {
        try {
            accepts(limits);
            return limits;
        } catch (const std::invalid_argument& refused) {
            // The largest configuration's reason is the one worth reading.
            error = refused.what();
        }
    }
    throw std::invalid_argument(error);
}

}  // namespace

std::vector<HierTopLimits> hier_top_configs() {
    std::vector<HierTopLimits> configs{kHierTopLimits};
#ifdef STEREO_COSIM_FULL_HIER
    configs.push_back(kHierTopFullLimits);
#endif
    return configs;
}

void check_hier_top(const h::Params& params) {
    first_accepting([&params](const HierTopLimits& limits) { check_config(params, limits); });
}

HierTopLimits check_hier_top(const h::Params& params, int width, int height) {
    const HierTopLimits limits = first_accepting(
        [&](const HierTopLimits& candidate) { check_size(params, width, height, candidate); });
    h::validate(params, width, height);
    return limits;
}

// One Verilated configuration behind HierTopSim: the ports it touches, for any of them.
struct HierTopSim::Model {
    virtual ~Model() = default;
    virtual void reset() = 0;
    virtual void configure(int width, int height, const h::Params& params,
                           const h::PlaneSetting& setting) = 0;
    // After every edge: the host's commit lasts one clock; at out_done `host` reads the
    // statistics and its setting is written and committed. Returns whether it was called.
    virtual bool serve(const Host& host) = 0;
    virtual StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                                const Traffic& traffic, std::uint64_t max_cycles,
                                const std::function<void()>& after_edge) = 0;
    virtual void idle_tick() = 0;  // no input, the output taken
};

namespace {

template <class Core>
class CoreModel final : public HierTopSim::Model {
  public:
    explicit CoreModel(const HierTopLimits& limits) : limits_(limits) {}

    void reset() override {
        harness_.model().plane_commit = 0;
        reset_axis_core(harness_);
    }
    void configure(int width, int height, const h::Params& params,
                   const h::PlaneSetting& setting) override {
        Core& m = harness_.model();
        put_pass_config(m, width, height, params, limits_.window);
        put_kernel(m.cfg_kernel_q, params.levels[0]);
        put_kernel(m.cfg_kernel_h, params.levels[1]);
        put_kernel(m.cfg_kernel_f, params.levels[2]);
        m.cfg_wait_plane = 1;
        put_setting(m, setting);
    }
    bool serve(const HierTopSim::Host& host) override {
        Core& core = harness_.model();
        core.plane_commit = 0;
        if (core.out_done == 0 || !host) {
            return false;
        }
        put_setting(core, host(read_statistics(core, limits_)));
        core.plane_commit = 1;
        return true;
    }
    StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                        const Traffic& traffic, std::uint64_t max_cycles,
                        const std::function<void()>& after_edge) override {
        return stream_axis(harness_, beats, expected_outputs, traffic, max_cycles,
                           [&after_edge](const Core&) { after_edge(); });
    }
    void idle_tick() override {
        Core& m = harness_.model();
        m.s_axis_tvalid = 0;
        m.m_axis_tready = 1;
        harness_.tick();
    }

  private:
    HierTopLimits limits_;
    VerilatedHarness<Core> harness_{"hier_top"};
};

std::unique_ptr<HierTopSim::Model> make_model(const HierTopLimits& limits) {
    if (limits.config == kHierTopLimits.config) {
        return std::make_unique<CoreModel<Vstereo_hier_top>>(limits);
    }
#ifdef STEREO_COSIM_FULL_HIER
    if (limits.config == kHierTopFullLimits.config) {
        return std::make_unique<CoreModel<Vstereo_hier_top_full>>(limits);
    }
#endif
    throw std::invalid_argument("no stereo_hier_top configuration named " +
                                std::string(limits.config) + " was built");
}

}  // namespace

HierTopSim::HierTopSim(const HierTopLimits& limits) : limits_(limits), model_(make_model(limits)) {
    reset();
}
HierTopSim::~HierTopSim() = default;

void HierTopSim::reset() {
    model_->reset();
}

void HierTopSim::configure(int width, int height, const h::Params& params,
                           const h::PlaneSetting& setting) {
    check_size(params, width, height, limits_);
    h::validate(params, width, height);
    model_->configure(width, height, params, setting);
}

void HierTopSim::set_host(Host host) {
    host_ = std::move(host);
}

void HierTopSim::serve_host() {
    if (model_->serve(host_)) {
        ++statistics_read_;
    }
}

StreamResult HierTopSim::stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                                const Traffic& traffic, std::uint64_t max_cycles) {
    return model_->stream(beats, expected_outputs, traffic, max_cycles, [this] { serve_host(); });
}

std::uint64_t HierTopSim::wait_for_statistics(std::size_t count, std::uint64_t max_clocks) {
    std::uint64_t clocks = 0;
    for (; clocks < max_clocks && statistics_read_ < count; ++clocks) {
        model_->idle_tick();
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
    HierTopSim core(check_hier_top(params, width, height));
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
    // (The full level's wait and flush: about 73 rows of its groups after the last input.)
    const std::uint64_t kStatisticsClocks = std::max<std::uint64_t>(100000, 4 * pixels_per_frame);
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
