// stereo_hier_top (the hierarchical search's whole streaming core, issue 45) against the model's
// hardware form, frame after frame with the host in the loop: for frame t the core's output
// beats equal the 1-D pass along the plane of setting t (sim::hier_pass_expected, the pass of
// stereo::hierarchical::match_frame), its statistics registers equal match_frame's statistics
// (the full level's votes against setting t), and the host's PlaneTracker turns those registers
// into setting t + 1, which the core waits for (cfg_wait_plane). A rig rolled and shifted by a
// plane (a Tsukuba crop and a random pair), input gaps and output stalls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_hier_top.h"
#include "axis_driver.hpp"
#include "hier_pass_sim.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_plane.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_hier_pairs.hpp"
#include "tb_real_pairs.hpp"

namespace stereo::tb {
namespace {

namespace h = stereo::hierarchical;

// The module's defaults (the Verilated configuration): 64x48, 16 labels, 5x5 pass, V = 16.
constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kPassWindow = 5;
constexpr int kVMin = -8;
constexpr int kVMax = 7;

h::Params core_params() {
    h::Params params;
    params.ndisp = 16;
    params.vrange = 16;
    params.cost = std::string(catalogue::cost(catalogue::Cost::census).name);
    params.field_level = {kPassWindow, fx::kDefaultSigma};
    return params;  // the API's validation: off (stage 6 as configured below)
}

template <class Port>
void put_kernel(Port& port, const std::vector<std::int32_t>& taps, int offset_taps) {
    for (std::size_t i = 0; i < taps.size(); ++i) {
        put_bits(port, (offset_taps + static_cast<int>(i)) * table::kTapBits, table::kTapBits,
                 static_cast<std::uint64_t>(taps[i]));
    }
}

class HierTopSim {
  public:
    HierTopSim() : harness_("hier_top") {
        auto& m = harness_.model();
        m.rst = 1;
        harness_.tick();
        harness_.tick();
        m.rst = 0;
    }

    void configure(const h::Params& params, const h::PlaneSetting& setting) {
        auto& m = harness_.model();
        m.cfg_width = kWidth;
        m.cfg_height = kHeight;
        m.cfg_ndisp = static_cast<std::uint16_t>(params.ndisp);
        m.cfg_radius = kPassWindow / 2;
        put_kernel(m.cfg_kernel, gaussian_kernel(kPassWindow, params.field_level.sigma), 0);
        put_kernel(m.cfg_kernel_q, gaussian_kernel(params.levels[0].window, params.levels[0].sigma),
                   0);
        put_kernel(m.cfg_kernel_h, gaussian_kernel(params.levels[1].window, params.levels[1].sigma),
                   0);
        put_kernel(m.cfg_kernel_f, gaussian_kernel(params.levels[2].window, params.levels[2].sigma),
                   0);
        m.cfg_use_ca = params.use_ca ? 1 : 0;
        m.cfg_uniqueness_en = params.validation.uniqueness ? 1 : 0;
        m.cfg_uniqueness = static_cast<std::uint8_t>(params.validation.uniqueness_ratio);
        m.cfg_lr_en = params.validation.left_right ? 1 : 0;
        m.cfg_lr_tolerance = static_cast<std::uint8_t>(params.validation.lr_tolerance);
        m.cfg_subpixel_en = params.validation.subpixel ? 1 : 0;
        m.cfg_wait_plane = 1;
        write_setting(setting);
    }

    void write_setting(const h::PlaneSetting& setting) {
        auto& m = harness_.model();
        m.plane_a = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.a));
        m.plane_b = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.b));
        m.plane_c = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.c));
        m.tolerance = static_cast<std::uint32_t>(setting.tolerance);
    }

    // Streams `frames` copies of the pair; after each frame's statistics the host (tracker)
    // writes the next setting and commits it. Returns the output beats and each frame's
    // statistics as the registers held them.
    // With `stray_start` >= 0, that beat of the first frame carries tuser too (a start of frame
    // inside a frame, which the core treats as a pixel).
    sim::StreamResult run(const Image& left, const Image& right, int frames,
                          h::PlaneTracker& tracker, std::vector<h::PlaneStatistics>& statistics,
                          const sim::Traffic& traffic, int stray_start = -1) {
        std::vector<sim::InputBeat> beats;
        for (int f = 0; f < frames; ++f) {
            const auto more = sim::frame_beats(left, right);
            beats.insert(beats.end(), more.begin(), more.end());
        }
        if (stray_start >= 0) {
            beats[static_cast<std::size_t>(stray_start)].user = true;
        }
        auto& m = harness_.model();
        const auto host = [&](Vstereo_hier_top& core) {
            core.plane_commit = 0;
            if (core.out_done == 0) {
                return;
            }
            statistics.push_back(read_statistics(core));
            tracker.update(statistics.back());
            write_setting(tracker.setting());
            core.plane_commit = 1;
        };
        m.plane_commit = 0;
        const auto result = sim::stream_axis(harness_, beats, beats.size(), traffic,
                                             60 * beats.size() + 200000, host);
        // The pass's last beat can leave before the levels' last winner: wait for the statistics.
        m.s_axis_tvalid = 0;
        for (int clock = 0; clock < 100000 && statistics.size() < static_cast<std::size_t>(frames);
             ++clock) {
            harness_.tick();
            host(m);
        }
        return result;
    }

  private:
    static h::PlaneStatistics read_statistics(Vstereo_hier_top& core) {
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
        s.v_min = kVMin;
        for (int bin = 0; bin <= kVMax - kVMin; ++bin) {
            core.hist_index = static_cast<std::uint8_t>(bin);
            core.eval();
            s.histogram.push_back(static_cast<std::int64_t>(core.hist_count));
        }
        return s;
    }

    sim::VerilatedHarness<Vstereo_hier_top> harness_;
};

