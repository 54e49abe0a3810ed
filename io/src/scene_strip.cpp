// The figure strip of one scene (scene_strip.hpp).
#include "stereo_io/scene_strip.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "stereo_io/io.hpp"
#include "stereo_io/metrics.hpp"

namespace stereo::io {
namespace {

// Text in the figures: small, black on white.
void label(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.38) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar::all(0), 1,
                cv::LINE_AA);
}

// A strip of five panels of width `panel` with a title above each and, below, what the colours
// mean: a colour bar in pixels of disparity under the two disparity maps, the signed-error
// scale, and the legend of the bad-pixel map (issue 23: figures readable without a caption).
cv::Mat annotate_strip(const cv::Mat& strip, int panel, int ndisp, const std::string& ours_title) {
    constexpr int kTitle = 18;
    constexpr int kKey = 48;
    cv::Mat out(strip.rows + kTitle + kKey, strip.cols, CV_8UC3, cv::Scalar::all(255));
    strip.copyTo(out(cv::Rect(0, kTitle, strip.cols, strip.rows)));
    const std::vector<std::string> titles = {"left image", "ground truth", ours_title,
                                             "signed error", "bad pixels (> 1 px)"};
    for (std::size_t i = 0; i < titles.size(); ++i) {
        label(out, titles[i], {static_cast<int>(i) * panel + 4, kTitle - 5}, 0.42);
    }
    const int key_top = kTitle + strip.rows + 4;
    constexpr int kBar = 10;
    // Disparity colour bar under panels 1 and 2: the mapping of io::float_disparity_to_colour.
    const int bar_left = panel + 8;
    const int bar_width = 2 * panel - 16;
    cv::Mat ramp(1, bar_width, CV_8UC1);
    for (int x = 0; x < bar_width; ++x) {
        ramp.at<std::uint8_t>(0, x) =
            static_cast<std::uint8_t>(255 * x / std::max(1, bar_width - 1));
    }
    cv::Mat ramp_colour;
    cv::applyColorMap(ramp, ramp_colour, cv::COLORMAP_TURBO);
    cv::resize(ramp_colour, ramp_colour, cv::Size(bar_width, kBar), 0, 0, cv::INTER_NEAREST);
    ramp_colour.copyTo(out(cv::Rect(bar_left, key_top, bar_width, kBar)));
    const int top_value = std::max(1, ndisp - 1);
    for (const int value : {0, top_value / 2, top_value}) {
        const int x = bar_left + value * (bar_width - 1) / top_value;
        cv::line(out, {x, key_top + kBar}, {x, key_top + kBar + 3}, cv::Scalar::all(0));
        label(out, std::to_string(value), {std::max(0, x - 6), key_top + kBar + 14});
    }
    label(out, "disparity (px); black: unknown / invalid",
          {bar_left + bar_width / 4, key_top + kBar + 28});
    // Signed error under panel 3: grey 128 + 16 (d - gt), clamped.
    const int err_left = 3 * panel + 8;
    const int err_width = panel - 16;
    for (int x = 0; x < err_width; ++x) {
        const int grey = 1 + 254 * x / std::max(1, err_width - 1);
        cv::line(out, {err_left + x, key_top}, {err_left + x, key_top + kBar - 1},
                 cv::Scalar::all(grey));
    }
    label(out, "-8", {err_left - 4, key_top + kBar + 14});
    label(out, "0", {err_left + err_width / 2 - 3, key_top + kBar + 14});
    label(out, "+8", {err_left + err_width - 12, key_top + kBar + 14});
    label(out, "d - gt (px)", {err_left + err_width / 4, key_top + kBar + 28});
    // Legend of io::error_map under panel 4.
    const std::vector<std::pair<cv::Scalar, std::string>> legend = {
        {cv::Scalar(128, 128, 128), "good"},
        {cv::Scalar(0, 0, 255), "wrong"},
        {cv::Scalar(255, 0, 0), "invalid"},
        {cv::Scalar(0, 0, 0), "not scored"}};
    for (std::size_t i = 0; i < legend.size(); ++i) {
        const int x = 4 * panel + 6 + static_cast<int>(i % 2) * (panel / 2);
        const int y = key_top + static_cast<int>(i / 2) * 16;
        cv::rectangle(out, cv::Rect(x, y, 10, 10), legend[i].first, cv::FILLED);
        label(out, legend[i].second, {x + 13, y + 9});
    }
    return out;
}

}  // namespace

cv::Mat scene_strip(const SceneData& data, const cv::Mat& ours, const std::string& ours_title) {
    const int ndisp = data.scene.ndisp;
    EvalInput input{{ours, "ours"}, data.ground_truth};
    input.all = data.all;
    const cv::Mat signed_grey = signed_error_image({ours, "ours"}, data.ground_truth);
    cv::Mat signed_bgr;
    cv::cvtColor(signed_grey, signed_bgr, cv::COLOR_GRAY2BGR);
    const std::vector<cv::Mat> panels = {
        data.left_bgr, float_disparity_to_colour(data.ground_truth.mat, ndisp),
        float_disparity_to_colour(ours, ndisp), signed_bgr, error_map(input)};
    std::vector<cv::Mat> halves;
    for (const cv::Mat& panel : panels) {
        cv::Mat half;
        cv::resize(panel, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
        halves.push_back(half);
    }
    cv::Mat strip;
    cv::hconcat(halves, strip);
    return annotate_strip(strip, halves.front().cols, ndisp, ours_title);
}

}  // namespace stereo::io
