// Synthetic illumination changes for the evaluation of illumination-invariant costs
// (docs/results-illumination.md, `stereo relight`): a uniform HSL lightness change, a
// camera-style gain / offset / gamma, and spatially varying lightness (a horizontal gradient, a
// vignette). 8-bit BGR in, 8-bit BGR out, computed in double precision and rounded once.
#pragma once

#include <opencv2/core/mat.hpp>

namespace stereo::io {

// Lightness change by p percent, p in [-kMaxLightnessPercent, kMaxLightnessPercent]: in HSL,
// hue and saturation are kept and the lightness moves p % of the way to white (p > 0) or to
// black (p < 0): L' = L + (1 - L) p/100, or L' = L (1 + p/100). (The Hue-Saturation
// "lightness" slider of common image editors; the thesis altered its images with one.)
inline constexpr double kMaxLightnessPercent = 100.0;

struct Lighting {
    double lightness_percent = 0.0;  // uniform HSL lightness change
    double gain = 1.0;               // camera response: v' = 255 (gain v/255 + offset/255)^gamma,
    double offset = 0.0;             //   clamped to [0, 255] before the power
    double gamma = 1.0;
    // Horizontal lightness gradient: the change goes linearly from gradient_left % at the left
    // pixel centre to gradient_right % at the right one (thesis Fig. 3.29: -50 .. +50).
    double gradient_left = 0.0;
    double gradient_right = 0.0;
    // Vignette: a lightness change of -vignette_percent * (r / R)^2, r the distance from the
    // image centre, R the half-diagonal (the corners lose vignette_percent %).
    double vignette_percent = 0.0;
};

// Throws std::invalid_argument (one line, naming the field) on a non-finite value, a lightness
// percentage (uniform, gradient end, vignette; also their sum at any pixel) outside
// [-100, 100], gain <= 0 or > 16, |offset| > 255, gamma outside [0.1, 10].
void validate(const Lighting& lighting);

// The lightness change first (uniform + gradient + vignette summed per pixel, clamped to
// [-100, 100]), then gain, offset and gamma per channel. Validates first.
cv::Mat relight(const cv::Mat& bgr, const Lighting& lighting);

// Histogram equalisation of the HSL lightness (hue and saturation kept), the pre-processing the
// thesis gives the AD baseline in Sec. 3.5.3.
cv::Mat equalise_lightness(const cv::Mat& bgr);

}  // namespace stereo::io
