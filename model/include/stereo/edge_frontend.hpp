// Edge-enhanced front end of the obstacle-avoidance stereo variant (thesis Sec. 4.1.1), bit-exact.
// LoG edges (zero crossings, zero threshold) are superimposed on both images, the matching cost
// is the truncated AD, there is no CA stage; aggregation and WTA are the model's own
// (stereo::aggregate, stereo::wta). Specified to the bit in docs/avoidance.md.
#pragma once

#include <cstdint>
#include <vector>

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/luma.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::edge_frontend {

// round(0.04 * 765): 4 % of the largest per-pixel cost (three 8-bit channels).
inline constexpr int kDefaultTruncation = 31;

struct EdgeParams {
    int log_window = 7;      // odd side of the Gaussian smoothing kernel (radius 3 sigma)
    double log_sigma = 1.0;  // Gaussian sigma in pixels
    int edge_value = 255;    // intensity written into every channel of an edge pixel
    int truncation = kDefaultTruncation;  // the AD cost saturates here
};

// Signed integer image of LoG responses, row-major.
struct Response {
    int width = 0;
    int height = 0;
    std::vector<std::int32_t> values;
    std::int32_t at(int x, int y) const { return values[static_cast<std::size_t>(y) * width + x]; }
    bool operator==(const Response&) const = default;
};

// Throws std::invalid_argument with a one-line message for impossible parameters.
void validate(const EdgeParams& params);

// ITU-R BT.601 integer luma (stereo/luma.hpp, shared with the census and ZNCC stages).
using stereo::luma;

// Integer LoG of a grey image: separable smoothing with gaussian_kernel(window, sigma) (taps
// summing to 256, replicated border), then the 4-neighbour Laplacian (replicated border).
// The result is 2^16 times the LoG of the image in grey levels.
Response log_response(const Image& grey, const std::vector<std::int32_t>& kernel);

// 1 where the response has strictly opposite signs (zero threshold) at (x,y) and at its right
// or its lower neighbour, L(x,y) * L(x+1,y) < 0 or L(x,y) * L(x,y+1) < 0; 0 elsewhere. 1 channel.
Image zero_crossings(const Response& response);

// A copy of `image` with every channel of every edge pixel set to `value`.
Image superimpose(const Image& image, const Image& edges, int value);

// luma -> log_response -> zero_crossings -> superimpose, on one image.
Image enhance(const Image& image, const EdgeParams& params);

// C(x,y,d) = min(sum_c |L - R|, truncation); fx::kCostOutside where x - d < 0. Grey pixels count
// as (g, g, g), as in stereo::cost.
Dsi truncated_cost(const Image& left, const Image& right, int ndisp, int truncation);

// The whole variant: enhance both images, truncated_cost, aggregate, wta. `params.use_ca` is
// ignored (there is no CA stage) and the invalid border is that of the CA-less pipeline.
DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params = {});

namespace naive {
// Obviously-correct versions of the new stages (direct 2-D sums, clamped coordinates) that
// must equal the ones above exactly.
Image luma(const Image& image);
Response log_response(const Image& grey, const std::vector<std::int32_t>& kernel);
Image zero_crossings(const Response& response);
Image superimpose(const Image& image, const Image& edges, int value);
Dsi truncated_cost(const Image& left, const Image& right, int ndisp, int truncation);
DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params = {});
}  // namespace naive

}  // namespace stereo::edge_frontend
