// The sparse matcher (the SLAM front end of thesis Sec. 4.2.1): the 1-D pipeline without the CA
// rules and with every stage-6 check on (uniqueness, left-right consistency, sub-pixel
// refinement; docs/fixed-point.md "Stage 6"), its valid pixels as sub-pixel disparities. The
// result is a sparse but reliable disparity map. Thresholds: docs/slam.md. Registered as method
// "sparse"; it has no validation code of its own.
#pragma once

#include <cstddef>
#include <vector>

#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::sparse {

struct Params {
    // Stage 6's uniqueness ratio U: invalid when C1 (100 + U) >= C2 100, i.e. valid when
    // (C2 - C1) / C1 > U / 100 (C2: the best cost outside the winner and its neighbours).
    int uniqueness = 10;
    int lr_tolerance = 1;  // stage 6's left-right tolerance: |dL - dR| <= this
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

// Why pixels were rejected, from stage 6's invalid reasons.
struct ValidationCounts {
    std::size_t candidates = 0;    // pixels outside the invalid border
    std::size_t uncertain = 0;     // failed the uniqueness test
    std::size_t inconsistent = 0;  // failed the left-right check
    std::size_t valid = 0;
};

// The pipeline parameters the sparse matcher runs: `match` without the CA rules, minimum
// disparity 0, uniqueness, left-right check and sub-pixel refinement on with `params`.
MatchParams stage6_params(const MatchParams& match, const Params& params);

// The valid pixels of a stage-6 result as disparities (fixed / 16), with the reason counts.
// The minimum disparity must be 0 (a valid disparity is never negative then).
SparseDisparity from_validated(const ValidatedDisparity& validated,
                               ValidationCounts* counts = nullptr);

// stereo::match_validated with stage6_params, then from_validated. Throws
// std::invalid_argument for impossible parameters.
SparseDisparity match(const Image& left, const Image& right, const MatchParams& match,
                      const Params& params, ValidationCounts* counts = nullptr);

// Throws std::invalid_argument unless the parameters fit an image of this size.
void validate(const MatchParams& match, const Params& params, int width, int height);

}  // namespace stereo::sparse
