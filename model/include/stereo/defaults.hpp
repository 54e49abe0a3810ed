// The defaults of `stereo match` (docs/results.md, "Defaults"): the matching cost, and stage 6's
// uniqueness ratio and left-right tolerance for each cost, in front of the speckle filter's
// defaults (stereo/speckle.hpp). The library's own defaults (MatchParams, ValidationParams) stay
// the thesis' pipeline with stage 6 off; these are what the tool turns on.
//
// How they were chosen (one rule for every cost, all eight scenes with ground truth, none tuned
// alone): with sub-pixel output and the speckle filter on, for each tolerance T in {0, 1} (at
// most the one-label disagreement that quantisation alone explains; OpenCV's sample uses 1) the
// smallest U whose error among the output (bad > 1) stays within 1.2x OpenCV SGBM's on every
// scene, then the T whose U gives the highest mean coverage
// (`stereo_experiments validation-eval --cost C --lr-check T`, docs/results.md "Defaults").
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "stereo/catalogue.hpp"
#include "stereo/matcher.hpp"

namespace stereo::defaults {

// The cost of `stereo match --method pipeline` where the engine has it (model, naive, hls, rtl),
// of `--method asw` (model, naive), of the quad-camera pair geometries (`--method
// vertical|diagonal`, `stereo quad`): the 5x5 census (catalogue::kDefaultCost). It has half of
// SGBM's error or less on every scene at near SGBM's coverage, and it is the cost that survives
// real exposure and lighting changes (docs/results-illumination.md). With adaptive support
// weights it lowers the mean error over the eight scenes with ground truth from 15.6 % (AD) to
// 12.3 % and stays below SGBM's error under a +-25 % lightness change where ASW + AD fails
// (docs/results-asw.md). Other methods and engines default to the thesis' AD cost.
inline constexpr std::string_view kCost = catalogue::cost(catalogue::kDefaultCost).name;
inline constexpr std::string_view kFallbackCost = catalogue::cost(catalogue::kFallbackCost).name;

using Validation = catalogue::Validation;

// The values of the catalogue's rows, as the rule above chose them:
// Census: T = 0 meets the bound at U = 0 (mean coverage 78.3 %, lowest 67.7 %, worst ratio to
// SGBM 0.84x), T = 1 at U = 0 too (81.7 %, 73.4 %, 0.88x): U = 0, T = 1.
inline constexpr int kCensusUniqueness =
    catalogue::cost(catalogue::Cost::census).validation.uniqueness;
inline constexpr int kCensusLrTolerance =
    catalogue::cost(catalogue::Cost::census).validation.lr_tolerance;
// AD: T = 0 at U = 6 (68.0 %, 42.8 %, 1.19x), T = 1 at U = 20 (65.0 %, 33.0 %, 1.19x): U = 6,
// T = 0 (with the calibrated sub-pixel table of stage 6; U = 8 with the plain parabola). LCDM
// and ZNCC, for which the rule was not run, have AD's.
inline constexpr int kAdUniqueness = catalogue::cost(catalogue::Cost::ad).validation.uniqueness;
inline constexpr int kAdLrTolerance = catalogue::cost(catalogue::Cost::ad).validation.lr_tolerance;
static_assert(kCensusUniqueness == 0 && kCensusLrTolerance == 1 && kAdUniqueness == 6 &&
                  kAdLrTolerance == 0,
              "the measured defaults above; re-run the rule before changing them");

// Stage 6's defaults for a cost (AD's for a name that is not in the catalogue).
constexpr Validation validation_for(std::string_view cost) {
    for (const catalogue::CostRow& row : catalogue::kCosts) {
        if (row.name == cost) {
            return row.validation;
        }
    }
    return catalogue::cost(catalogue::kFallbackCost).validation;
}

// The one definition of what a default run is, for every interface (stereo match, Python's
// stereo.match, the C++ API, stereo cosim where the core has it): the method's default cost on
// this engine (catalogue::default_cost), the pipeline's window, sigma and CA rules, and for the
// methods with stage 6 every validation step on with the cost's ratio and tolerance, plus the
// speckle filter's defaults (stereo/speckle.hpp). Throws std::invalid_argument for an unknown
// method or engine.
MatchConfig match_config(std::string_view method = "pipeline", std::string_view engine = "model");

// What a caller changes of a run, by the one rule every interface follows (stereo match's options,
// Python's keywords): a cost brings its own uniqueness ratio and left-right tolerance;
// validation = false turns every stage-6 step and the speckle filter off (--no-validation); then
// each given value turns its step on with it (subpixel = false and speckle_size = 0: off).
struct Overrides {
    std::optional<std::string> cost;
    bool validation = true;
    std::optional<int> uniqueness;
    std::optional<int> lr_tolerance;
    std::optional<bool> subpixel;
    std::optional<int> speckle_size;
    std::optional<int> speckle_range;
};
void apply(const Overrides& overrides, MatchConfig& config);

}  // namespace stereo::defaults
