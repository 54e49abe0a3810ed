// The edge-enhanced front end (thesis Sec. 4.1.1) against its naive reference, bit for bit, and
// hand-computed cases of each new stage.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <tuple>

#include "stereo/edge_frontend.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

namespace ef = edge_frontend;

struct Case {
    int width;
    int height;
    int channels;
    int ndisp;
    int window;
};

class EdgeStagesEqualNaive : public ::testing::TestWithParam<Case> {};

TEST_P(EdgeStagesEqualNaive, EveryStageBitExact) {
    const Case c = GetParam();
    const auto [left, right] =
        test::seeded_shifted_pair(c.width, c.height, c.channels, 3, 6, c.width * 7 + c.channels);
    const ef::EdgeParams edges;
    const auto kernel = gaussian_kernel(edges.log_window, edges.log_sigma);

    const Image grey = ef::luma(left);
    ASSERT_EQ(ef::naive::luma(left).pixels, grey.pixels) << "luma";
    const ef::Response response = ef::log_response(grey, kernel);
    ASSERT_EQ(ef::naive::log_response(grey, kernel), response) << "log_response";
    const Image crossings = ef::zero_crossings(response);
    ASSERT_EQ(ef::naive::zero_crossings(response).pixels, crossings.pixels) << "zero_crossings";
    for (const int value : {0, 255}) {
        ASSERT_EQ(ef::naive::superimpose(left, crossings, value).pixels,
                  ef::superimpose(left, crossings, value).pixels)
            << "superimpose " << value;
    }
    for (const int truncation : {0, 31, 765}) {
        ASSERT_EQ(ef::naive::truncated_cost(left, right, c.ndisp, truncation),
                  ef::truncated_cost(left, right, c.ndisp, truncation))
            << "truncated_cost " << truncation;
    }
    MatchParams params;
    params.ndisp = c.ndisp;
    params.window = c.window;
    ASSERT_EQ(ef::naive::match(left, right, params), ef::match(left, right, params));
}

INSTANTIATE_TEST_SUITE_P(RandomOddSizes, EdgeStagesEqualNaive,
                         ::testing::Values(Case{37, 23, 1, 8, 5}, Case{41, 29, 3, 12, 7},
                                           Case{64, 17, 3, 5, 3}, Case{9, 31, 1, 3, 1}));

TEST(EdgeFrontend, LumaIsBt601Integer) {
    Image colour(2, 1, 3);
    colour.at(0, 0, 0) = 255;  // pure red: (77 * 255 + 128) >> 8 = 77
    colour.at(1, 0, 0) = 10;
    colour.at(1, 0, 1) = 20;
    colour.at(1, 0, 2) = 30;  // 770 + 3000 + 870 = 4640; (4640 + 128) >> 8 = 18
    const Image grey = ef::luma(colour);
    EXPECT_EQ(grey.at(0, 0, 0), 77);
    EXPECT_EQ(grey.at(1, 0, 0), 18);
}

TEST(EdgeFrontend, FlatImageHasNoEdgesAndAStepHasThem) {
    const auto kernel = gaussian_kernel(5, 1.0);
    Image flat(12, 9, 1);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 100);
    const ef::Response zero = ef::log_response(flat, kernel);
    for (const auto v : zero.values) {
        ASSERT_EQ(v, 0);
    }
    for (const auto e : ef::zero_crossings(zero).pixels) {
        ASSERT_EQ(e, 0);
    }
    // A vertical step between x = 5 and x = 6: the LoG is positive on the dark side and negative
    // on the bright side, so the crossing is marked at x = 5 in every row; the flat zero
    // response beyond the negative lobe (x >= 9) is not a sign change, so x = 8 is no edge.
    Image step = flat;
    for (int y = 0; y < step.height; ++y) {
        for (int x = 6; x < step.width; ++x) {
            step.at(x, y, 0) = 200;
        }
    }
    const ef::Response response = ef::log_response(step, kernel);
    EXPECT_GT(response.at(5, 4), 0);
    EXPECT_LT(response.at(6, 4), 0);
    const Image edges = ef::zero_crossings(response);
    for (int y = 0; y < step.height; ++y) {
        EXPECT_EQ(edges.at(5, y, 0), 1) << y;
        EXPECT_EQ(edges.at(0, y, 0), 0) << y;
        EXPECT_EQ(edges.at(8, y, 0), 0) << y;
        EXPECT_EQ(edges.at(11, y, 0), 0) << y;
    }
}

TEST(EdgeFrontend, TruncatedCostHandComputed) {
    Image left(3, 1, 1);
    Image right(3, 1, 1);
    left.pixels = {10, 50, 60};
    right.pixels = {12, 40, 200};
    const Dsi cost = ef::truncated_cost(left, right, 2, 31);
    EXPECT_EQ(cost.at(0, 0, 0), 6);   // 3 * |10 - 12|
    EXPECT_EQ(cost.at(1, 0, 0), 30);  // 3 * 10
    EXPECT_EQ(cost.at(2, 0, 0), 31);  // 3 * 140, truncated
    EXPECT_EQ(cost.at(0, 0, 1), fx::kCostOutside);
    EXPECT_EQ(cost.at(1, 0, 1), 31);  // 3 * |50 - 12| = 114, truncated
    EXPECT_EQ(cost.at(2, 0, 1), 31);  // 3 * 20 = 60, truncated
}

TEST(EdgeFrontend, FindsAShiftOnTexture) {
    const auto [left, right] = test::seeded_shifted_pair(60, 30, 1, 4, 2);
    MatchParams params;
    params.ndisp = 8;
    params.window = 5;
    const DisparityMap map = ef::match(left, right, params);
    const test::ValidCount count = test::count_valid_at(map.valid, map.disparity, 4);
    EXPECT_GT(count.valid, 0);
    EXPECT_GT(count.at_value, count.valid * 9 / 10);
}

TEST(EdgeFrontend, RejectsBadParameters) {
    const Image image(10, 10, 1);
    ef::EdgeParams bad;
    bad.edge_value = 256;
    EXPECT_THROW(ef::enhance(image, bad), std::invalid_argument);
    bad = {};
    bad.log_window = 4;
    EXPECT_THROW(ef::enhance(image, bad), std::invalid_argument);
    EXPECT_THROW(ef::truncated_cost(image, image, 2, 766), std::invalid_argument);
    EXPECT_THROW(ef::truncated_cost(image, Image(11, 10, 1), 2, 31), std::invalid_argument);
    EXPECT_THROW(ef::superimpose(image, Image(9, 10, 1), 255), std::invalid_argument);
}

}  // namespace
}  // namespace stereo
