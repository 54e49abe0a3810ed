// The plane field's hardware form (stereo/hierarchical_plane.hpp, docs/hierarchical.md "Hardware
// form of the field"): the frame statistics and the fit by hand, the tracker's sequence, and a
// static rig whose frames reach the plane of FieldModel::plane and then its output.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "shifted_pairs.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_plane.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::hierarchical {
namespace {

// A 4 x 3 map: offsets by hand, (3, 2) invalid.
LevelMap small_map() {
    LevelMap level{4, 3, std::vector<std::int16_t>(12, 0), {}, {}};
    level.vertical = {1,  1, 2, 5,  //
                      1,  0, 1, 1,  //
                      -1, 1, 1, 7};
    level.valid = {1, 1, 1, 1,  //
                   1, 1, 1, 1,  //
                   1, 1, 1, 0};
    return level;
}

TEST(PlaneStatistics, HandComputed) {
    // The constant plane 1 with tolerance 1: inliers are the valid offsets 0, 1 and 2, i.e. all
    // valid pixels but (3, 0) (5) and (0, 2) (-1): (0,0) (1,0) (2,0) (0,1) (1,1) (2,1) (3,1)
    // (1,2) (2,2) with offsets 1 1 2 1 0 1 1 1 1.
    const PlaneSetting setting{Plane{kPlaneOne, 0, 0}, kPlaneOne};
    const PlaneStatistics s = plane_statistics(small_map(), setting, -2, 5);
    EXPECT_EQ(s.count, 9);
    EXPECT_EQ(s.sum_x, 0 + 1 + 2 + 0 + 1 + 2 + 3 + 1 + 2);
    EXPECT_EQ(s.sum_y, 0 + 0 + 0 + 1 + 1 + 1 + 1 + 2 + 2);
    EXPECT_EQ(s.sum_xx, 0 + 1 + 4 + 0 + 1 + 4 + 9 + 1 + 4);
    EXPECT_EQ(s.sum_xy, 0 + 0 + 0 + 0 + 1 + 2 + 3 + 2 + 4);
    EXPECT_EQ(s.sum_yy, 0 + 0 + 0 + 1 + 1 + 1 + 1 + 4 + 4);
    EXPECT_EQ(s.sum_v, 1 + 1 + 2 + 1 + 0 + 1 + 1 + 1 + 1);
    EXPECT_EQ(s.sum_xv, 0 + 1 + 4 + 0 + 0 + 2 + 3 + 1 + 2);
    EXPECT_EQ(s.sum_yv, 0 + 0 + 0 + 1 + 0 + 1 + 1 + 2 + 2);
    // Histogram over -2..5 of the 11 valid offsets: -1 once, 0 once, 1 seven times, 2 once, 5
    // once (the invalid 7 is not counted).
    EXPECT_EQ(s.v_min, -2);
    EXPECT_EQ(s.histogram, (std::vector<std::int64_t>{0, 1, 1, 7, 1, 0, 0, 1}));
    EXPECT_EQ(histogram_mode(s), 1);
    // An offset outside the histogram's range is refused.
    EXPECT_THROW((void)plane_statistics(small_map(), setting, -2, 4), std::invalid_argument);
}

TEST(PlaneStatistics, ToleranceIsInclusiveAndFollowsThePlane) {
    // The plane v = x / 2 with tolerance 1/2: at x = 3 the plane is 1.5, so 1 and 2 are both
    // inliers (|1 - 1.5| = |2 - 1.5| = 0.5); at x = 0 the plane is 0 and only |v| <= 0.5, v = 0.
    LevelMap level{4, 1, std::vector<std::int16_t>(4, 0), {0, 1, 1, 2}, {1, 1, 1, 1}};
    const PlaneSetting setting{Plane{0, kPlaneOne / 2, 0}, kPlaneOne / 2};
    const PlaneStatistics s = plane_statistics(level, setting, -8, 7);
    // x = 0: v 0, plane 0: in. x = 1: v 1, plane 0.5: in. x = 2: v 1, plane 1: in. x = 3: v 2,
    // plane 1.5: in.
    EXPECT_EQ(s.count, 4);
    level.vertical = {1, 1, 1, 1};
    // x = 0: |1 - 0| = 1 > 0.5: out. x = 3: |1 - 1.5| = 0.5: in.
    EXPECT_EQ(plane_statistics(level, setting, -8, 7).count, 3);
}

TEST(PlaneStatistics, VotesSitAtTheRightColumn) {
    // One row of 5 winners, displacements d = 0, 3, 1, 1, 2 and offsets 2, 1, 1, 1, 4: the votes
    // sit at xr = x - d = 0, -2 (outside: no vote, not in the histogram), 1, 2, 2. The plane
    // v = xr / 2 with tolerance 1/2: xr 0 v 2 (plane 0: out), xr 1 v 1 (0.5: in), xr 2 v 1
    // (1: in), xr 2 v 4 (1: out).
    LevelMap level{5, 1, {0, 3, 1, 1, 2}, {2, 1, 1, 1, 4}, {1, 1, 1, 1, 1}};
    const PlaneSetting setting{Plane{0, kPlaneOne / 2, 0}, kPlaneOne / 2};
    const PlaneStatistics s = plane_statistics(level, setting, 0, 4);
    EXPECT_EQ(s.count, 2);
    EXPECT_EQ(s.sum_x, 1 + 2);
    EXPECT_EQ(s.sum_xx, 1 + 4);
    EXPECT_EQ(s.sum_xv, 1 * 1 + 2 * 1);
    EXPECT_EQ(s.sum_v, 2);
    EXPECT_EQ(s.histogram, (std::vector<std::int64_t>{0, 2, 1, 0, 1}));
    // At the left columns (every d = 0) the inliers would be x = 1, 2, 3 (planes 0.5, 1, 1.5).
    level.disparity = {0, 0, 0, 0, 0};
    EXPECT_EQ(plane_statistics(level, setting, 0, 4).sum_x, 1 + 2 + 3);
}

TEST(HistogramMode, TiesToTheSmallerMagnitudeThenTheSmallerOffset) {
    PlaneStatistics s;
    s.v_min = -3;
    s.histogram = {4, 0, 0, 0, 0, 0, 4};  // -3 and 3
    EXPECT_EQ(histogram_mode(s), -3);
    s.histogram = {4, 0, 4, 0, 0, 0, 5};  // -1 and -3 tie below 3's 5
    EXPECT_EQ(histogram_mode(s), 3);
    s.histogram = {4, 0, 4, 4, 0, 0, 0};  // -3, -1, 0 tie: 0
    EXPECT_EQ(histogram_mode(s), 0);
    s.histogram.assign(7, 0);
    EXPECT_EQ(histogram_mode(s), 0);
}

TEST(SolvePlane, ExactPlaneAndDegenerateCases) {
    // Offsets exactly on v = 2 + x - y over a 5 x 4 grid: the fit is that plane.
    LevelMap level{5, 4, std::vector<std::int16_t>(20, 0), std::vector<std::int16_t>(20),
                   std::vector<std::uint8_t>(20, 1)};
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) {
            level.vertical[level.index(x, y)] = static_cast<std::int16_t>(2 + x - y);
        }
    }
    const PlaneSetting everything{Plane{}, 100 * kPlaneOne};
    const auto plane = solve_plane(plane_statistics(level, everything, -8, 7));
    ASSERT_TRUE(plane.has_value());
    EXPECT_EQ(*plane, (Plane{2 * kPlaneOne, kPlaneOne, -kPlaneOne}));
    // One column only (x = 0): collinear, no plane.
    for (int y = 0; y < 4; ++y) {
        for (int x = 1; x < 5; ++x) {
            level.valid[level.index(x, y)] = 0;
        }
    }
    EXPECT_FALSE(solve_plane(plane_statistics(level, everything, -8, 7)).has_value());
    // Two pixels: too few.
    level.valid.assign(20, 0);
    level.valid[0] = level.valid[6] = 1;
    EXPECT_FALSE(solve_plane(plane_statistics(level, everything, -8, 7)).has_value());
}

