// Stage 6 (validation, sub-pixel output, minimum disparity): the model's streaming selector
// against the naive reference that scans whole final volumes, the per-pixel arithmetic against
// exact rationals, and hand-made pairs whose answers are known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "stereo/pipeline.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/validate.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using test::same_validated;

// ---- the per-pixel arithmetic against exact rationals ---------------------------------------

TEST(ValidationArithmetic, SubpixelOffsetIsTheRoundedParabolaVertex) {
    // Every cost triple with the centre the minimum, up to a size where all cases are cheap; the
    // vertex (before - after) / (2 (before + after - 2 centre)) in 1/16 is compared with an
    // exact rational rounding, halves away from zero.
    for (int centre = 0; centre <= 40; centre += 7) {
        for (int before = centre; before <= centre + 60; ++before) {
            for (int after = centre; after <= centre + 60; ++after) {
                const int den = before + after - 2 * centre;
                int expected = 0;
                if (den > 0) {
                    const int num = 8 * (before - after);  // offset = num / den sixteenths
                    const int mag = std::abs(num);
                    // round(mag / den), halves up: the largest q with q - 1/2 <= mag / den.
                    int q = 0;
                    while (2 * (q + 1) * den <= 2 * mag + den) {
                        ++q;
                    }
                    expected = num >= 0 ? q : -q;
                }
                ASSERT_EQ(validation::parabola_offset(before, centre, after), expected)
                    << before << " " << centre << " " << after;
                ASSERT_LE(std::abs(expected), fx::kSubpixelScale / 2);
                // Stage 6's offset: the vertex through the correction table, sign kept.
                const int corrected = fx::kSubpixelCorrection.at(std::abs(expected));
                ASSERT_EQ(validation::subpixel_offset(before, centre, after),
                          expected >= 0 ? corrected : -corrected);
            }
        }
    }
    // Hand cases: a symmetric valley has its vertex on the label; (4, 0, 0) is halfway to d + 1
    // (the parabola through (-1,4), (0,0), (1,0) has its vertex at +1/2 = 8/16).
    EXPECT_EQ(validation::parabola_offset(10, 2, 10), 0);
    EXPECT_EQ(validation::parabola_offset(4, 0, 0), 8);
    EXPECT_EQ(validation::parabola_offset(0, 0, 4), -8);
    // (6, 2, 4): vertex (6 - 4) / (2 * 6) = 1/6 pixel = 2.67/16 -> 3.
    EXPECT_EQ(validation::parabola_offset(6, 2, 4), 3);
    EXPECT_EQ(validation::parabola_offset(5, 5, 5), 0);  // flat: no curvature
    // Through the table {0, 2, 4, 5, 6, 6, 7, 8, 8} (docs/fixed-point.md): 0 and +-8 stay, 3 -> 5.
    EXPECT_EQ(validation::subpixel_offset(10, 2, 10), 0);
    EXPECT_EQ(validation::subpixel_offset(4, 0, 0), 8);
    EXPECT_EQ(validation::subpixel_offset(0, 0, 4), -8);
    EXPECT_EQ(validation::subpixel_offset(6, 2, 4), 5);
    EXPECT_EQ(validation::subpixel_offset(4, 2, 6), -5);
    // A centre that is not the minimum (no caller does this): the vertex lies outside half a
    // pixel, (0 - 20) / (2 * 10) = -1 px = -16/16, and the table index stays inside.
    EXPECT_EQ(validation::parabola_offset(0, 5, 20), -16);
    EXPECT_EQ(validation::subpixel_offset(0, 5, 20), -8);
}

TEST(ValidationArithmetic, CertaintyAndUniqueness) {
    for (int c2 = 0; c2 <= fx::kAggMax; c2 += 37) {
        for (int c1 = 0; c1 <= c2; c1 += 11) {
            const double exact = 256.0 * (c2 - c1) / (c2 + 1.0);
            ASSERT_EQ(validation::certainty(c1, c2), static_cast<int>(std::floor(exact)));
            ASSERT_LE(validation::certainty(c1, c2), 255);
            for (const int ratio : {0, 5, 10, 15, 50, 255}) {
                // Unique when c2 exceeds c1 by more than ratio percent.
                const bool expected = 100.0 * c2 > (100.0 + ratio) * c1;
                ASSERT_EQ(validation::unique(c1, c2, ratio), expected) << c1 << " " << c2;
            }
        }
    }
    EXPECT_TRUE(validation::unique(fx::kAggMax, fx::kNoSecondCost, 255));  // no second label
    EXPECT_EQ(validation::certainty(5, 5), 0);
    EXPECT_EQ(validation::certainty(0, 255), 255);  // 256 * 255 / 256
}

