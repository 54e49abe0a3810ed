#include "stereo/sparse.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"

namespace stereo::sparse {

double SparseDisparity::valid_fraction() const {
    if (disparity.empty()) {
        return 0.0;
    }
    const auto count =
        std::count_if(disparity.begin(), disparity.end(), [](float d) { return d >= 0.0f; });
    return static_cast<double>(count) / static_cast<double>(disparity.size());
}

double parabola_offset(double c_minus, double c0, double c_plus) {
    const double curvature = c_minus - 2.0 * c0 + c_plus;
    if (!(curvature > 0.0)) {
        return 0.0;
    }
    return std::clamp((c_minus - c_plus) / (2.0 * curvature), -0.5, 0.5);
}

void validate(const MatchParams& match, const Params& params, int width, int height) {
    MatchParams model = match;
    model.use_ca = false;
    stereo::validate(model, width, height);
    if (match.ndisp < 3) {
        throw std::invalid_argument("the certainty test needs at least 3 disparity labels, got " +
                                    std::to_string(match.ndisp));
    }
    if (!(params.certainty >= 0.0) || !std::isfinite(params.certainty)) {
        throw std::invalid_argument("certainty threshold must be a number >= 0");
    }
    if (params.lr_tolerance < 0) {
        throw std::invalid_argument("left-right tolerance must be >= 0");
    }
}

SparseDisparity validate_dsi(const Dsi& aggregated, const Params& params, int reach,
                             ValidationCounts* counts) {
    const int width = aggregated.width();
    const int height = aggregated.height();
    const int ndisp = aggregated.ndisp();
    SparseDisparity out(width, height);
    ValidationCounts tally;
    // One row of the DSI transposed to [x][d], so that each cost curve is contiguous.
    std::vector<double> curve(static_cast<std::size_t>(width) * ndisp);
    std::vector<int> right_best(width, -1);

    for (int y = reach; y < height - reach; ++y) {
        for (int d = 0; d < ndisp; ++d) {
            const auto plane = aggregated.plane(d);
            const std::size_t row = static_cast<std::size_t>(y) * width;
            for (int x = 0; x < width; ++x) {
                curve[static_cast<std::size_t>(x) * ndisp + d] = plane[row + x];
            }
        }
        const auto cost = [&](int x, int d) {
            return curve[static_cast<std::size_t>(x) * ndisp + d];
        };
        // Right view: the right pixel xr is seen by left pixels xr + d.
        for (int xr = reach; xr < width - reach; ++xr) {
            const int dmax = std::min(ndisp - 1, width - 1 - reach - xr);
            int best = 0;
            for (int d = 1; d <= dmax; ++d) {
                if (cost(xr + d, d) < cost(xr + best, best)) {
                    best = d;
                }
            }
            right_best[xr] = best;
        }
        for (int x = reach; x < width - reach; ++x) {
            const int dmax = std::min(ndisp - 1, x - reach);
            if (dmax < 2) {
                continue;
            }
            ++tally.candidates;
            int d1 = 0;
            for (int d = 1; d <= dmax; ++d) {
                if (cost(x, d) < cost(x, d1)) {
                    d1 = d;
                }
            }
            double c2 = std::numeric_limits<double>::infinity();
            for (int d = 0; d <= dmax; ++d) {
                if (std::abs(d - d1) >= 2) {
                    c2 = std::min(c2, cost(x, d));
                }
            }
            const double c1 = cost(x, d1);
            const bool certain = c1 > 0.0 ? (c2 - c1) / c1 > params.certainty : c2 > 0.0;
            if (!certain) {
                ++tally.uncertain;
                continue;
            }
            const int xr = x - d1;  // >= reach, so right_best[xr] was computed
            if (std::abs(right_best[xr] - d1) > params.lr_tolerance) {
                ++tally.inconsistent;
                continue;
            }
            double offset = 0.0;
            if (d1 > 0 && d1 < dmax) {
                offset = parabola_offset(cost(x, d1 - 1), c1, cost(x, d1 + 1));
            }
            out.at(x, y) = static_cast<float>(d1 + offset);
            ++tally.valid;
        }
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
    const Dsi aggregated = aggregate(cost_volume(*make_cost(match.cost), left, right, match.ndisp),
                                     gaussian_kernel(match.window, match.sigma));
    return validate_dsi(aggregated, params, match.window / 2, counts);
}

}  // namespace stereo::sparse
