// stereo_hier_pass (the hierarchical core's 1-D pass along a plane, issue 45) against the model,
// bit for bit: stereo::hierarchical::match_along_field over plane_field(plane) for the beat
// (disparity x 16, reason, certainty) and field_at_match for the vertical offset beside it.
// Pairs whose right image is moved by a plane's offsets (shift, roll) and random pairs, planes
// reaching both ends of the offset range, input gaps and output stalls, frames back to back
// with different planes and sizes, and a reset in the middle of a frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "hier_pass_sim.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_hier_pairs.hpp"
#include "tb_real_pairs.hpp"

namespace stereo::tb {
namespace {

namespace h = stereo::hierarchical;

constexpr int kMaxWidth = sim::kHierPassLimits.width;
constexpr int kMaxHeight = sim::kHierPassLimits.height;
constexpr int kVMin = sim::kHierPassLimits.v_min;
constexpr int kVMax = sim::kHierPassLimits.v_max;

struct Frame {
    Image left;
    Image right;
    h::Plane plane;
};

using Expected = sim::HierPassOutput;

h::Params pass_params(const ValidationParams& validation, bool use_ca) {
    h::Params params;
    params.ndisp = sim::kHierPassLimits.ndisp;
    params.cost = "census";
    params.use_ca = use_ca;
    params.field_level = {sim::kHierPassLimits.window, fx::kDefaultSigma};
    params.validation = validation;
    return params;
}

Expected expected(const Frame& frame, const h::Params& params) {
    return sim::hier_pass_expected(frame.left, frame.right, frame.plane, params);
}

// Streams the frames back to back. The first frame's setting is written before its first beat;
// the next frame's as a host would, once the current frame's first result has come out (the
// core sampled the setting when the frame started and keeps it until the frame leaves), usually
// while the current frame is still streaming in.
sim::StreamResult stream(sim::HierPassSim& rtl, const std::vector<Frame>& frames,
                         const h::Params& params, const sim::Traffic& traffic) {
    std::vector<sim::InputBeat> beats;
    for (const Frame& frame : frames) {
        const auto more = sim::frame_beats(frame.left, frame.right);
        beats.insert(beats.end(), more.begin(), more.end());
    }
    const auto configure = [&](std::size_t i) {
        rtl.configure(frames[i].left.width, frames[i].left.height, frames[i].plane, params);
    };
    configure(0);
    return rtl.stream(beats, beats.size(), traffic, 40 * beats.size() + 100000,
                      [&](std::size_t started) {
                          if (started < frames.size()) {
                              configure(started);
                          }
                      });
}

// Compares the frame's beats (starting at `first`) with the model, pixel by pixel; returns the
// number of mismatching pixels and reports the first few.
int mismatches(const std::vector<sim::OutputBeat>& beats, std::size_t first, const Frame& frame,
               const Expected& want) {
    const Expected got = sim::hier_pass_assemble(beats, first, frame.left.width, frame.left.height);
    int wrong = 0;
    for (std::size_t p = 0; p < got.vertical.size(); ++p) {
        const auto& g = got.validated;
        const auto& w = want.validated;
        if (g.fixed[p] != w.fixed[p] || g.reason[p] != w.reason[p] ||
            g.certainty[p] != w.certainty[p] || got.vertical[p] != want.vertical[p]) {
            if (++wrong <= 5) {
                ADD_FAILURE() << "pixel (" << p % frame.left.width << ", " << p / frame.left.width
                              << "): rtl fixed " << g.fixed[p] << " reason "
                              << static_cast<int>(g.reason[p]) << " certainty "
                              << static_cast<int>(g.certainty[p]) << " v "
                              << static_cast<int>(got.vertical[p]) << "; model " << w.fixed[p]
                              << " " << static_cast<int>(w.reason[p]) << " "
                              << static_cast<int>(w.certainty[p]) << " "
                              << static_cast<int>(want.vertical[p]);
            }
        }
    }
    return wrong;
}

h::Plane plane_of(double a, double b, double c) {
    return {std::llround(a * h::kPlaneOne), std::llround(b * h::kPlaneOne),
            std::llround(c * h::kPlaneOne)};
}

TEST(StereoHierPass, PlanesShiftsAndRollsEqualModel) {
    auto rng = test::seeded_rng(450);
    const h::Params params = pass_params({true, 10, true, 1, true}, true);
    const std::vector<h::Plane> planes = {
        plane_of(0, 0, 0),             // the 1-D pipeline
        plane_of(3, 0, 0),             // a shift of 3 rows
        plane_of(-2.5, 0.03, 0.0),     // a roll about a point left of the frame
        plane_of(20, -0.4, 0.1),       // clamped to V_MAX on the left, down to V_MIN
        plane_of(-20, 0, 0),           // clamped to V_MIN everywhere
        plane_of(1.5, -0.02, 0.015)};  // halves: rounding up
    for (std::size_t i = 0; i < planes.size(); ++i) {
        Frame frame;
        frame.left = test::random_image(kMaxWidth, kMaxHeight, 3, rng);
        frame.plane = planes[i];
        frame.right = moved_by_plane(frame.left, frame.plane, 5, rng, kVMin, kVMax);
        sim::HierPassSim rtl;
        const auto result = stream(
            rtl, {frame}, params,
            {i % 2 == 0 ? 0.0 : 0.2, i % 2 == 0 ? 0.0 : 0.2, static_cast<std::uint32_t>(i + 1)});
        SCOPED_TRACE("plane " + std::to_string(i));
        ASSERT_TRUE(result.completed) << result.outputs.size() << " beats";
        EXPECT_EQ(result.protocol_error, "");
        const Expected want = expected(frame, params);
        EXPECT_EQ(mismatches(result.outputs, 0, frame, want), 0);
        if (i == 1) {
            // The shift is found: most pixels valid, at disparity 5 and offset 3.
            int right_answers = 0;
            for (std::size_t p = 0; p < want.vertical.size(); ++p) {
                right_answers += want.validated.valid(p) && want.validated.fixed[p] == 5 * 16 &&
                                         want.vertical[p] == 3
                                     ? 1
                                     : 0;
            }
            EXPECT_GT(right_answers, static_cast<int>(want.vertical.size()) / 2);
        }
    }
}

// Frames back to back, each with its own plane and size (the queue of settings), validation and
// CA off on one run: every frame equals the model.
TEST(StereoHierPass, FramesBackToBackWithTheirOwnPlanes) {
    auto rng = test::seeded_rng(451);
    for (const bool stage6 : {true, false}) {
        const h::Params params = pass_params(
            stage6 ? ValidationParams{true, 15, true, 0, true} : ValidationParams{}, stage6);
        std::vector<Frame> frames;
        const std::vector<std::pair<int, int>> sizes = {{64, 48}, {40, 30}, {64, 20}, {23, 17}};
        std::uniform_real_distribution<double> offset(-9.0, 9.0);
        std::uniform_real_distribution<double> slope(-0.08, 0.08);
        for (const auto& [width, height] : sizes) {
            Frame frame;
            frame.left = test::random_image(width, height, 3, rng);
            frame.plane = plane_of(offset(rng), slope(rng), slope(rng));
            frame.right = moved_by_plane(frame.left, frame.plane, 3, rng, kVMin, kVMax);
            frames.push_back(std::move(frame));
        }
        sim::HierPassSim rtl;
        const auto result = stream(rtl, frames, params, {0.1, 0.15, stage6 ? 7U : 8U});
        ASSERT_TRUE(result.completed) << result.outputs.size() << " beats";
        EXPECT_EQ(result.protocol_error, "");
        std::size_t first = 0;
        for (std::size_t i = 0; i < frames.size(); ++i) {
            SCOPED_TRACE("frame " + std::to_string(i) + (stage6 ? ", stage 6" : ", plain"));
            EXPECT_EQ(mismatches(result.outputs, first, frames[i], expected(frames[i], params)), 0);
            first += static_cast<std::size_t>(frames[i].left.width) * frames[i].left.height;
        }
    }
}

// A reset in the middle of a frame abandons it; the next frame is the model's.
TEST(StereoHierPass, ResetInTheMiddleOfAFrame) {
    auto rng = test::seeded_rng(452);
    const h::Params params = pass_params({true, 10, true, 1, true}, true);
    Frame abandoned{test::random_image(64, 48, 3, rng), test::random_image(64, 48, 3, rng),
                    plane_of(4, 0.05, 0)};
    sim::HierPassSim rtl;
    rtl.configure(64, 48, abandoned.plane, params);
    auto beats = sim::frame_beats(abandoned.left, abandoned.right);
    beats.resize(1500);  // half the frame: the row select and stereo_top both hold some of it
    (void)rtl.stream(beats, 1, {0.0, 0.3, 3U}, 5000);
    rtl.reset();
    Frame frame;
    frame.left = test::random_image(50, 40, 3, rng);
    frame.plane = plane_of(-3.5, 0.02, -0.04);
    frame.right = moved_by_plane(frame.left, frame.plane, 6, rng, kVMin, kVMax);
    const auto result = stream(rtl, {frame}, params, {0.2, 0.2, 4U});
    ASSERT_TRUE(result.completed);
    EXPECT_EQ(mismatches(result.outputs, 0, frame, expected(frame, params)), 0);
}

// A real crop (Tsukuba, 64x48) whose right image is rolled and shifted by a plane: the pass along
// that plane equals the model, and finds more valid pixels than the pass along the plane 0.
TEST(StereoHierPass, RealCropAlongItsPlane) {
    const auto crop = tsukuba_crop();
    if (!crop) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    const h::Params params = pass_params({true, 10, true, 1, true}, true);
    const h::Plane plane = plane_of(1.2, 0.03, 0.0);
    const auto field = h::plane_field(plane, crop->right.width, crop->right.height, kVMin, kVMax);
    // The right image moved down by the field (its pixel (x, y + v) shows (x, y)).
    Image right = crop->right;
    for (int y = 0; y < right.height; ++y) {
        for (int x = 0; x < right.width; ++x) {
            const int row = y + field[static_cast<std::size_t>(y) * right.width + x];
            if (row >= 0 && row < right.height) {
                for (int c = 0; c < right.channels; ++c) {
                    right.at(x, row, c) = crop->right.at(x, y, c);
                }
            }
        }
    }
    const Frame along{crop->left, right, plane};
    const Frame flat{crop->left, right, h::Plane{}};
    sim::HierPassSim rtl;
    const auto result = stream(rtl, {along, flat}, params, {0.1, 0.1, 5U});
    ASSERT_TRUE(result.completed);
    const Expected want_along = expected(along, params);
    const Expected want_flat = expected(flat, params);
    EXPECT_EQ(mismatches(result.outputs, 0, along, want_along), 0);
    EXPECT_EQ(mismatches(result.outputs, 64 * 48, flat, want_flat), 0);
    const auto valid = [](const Expected& e) {
        return std::count(e.validated.reason.begin(), e.validated.reason.end(), fx::kReasonValid);
    };
    std::cout << "[real crop] valid along the plane " << valid(want_along) << ", along 0 "
              << valid(want_flat) << " of " << 64 * 48 << '\n';
    EXPECT_GT(valid(want_along), valid(want_flat));
}

}  // namespace
}  // namespace stereo::tb
