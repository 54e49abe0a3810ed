// The optimised golden-model stages against the naive reference, bit for bit, and hand-made
// cases whose expected values are worked out in the comments.
#include <gtest/gtest.h>
#include <algorithm>

#include <filesystem>
#include <random>

#include "middlebury_crop.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/reference.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using test::same_map;
using test::same_volume;

struct Case {
    int width, height, channels, ndisp, window;
    double sigma;
};

class StagesEqualNaive : public ::testing::TestWithParam<Case> {};

TEST_P(StagesEqualNaive, EveryStageBitExact) {
    const Case c = GetParam();
    const auto [left, right] =
        test::seeded_shifted_pair(c.width, c.height, c.channels, 3, 20, c.width * 131 + c.window);
    const auto kernel = gaussian_kernel(c.window, c.sigma);

    const Dsi costs = cost(left, right, c.ndisp);
    ASSERT_TRUE(same_volume(naive::cost(left, right, c.ndisp), costs)) << "cost";
    const Dsi aggregated = aggregate(costs, kernel);
    ASSERT_TRUE(same_volume(naive::aggregate(costs, kernel), aggregated)) << "aggregate";
    const Dsi rule1 = ca_rule1(aggregated);
    ASSERT_TRUE(same_volume(naive::ca_rule1(aggregated), rule1)) << "ca_rule1";
    const Dsi rule2 = ca_rule2(rule1);
    ASSERT_TRUE(same_volume(naive::ca_rule2(rule1), rule2)) << "ca_rule2";
    const MatchParams params{c.ndisp, c.window, c.sigma, true};
    ASSERT_TRUE(
        same_map(naive::wta(rule2, invalid_border(params)), wta(rule2, invalid_border(params))));
    ASSERT_TRUE(same_map(naive::match(left, right, params), match(left, right, params)));
    // match() streams the planes through the same kernels; it must equal the volume stages.
    ASSERT_TRUE(same_map(wta(rule2, invalid_border(params)), match(left, right, params)));
    MatchParams no_ca = params;
    no_ca.use_ca = false;
    ASSERT_TRUE(same_map(naive::match(left, right, no_ca), match(left, right, no_ca)));
}

INSTANTIATE_TEST_SUITE_P(RandomOddSizes, StagesEqualNaive,
                         ::testing::Values(Case{37, 23, 3, 8, 5, 1.5}, Case{37, 23, 1, 8, 5, 1.5},
                                           Case{64, 48, 3, 16, 11, 3.0}, Case{41, 29, 3, 5, 1, 1.0},
                                           Case{53, 40, 3, 12, 31, 20.0},
                                           Case{631, 479, 3, 16, 11, 3.0}));

// Extreme images: all zero, all 255, and one black / one white. Costs hit 0 and fx::kCostMax.
TEST(StagesEqualNaive, ConstantAndExtremeImages) {
    for (const auto& [l, r, left, right] : test::constant_pairs(40, 30, 3)) {
        const MatchParams params{8, 5, 2.0, true};
        const Dsi costs = cost(left, right, params.ndisp);
        EXPECT_TRUE(same_volume(naive::cost(left, right, params.ndisp), costs));
        EXPECT_EQ(costs.at(20, 10, 3), 3 * std::abs(l - r));
        const Dsi aggregated = aggregate(costs, gaussian_kernel(5, 2.0));
        // Interior cells average a constant: the weighted mean is exact, times 2^kAggFracBits.
        EXPECT_EQ(aggregated.at(20, 15, 3), (3 * std::abs(l - r)) << fx::kAggFracBits);
        EXPECT_TRUE(same_map(naive::match(left, right, params), match(left, right, params)));
    }
}

TEST(StagesEqualNaive, RealPairCrop) {
    const auto pair = test::middlebury_crop("cones", 200, 150, 120, 90);
    if (!pair) {
        GTEST_SKIP() << "Middlebury cones not found under " << io::data_dir();
    }
    const MatchParams params{40, 11, fx::kDefaultSigma, true};
    EXPECT_TRUE(same_map(naive::match(pair->left, pair->right, params),
                         match(pair->left, pair->right, params)));
}

TEST(Cost, HandComputed) {
    // Left row (10,20,30) (40,50,60); right row (13,18,30) (0,0,0).
    Image left(2, 1, 3);
    Image right(2, 1, 3);
    left.pixels = {10, 20, 30, 40, 50, 60};
    right.pixels = {13, 18, 30, 0, 0, 0};
    const Dsi c = cost(left, right, 2);
    EXPECT_EQ(c.at(0, 0, 0), 3 + 2 + 0);
    EXPECT_EQ(c.at(1, 0, 0), 40 + 50 + 60);
    EXPECT_EQ(c.at(0, 0, 1), fx::kCostMax);  // x - d < 0: the right pixel is outside
    EXPECT_EQ(c.at(1, 0, 1), 27 + 32 + 30);  // left(1) against right(0)
    Image grey_left(2, 1, 1);
    Image grey_right(2, 1, 1);
    grey_left.pixels = {100, 7};
    grey_right.pixels = {90, 0};
    EXPECT_EQ(cost(grey_left, grey_right, 1).at(0, 0, 0), 30);  // 3 * |100 - 90|
}