// ---- the streaming selector against the naive reference --------------------------------------

struct Case {
    int width, height, channels, ndisp, min_disp, window, shift;
    bool use_ca;
    const char* cost;
};

class ValidationEqualsNaive : public ::testing::TestWithParam<Case> {};

TEST_P(ValidationEqualsNaive, EveryStageCombination) {
    const Case c = GetParam();
    const auto [left, right] = test::seeded_shifted_pair(c.width, c.height, c.channels, c.shift, 30,
                                                         c.width * 7 + c.ndisp);
    MatchParams params{c.ndisp, c.window, 2.0, c.use_ca, c.cost};
    params.min_disp = c.min_disp;
    for (const bool uniqueness : {false, true}) {
        for (const bool left_right : {false, true}) {
            for (const bool subpixel : {false, true}) {
                params.validation = {uniqueness, uniqueness ? 15 : 10, left_right,
                                     left_right ? 0 : 1, subpixel};
                const auto expected = naive::match_validated(left, right, params);
                ASSERT_TRUE(same_validated(expected, match_validated(left, right, params)))
                    << "uniqueness " << uniqueness << " left-right " << left_right << " subpixel "
                    << subpixel;
                ASSERT_EQ(to_label_map(expected), match(left, right, params));
            }
        }
    }
    // The ratio and the tolerance reach the arithmetic (other values than above).
    params.validation = {true, 0, true, 3, true};
    ASSERT_TRUE(same_validated(naive::match_validated(left, right, params),
                               match_validated(left, right, params)));
}

INSTANTIATE_TEST_SUITE_P(
    RandomPairs, ValidationEqualsNaive,
    ::testing::Values(
        Case{37, 23, 3, 8, 0, 5, 3, true, "ad"}, Case{37, 23, 1, 8, -4, 5, -2, true, "ad"},
        Case{48, 20, 3, 12, -10, 3, -6, false, "ad"}, Case{41, 29, 3, 6, 2, 1, 4, true, "census"},
        Case{30, 16, 3, 1, 0, 3, 0, true, "ad"},   // one label: no neighbours
        Case{30, 16, 3, 3, -1, 3, 0, true, "ad"},  // no label outside the winner's
        Case{30, 16, 3, 4, 5, 3, 6, false, "ad"}, Case{64, 48, 3, 16, -8, 11, -5, true, "ad"}));

// With every stage off and min_disp 0, the validated output is the plain pipeline's.
TEST(Validation, OffIsThePlainPipeline) {
    const auto [left, right] = test::seeded_shifted_pair(70, 33, 3, 7, 20, 5);
    const MatchParams params{16, 7, 2.0, true};
    const ValidatedDisparity validated = match_validated(left, right, params);
    const DisparityMap plain = match(left, right, params);
    EXPECT_EQ(to_label_map(validated), plain);
    for (std::size_t i = 0; i < plain.valid.size(); ++i) {
        ASSERT_EQ(validated.reason[i], plain.valid[i] != 0 ? fx::kReasonValid : fx::kReasonBorder);
        ASSERT_EQ(validated.fixed[i], plain.disparity[i] * fx::kSubpixelScale);
    }
}