TEST(PlaneTracker, StartsFromTheModeThenFitsAndRestartsWhenTheFitFails) {
    PlaneTracker tracker;
    EXPECT_EQ(tracker.setting(), (PlaneSetting{Plane{}, kFirstFitTolerance}));
    // Frame 0: a start frame: the next plane is the constant mode, whatever the sums say.
    PlaneStatistics frame;
    frame.v_min = -2;
    frame.histogram = {0, 0, 1, 0, 6};  // mode 2
    frame.count = 50;                   // sums of no plane: not used on a start frame
    tracker.update(frame);
    EXPECT_EQ(tracker.setting(), (PlaneSetting{Plane{2 * kPlaneOne, 0, 0}, kFirstFitTolerance}));
    // Frame 1: the sums of v = 2 + x - y on a 5 x 4 grid: the fit, then the fit tolerance.
    LevelMap level{5, 4, std::vector<std::int16_t>(20, 0), std::vector<std::int16_t>(20),
                   std::vector<std::uint8_t>(20, 1)};
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) {
            level.vertical[level.index(x, y)] = static_cast<std::int16_t>(2 + x - y);
        }
    }
    tracker.update(plane_statistics(level, PlaneSetting{Plane{}, 100 * kPlaneOne}, -8, 7));
    EXPECT_EQ(tracker.setting(),
              (PlaneSetting{Plane{2 * kPlaneOne, kPlaneOne, -kPlaneOne}, kFitTolerance}));
    // Frame 2: no inliers (the fit fails): a new start from this frame's mode (-1).
    frame.histogram = {0, 3, 1, 0, 0};
    frame.count = 0;
    tracker.update(frame);
    EXPECT_EQ(tracker.setting(), (PlaneSetting{Plane{-kPlaneOne, 0, 0}, kFirstFitTolerance}));
    tracker.restart();
    EXPECT_EQ(tracker.setting(), PlaneSetting{});
}