TEST(CaRule1, HandComputed) {
    // 3x3x3 volume. Plane d=1 holds 1..9 with centre 10 instead of 5; plane 0 holds 12 at the
    // centre: |10 - 12| = 2 < 10/2 so the centre fires and becomes round((1+2+3+4+10+6+7+8+9)/9)
    // = round(50/9) = round(5.56) = 6.
    Dsi dsi(3, 3, 3);
    const int plane1[9] = {1, 2, 3, 4, 10, 6, 7, 8, 9};
    for (int i = 0; i < 9; ++i) {
        dsi.at(i % 3, i / 3, 1) = static_cast<Dsi::Value>(plane1[i]);
        dsi.at(i % 3, i / 3, 0) = 100;
        dsi.at(i % 3, i / 3, 2) = 100;
    }
    dsi.at(1, 1, 0) = 12;
    const Dsi out = ca_rule1(dsi);
    EXPECT_EQ(out.at(1, 1, 1), 6);
    // Corner (0,0,1) = 1: neighbours 100 and 100 differ by 99 >= 0.5, unchanged.
    EXPECT_EQ(out.at(0, 0, 1), 1);
    // Plane 0 centre 12: its only d-neighbour (d=1) is 10, |12-10| = 2 < 6: fires. Zero padding
    // is not involved at the centre: round((8*100 + 12) / 9) = round(90.2) = 90.
    EXPECT_EQ(out.at(1, 1, 0), 90);
    // Plane 0 corner (0,0) = 100, d-neighbour 1: no. Plane 2 corner 100 vs 1: no.
    EXPECT_EQ(out.at(0, 0, 0), 100);
    // Plane 2 centre 100 vs 10: no.
    EXPECT_EQ(out.at(1, 1, 2), 100);
}

TEST(CaRule2, HandComputed) {
    // Centre 40; neighbours 30 (|10| < 20 yes) x6, 61 (|21| no) x1, 59 (|19| yes) x1: 7 agree,
    // so the centre becomes round(40 / 1.3) = round(30.77) = 31. With two disagreeing
    // neighbours it stays 40.
    Dsi dsi(3, 3, 1);
    const int plane[9] = {30, 30, 30, 30, 40, 30, 30, 61, 59};
    for (int i = 0; i < 9; ++i) {
        dsi.at(i % 3, i / 3, 0) = static_cast<Dsi::Value>(plane[i]);
    }
    EXPECT_EQ(ca_rule2(dsi).at(1, 1, 0), 31);
    dsi.at(2, 2, 0) = 61;
    EXPECT_EQ(ca_rule2(dsi).at(1, 1, 0), 40);
    // Border cells have at most 5 neighbours inside the image: never divided.
    EXPECT_EQ(ca_rule2(dsi).at(0, 0, 0), 30);
}

TEST(Wta, TiesGoToSmallestDisparityAndBorderIsInvalid) {
    Dsi dsi(4, 1, 3);
    // x=0: 5 5 5 -> 0; x=1: 9 4 4 -> 1; x=2: 3 2 1 -> 2; x=3: 7 7 1 -> 2.
    const int values[3][4] = {{5, 9, 3, 7}, {5, 4, 2, 7}, {5, 4, 1, 1}};
    for (int d = 0; d < 3; ++d) {
        for (int x = 0; x < 4; ++x) {
            dsi.at(x, 0, d) = static_cast<Dsi::Value>(values[d][x]);
        }
    }
    const DisparityMap all = wta(dsi, InvalidBorder{});
    EXPECT_EQ(all.disparity, (std::vector<std::uint8_t>{0, 1, 2, 2}));
    EXPECT_EQ(all.valid, (std::vector<std::uint8_t>{1, 1, 1, 1}));
    // Reach 0: x=2 wins d=2 and x - d = 0 >= 0, valid; x=1 wins d=1, valid.
    // With a 1x... image height 1 any reach >= 1 leaves no row inside: all invalid.
    const DisparityMap none = wta(dsi, InvalidBorder{1});
    EXPECT_EQ(none.valid, (std::vector<std::uint8_t>{0, 0, 0, 0}));
    EXPECT_EQ(none.disparity, (std::vector<std::uint8_t>{0, 0, 0, 0}));
}

