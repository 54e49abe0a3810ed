// stereo_hls_top: the whole pipeline as one streaming loop, one pixel step per iteration
// (RTL: rtl/stereo_top.sv; architecture in docs/rtl.md).
//
// `pipeline` holds the seven stages, each a small object with its line buffers and registers;
// stereo_hls_top runs one frame through them: W*H iterations that read one input beat each,
// then flush iterations that push zero pixels whose coordinates continue the raster, until the
// frame's last result has entered the output register (stage 6's lr_check). Every iteration that
// leaves a frame pixel in that register writes one output beat, so exactly W*H beats come out, in
// raster order.
//
// As in the RTL, every stage carries the coordinates of its data and decides zero padding from
// them, so nothing is cleared between frames: the stage objects keep their RAM contents, only
// their coordinate registers are set to "no pixel" at the start of a frame.
#pragma once

#include "stereo/hls/aggregate.hpp"
#include "stereo/hls/ca_rule.hpp"
#include "stereo/hls/census.hpp"
#include "stereo/hls/cost.hpp"
#include "stereo/hls/cost_lcdm.hpp"
#include "stereo/hls/stream.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/hls/validate.hpp"
#include "stereo/hls/wta.hpp"

namespace stereo::hls {

// Status bits returned by stereo_hls_top, as the RTL's sticky status port (stage_table.hpp).
inline constexpr status_t kStatusEolMisplaced = 1U << table::kStatusEolMisplaced;
inline constexpr status_t kStatusSofMisplaced = 1U << table::kStatusSofMisplaced;
inline constexpr status_t kStatusConfigClamped = 1U << table::kStatusConfigClamped;

// The stage table's code of a cost stage's measure (table::kCostAd, kCostLcdm, kCostCensus).
template <class MEASURE>
inline constexpr int kMeasureCost = kIsCensus<MEASURE>                      ? table::kCostCensus
                                    : std::is_same_v<MEASURE, lcdm_measure> ? table::kCostLcdm
                                                                            : table::kCostAd;

// Pixel steps from a pixel entering the first stage to its result leaving the output register
// (stage 6's lr_check), R = WINDOW/2 of the synthesised window, N = NDISP, K = max(0, -min_disp):
// the stage table's table::hls_pipeline_latency, (R + 2) * W + R + 9 + N + K, and 2 * W + 3 more
// with the census stage (the RTL's CA rules and census stage take one step more each: their
// windows have an input register for Fmax, hls/README.md).
template <int NDISP, int WINDOW, class MEASURE = ad_measure>
constexpr int pipeline_delay(int width, int min_disp = 0) {
    return table::hls_pipeline_latency(width, WINDOW, NDISP, min_disp, kMeasureCost<MEASURE>);
}

// Iterations of one frame: the pixels, then the flush. The result of the last pixel is in the
// output register after its own step plus pipeline_delay - 1 more (the RTL's D counts the
// output beat's cycle too).
template <int NDISP, int WINDOW, class MEASURE = ad_measure>
constexpr int frame_steps(int width, int height, int min_disp = 0) {
    return width * height + pipeline_delay<NDISP, WINDOW, MEASURE>(width, min_disp) - 1;
}

// The census stage of a pipeline whose measure is not census: nothing.
struct no_census_stage {
    void reset() {}
};

// The state of stereo_hls_top: the stages of rtl/stereo_top.sv. Large (the line buffers are
// WIDTH columns of whole disparity columns): a static object in a synthesis top, a heap object
// in C-simulation hosts.
// MEASURE is the cost stage's measure: ad_measure (AD over RGB), lcdm_measure (LCDM, thesis
// Sec. 3.5) or census_measure (the census stage in front of the cost stage), as stereo_top's
// COST parameter.
template <int WIDTH, int HEIGHT, int NDISP, int WINDOW,
          int MAX_MIN_DISP = table::kDefaultMaxMinDisp, class MEASURE = ad_measure>
class pipeline : public winner_stages<NDISP> {
    static_assert(WIDTH >= 1 && WIDTH <= kMaxFrameSide && HEIGHT >= 1 && HEIGHT <= kMaxFrameSide);

  public:
    // Every stage's coordinate registers to "no pixel"; data registers and RAMs keep their
    // contents (stale data is masked by coordinates).
    void reset() {
        winner_stages<NDISP>::reset();
        reset_stages(census_, cost_, aggregate_, rule1_, rule2_);
    }

    // One pixel step of every stage with the pixel pair of raster position (x, y). The stages
    // are stepped from the last to the first, so that each reads the output register of the
    // one before it as it was before this step: the registers between the RTL's modules.
    void step(coord_t x, coord_t y, const Rgb& left, const Rgb& right,
              const FrameConfig<WINDOW>& cfg) {
#pragma HLS INLINE
        this->step_winner(rule2_.out_x(), rule2_.out_y(), rule2_.out_data(), cfg, cfg.radius,
                          cfg.use_ca);
        rule2_.step(rule1_.out_x(), rule1_.out_y(), rule1_.out_data(), cfg.width, cfg.height,
                    cfg.ndisp, cfg.use_ca);
        rule1_.step(aggregate_.out_x(), aggregate_.out_y(), aggregate_.out_data(), cfg.width,
                    cfg.height, cfg.ndisp, cfg.use_ca);
        aggregate_.step(cost_.out_x(), cost_.out_y(), cost_.out_data(), cfg.width, cfg.height,
                        cfg.kernel);
        if constexpr (kIsCensus<MEASURE>) {
            cost_.step(census_.out_x(), census_.out_y(), census_.out_left(), census_.out_right(),
                       cfg.width, cfg.min_disp);
            census_.step(x, y, left, right, cfg.width, cfg.height);
        } else {
            cost_.step(x, y, left, right, cfg.width, cfg.min_disp);
        }
    }

