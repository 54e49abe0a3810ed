#include "stereo_io/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace stereo::io {

namespace {

std::string size_text(const cv::Mat& mat) {
    return std::to_string(mat.cols) + "x" + std::to_string(mat.rows);
}

void check_type(const NamedMat& input, int type, const std::string& expected) {
    if (input.mat.empty() || input.mat.type() != type) {
        throw std::invalid_argument(input.name + " must be a non-empty " + expected + " matrix");
    }
}

void check_matches(const NamedMat& input, int type, const std::string& expected,
                   const NamedMat& reference) {
    check_type(input, type, expected);
    if (input.mat.size() != reference.mat.size()) {
        throw std::invalid_argument(input.name + " is " + size_text(input.mat) + " but " +
                                    reference.name + " is " + size_text(reference.mat));
    }
}

void check_input(const EvalInput& input) {
    check_type(input.disparity, CV_32FC1, "float");
    check_matches(input.ground_truth, CV_32FC1, "float", input.disparity);
    for (const auto* mask : {&input.nonocc, &input.all, &input.disc, &input.scored}) {
        if (mask->has_value()) {
            check_matches(**mask, CV_8UC1, "8-bit single-channel", input.disparity);
        }
    }
    if (!std::isfinite(input.threshold) || input.threshold < 0.0) {
        throw std::invalid_argument("threshold must be a non-negative number, got " +
                                    std::to_string(input.threshold));
    }
}

bool in_mask(const std::optional<NamedMat>& mask, int x, int y) {
    return mask->mat.at<std::uint8_t>(y, x) == 255;
}

// `all` defaults to every pixel when no mask is given; the other regions to none.
bool in_all(const EvalInput& input, int x, int y) {
    return !input.all.has_value() || in_mask(input.all, x, y);
}

void count(RegionScore& score, bool bad) {
    ++score.evaluated;
    score.bad += bad ? 1 : 0;
}

nlohmann::json or_null(const std::optional<double>& value) {
    return value.has_value() ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json region_counts(const RegionScore& score) {
    return {{"evaluated", score.evaluated}, {"bad", score.bad}};
}

nlohmann::json region_counts(const std::optional<RegionScore>& score) {
    return score.has_value() ? region_counts(*score) : nlohmann::json(nullptr);
}

}  // namespace

std::optional<double> RegionScore::percent() const {
    if (evaluated == 0) {
        return std::nullopt;
    }
    return 100.0 * static_cast<double>(bad) / static_cast<double>(evaluated);
}

ValueRange value_range(const EvalInput& input) {
    check_input(input);
    ValueRange range;
    for (int y = 0; y < input.disparity.mat.rows; ++y) {
        for (int x = 0; x < input.disparity.mat.cols; ++x) {
            const float gt = input.ground_truth.mat.at<float>(y, x);
            if (input.gt_zero_is_unknown ? gt > 0.0F : std::isfinite(gt)) {
                range.gt_max = std::max(range.gt_max, std::abs(static_cast<double>(gt)));
            }
            const float d = input.disparity.mat.at<float>(y, x);
            if (input.zero_is_invalid ? d > 0.0F : std::isfinite(d)) {
                range.map_max = std::max(range.map_max, std::abs(static_cast<double>(d)));
                ++range.map_valid;
            }
        }
    }
    return range;
}

void check_ground_truth_range(const EvalInput& input, const std::string& hint) {
    const ValueRange range = value_range(input);
    if (range.map_valid == 0 ||
        range.gt_max <= kGroundTruthRangeFactor * std::max(range.map_max, 1.0)) {
        return;
    }
    char numbers[160];
    std::snprintf(numbers, sizeof numbers, " reaches %.4g px but %s only %.4g px (more than %gx)",
                  range.gt_max, "the map", range.map_max, kGroundTruthRangeFactor);
    throw std::invalid_argument(input.ground_truth.name + numbers + ": " + hint);
}

EvalResult evaluate(const EvalInput& input) {
    check_input(input);
    EvalResult result;
    result.threshold = input.threshold;
    if (input.nonocc.has_value()) {
        result.nonocc = RegionScore{};
    }
    if (input.disc.has_value()) {
        result.disc = RegionScore{};
    }
    double squared_error = 0.0;
    double squared_truth = 0.0;
    const cv::Mat& disparity = input.disparity.mat;
    const cv::Mat& truth = input.ground_truth.mat;
    for (int y = 0; y < truth.rows; ++y) {
        for (int x = 0; x < truth.cols; ++x) {
            const float gt = truth.at<float>(y, x);
            const bool known = input.gt_zero_is_unknown ? gt > 0.0F : std::isfinite(gt);
            if (!known || (input.scored.has_value() && !in_mask(input.scored, x, y))) {
                continue;  // NaN is never known
            }
            ++result.known;
            const float d = disparity.at<float>(y, x);
            const bool valid = input.zero_is_invalid ? d > 0.0F : std::isfinite(d);
            result.known_and_valid += valid ? 1 : 0;
            const bool bad = !valid || std::abs(d - gt) > input.threshold;
            if (in_all(input, x, y)) {
                count(result.all, bad);
                if (valid) {
                    count(result.valid, bad);
                    ++result.nmse_pixels;
                    squared_error += static_cast<double>(d - gt) * (d - gt);
                    squared_truth += static_cast<double>(gt) * gt;
                }
            }
            if (result.nonocc.has_value() && in_mask(input.nonocc, x, y)) {
                count(*result.nonocc, bad);
            }
            if (result.disc.has_value() && in_mask(input.disc, x, y)) {
                count(*result.disc, bad);
            }
        }
    }
    if (result.nmse_pixels > 0 && squared_truth > 0.0) {
        result.nmse = squared_error / squared_truth;
    }
    if (result.known > 0) {
        result.coverage =
            static_cast<double>(result.known_and_valid) / static_cast<double>(result.known);
    }
    return result;
}

void to_json(nlohmann::json& json, const EvalResult& result) {
    const auto percent = [](const std::optional<RegionScore>& score) {
        return score.has_value() ? score->percent() : std::nullopt;
    };
    json = {
        {"bad_nonocc", or_null(percent(result.nonocc))},
        {"bad_all", or_null(result.all.percent())},
        {"bad_valid", or_null(result.valid.percent())},
        {"bad_disc", or_null(percent(result.disc))},
        {"nmse", or_null(result.nmse)},
        {"coverage", or_null(result.coverage)},
        {"threshold", result.threshold},
        {"counts",
         {{"nonocc", region_counts(result.nonocc)},
          {"all", region_counts(result.all)},
          {"disc", region_counts(result.disc)},
          {"known", result.known},
          {"known_and_valid", result.known_and_valid},
          {"nmse_pixels", result.nmse_pixels}}},
    };
}

cv::Mat error_map(const EvalInput& input) {
    check_input(input);
    const cv::Vec3b black(0, 0, 0);
    const cv::Vec3b grey(128, 128, 128);
    const cv::Vec3b red(0, 0, 255);  // BGR
    const cv::Vec3b blue(255, 0, 0);
    const cv::Mat& disparity = input.disparity.mat;
    const cv::Mat& truth = input.ground_truth.mat;
    cv::Mat out(truth.size(), CV_8UC3, cv::Scalar::all(0));
    for (int y = 0; y < truth.rows; ++y) {
        for (int x = 0; x < truth.cols; ++x) {
            const float gt = truth.at<float>(y, x);
            const float d = disparity.at<float>(y, x);
            cv::Vec3b colour = black;
            const bool known = input.gt_zero_is_unknown ? gt > 0.0F : std::isfinite(gt);
            const bool valid = input.zero_is_invalid ? d > 0.0F : std::isfinite(d);
            const bool scored = !input.scored.has_value() || in_mask(input.scored, x, y);
            if (known && scored && in_all(input, x, y)) {
                if (!valid) {
                    colour = blue;
                } else if (std::abs(d - gt) > input.threshold) {
                    colour = red;
                } else {
                    colour = grey;
                }
            }
            out.at<cv::Vec3b>(y, x) = colour;
        }
    }
    return out;
}

cv::Mat signed_error_image(const NamedMat& disparity, const NamedMat& ground_truth) {
    check_type(disparity, CV_32FC1, "float");
    check_matches(ground_truth, CV_32FC1, "float", disparity);
    cv::Mat out(ground_truth.mat.size(), CV_8UC1, cv::Scalar::all(0));
    for (int y = 0; y < out.rows; ++y) {
        for (int x = 0; x < out.cols; ++x) {
            const float gt = ground_truth.mat.at<float>(y, x);
            const float d = disparity.mat.at<float>(y, x);
            if (gt > 0.0F && d > 0.0F) {
                const double value = std::round(128.0 + 16.0 * (static_cast<double>(d) - gt));
                out.at<std::uint8_t>(y, x) =
                    static_cast<std::uint8_t>(std::clamp(value, 1.0, 255.0));
            }
        }
    }
    return out;
}

}  // namespace stereo::io