// A negative true disparity is found only when the range reaches it.
TEST(Validation, NegativeDisparitiesNeedAMinimumDisparity) {
    const auto [left, right] = test::seeded_shifted_pair(80, 30, 3, -6, 0, 9);  // d = -6 everywhere
    MatchParams params{12, 5, 1.5, true};
    params.min_disp = -10;
    const ValidatedDisparity out = match_validated(left, right, params);
    const InvalidBorder border = invalid_border(params);
    int checked = 0;
    for (int y = 0; y < out.height; ++y) {
        // Columns whose right window stays clear of the clamped copy at the right edge.
        for (int x = 0; x + 6 + border.reach < out.width; ++x) {
            const auto i = out.index(x, y);
            if (!border.window_inside(x, y, out.width, out.height)) {
                continue;
            }
            ASSERT_EQ(out.reason[i], fx::kReasonValid) << x << "," << y;
            ASSERT_EQ(out.fixed[i], -6 * fx::kSubpixelScale) << x << "," << y;
            ++checked;
        }
    }
    EXPECT_GT(checked, 500);
    // With min_disp 0 the true match is outside the range: never -6.
    params.min_disp = 0;
    for (const auto value : match_validated(left, right, params).fixed) {
        ASSERT_GE(value, 0);
    }
}

// Left-right check: where the right image's content is missing from the left image (an
// occlusion), the two winners disagree. A pair with a band occluded in the left view.
TEST(Validation, LeftRightCheckFlagsOcclusions) {
    auto rng = test::seeded_rng(11);
    const Image background = test::random_image(90, 30, 3, rng);
    const Image foreground = test::random_image(90, 30, 3, rng);
    // Right: foreground at x in [32, 52). Left: the foreground at x in [40, 60) (disparity 8),
    // the background everywhere else at disparity 2.
    Image left(90, 30, 3);
    Image right(90, 30, 3);
    for (int y = 0; y < 30; ++y) {
        for (int x = 0; x < 90; ++x) {
            for (int c = 0; c < 3; ++c) {
                right.at(x, y, c) =
                    (x >= 32 && x < 52) ? foreground.at(x, y, c) : background.at(x, y, c);
                const int fx_source = x - 8;
                const int bg_source = x - 2;
                const bool in_front = x >= 40 && x < 60;
                left.at(x, y, c) = in_front ? foreground.at(fx_source, y, c)
                                            : background.at(std::max(bg_source, 0), y, c);
            }
        }
    }
    MatchParams params{16, 5, 1.5, false};
    params.validation.left_right = true;
    params.validation.lr_tolerance = 0;
    const ValidatedDisparity checked = match_validated(left, right, params);
    EXPECT_TRUE(same_validated(naive::match_validated(left, right, params), checked));
    int flagged = 0;
    for (int y = 3; y < 27; ++y) {
        // Left pixels 34..39 show background at right x - 2 = 32..37, where the right view
        // shows the foreground: occluded.
        for (int x = 34; x < 40; ++x) {
            flagged += checked.reason[checked.index(x, y)] == fx::kReasonLeftRight ? 1 : 0;
        }
    }
    EXPECT_GT(flagged, 24 * 6 / 2) << "most occluded pixels fail the left-right check";
}

TEST(Validation, RealPairCropEqualsNaive) {
    const auto dir = io::data_dir() / "middlebury2003" / "teddy";
    if (!std::filesystem::exists(dir / "left.png") || !std::filesystem::exists(dir / "right.png")) {
        GTEST_SKIP() << "Middlebury teddy not found under " << dir;
    }
    const cv::Rect crop(150, 120, 110, 70);
    const Image left = io::to_image(io::load_bgr(dir / "left.png")(crop), "left");
    const Image right = io::to_image(io::load_bgr(dir / "right.png")(crop), "right");
    MatchParams params{40, 11, fx::kDefaultSigma, true};
    params.min_disp = -4;
    params.validation = {true, 10, true, 1, true};
    EXPECT_TRUE(same_validated(naive::match_validated(left, right, params),
                               match_validated(left, right, params)));
}

TEST(Validation, RejectsImpossibleParameters) {
    MatchParams params{16, 5, 2.0, true};
    params.min_disp = fx::kMaxMinDisparity + 1;
    EXPECT_THROW(validate(params, 5000, 100), std::invalid_argument);
    params.min_disp = 100;  // the whole range lies right of a 100-pixel image
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
    params.min_disp = -115;  // -115 .. -100: every match leaves the image
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
    params.min_disp = -50;
    EXPECT_NO_THROW(validate(params, 100, 100));
    params.validation.uniqueness_ratio = fx::kMaxUniqueness + 1;
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
    params.validation.uniqueness_ratio = -1;
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
    params.validation.uniqueness_ratio = 10;
    params.validation.lr_tolerance = -1;
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
}

}  // namespace
}  // namespace stereo