TEST(Wta, WinnerMustKeepItsWindowInsideTheRightImage) {
    // 5x3 image, reach 1: only row 1, columns 1..3 have their window inside. At x=1 a winning
    // d=1 would read right column x - d - reach = -1: invalid; at x=3, d=1 is fine.
    Dsi dsi(5, 3, 2);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 5; ++x) {
            dsi.at(x, y, 0) = 10;
            dsi.at(x, y, 1) = 5;  // d = 1 wins everywhere
        }
    }
    const DisparityMap map = wta(dsi, InvalidBorder{1});
    EXPECT_EQ(map.valid, (std::vector<std::uint8_t>{0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0}));
    EXPECT_EQ(map.disparity[map.index(2, 1)], 1);
    EXPECT_EQ(map.disparity[map.index(1, 1)], fx::kInvalidDisparity);
}

TEST(InvalidBorderTest, ReachIsRadiusPlusOneWithCa) {
    EXPECT_EQ(invalid_border({16, 11, 3.0, true}).reach, 5 + 1);
    EXPECT_EQ(invalid_border({16, 11, 3.0, false}).reach, 5);
    EXPECT_EQ(invalid_border({1, 1, 3.0, false}).reach, 0);
}

TEST(Match, RecoversAShiftAndFlagsEveryPixelByTheBorderRule) {
    const auto [left, right] =
        test::seeded_shifted_pair(80, 40, 3, 5, 0);  // right(x) = left(x + 5): d = 5
    const MatchParams params{12, 5, 1.5, true};
    const DisparityMap map = match(left, right, params);
    const InvalidBorder border = invalid_border(params);
    int wrong = 0;
    int valid = 0;
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const auto i = map.index(x, y);
            if (map.valid[i] == 0) {
                ASSERT_EQ(map.disparity[i], fx::kInvalidDisparity) << x << "," << y;
                // An invalid pixel is one whose window leaves the image or whose winner reads
                // outside the right image; the true d = 5 would have been valid and must not be
                // where it was also the unique best match (checked below).
                ASSERT_FALSE(border.valid(x, y, 5, map.width, map.height) &&
                             x + 5 + border.reach < map.width)
                    << "pixel " << x << "," << y << " with a clean d=5 match marked invalid";
                continue;
            }
            ++valid;
            ASSERT_TRUE(border.valid(x, y, map.disparity[i], map.width, map.height));
            // Columns whose right window is untouched by the clamped copy must recover d = 5.
            if (x - 5 >= border.reach && x + 5 + border.reach < map.width &&
                map.disparity[i] != 5) {
                ++wrong;
            }
        }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(valid, 0);
}

TEST(Validate, RejectsImpossibleParameters) {
    EXPECT_THROW(validate({0, 11, 3.0, true}, 100, 100), std::invalid_argument);
    EXPECT_THROW(validate({100, 11, 3.0, true}, 100, 100), std::invalid_argument);
    EXPECT_THROW(validate({257, 11, 3.0, true}, 1000, 100), std::invalid_argument);
    EXPECT_THROW(validate({16, 10, 3.0, true}, 100, 100), std::invalid_argument);
    EXPECT_THROW(validate({16, 33, 3.0, true}, 100, 100), std::invalid_argument);
    EXPECT_THROW(validate({16, 11, 0.0, true}, 100, 100), std::invalid_argument);
    EXPECT_THROW(validate({16, 11, 3.0, true}, 100, 12), std::invalid_argument);  // too small
    EXPECT_NO_THROW(validate({16, 11, 3.0, true}, 100, 13));
    EXPECT_THROW(validate({8, 11, 3.0, true}, 12, 100), std::invalid_argument);
    Image a(10, 10, 3);
    Image b(11, 10, 3);
    Image grey(10, 10, 1);
    EXPECT_THROW(check_pair(a, b), std::invalid_argument);
    EXPECT_THROW(check_pair(a, grey), std::invalid_argument);
    EXPECT_THROW(Image(0, 5, 3), std::invalid_argument);
    EXPECT_THROW(Image(5, 5, 2), std::invalid_argument);
}

}  // namespace
}  // namespace stereo

namespace stereo {
namespace {

// The documented sigma limits: a single tap at the lower one, a box (taps within one unit of
// each other) at the upper one, for every window; just outside them, a one-line error.
TEST(Kernel, SigmaLimits) {
    for (int window = fx::kMinWindow; window <= fx::kMaxWindow; window += 2) {
        const auto narrow = gaussian_kernel(window, kMinSigma);
        EXPECT_EQ(narrow[static_cast<std::size_t>(window / 2)], fx::kKernelSum) << window;
        const auto wide = gaussian_kernel(window, kMaxSigma);
        const auto [low, high] = std::minmax_element(wide.begin(), wide.end());
        EXPECT_LE(*high - *low, 1) << window;
    }
    EXPECT_THROW(gaussian_kernel(11, kMinSigma / 2), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(11, kMaxSigma * 2), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(11, 1e-300), std::invalid_argument);
}

}  // namespace
}  // namespace stereo
