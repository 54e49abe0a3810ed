#include "stereo/sparse.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "stereo/constants.hpp"

namespace stereo::sparse {

double SparseDisparity::valid_fraction() const {
    if (disparity.empty()) {
        return 0.0;
    }
    const auto count =
        std::count_if(disparity.begin(), disparity.end(), [](float d) { return d >= 0.0f; });
    return static_cast<double>(count) / static_cast<double>(disparity.size());
}

MatchParams stage6_params(const MatchParams& match, const Params& params) {
    MatchParams out = match;
    out.use_ca = false;
    out.min_disp = 0;
    out.validation = {.uniqueness = true,
                      .uniqueness_ratio = params.uniqueness,
                      .left_right = true,
                      .lr_tolerance = params.lr_tolerance,
                      .subpixel = true};
    return out;
}

void validate(const MatchParams& match, const Params& params, int width, int height) {
    if (match.ndisp < 3) {
        // Below 3 labels there is no cost outside the winner and its neighbours.
        throw std::invalid_argument("the uniqueness test needs at least 3 disparity labels, got " +
                                    std::to_string(match.ndisp));
    }
    if (match.min_disp != 0) {
        throw std::invalid_argument("the sparse matcher searches from disparity 0 (--min-disp " +
                                    std::to_string(match.min_disp) + ")");
    }
    stereo::validate(stage6_params(match, params), width, height);
}

SparseDisparity from_validated(const ValidatedDisparity& validated, ValidationCounts* counts) {
    SparseDisparity out(validated.width, validated.height);
    ValidationCounts tally;
    for (std::size_t i = 0; i < validated.reason.size(); ++i) {
        switch (validated.reason[i]) {
            case fx::kReasonValid:
                if (validated.fixed[i] < 0) {
                    throw std::invalid_argument(
                        "sparse: a negative disparity (minimum disparity "
                        "must be 0)");
                }
                out.disparity[i] = static_cast<float>(validated.disparity(i));
                ++tally.valid;
                break;
            case fx::kReasonUniqueness:
                ++tally.uncertain;
                break;
            case fx::kReasonLeftRight:
                ++tally.inconsistent;
                break;
            default:
                continue;  // border: not a candidate
        }
        ++tally.candidates;
    }
    if (counts != nullptr) {
        *counts = tally;
    }
    return out;
}

SparseDisparity match(const Image& left, const Image& right, const MatchParams& match,
                      const Params& params, ValidationCounts* counts) {
    check_pair(left, right);
    validate(match, params, left.width, left.height);
    return from_validated(match_validated(left, right, stage6_params(match, params)), counts);
}

}  // namespace stereo::sparse
