// Middlebury-style evaluation of a disparity map against ground truth.
//
// Inputs are float disparities (CV_32FC1) where 0 means "invalid" in our map and "unknown" in
// the ground truth (GT), and optional 8-bit masks (CV_8UC1) where exactly 255 marks a pixel
// that is evaluated (Middlebury's nonocc/all are 255/0; disc is 255/128/0, only 255 counts).
//
// Definitions (a pixel is "known" when GT > 0):
//   region R        = known pixels with mask R == 255; with no mask for R, only `all` is
//                     computed, over every known pixel, and nonocc/disc are not reported.
//   bad pixel in R  = our disparity is invalid (0) or |d - gt| > threshold.
//   bad_R           = 100 * bad pixels in R / pixels in R        (percent)
//   nmse            = sum (d - gt)^2 / sum gt^2 over known pixels where ours is valid, inside
//                     the `all` mask when one is given. Invalid pixels are left out, as in the
//                     thesis, which excludes the frame the pipeline does not compute.
//   coverage        = known pixels where ours is valid / known pixels (no mask applied).
//   bad_valid       = 100 * pixels in `all` where ours is valid and |d - gt| > threshold / pixels
//                     in `all` where ours is valid: the error among the pixels a method outputs.
// With zero_is_invalid = false a disparity is valid when finite (0 and negatives included), and
// with gt_zero_is_unknown = false a GT value is known when finite.
// A value with an empty denominator is not reported (std::nullopt, null in JSON).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core/mat.hpp>

namespace stereo::io {

// A matrix with the name used for it in error messages (a file path in the CLI).
struct NamedMat {
    cv::Mat mat;
    std::string name;
};

struct EvalInput {
    NamedMat disparity;                             // CV_32FC1, 0 = invalid
    NamedMat ground_truth;                          // CV_32FC1, 0 = unknown
    std::optional<NamedMat> nonocc = std::nullopt;  // 255 = scored
    std::optional<NamedMat> all = std::nullopt;
    std::optional<NamedMat> disc = std::nullopt;
    double threshold = 1.0;  // a pixel is bad when |d - gt| > threshold
    // false: every finite disparity is valid (0 and negative ones too) and NaN / inf mark invalid
    // pixels, as in PFM files and stage 6's output; true: 0 (and below) is invalid.
    bool zero_is_invalid = true;
    // false: every finite GT value is known (signed GT, e.g. the light field); true: GT > 0.
    bool gt_zero_is_unknown = true;
    // Only pixels where this mask is 255 are scored at all (to compare two maps on the same
    // pixel set: the pixels both output).
    std::optional<NamedMat> scored = std::nullopt;
};

struct RegionScore {
    std::int64_t evaluated = 0;  // known pixels inside the mask
    std::int64_t bad = 0;
    std::optional<double> percent() const;  // nullopt when nothing was evaluated
};

struct EvalResult {
    std::optional<RegionScore> nonocc;  // nullopt when no mask was given
    RegionScore all;                    // every known pixel when no `all` mask was given
    std::optional<RegionScore> disc;
    // Among the known pixels (inside `all`) where ours is valid: bad = |d - gt| > threshold. The
    // error rate of what a method outputs, beside its coverage.
    RegionScore valid;
    std::int64_t known = 0;            // GT > 0
    std::int64_t known_and_valid = 0;  // GT > 0 and ours valid: coverage numerator
    std::int64_t nmse_pixels = 0;      // pixels in the NMSE sums
    std::optional<double> nmse;
    std::optional<double> coverage;
    double threshold = 1.0;
};

// Throws std::invalid_argument when a size or type does not match (naming both) or the
// threshold is negative or not finite.
EvalResult evaluate(const EvalInput& input);

// A ground truth at the wrong scale scores every pixel bad and still exits 0 (Middlebury 2003's
// gt.png holds 4 d, KITTI's 256 d). check_ground_truth_range throws std::invalid_argument, with
// `hint` appended, when the ground truth's largest known |value| is more than
// kGroundTruthRangeFactor times the map's largest valid |disparity| (at least 1 pixel), i.e. far
// outside anything the map searched. Nothing is checked when the map has no valid pixel.
inline constexpr double kGroundTruthRangeFactor = 2.0;
struct ValueRange {
    double map_max = 0.0;  // largest valid |d|, 0 when none
    double gt_max = 0.0;   // largest known |gt|, 0 when none
    std::int64_t map_valid = 0;
};
ValueRange value_range(const EvalInput& input);
void check_ground_truth_range(const EvalInput& input, const std::string& hint);

// Keys bad_nonocc, bad_all, bad_disc (percent), nmse, coverage (fraction), threshold, with null
// for what was not computed, plus a "counts" object.
void to_json(nlohmann::json& json, const EvalResult& result);

// Error map for figures, in OpenCV BGR order (write_png stores it as RGB):
//   black = not evaluated (GT unknown, or outside the `all` mask when one is given),
//   grey 128 = correct, red = bad (wrong disparity), blue = bad because ours is invalid.
// The left image is deliberately not used as a backdrop, so the map stands on its own.
cv::Mat error_map(const EvalInput& input);

// Signed error as an 8-bit grey image: 128 + 16 * (d - gt), clamped to 1..255 so that 0 (black)
// is reserved for "no data" (GT unknown or ours invalid). Masks are ignored.
cv::Mat signed_error_image(const NamedMat& disparity, const NamedMat& ground_truth);

}  // namespace stereo::io
