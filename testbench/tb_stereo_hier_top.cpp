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

#include "hier_top_sim.hpp"
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
constexpr sim::HierTopLimits kCore = sim::kHierTopLimits;
constexpr int kWidth = kCore.width;
constexpr int kHeight = kCore.height;
constexpr int kVMin = kCore.v_min;
constexpr int kVMax = kCore.v_max;

h::Params core_params() {
    h::Params params;
    params.ndisp = kCore.ndisp;
    params.vrange = kVMax - kVMin + 1;
    params.cost = std::string(catalogue::cost(catalogue::Cost::census).name);
    params.field_level = {kCore.window, fx::kDefaultSigma};
    return params;  // the API's validation: off (stage 6 as configured below)
}

// Runs `frames` frames of the pair through the core with the host in the loop
// (sim::run_hier_top) and checks every frame against the model's hardware form; returns the
// settings the host wrote.
std::vector<h::PlaneSetting> check_frames(const Image& left, const Image& right, int frames,
                                          const sim::Traffic& traffic, int stray_start = -1) {
    const h::Params params = core_params();
    sim::HierTopRunOptions options;
    options.frames = frames;
    options.traffic = traffic;
    options.stray_start = stray_start;
    const sim::HierTopRun run = sim::run_hier_top(left, right, params, options);
    EXPECT_EQ(run.frames.size(), static_cast<std::size_t>(frames));
    const auto expected = sim::hier_top_expected(left, right, params, frames);
    std::vector<h::PlaneSetting> settings;
    for (std::size_t f = 0; f < run.frames.size(); ++f) {
        const sim::HierTopFrame& got = run.frames[f];
        settings.push_back(got.setting);
        EXPECT_EQ(got.setting, expected[f].setting) << "frame " << f;
        EXPECT_EQ(got.statistics, expected[f].statistics) << "frame " << f;
        EXPECT_EQ(sim::differing_pixels(got.output, expected[f].output).size(), 0U)
            << "frame " << f << ": pixels whose beat differs from the model";
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
