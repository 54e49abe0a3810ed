// The defaults of `stereo match` (docs/results.md, "Defaults"): the matching cost, and stage 6's
// uniqueness ratio and left-right tolerance for each cost, in front of the speckle filter's
// defaults (stereo/speckle.hpp). The library's own defaults (MatchParams, ValidationParams) stay
// the thesis' pipeline with stage 6 off; these are what the tool turns on.
//
// How they were chosen (one rule for every cost, all eight scenes with ground truth, none tuned
// alone): with sub-pixel output and the speckle filter on, the pair (U, T), T in {0, 1, 2}, with
// the highest mean coverage among those whose error among the output (bad > 1) stays within
// 1.2x OpenCV SGBM's on every scene (`stereo_experiments validation-eval --cost C --lr-check T`).
#pragma once

#include <string_view>

namespace stereo::defaults {

// The cost of `stereo match --method pipeline` where the engine has it (model, naive, hls, rtl):
// the 5x5 census. It has half of SGBM's error or less on every scene at near SGBM's coverage, and
// it is the cost that survives real exposure and lighting changes (docs/results-illumination.md).
// Other methods and engines default to the thesis' AD cost.
inline constexpr std::string_view kCost = "census";
inline constexpr std::string_view kFallbackCost = "ad";

struct Validation {
    int uniqueness;    // U, percent
    int lr_tolerance;  // T, labels
};

// Census: MEASURED_CENSUS_RULE
inline constexpr int kCensusUniqueness = 0;
inline constexpr int kCensusLrTolerance = 1;
// AD: U = 8 at T = 0 (mean coverage 67.2 %, lowest 41.3 %, worst 1.17x SGBM).
inline constexpr int kAdUniqueness = 8;
inline constexpr int kAdLrTolerance = 0;

// Stage 6's defaults for a cost (AD's for any cost the rule was not run for).
constexpr Validation validation_for(std::string_view cost) {
    if (cost == "census") {
        return {kCensusUniqueness, kCensusLrTolerance};
    }
    return {kAdUniqueness, kAdLrTolerance};
}

}  // namespace stereo::defaults
