// Middlebury-style metrics (io/include/stereo_io/metrics.hpp) on a 4x3 example worked out by
// hand. Every expected value below is derived in the comment next to it.
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stereo_io/metrics.hpp"

namespace stereo::io {
namespace {

// Ground truth, 0 = unknown:         Ours, 0 = invalid:            Per pixel (threshold 1):
//   10  10  10   0                     10    12  0  5              ok  bad(2)  invalid  unknown
//   20  20  20  20                     20.5  21 19  0              ok  ok(1)   ok(1)    invalid
//   30  30  30  30                     30    33 29 30              ok  bad(3)  ok(1)    ok
//
// known = 11, bad = (1,0) (2,0) (3,1) (1,2) = 4, valid among known = 9.
// Squared errors over the 9: 0 + 4 + 0.25 + 1 + 1 + 0 + 9 + 1 + 0 = 16.25
// Squared GT over the 9:     2 * 100 + 3 * 400 + 4 * 900           = 5000
NamedMat truth() {
    return {(cv::Mat_<float>(3, 4) << 10, 10, 10, 0,  //
             20, 20, 20, 20,                          //
             30, 30, 30, 30),
            "ground truth 'gt.png'"};
}

NamedMat ours() {
    return {(cv::Mat_<float>(3, 4) << 10, 12, 0, 5,  //
             20.5F, 21, 19, 0,                       //
             30, 33, 29, 30),
            "disparity 'd.png'"};
}

NamedMat mask(const cv::Mat& values, const std::string& name) {
    return {values, name};
}

EvalInput example() {
    return {.disparity = ours(), .ground_truth = truth()};
}

template <typename Call>
void expect_invalid(Call&& call, const std::string& part) {
    try {
        call();
        FAIL() << "no exception, expected one mentioning: " << part;
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
}

TEST(Evaluate, WithoutMasksScoresEveryKnownPixelAsAll) {
    const EvalResult result = evaluate(example());
    EXPECT_FALSE(result.nonocc.has_value());
    EXPECT_FALSE(result.disc.has_value());
    EXPECT_EQ(result.all.evaluated, 11);
    EXPECT_EQ(result.all.bad, 4);
    EXPECT_DOUBLE_EQ(*result.all.percent(), 400.0 / 11.0);  // 36.36 %
    EXPECT_EQ(result.known, 11);
    EXPECT_EQ(result.known_and_valid, 9);
    EXPECT_EQ(result.nmse_pixels, 9);
    EXPECT_DOUBLE_EQ(*result.nmse, 16.25 / 5000.0);  // 0.00325
    EXPECT_DOUBLE_EQ(*result.coverage, 9.0 / 11.0);
}

TEST(Evaluate, ThresholdIsStrict) {
    EvalInput input = example();
    // At 0.5, the errors of exactly 1 at (1,1) (2,1) (2,2) become bad; 0.5 at (0,1) does not.
    input.threshold = 0.5;
    EXPECT_EQ(evaluate(input).all.bad, 7);  // 7 of 11 = 63.6 %
    // At 3 only the two invalid pixels are bad: 2 (1,0) and 3 (1,2) are not > 3.
    input.threshold = 3.0;
    EXPECT_EQ(evaluate(input).all.bad, 2);
}

TEST(Evaluate, MasksSelectOnlyValue255) {
    EvalInput input = example();
    // nonocc: known and 255 = (0,0) (1,0) | (0,1) (1,1) (2,1) | (0,2) (2,2) (3,2) = 8 pixels,
    // of which only (1,0) is bad: 1 / 8 = 12.5 %. (3,0) is 255 but its GT is unknown.
    input.nonocc = mask((cv::Mat_<std::uint8_t>(3, 4) << 255, 255, 0, 255,  //
                         255, 255, 255, 0,                                  //
                         255, 0, 255, 255),
                        "nonocc mask 'n.png'");
    // all: everything but (0,0): 10 known pixels, the same 4 bad: 40 %. The NMSE loses (0,0),
    // whose error is 0 and GT 10: 16.25 / (5000 - 100).
    cv::Mat all_values(3, 4, CV_8UC1, cv::Scalar(255));
    all_values.at<std::uint8_t>(0, 0) = 0;
    input.all = mask(all_values, "all mask 'a.png'");
    // disc: 255 at the four bad pixels only; the 128s (occluded in Middlebury) do not count.
    input.disc = mask((cv::Mat_<std::uint8_t>(3, 4) << 128, 255, 255, 0,  //
                       0, 0, 0, 255,                                      //
                       128, 255, 0, 0),
                      "disc mask 'c.png'");

    const EvalResult result = evaluate(input);
    ASSERT_TRUE(result.nonocc.has_value());
    EXPECT_EQ(result.nonocc->evaluated, 8);
    EXPECT_EQ(result.nonocc->bad, 1);
    EXPECT_DOUBLE_EQ(*result.nonocc->percent(), 12.5);
    EXPECT_EQ(result.all.evaluated, 10);
    EXPECT_EQ(result.all.bad, 4);
    EXPECT_DOUBLE_EQ(*result.all.percent(), 40.0);
    ASSERT_TRUE(result.disc.has_value());
    EXPECT_EQ(result.disc->evaluated, 4);
    EXPECT_DOUBLE_EQ(*result.disc->percent(), 100.0);
    EXPECT_EQ(result.nmse_pixels, 8);
    EXPECT_DOUBLE_EQ(*result.nmse, 16.25 / 4900.0);
    EXPECT_DOUBLE_EQ(*result.coverage, 9.0 / 11.0);  // coverage ignores the masks
}

TEST(Evaluate, PerfectMatchScoresZero) {
    const EvalResult result = evaluate({.disparity = {truth().mat, "d"}, .ground_truth = truth()});
    EXPECT_DOUBLE_EQ(*result.all.percent(), 0.0);
    EXPECT_DOUBLE_EQ(*result.nmse, 0.0);
    EXPECT_DOUBLE_EQ(*result.coverage, 1.0);
}

TEST(Evaluate, NothingKnownLeavesScoresEmpty) {
    const EvalResult result =
        evaluate({.disparity = ours(), .ground_truth = {cv::Mat::zeros(3, 4, CV_32FC1), "gt"}});
    EXPECT_EQ(result.all.evaluated, 0);
    EXPECT_FALSE(result.all.percent().has_value());
    EXPECT_FALSE(result.nmse.has_value());
    EXPECT_FALSE(result.coverage.has_value());
}

TEST(Evaluate, JsonHasNullForWhatWasNotComputed) {
    EvalInput input = example();
    input.nonocc = mask(cv::Mat(3, 4, CV_8UC1, cv::Scalar(255)), "nonocc");
    const nlohmann::json json = evaluate(input);
    EXPECT_DOUBLE_EQ(json.at("bad_nonocc").get<double>(), 400.0 / 11.0);
    EXPECT_DOUBLE_EQ(json.at("bad_all").get<double>(), 400.0 / 11.0);
    EXPECT_TRUE(json.at("bad_disc").is_null());
    EXPECT_DOUBLE_EQ(json.at("nmse").get<double>(), 0.00325);
    EXPECT_DOUBLE_EQ(json.at("coverage").get<double>(), 9.0 / 11.0);
    EXPECT_DOUBLE_EQ(json.at("threshold").get<double>(), 1.0);
    EXPECT_EQ(json.at("counts").at("all").at("bad").get<int>(), 4);
    EXPECT_TRUE(json.at("counts").at("disc").is_null());
}

TEST(Evaluate, GroundTruthSizeMismatchNamesBoth) {
    EvalInput input = example();
    input.ground_truth.mat = cv::Mat::ones(3, 5, CV_32FC1);
    expect_invalid([&] { (void)evaluate(input); },
                   "ground truth 'gt.png' is 5x3 but disparity 'd.png' is 4x3");
}

TEST(Evaluate, MaskSizeMismatchNamesBoth) {
    EvalInput nonocc = example();
    nonocc.nonocc = mask(cv::Mat(4, 4, CV_8UC1, cv::Scalar(255)), "nonocc mask 'n.png'");
    expect_invalid([&] { (void)evaluate(nonocc); },
                   "nonocc mask 'n.png' is 4x4 but disparity 'd.png' is 4x3");

    EvalInput all = example();
    all.all = mask(cv::Mat(3, 3, CV_8UC1, cv::Scalar(255)), "all mask 'a.png'");
    expect_invalid([&] { (void)evaluate(all); }, "all mask 'a.png' is 3x3");

    EvalInput disc = example();
    disc.disc = mask(cv::Mat(1, 1, CV_8UC1, cv::Scalar(255)), "disc mask 'c.png'");
    expect_invalid([&] { (void)error_map(disc); }, "disc mask 'c.png' is 1x1");
}

TEST(Evaluate, RejectsWrongTypesAndThresholds) {
    EvalInput input = example();
    input.disparity.mat = cv::Mat(3, 4, CV_8UC1, cv::Scalar(1));
    expect_invalid([&] { (void)evaluate(input); }, "disparity 'd.png' must be a non-empty float");

    EvalInput negative = example();
    negative.threshold = -1.0;
    expect_invalid([&] { (void)evaluate(negative); }, "threshold must be a non-negative number");
}

TEST(ErrorMap, ColoursEachClass) {
    EvalInput input = example();
    const cv::Mat map = error_map(input);
    ASSERT_EQ(map.type(), CV_8UC3);
    const cv::Vec3b grey(128, 128, 128);
    const cv::Vec3b red(0, 0, 255);  // BGR in memory
    const cv::Vec3b blue(255, 0, 0);
    const cv::Vec3b black(0, 0, 0);
    EXPECT_EQ(map.at<cv::Vec3b>(0, 0), grey);
    EXPECT_EQ(map.at<cv::Vec3b>(0, 1), red);
    EXPECT_EQ(map.at<cv::Vec3b>(0, 2), blue);
    EXPECT_EQ(map.at<cv::Vec3b>(0, 3), black);  // GT unknown
    EXPECT_EQ(map.at<cv::Vec3b>(1, 3), blue);
    EXPECT_EQ(map.at<cv::Vec3b>(2, 1), red);

    cv::Mat all_values(3, 4, CV_8UC1, cv::Scalar(255));
    all_values.at<std::uint8_t>(0, 1) = 0;
    input.all = mask(all_values, "all");
    EXPECT_EQ(error_map(input).at<cv::Vec3b>(0, 1), black);  // outside `all`: not evaluated
}

TEST(SignedError, CentresOn128WithSixteenLevelsPerPixel) {
    NamedMat disparity = ours();
    disparity.mat.at<float>(2, 0) = 1.0F;   // 1 - 30 = -29: clamps to 1, not to black
    disparity.mat.at<float>(2, 3) = 60.0F;  // +30: clamps to 255
    const cv::Mat image = signed_error_image(disparity, truth());
    ASSERT_EQ(image.type(), CV_8UC1);
    EXPECT_EQ(image.at<std::uint8_t>(0, 0), 128);  // 0
    EXPECT_EQ(image.at<std::uint8_t>(0, 1), 160);  // +2
    EXPECT_EQ(image.at<std::uint8_t>(1, 0), 136);  // +0.5
    EXPECT_EQ(image.at<std::uint8_t>(1, 2), 112);  // -1
    EXPECT_EQ(image.at<std::uint8_t>(2, 1), 176);  // +3
    EXPECT_EQ(image.at<std::uint8_t>(0, 2), 0);    // ours invalid
    EXPECT_EQ(image.at<std::uint8_t>(0, 3), 0);    // GT unknown
    EXPECT_EQ(image.at<std::uint8_t>(2, 0), 1);
    EXPECT_EQ(image.at<std::uint8_t>(2, 3), 255);
}

}  // namespace
}  // namespace stereo::io
