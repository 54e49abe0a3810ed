// Golden model of the enhanced-disparity stereo pipeline (thesis Sec. 3.1), bit-exact.
// Every stage is specified to the bit in docs/fixed-point.md; the RTL modules and the HLS
// kernels carry the same names and must reproduce these functions exactly.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/validated.hpp"
#include "stereo/validation_params.hpp"

namespace stereo {

struct MatchParams {
    int ndisp = fx::kDefaultDisparities;  // labels 0 .. ndisp-1: d = min_disp + label
    int window = fx::kDefaultWindow;      // odd side of the square aggregation window
    double sigma = fx::kDefaultSigma;     // Gaussian sigma in pixels
    bool use_ca = true;                   // apply CA rules 1 and 2
    std::string cost = "ad";              // a cost of the catalogue (stereo/catalogue.hpp)
    int min_disp = 0;                     // smallest disparity searched (may be negative)
    ValidationParams validation{};        // 1-D pipeline only
};

// Throws std::invalid_argument with a one-line message when the parameters are impossible
// for this image size (even/too-large window, ndisp out of range, image smaller than border).
void validate(const MatchParams& params, int width, int height);
// The checks of validate() that do not depend on the image size.
void validate_params(const MatchParams& params);

// The sigmas a kernel may have: below 0.01 every window is a single tap, above 1000 every window
// up to fx::kMaxWindow is a box to the kernel's precision (docs/fixed-point.md).
inline constexpr double kMinSigma = 0.01;
inline constexpr double kMaxSigma = 1000.0;

// Integer 1-D Gaussian kernel of `window` taps (odd), non-negative, summing to fx::kKernelSum.
// Throws std::invalid_argument for a window outside [fx::kMinWindow, fx::kMaxWindow], an even
// window, or a sigma outside [kMinSigma, kMaxSigma] (NaN included).
std::vector<std::int32_t> gaussian_kernel(int window, double sigma);

InvalidBorder invalid_border(const MatchParams& params);

// Stage 1 (the AD cost plug-in over a whole volume). C(x,y,d) = sum over channels |L(x,y) -
// R(x-d,y)|; fx::kCostMax where x-d < 0 (a match outside the right image costs the most, so it
// never wins). Grey images are matched as if every channel held the grey value (3 * |L - R|).
Dsi cost(const Image& left, const Image& right, int ndisp);

// Stage 2. Gaussian-weighted window sum with zero padding, one final rounding shift.
Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel);

// Stage 3. CA rule 1 (synchronous): a cell whose d-1 or d+1 neighbour differs from it by less
// than half its value becomes the rounded mean of its 3x3 in-plane neighbourhood.
Dsi ca_rule1(const Dsi& dsi);

// Stage 4. CA rule 2 (synchronous): a cell with at least 7 of 8 in-plane neighbours that differ
// from it by less than half its value is divided by 1.3 (rounded).
Dsi ca_rule2(const Dsi& dsi);

// Stage 5. Argmin over d (ties to the smallest d); pixels the border rule marks invalid get
// disparity fx::kInvalidDisparity and valid flag 0.
DisparityMap wta(const Dsi& dsi, const InvalidBorder& border);

// The whole pipeline: validate, cost (params.cost), aggregate, [ca_rule1, ca_rule2], wta, run
// by the plane scheduler (stereo/search.hpp). The 8-bit view (to_label_map) of
// match_validated: with min_disp 0 and every validation stage off, the plain winners.
DisparityMap match(const Image& left, const Image& right, const MatchParams& params);

// The same with stage 6 (params.min_disp, params.validation): signed sub-pixel disparity x 16,
// invalid reason and certainty per pixel.
ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params);

// match_validated with the winner's final cost of every pixel (the same map, bit for bit).
CostedDisparity match_validated_with_costs(const Image& left, const Image& right,
                                           const MatchParams& params);

// The checks of validate() that depend on the image size (ndisp against the width, the invalid
// border against the size), for callers that built the kernel and the cost already.
void validate_size(const MatchParams& params, int width, int height);

class CostFunction;
// The pipeline with a cost function and kernel of the caller's (params.cost, params.sigma are
// not read; the kernel must have params.window taps): the edge front end's truncated AD, a
// matcher that builds its stages once.
DisparityMap match_with(const CostFunction& cost, const std::vector<std::int32_t>& kernel,
                        const Image& left, const Image& right, const MatchParams& params);
ValidatedDisparity match_validated_with(const CostFunction& cost,
                                        const std::vector<std::int32_t>& kernel, const Image& left,
                                        const Image& right, const MatchParams& params);

// What the stages after the cost gave some pixels, each label k (disparity min_disp + k): the
// aggregate, CA rule 1 and CA rule 2 (both equal to the aggregate with use_ca off). `stereo
// cosim` compares them with the RTL's stage outputs to say which stage a mismatch starts in.
struct PixelStageValues {
    int x = 0;
    int y = 0;
    std::vector<std::uint16_t> aggregate;
    std::vector<std::uint16_t> rule1;
    std::vector<std::uint16_t> rule2;
};
std::vector<PixelStageValues> stage_values_at(const Image& left, const Image& right,
                                              const MatchParams& params,
                                              const std::vector<std::pair<int, int>>& pixels);

// Throws std::invalid_argument unless the two images have the same size and channel count.
void check_pair(const Image& left, const Image& right);

}  // namespace stereo
