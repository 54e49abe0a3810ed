#include "stereo_io/colour_key.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "stereo_io/io.hpp"

namespace stereo::io {
namespace {

constexpr int kBarRows = 10;  // the gradient's height inside the strip
constexpr double kFontScale = 0.35;
const cv::Scalar kText(255, 255, 255);

cv::Mat turbo_row(int width) {
    cv::Mat ramp(1, width, CV_8UC1);
    for (int x = 0; x < width; ++x) {
        ramp.at<std::uint8_t>(0, x) =
            static_cast<std::uint8_t>(width > 1 ? (255 * x + (width - 1) / 2) / (width - 1) : 0);
    }
    cv::Mat colour;
    cv::applyColorMap(ramp, colour, cv::COLORMAP_TURBO);
    return colour;
}

int text_width(const std::string& text) {
    int baseline = 0;
    return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, kFontScale, 1, &baseline).width;
}

void put(cv::Mat& image, const std::string& text, int x, int y) {
    cv::putText(image, text, {x, y}, cv::FONT_HERSHEY_SIMPLEX, kFontScale, kText, 1, cv::LINE_AA);
}

}  // namespace

cv::Mat colour_view(const DisparityMap& map, int ndisp, int min_disp, bool bar) {
    cv::Mat view = disparity_to_colour(map, ndisp);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            if (map.valid[map.index(x, y)] == 0) {
                view.at<cv::Vec3b>(y, x) = kInvalidColour;
            }
        }
    }
    if (!bar) {
        return view;
    }
    cv::Mat out(map.height + kKeyHeight, map.width, CV_8UC3, cv::Scalar::all(0));
    view.copyTo(out.rowRange(0, map.height));
    // The "invalid" swatch takes the right end when there is room for it.
    const std::string invalid = "invalid";
    const int swatch = 10;
    const int key_width = swatch + 4 + text_width(invalid) + 4;
    const int ramp_width = map.width >= 3 * key_width ? map.width - key_width : map.width;
    const int top = map.height + 2;
    cv::Mat ramp;
    cv::resize(turbo_row(ramp_width), ramp, {ramp_width, kBarRows}, 0, 0, cv::INTER_NEAREST);
    ramp.copyTo(out(cv::Rect(0, top, ramp_width, kBarRows)));
    if (ramp_width < map.width) {
        const int x = ramp_width + 4;
        out(cv::Rect(x, top, swatch, kBarRows)).setTo(cv::Scalar(kInvalidColour));
        put(out, invalid, x + swatch + 4, top + kBarRows - 1);
    }
    // Ticks: the first and last label's disparity, and between them as many as fit.
    const int baseline = map.height + kKeyHeight - 4;
    const auto label_x = [&](int label) {
        return ndisp > 1 ? label * (ramp_width - 1) / (ndisp - 1) : 0;
    };
    std::vector<int> labels = {0};
    const int room = std::max(1, ramp_width / 48);
    for (int k = 1; k < room; ++k) {
        labels.push_back(k * (ndisp - 1) / room);
    }
    if (ndisp > 1) {
        labels.push_back(ndisp - 1);
    }
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    int free_from = 0;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        const std::string text = std::to_string(min_disp + labels[i]) +
                                 (i + 1 == labels.size() && ramp_width >= 60 ? " px" : "");
        const int width = text_width(text);
        const int x =
            std::clamp(label_x(labels[i]) - width / 2, 0, std::max(0, ramp_width - width));
        if (x < free_from) {
            continue;
        }
        out(cv::Rect(label_x(labels[i]), top + kBarRows, 1, 3)).setTo(kText);
        put(out, text, x, baseline);
        free_from = x + width + 6;
    }
    return out;
}

cv::Mat with_error_legend(const cv::Mat& error_map) {
    cv::Mat out(error_map.rows + kKeyHeight, error_map.cols, CV_8UC3, cv::Scalar::all(40));
    error_map.copyTo(out.rowRange(0, error_map.rows));
    const std::vector<std::pair<std::string, cv::Scalar>> entries = {{"correct", {128, 128, 128}},
                                                                     {"bad", {0, 0, 255}},
                                                                     {"invalid", {255, 0, 0}},
                                                                     {"not scored", {0, 0, 0}}};
    int x = 4;
    int row = error_map.rows + 4;
    for (const auto& [name, colour] : entries) {
        const int width = 10 + 4 + text_width(name) + 10;
        if (x + width > out.cols && x > 4) {  // next line
            x = 4;
            row += 13;
        }
        if (row + 10 > out.rows) {
            break;  // a very narrow map: the rest does not fit
        }
        cv::rectangle(out, cv::Rect(x, row, 10, 10), colour, cv::FILLED);
        cv::rectangle(out, cv::Rect(x, row, 10, 10), cv::Scalar::all(200), 1);
        put(out, name, x + 14, row + 9);
        x += width;
    }
    return out;
}

}  // namespace stereo::io
