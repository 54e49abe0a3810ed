#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "stereo/pipeline.hpp"

namespace stereo {
namespace {

// Sum of the symmetric integer kernel whose taps are round(scale * g[|i|]).
std::int64_t rounded_sum(const std::vector<double>& half, double scale) {
    std::int64_t sum = std::llround(scale * half[0]);
    for (std::size_t i = 1; i < half.size(); ++i) {
        sum += 2 * std::llround(scale * half[i]);
    }
    return sum;
}

}  // namespace

std::vector<std::int32_t> gaussian_kernel(int window, double sigma) {
    if (window < fx::kMinWindow || window > fx::kMaxWindow || window % 2 == 0) {
        throw std::invalid_argument("window must be odd and in [" + std::to_string(fx::kMinWindow) +
                                    ", " + std::to_string(fx::kMaxWindow) + "], got " +
                                    std::to_string(window));
    }
    // Outside this range the kernel no longer changes (a single tap below, a box above) and the
    // arithmetic below would leave the range of doubles (sigma^2 underflows for 1e-300).
    if (!(sigma >= kMinSigma && sigma <= kMaxSigma)) {
        char text[96];
        std::snprintf(text, sizeof text, "sigma must be in [%g, %g], got %g", kMinSigma, kMaxSigma,
                      sigma);
        throw std::invalid_argument(text);
    }
    const int radius = window / 2;
    std::vector<double> half(static_cast<std::size_t>(radius + 1));  // g(0) .. g(radius)
    for (int i = 0; i <= radius; ++i) {
        half[static_cast<std::size_t>(i)] = std::exp(-(i * i) / (2.0 * sigma * sigma));
    }

    // Every tap is the same scaled Gaussian, rounded: find the smallest scale whose rounded taps
    // sum to at least 2^kKernelBits (the sum is monotone in the scale). Rounding all taps alike
    // keeps the kernel's shape; only when a symmetric pair jumps past the target (sum + 1) does
    // the centre tap give back that one unit.
    double low = 0.0;
    double high = 2.0 * fx::kKernelSum;  // g(0) = 1, so this scale alone exceeds the target
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double middle = 0.5 * (low + high);
        (rounded_sum(half, middle) >= fx::kKernelSum ? high : low) = middle;
    }
    std::vector<std::int32_t> taps(static_cast<std::size_t>(window));
    for (int i = -radius; i <= radius; ++i) {
        taps[static_cast<std::size_t>(i + radius)] = static_cast<std::int32_t>(
            std::llround(high * half[static_cast<std::size_t>(std::abs(i))]));
    }
    const std::int64_t excess = rounded_sum(half, high) - fx::kKernelSum;
    taps[static_cast<std::size_t>(radius)] -= static_cast<std::int32_t>(excess);
    if (excess < 0 || excess > 1 || taps[static_cast<std::size_t>(radius)] < 0) {
        char text[96];
        std::snprintf(text, sizeof text,
                      "cannot build a %d-tap kernel for sigma %g at the kernel "
                      "precision",
                      window, sigma);
        throw std::invalid_argument(text);
    }
    return taps;
}

}  // namespace stereo
