// The keyed images of the CLI (stereo_io/colour_key.hpp, issue 47): invalid drawn in a colour
// TURBO never uses, the colour bar's ends are the colour map's ends, the strips are optional.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "stereo_io/colour_key.hpp"
#include "stereo_io/io.hpp"

namespace stereo::io {
namespace {

cv::Vec3b turbo(int value) {
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(value));
    cv::Mat colour;
    cv::applyColorMap(one, colour, cv::COLORMAP_TURBO);
    return colour.at<cv::Vec3b>(0, 0);
}

double distance(const cv::Vec3b& a, const cv::Vec3b& b) {
    return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

DisparityMap ramp_map(int width, int height, int ndisp) {
    DisparityMap map(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const auto i = map.index(x, y);
            map.disparity[i] = static_cast<std::uint8_t>(x * (ndisp - 1) / (width - 1));
            map.valid[i] = (x + y) % 7 != 0 ? 1 : 0;
        }
    }
    return map;
}

TEST(ColourKey, InvalidIsFarFromEveryTurboColour) {
    double nearest = 1e9;
    for (int v = 0; v < 256; ++v) {
        nearest = std::min(nearest, distance(turbo(v), kInvalidColour));
    }
    // Black, the old invalid colour, is within about 80 of TURBO's dark purple end.
    EXPECT_GT(nearest, 100.0);
    EXPECT_LT(distance(turbo(0), cv::Vec3b(0, 0, 0)), 90.0);
}

TEST(ColourKey, ViewKeepsTheMapAndAddsABar) {
    const int ndisp = 32;
    const DisparityMap map = ramp_map(200, 40, ndisp);
    const cv::Mat bare = colour_view(map, ndisp, 0, false);
    const cv::Mat keyed = colour_view(map, ndisp, 0, true);
    ASSERT_EQ(bare.size(), cv::Size(200, 40));
    ASSERT_EQ(keyed.size(), cv::Size(200, 40 + kKeyHeight));
    EXPECT_EQ(cv::norm(keyed.rowRange(0, 40), bare, cv::NORM_INF), 0.0);
    const cv::Mat plain = disparity_to_colour(map, ndisp);
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 200; ++x) {
            const bool valid = map.valid[map.index(x, y)] != 0;
            EXPECT_EQ(bare.at<cv::Vec3b>(y, x), valid ? plain.at<cv::Vec3b>(y, x) : kInvalidColour)
                << x << "," << y;
        }
    }
    // The bar's first column is label 0's colour, and label ndisp-1's colour is in the bar.
    const int bar_row = 40 + 4;
    EXPECT_EQ(keyed.at<cv::Vec3b>(bar_row, 0), turbo(0));
    bool has_last = false;
    bool has_invalid_swatch = false;
    for (int x = 0; x < 200; ++x) {
        has_last = has_last || keyed.at<cv::Vec3b>(bar_row, x) == turbo(255);
        has_invalid_swatch =
            has_invalid_swatch || keyed.at<cv::Vec3b>(bar_row, x) == kInvalidColour;
    }
    EXPECT_TRUE(has_last);
    EXPECT_TRUE(has_invalid_swatch);
    // Tick labels are drawn: the text rows are not all black.
    EXPECT_GT(cv::countNonZero(keyed.rowRange(40 + 16, 40 + kKeyHeight).reshape(1)), 0);
}

TEST(ColourKey, NarrowMapsStillGetABar) {
    const DisparityMap map = ramp_map(16, 8, 4);
    const cv::Mat keyed = colour_view(map, 4, -2, true);
    EXPECT_EQ(keyed.size(), cv::Size(16, 8 + kKeyHeight));
}

TEST(ColourKey, ErrorLegendKeepsTheMap) {
    cv::Mat errors(20, 120, CV_8UC3, cv::Scalar(128, 128, 128));
    const cv::Mat legend = with_error_legend(errors);
    ASSERT_EQ(legend.size(), cv::Size(120, 20 + kKeyHeight));
    EXPECT_EQ(cv::norm(legend.rowRange(0, 20), errors, cv::NORM_INF), 0.0);
    // The red and blue swatches are in the strip.
    bool red = false;
    bool blue = false;
    for (int y = 20; y < legend.rows; ++y) {
        for (int x = 0; x < legend.cols; ++x) {
            red = red || legend.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 255);
            blue = blue || legend.at<cv::Vec3b>(y, x) == cv::Vec3b(255, 0, 0);
        }
    }
    EXPECT_TRUE(red);
    EXPECT_TRUE(blue);
}

}  // namespace
}  // namespace stereo::io