// A static rig: the same misaligned pair frame after frame. The tracker's plane reaches
// vertical_plane's (one iteration per frame), and from then on match_frame's output is match's
// with FieldModel::plane, bit for bit; every frame's pass equals the naive pass along that field.
TEST(MatchFrame, StaticRigReachesThePlaneFieldOutput) {
    auto rng = test::seeded_rng(45);
    const Image left = test::random_image(96, 72, 3, rng);
    // The right image lower by 1 row at the left edge to 3 at the right (a roll), 5 columns
    // across: a plane with a slope, which takes fits, not only the mode.
    Image right = test::random_image(left.width, left.height, 3, rng);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x + 5 < left.width; ++x) {
            const int sy = y - (1 + 3 * x / left.width);
            for (int c = 0; sy >= 0 && c < 3; ++c) {
                right.at(x, y, c) = left.at(x + 5, sy, c);
            }
        }
    }
    Params params;
    params.ndisp = 16;
    params.vrange = 16;
    params.cost = "census";
    params.field_model = FieldModel::plane;
    params.validation = {true, 6, true, 0, true};
    const Result reference = match(left, right, params);
    const Plane converged = vertical_plane(reference.levels[2]);

    PlaneTracker tracker;
    int frames_to_converge = -1;
    for (int frame = 0; frame < 8 && frames_to_converge < 0; ++frame) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const PlaneSetting setting = tracker.setting();
        const FrameResult out = match_frame(left, right, params, setting);
        const SearchRange range = level_range(params, 1);
        EXPECT_EQ(out.result.field, naive::plane_field(setting.plane, left.width, left.height,
                                                       range.v_min, range.v_max));
        const ValidatedDisparity naive_pass =
            naive::match_along_field(left, right, out.result.field, params);
        EXPECT_TRUE(test::same_validated(naive_pass, out.result.validated));
        if (setting.plane == converged && frames_to_converge < 0) {
            frames_to_converge = frame;
            EXPECT_EQ(out.result.field, reference.field);
            EXPECT_TRUE(test::same_validated(reference.validated, out.result.validated));
        }
        tracker.update(out.statistics);
    }
    std::cout << "[plane] frames to reach vertical_plane's plane: " << frames_to_converge << '\n';
    // The plane slopes down across (about 2 rows over the width), so the mode is not the plane.
    EXPECT_GT(converged.b * left.width, kPlaneOne);
    EXPECT_LT(std::abs(converged.c) * left.height, kPlaneOne / 2);
    EXPECT_GE(frames_to_converge, 2);  // the start frame and the mode frame come first
    EXPECT_LE(frames_to_converge, 6);
}

}  // namespace
}  // namespace stereo::hierarchical
