// The validated output of the 1-D pipeline (docs/fixed-point.md stage 6): a signed sub-pixel
// disparity x 16, the reason a pixel is invalid and the certainty of its winner, per pixel. It is
// what stereo_top's output beat carries; DisparityMap is its 8-bit view.
#pragma once

#include <cstdint>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/image.hpp"

namespace stereo {

struct ValidatedDisparity : PixelGrid {
    // Disparity x fx::kSubpixelScale (the integer winner x 16 when sub-pixel refinement is off);
    // 0 where invalid.
    std::vector<std::int16_t> fixed;
    std::vector<std::uint8_t> reason;     // fx::kReasonValid, kReasonBorder, ...
    std::vector<std::uint8_t> certainty;  // 0 .. 255, every pixel (border pixels too)

    ValidatedDisparity() = default;
    ValidatedDisparity(int w, int h)
        : PixelGrid{w, h},
          fixed(static_cast<std::size_t>(w) * h, 0),
          reason(static_cast<std::size_t>(w) * h, fx::kReasonBorder),
          certainty(static_cast<std::size_t>(w) * h, 0) {}

    bool valid(std::size_t i) const { return reason[i] == fx::kReasonValid; }
    // The disparity in pixels; meaningful where valid.
    double disparity(std::size_t i) const {
        return static_cast<double>(fixed[i]) / fx::kSubpixelScale;
    }
    bool operator==(const ValidatedDisparity&) const = default;
};

// A validated map and, per pixel, the final aggregated cost of its winning label (C1, 0 ..
// fx::kAggMax; every pixel, border pixels too): what the quad-camera fusion by cost compares.
struct CostedDisparity {
    ValidatedDisparity map;
    std::vector<std::uint16_t> cost;
};

// The nearest integer disparity (halves up) where it is valid and in 0 .. 255; invalid (0)
// elsewhere. With every validation stage off and min_disp 0 this is stereo::match's map.
DisparityMap to_label_map(const ValidatedDisparity& validated);

}  // namespace stereo
