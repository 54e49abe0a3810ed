// Checks and helpers shared by the edge front end (edge_frontend.cpp) and its naive reference
// (reference/edge_naive.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/edge_frontend.hpp"

namespace stereo::edge_frontend::detail {

using Value = Dsi::Value;

using fx::kLumaB;
using fx::kLumaG;
using fx::kLumaR;
using fx::kLumaShift;

// Widths: the smoothed image is at most 255 * 2^16 (24 bits); the Laplacian is at most 8 times
// that in magnitude, which fits a signed 32-bit value.
static_assert(static_cast<std::int64_t>(fx::kPixelMax) * fx::kKernelSum * fx::kKernelSum * 8 <
              (std::int64_t{1} << 31));

inline void check_grey(const Image& grey) {
    if (grey.empty() || grey.channels != 1) {
        throw std::invalid_argument("the LoG needs a non-empty grey image");
    }
}

// What both LoG versions start from: a checked grey image's size and the kernel's radius.
struct LogShape {
    int w;
    int h;
    int r;
};

inline LogShape log_shape(const Image& grey, const std::vector<std::int32_t>& kernel) {
    check_grey(grey);
    return {grey.width, grey.height, static_cast<int>(kernel.size()) / 2};
}

inline void check_same_size(const Image& image, const Image& edges) {
    if (edges.channels != 1 || edges.width != image.width || edges.height != image.height) {
        throw std::invalid_argument("edge map must be a grey image of the same size");
    }
}

inline void check_truncation(int truncation) {
    if (truncation < 0 || truncation > fx::kCostMax) {
        throw std::invalid_argument("truncation must be in [0, " + std::to_string(fx::kCostMax) +
                                    "], got " + std::to_string(truncation));
    }
}

inline void check_cost_inputs(const Image& left, const Image& right, int ndisp, int truncation) {
    check_pair(left, right);
    if (ndisp < 1 || ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp out of range: " + std::to_string(ndisp));
    }
    check_truncation(truncation);
}

// Per-pixel colour as three values, grey repeated, so both versions count channels alike.
inline std::array<int, 3> rgb(const Image& image, int x, int y) {
    if (image.channels == 1) {
        const int g = image.at(x, y, 0);
        return {g, g, g};
    }
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

// Strictly opposite signs; a zero is neither, so the flat zero response beside a lobe is not a
// crossing.
inline bool opposite(std::int32_t a, std::int32_t b) {
    return (a < 0 && b > 0) || (a > 0 && b < 0);
}

// The checks both match() versions run first (pair, matching and edge parameters); returns
// the matching parameters without the CA rules, which the edge front end does not use.
inline MatchParams checked_plain_params(const Image& left, const Image& right, MatchParams params,
                                        const EdgeParams& edge_params) {
    check_pair(left, right);
    params.use_ca = false;
    stereo::validate(params, left.width, left.height);
    validate(edge_params);
    return params;
}

}  // namespace stereo::edge_frontend::detail
