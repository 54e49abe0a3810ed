// The speckle filter: a host-side post-filter of a validated disparity map (after stage 6, for
// every engine; the RTL's output beat never carries its reason). Small islands of valid
// disparities, cut off from the surface around them by invalid pixels or by a jump, are
// mostly wrong matches (a repeated texture, a reflection, a window straddling an occlusion);
// removing them is what OpenCV's filterSpeckles does after StereoSGBM. docs/fixed-point.md,
// "The speckle filter", gives the rule and the measured effect.
#pragma once

#include "stereo/validated.hpp"

namespace stereo::speckle {

inline constexpr int kMaxSize = 1 << 20;  // pixels; larger regions cannot be speckles in practice
inline constexpr int kMaxRange = 255;     // pixels

// The defaults of `stereo match` (docs/results.md, "The speckle filter"). The size is OpenCV's
// sample value and keeps every object of 10 x 10 pixels or more (a robot's small obstacles); the
// range is the stricter of the two OpenCV recommends. With the filter removing islands, stage 6's
// uniqueness ratio can be lower than it needs alone (stereo/defaults.hpp gives the ratio per
// cost). The library's default is off.
inline constexpr int kDefaultSize = 100;
inline constexpr int kDefaultRange = 1;

struct Params {
    // A connected region of valid pixels (4-neighbours whose disparities differ by at most
    // `range` pixels) with at most `max_size` pixels becomes invalid (fx::kReasonSpeckle).
    // 0 switches the filter off.
    int max_size = 0;
    int range = 1;
    bool operator==(const Params&) const = default;
    bool enabled() const { return max_size > 0; }
    static constexpr Params defaults() { return {kDefaultSize, kDefaultRange}; }
};

// Throws std::invalid_argument (one line) for a size outside 0 .. kMaxSize or a range outside
// 0 .. kMaxRange.
void validate(const Params& params);

// Marks every pixel of every speckle invalid (reason fx::kReasonSpeckle, disparity 0) in place;
// the certainty stays. Disparities are compared in the map's fixed point (x 16), so `range`
// pixels is range * 16 there. Returns how many pixels it invalidated.
int filter(ValidatedDisparity& map, const Params& params);

}  // namespace stereo::speckle