  private:
    std::conditional_t<kIsCensus<MEASURE>, census_transform<WIDTH>, no_census_stage> census_;
    cost<NDISP, MAX_MIN_DISP, MEASURE> cost_;
    aggregate<WIDTH, NDISP, WINDOW> aggregate_;
    ca_rule1<WIDTH, NDISP> rule1_;
    ca_rule2<WIDTH, NDISP> rule2_;
};

// A configuration value outside [low, high] becomes high (a size of 0 or above the maximum
// becomes the maximum), as the RTL clamps it, and sets kStatusConfigClamped.
inline void clamp_config(int& value, int low, int high, status_t& status) {
    if (value < low || value > high) {
        value = high;
        status |= kStatusConfigClamped;
    }
}

// The fields every core's configuration has (FrameConfig, AswConfig), clamped as the RTL does:
// the size and the labels to the build's; the minimum disparity to the nearer end of
// +-MAX_MIN_DISP; the ratio and the tolerance are 8-bit ports in the RTL, which hold every value
// of their range.
template <int WIDTH, int HEIGHT, int NDISP, int MAX_MIN_DISP, class Config>
void sanitise_common(Config& cfg, status_t& status) {
#pragma HLS INLINE
    clamp_config(cfg.width, 1, WIDTH, status);
    clamp_config(cfg.height, 1, HEIGHT, status);
    clamp_config(cfg.ndisp, 1, NDISP, status);
    if (cfg.min_disp > MAX_MIN_DISP || cfg.min_disp < -MAX_MIN_DISP) {
        cfg.min_disp = cfg.min_disp > 0 ? MAX_MIN_DISP : -MAX_MIN_DISP;
        status |= kStatusConfigClamped;
    }
    cfg.uniqueness_ratio &= (1 << table::kCfgUniquenessBits) - 1;
    cfg.lr_tolerance &= (1 << table::kCfgLrToleranceBits) - 1;
}

// The configuration as the stages will use it (sanitise_common, and the CA radius to the
// window's), with kStatusConfigClamped set when anything was clamped.
template <int WIDTH, int HEIGHT, int NDISP, int WINDOW, int MAX_MIN_DISP>
FrameConfig<WINDOW> sanitise(const FrameConfig<WINDOW>& requested, status_t& status) {
#pragma HLS INLINE
    FrameConfig<WINDOW> cfg = requested;
    sanitise_common<WIDTH, HEIGHT, NDISP, MAX_MIN_DISP>(cfg, status);
    clamp_config(cfg.radius, 0, WINDOW / 2, status);
    return cfg;
}

// The frame loop of every HLS top: `steps` pixel steps (the frame's pixels, then the flush with
// zero pixels), an input beat read per pixel with its framing checked (status bits added to
// `status`), the state stepped once a step, an output beat written for every step whose output
// pixel lies inside the frame. MAX_STEPS bounds the loop for the trip-count pragma.
template <int MAX_STEPS, class Config, class State>
void stream_frame(stream<InputBeat>& in, stream<OutputBeat>& out, const Config& cfg, State& state,
                  int steps, status_t& status) {
#pragma HLS INLINE
    const int pixels = cfg.width * cfg.height;
    int x = 0;  // raster position of this step's input; y >= height while flushing
    int y = 0;
frame_loop:
    for (int step = 0; step < steps; ++step) {
#pragma HLS PIPELINE II = 1
#pragma HLS LOOP_TRIPCOUNT min = 1 max = MAX_STEPS
        // Loops inside the stages have constant bounds and are unrolled by the pipelining: all
        // lanes and all window taps of one pixel in one iteration.
        InputBeat beat;  // flush steps push zero pixels
        if (step < pixels) {
            beat = in.read();
            if (beat.eol != (x == cfg.width - 1)) {
                status |= kStatusEolMisplaced;
            }
            if (beat.sof != (step == 0)) {
                status |= kStatusSofMisplaced;
            }
        }
        state.step(to_coord(x), to_coord(y), beat.left, beat.right, cfg);
        const int out_x = state.out_x();
        const int out_y = state.out_y();
        if (inside(out_x, out_y, cfg.width, cfg.height)) {
            OutputBeat result;
            result.result = state.out();
            result.sof = out_x == 0 && out_y == 0;
            result.eol = out_x == cfg.width - 1;
            out.write(result);
        }
        if (++x == cfg.width) {
            x = 0;
            ++y;
        }
    }
}

// One frame: cfg.width * cfg.height beats from `in`, as many to `out`. Returns the status bits.
// Unlike the RTL, which drops beats until a start of frame, a call reads exactly one frame's
// beats; misplaced sof/eol flags are reported, not resynchronised on.
template <int WIDTH, int HEIGHT, int NDISP, int WINDOW, int MAX_MIN_DISP, class MEASURE>
status_t stereo_hls_top(stream<InputBeat>& in, stream<OutputBeat>& out,
                        const FrameConfig<WINDOW>& requested,
                        pipeline<WIDTH, HEIGHT, NDISP, WINDOW, MAX_MIN_DISP, MEASURE>& state) {
#pragma HLS INLINE
    constexpr int kMaxSteps = frame_steps<NDISP, WINDOW, MEASURE>(WIDTH, HEIGHT, -MAX_MIN_DISP);
    status_t status = 0;
    const FrameConfig<WINDOW> cfg =
        sanitise<WIDTH, HEIGHT, NDISP, WINDOW, MAX_MIN_DISP>(requested, status);
    state.reset();
    const int steps = frame_steps<NDISP, WINDOW, MEASURE>(cfg.width, cfg.height, cfg.min_disp);
    stream_frame<kMaxSteps>(in, out, cfg, state, steps, status);
    return status;
}

}  // namespace stereo::hls