// Runs `frames` frames of the pair through the core with the host in the loop and checks every
// frame against the model's hardware form; returns the settings the host wrote.
std::vector<h::PlaneSetting> check_frames(const Image& left, const Image& right, int frames,
                                          const sim::Traffic& traffic, int stray_start = -1) {
    const h::Params params = core_params();
    HierTopSim core;
    h::PlaneTracker host;
    core.configure(params, host.setting());
    std::vector<h::PlaneStatistics> statistics;
    const auto result = core.run(left, right, frames, host, statistics, traffic, stray_start);
    EXPECT_EQ(result.outputs.size(), static_cast<std::size_t>(frames) * kWidth * kHeight);
    EXPECT_EQ(statistics.size(), static_cast<std::size_t>(frames));
    h::PlaneTracker model_host;
    std::vector<h::PlaneSetting> settings;
    for (int f = 0; f < frames && static_cast<std::size_t>(f) < statistics.size(); ++f) {
        const h::PlaneSetting setting = model_host.setting();
        settings.push_back(setting);
        const h::FrameResult want = h::match_frame(left, right, params, setting);
        EXPECT_EQ(statistics[static_cast<std::size_t>(f)], want.statistics) << "frame " << f;
        const auto got = sim::hier_pass_assemble(
            result.outputs, static_cast<std::size_t>(f) * kWidth * kHeight, kWidth, kHeight);
        const auto pass = sim::hier_pass_expected(left, right, setting.plane, params);
        int wrong = 0;
        for (std::size_t p = 0; p < got.vertical.size(); ++p) {
            if (got.validated.fixed[p] != pass.validated.fixed[p] ||
                got.validated.reason[p] != pass.validated.reason[p] ||
                got.vertical[p] != pass.vertical[p]) {
                ++wrong;
            }
        }
        EXPECT_EQ(wrong, 0) << "frame " << f << ": pixels whose beat differs from the model";
        model_host.update(want.statistics);
    }
    return settings;
}

TEST(StereoHierTop, RandomRollFrameAfterFrameEqualsModel) {
    std::mt19937 rng(4521);
    const Image left = test::random_image(kWidth, kHeight, 3, rng);
    const h::Plane roll{std::llround(1.5 * h::kPlaneOne), std::llround(0.04 * h::kPlaneOne), 0};
    const Image right = moved_by_plane(left, roll, 3, rng, kVMin, kVMax);
    const auto settings = check_frames(left, right, 4, {.input_gap = 0.2, .output_stall = 0.2});
    ASSERT_EQ(settings.size(), 4U);
    // The host's loop moves the plane off 0 after the start frame (the mode), then fits it.
    EXPECT_NE(settings[1].plane, h::Plane{});
    EXPECT_NE(settings[2].plane.b, 0);
}

// A start of frame in the middle of a frame is a pixel for the pass and the levels alike: both
// frames still equal the model.
TEST(StereoHierTop, StrayStartOfFrameKeepsOneRaster) {
    std::mt19937 rng(4523);
    const Image left = test::random_image(kWidth, kHeight, 3, rng);
    const h::Plane shift{2 * h::kPlaneOne, 0, 0};
    const Image right = moved_by_plane(left, shift, 4, rng, kVMin, kVMax);
    check_frames(left, right, 2, {}, kWidth * kHeight / 2 + 7);
}

TEST(StereoHierTop, RolledTsukubaCropEqualsModel) {
    const auto crop = tsukuba_crop();
    if (!crop) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    std::mt19937 rng(4522);
    const h::Plane roll{std::llround(-2.0 * h::kPlaneOne), std::llround(0.03 * h::kPlaneOne), 0};
    const Image right = moved_by_plane(crop->left, roll, 5, rng, kVMin, kVMax);
    check_frames(crop->left, right, 3, {});
}

}  // namespace
}  // namespace stereo::tb
