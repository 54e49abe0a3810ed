// Point clouds (issue 22): the pinhole back-projection on a hand-computed map and the PLY
// writer read back bit for bit in both formats.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "stereo_io/point_cloud.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::io {
namespace {

TEST(PointCloud, BackProjectsValidPixelsWithPositiveDepth) {
    // 3 x 2 map: d = 10 at (1, 0), d = 4 at (2, 1); NaN and d + doffs <= 0 are skipped.
    cv::Mat disparity(2, 3, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
    disparity.at<float>(0, 1) = 8.0F;   // + doffs 2 = 10
    disparity.at<float>(1, 2) = 2.0F;   // + 2 = 4
    disparity.at<float>(1, 0) = -2.0F;  // + 2 = 0: no depth
    cv::Mat bgr(2, 3, CV_8UC3, cv::Scalar(1, 2, 3));
    bgr.at<cv::Vec3b>(1, 2) = cv::Vec3b(30, 20, 10);
    const CloudGeometry g{100.0, 0.5, 1.0, 0.5, 2.0};
    const auto points = disparity_to_points(disparity, bgr, g);
    ASSERT_EQ(points.size(), 2U);
    // Z = 100 * 0.5 / 10 = 5; X = (1 - 1) * 5 / 100 = 0; Y = (0 - 0.5) * 5 / 100 = -0.025.
    EXPECT_EQ(points[0], (CloudPoint{0.0F, static_cast<float>(-0.025), 5.0F, 3, 2, 1}));
    // Z = 50 / 4 = 12.5; X = 1 * 12.5 / 100 = 0.125; Y = 0.5 * 12.5 / 100 = 0.0625.
    EXPECT_EQ(points[1], (CloudPoint{0.125F, 0.0625F, 12.5F, 10, 20, 30}));
    EXPECT_THROW(disparity_to_points(disparity, cv::Mat(3, 3, CV_8UC3), g), std::invalid_argument);
    EXPECT_THROW(disparity_to_points(disparity, bgr, {0.0, 0.5, 0, 0, 0}), std::invalid_argument);
}

TEST(PointCloud, PlyRoundTripIsExactInBothFormats) {
    auto rng = test::seeded_rng(31);
    std::uniform_real_distribution<float> coordinate(-1e4F, 1e4F);
    std::uniform_int_distribution<int> colour(0, 255);
    std::vector<CloudPoint> points(257);
    for (auto& p : points) {
        p = {coordinate(rng),
             coordinate(rng) * 1e-6F,
             coordinate(rng),
             static_cast<std::uint8_t>(colour(rng)),
             static_cast<std::uint8_t>(colour(rng)),
             static_cast<std::uint8_t>(colour(rng))};
    }
    for (const bool binary : {false, true}) {
        const std::string bytes = encode_ply(points, binary);
        EXPECT_EQ(decode_ply(bytes, "cloud.ply"), points) << (binary ? "binary" : "ascii");
    }
    EXPECT_TRUE(decode_ply(encode_ply({}, false), "empty.ply").empty());
    EXPECT_THROW(decode_ply("ply\nformat ascii 1.0\nend_header\n", "bad.ply"), std::runtime_error);
    std::string truncated = encode_ply(points, true);
    truncated.pop_back();
    EXPECT_THROW(decode_ply(truncated, "short.ply"), std::runtime_error);
}

}  // namespace
}  // namespace stereo::io
