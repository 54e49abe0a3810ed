// The sparse matcher (the SLAM front end of thesis Sec. 4.2.1): the golden model's
// Gaussian-aggregated AD costs, then a double validation (certainty of the cost curve, left-right
// consistency) and a sub-pixel parabola, in floating point on the host. The result is a sparse
// but reliable disparity map. Thresholds: docs/slam.md. Registered as method "sparse".
#pragma once

#include <cstddef>
#include <vector>

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::sparse {

struct Params {
    double certainty = 0.1;  // (C2 - C1) / C1 must be larger than this
    int lr_tolerance = 1;    // |dL - dR| <= this
};

inline constexpr float kNoDisparity = -1.0f;

// Sub-pixel disparities of the left image; kNoDisparity where a pixel failed validation.
struct SparseDisparity {
    int width = 0;
    int height = 0;
    std::vector<float> disparity;

    SparseDisparity() = default;
    SparseDisparity(int w, int h)
        : width(w), height(h), disparity(static_cast<std::size_t>(w) * h, kNoDisparity) {}
    float at(int x, int y) const { return disparity[static_cast<std::size_t>(y) * width + x]; }
    float& at(int x, int y) { return disparity[static_cast<std::size_t>(y) * width + x]; }
    bool valid(int x, int y) const { return at(x, y) >= 0.0f; }
    double valid_fraction() const;
};

// Vertex of the parabola through (-1, c_minus), (0, c0), (1, c_plus), relative to the middle
// sample: (c_minus - c_plus) / (2 (c_minus - 2 c0 + c_plus)). When c0 is the smallest of the
// three the offset lies in [-0.5, 0.5]; a flat or concave triple gives 0.
double parabola_offset(double c_minus, double c0, double c_plus);

// Why a pixel was rejected, for statistics.
struct ValidationCounts {
    std::size_t candidates = 0;    // pixels whose window and 3 or more labels lie in the images
    std::size_t uncertain = 0;     // failed the certainty test
    std::size_t inconsistent = 0;  // failed the left-right check
    std::size_t valid = 0;
};

// The validation on an aggregated DSI (C(x, y, d) compares L(x) with R(x - d)). `reach` is the
// aggregation radius: a pixel is a candidate when its window lies in the image and labels
// 0 .. min(ndisp - 1, x - reach) number at least 3. For the best label d1 (cost C1, ties to the
// smallest d) and C2 the best cost with |d - d1| >= 2:
//   certainty: C1 > 0 ? (C2 - C1) / C1 > params.certainty : C2 > 0;
//   left-right: dR(x - d1) within params.lr_tolerance of d1, where dR(xr) = argmin_d C(xr + d, d)
//   over the labels whose window lies in the image;
//   sub-pixel: d1 + parabola_offset(C(d1 - 1), C1, C(d1 + 1)) when both neighbours exist.
SparseDisparity validate_dsi(const Dsi& aggregated, const Params& params, int reach,
                             ValidationCounts* counts = nullptr);

// Model cost and aggregation (stereo::cost, stereo::aggregate; `match.use_ca` is not read), then
// validate_dsi. Throws std::invalid_argument for impossible parameters (through stereo::validate)
// or a certainty < 0.
SparseDisparity match(const Image& left, const Image& right, const MatchParams& match,
                      const Params& params, ValidationCounts* counts = nullptr);

// Throws std::invalid_argument unless the parameters fit an image of this size.
void validate(const MatchParams& match, const Params& params, int width, int height);

}  // namespace stereo::sparse
