// Synthetic illumination changes (stereo_io/lighting.hpp).
#include "stereo_io/lighting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace stereo::io {
namespace {

struct Hsl {
    double h = 0;  // sixths of a turn, [0, 6)
    double s = 0;
    double l = 0;
};

Hsl to_hsl(double r, double g, double b) {
    const double mx = std::max({r, g, b});
    const double mn = std::min({r, g, b});
    const double c = mx - mn;
    Hsl out;
    out.l = (mx + mn) / 2.0;
    if (c <= 0.0) {
        return out;
    }
    out.s = c / (1.0 - std::abs(2.0 * out.l - 1.0));
    if (mx == r) {
        out.h = std::fmod((g - b) / c + 6.0, 6.0);
    } else if (mx == g) {
        out.h = (b - r) / c + 2.0;
    } else {
        out.h = (r - g) / c + 4.0;
    }
    return out;
}

std::array<double, 3> to_rgb(const Hsl& hsl) {
    const double c = (1.0 - std::abs(2.0 * hsl.l - 1.0)) * hsl.s;
    const double x = c * (1.0 - std::abs(std::fmod(hsl.h, 2.0) - 1.0));
    const double m = hsl.l - c / 2.0;
    std::array<double, 3> rgb{};
    switch (static_cast<int>(hsl.h) % 6) {
        case 0:
            rgb = {c, x, 0};
            break;
        case 1:
            rgb = {x, c, 0};
            break;
        case 2:
            rgb = {0, c, x};
            break;
        case 3:
            rgb = {0, x, c};
            break;
        case 4:
            rgb = {x, 0, c};
            break;
        default:
            rgb = {c, 0, x};
            break;
    }
    for (double& v : rgb) {
        v += m;
    }
    return rgb;
}

double change_lightness(double l, double percent) {
    const double p = std::clamp(percent, -kMaxLightnessPercent, kMaxLightnessPercent) / 100.0;
    return p >= 0 ? l + (1.0 - l) * p : l * (1.0 + p);
}

std::uint8_t to_byte(double unit) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(unit, 0.0, 1.0) * 255.0));
}

void check(bool ok, const std::string& message) {
    if (!ok) {
        throw std::invalid_argument(message);
    }
}

void check_percent(double value, const char* name) {
    check(std::isfinite(value) && std::abs(value) <= kMaxLightnessPercent,
          std::string(name) + " must be a finite percentage in [-100, 100], got " +
              std::to_string(value));
}

void check_bgr(const cv::Mat& bgr) {
    check(bgr.type() == CV_8UC3 && !bgr.empty(), "relight needs an 8-bit colour image");
}

}  // namespace

void validate(const Lighting& lighting) {
    check_percent(lighting.lightness_percent, "lightness");
    check_percent(lighting.gradient_left, "gradient start");
    check_percent(lighting.gradient_right, "gradient end");
    check_percent(lighting.vignette_percent, "vignette");
    check(std::isfinite(lighting.gain) && lighting.gain > 0 && lighting.gain <= 16,
          "gain must be in (0, 16], got " + std::to_string(lighting.gain));
    check(std::isfinite(lighting.offset) && std::abs(lighting.offset) <= 255,
          "offset must be in [-255, 255], got " + std::to_string(lighting.offset));
    check(std::isfinite(lighting.gamma) && lighting.gamma >= 0.1 && lighting.gamma <= 10,
          "gamma must be in [0.1, 10], got " + std::to_string(lighting.gamma));
}

cv::Mat relight(const cv::Mat& bgr, const Lighting& lighting) {
    validate(lighting);
    check_bgr(bgr);
    cv::Mat out(bgr.size(), CV_8UC3);
    const double cx = (bgr.cols - 1) / 2.0;
    const double cy = (bgr.rows - 1) / 2.0;
    const double half_diagonal = std::hypot(bgr.cols, bgr.rows) / 2.0;
    const double span = std::max(bgr.cols - 1, 1);
    const bool camera = lighting.gain != 1.0 || lighting.offset != 0.0 || lighting.gamma != 1.0;
    for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < bgr.cols; ++x) {
            const auto& in = bgr.at<cv::Vec3b>(y, x);
            const double rho = std::hypot(x - cx, y - cy) / half_diagonal;
            const double percent = lighting.lightness_percent + lighting.gradient_left +
                                   (lighting.gradient_right - lighting.gradient_left) * (x / span) -
                                   lighting.vignette_percent * rho * rho;
            std::array<double, 3> rgb = {in[2] / 255.0, in[1] / 255.0, in[0] / 255.0};
            if (percent != 0.0) {
                Hsl hsl = to_hsl(rgb[0], rgb[1], rgb[2]);
                hsl.l = change_lightness(hsl.l, percent);
                rgb = to_rgb(hsl);
            }
            if (camera) {
                for (double& v : rgb) {
                    v = std::pow(std::clamp(lighting.gain * v + lighting.offset / 255.0, 0.0, 1.0),
                                 lighting.gamma);
                }
            }
            out.at<cv::Vec3b>(y, x) = {to_byte(rgb[2]), to_byte(rgb[1]), to_byte(rgb[0])};
        }
    }
    return out;
}

cv::Mat equalise_lightness(const cv::Mat& bgr) {
    check_bgr(bgr);
    cv::Mat lightness(bgr.size(), CV_8UC1);
    for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < bgr.cols; ++x) {
            const auto& p = bgr.at<cv::Vec3b>(y, x);
            lightness.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(
                (std::max({p[0], p[1], p[2]}) + std::min({p[0], p[1], p[2]}) + 1) / 2);
        }
    }
    cv::Mat equalised;
    cv::equalizeHist(lightness, equalised);
    cv::Mat out(bgr.size(), CV_8UC3);
    for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < bgr.cols; ++x) {
            const auto& p = bgr.at<cv::Vec3b>(y, x);
            Hsl hsl = to_hsl(p[2] / 255.0, p[1] / 255.0, p[0] / 255.0);
            hsl.l = equalised.at<std::uint8_t>(y, x) / 255.0;
            const auto rgb = to_rgb(hsl);
            out.at<cv::Vec3b>(y, x) = {to_byte(rgb[2]), to_byte(rgb[1]), to_byte(rgb[0])};
        }
    }
    return out;
}

}  // namespace stereo::io
