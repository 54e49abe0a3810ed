// The independent references of the ASW aggregator (stereo/asw.hpp): the fixed-point
// definition evaluated one pixel and one disparity at a time, straight from docs/asw.md, and the
// real-valued algorithm with exact logarithms and no rounding.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <vector>

#include "stereo/asw.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/reference.hpp"

namespace stereo::asw {
namespace {

bool inside(int x, int y, int width, int height) {
    return x >= 0 && y >= 0 && x < width && y < height;
}

// The support weight of neighbour q = p + o for pixel p at disparity d (docs/asw.md).
int naive_weight(const Image& left, const Image& right, const ResponseTables& tables,
                 const Params& params, const std::vector<std::int16_t>& labels, int x, int y,
                 const Offset& o, int d) {
    const int qx = x + o.dx;
    const int qy = y + o.dy;
    const int colour_left =
        tables.colour[static_cast<std::size_t>(colour_difference(left, x, y, left, qx, qy))];
    int w = (o.proximity * colour_left + 128) >> kResponseBits;
    if (params.continuity && !labels.empty()) {
        const int jump = std::abs(labels[static_cast<std::size_t>(y) * left.width + x] -
                                  labels[static_cast<std::size_t>(qy) * left.width + qx]);
        w = (w * tables.continuity[static_cast<std::size_t>(jump)] + 128) >> kResponseBits;
    }
    if (params.right_weights) {
        int colour_right = kResponseMax;  // either right pixel outside the right image
        if (inside(x - d, y, right.width, right.height) &&
            inside(qx - d, qy, right.width, right.height)) {
            colour_right = tables.colour[static_cast<std::size_t>(
                colour_difference(right, x - d, y, right, qx - d, qy))];
        }
        w = (w * colour_right + 128) >> kResponseBits;
    }
    return w;
}

Dsi naive_pass(const Dsi& in, const Image& left, const Image& right, int min_disp,
               const std::vector<Offset>& offsets, const ResponseTables& tables,
               const Params& params, const std::vector<std::int16_t>& labels, int out_shift) {
    Dsi out(in.width(), in.height(), in.ndisp());
    for (int k = 0; k < in.ndisp(); ++k) {
        for (int y = 0; y < in.height(); ++y) {
            for (int x = 0; x < in.width(); ++x) {
                std::uint64_t num = 0;
                std::uint64_t den = 0;
                for (const Offset& o : offsets) {
                    if (!inside(x + o.dx, y + o.dy, in.width(), in.height())) {
                        continue;
                    }
                    const int w =
                        naive_weight(left, right, tables, params, labels, x, y, o, min_disp + k);
                    num += static_cast<std::uint64_t>(w) * in.at(x + o.dx, y + o.dy, k);
                    den += static_cast<std::uint64_t>(w);
                }
                if (num > std::numeric_limits<std::uint32_t>::max() || den == 0) {
                    throw std::logic_error("ASW sums outside the proved widths");
                }
                out.at(x, y, k) = static_cast<Dsi::Value>(((num << out_shift) + den / 2) / den);
            }
        }
    }
    return out;
}

// Whether label k of a pixel in column x is a candidate: its match x - d lies inside the right
// image (docs/asw.md, "Border and validity").
bool has_partner(int x, int k, int min_disp, int width) {
    const int xr = x - (min_disp + k);
    return xr >= 0 && xr < width;
}

// The preliminary map: each pixel's first smallest cost among its candidates; a pixel with none
// takes min_disp (label 0).
std::vector<std::int16_t> naive_winners(const Dsi& volume, int min_disp) {
    std::vector<std::int16_t> winners(static_cast<std::size_t>(volume.width()) * volume.height());
    for (int y = 0; y < volume.height(); ++y) {
        for (int x = 0; x < volume.width(); ++x) {
            int best = -1;
            for (int k = 0; k < volume.ndisp(); ++k) {
                if (has_partner(x, k, min_disp, volume.width()) &&
                    (best < 0 || volume.at(x, y, k) < volume.at(x, y, best))) {
                    best = k;  // strict: ties stay with the smaller label
                }
            }
            winners[static_cast<std::size_t>(y) * volume.width() + x] =
                static_cast<std::int16_t>(min_disp + std::max(best, 0));
        }
    }
    return winners;
}

}  // namespace

Dsi aggregate_naive(const Dsi& cost, const Image& left, const Image& right, int min_disp,
                    const Params& params, const std::vector<std::int16_t>& labels) {
    validate(params, left.width, left.height);
    const ResponseTables tables = response_tables(params);
    const std::vector<Offset> region = support_region(params);
    if (!params.separable) {
        return naive_pass(cost, left, right, min_disp, region, tables, params, labels,
                          kOutputFracBits);
    }
    const std::vector<Offset> column = axis_offsets(region, true);
    const std::vector<Offset> row = axis_offsets(region, false);
    // The vertical pass has no continuity factor (docs/asw.md).
    Params vertical_params = params;
    vertical_params.continuity = false;
    const Dsi vertical = naive_pass(cost, left, right, min_disp, column, tables, vertical_params,
                                    {}, kOutputFracBits);
    return naive_pass(vertical, left, right, min_disp, row, tables, params, labels, 0);
}

namespace {

// The matching cost by its naive reference, then min(C, T) cell by cell (outside matches too).
// T by docs/asw.md "The truncated cost": params.truncation, or by the cost (census none, every
// other cost kDefaultTruncation); 0 is none.
Dsi truncated_cost_volume(const Image& left, const Image& right, const MatchParams& match,
                          const Params& params) {
    Dsi cost = stereo::naive::cost_volume(match.cost, left, right, match.ndisp, match.min_disp);
    int truncation = params.truncation;
    if (truncation == kTruncationByCost) {
        truncation = catalogue::cost(match.cost).asw_truncation;
    }
    if (truncation == 0) {
        return cost;
    }
    for (int y = 0; y < cost.height(); ++y) {
        for (int x = 0; x < cost.width(); ++x) {
            for (int k = 0; k < cost.ndisp(); ++k) {
                if (cost.at(x, y, k) > truncation) {
                    cost.at(x, y, k) = static_cast<Dsi::Value>(truncation);
                }
            }
        }
    }
    return cost;
}

}  // namespace

ValidatedDisparity match_naive(const Image& left, const Image& right, const MatchParams& match,
                               const Params& params) {
    validate(params, left.width, left.height);
    const Dsi cost = truncated_cost_volume(left, right, match, params);
    Params first = params;
    first.continuity = false;
    Dsi aggregated = aggregate_naive(cost, left, right, match.min_disp, first, {});
    if (params.continuity) {
        aggregated = aggregate_naive(cost, left, right, match.min_disp, params,
                                     naive_winners(aggregated, match.min_disp));
    }
    // Stage 6 by its definition, a pixel's outside matches no candidates (the naive reference's
    // own scan of the volume, not the model's selector).
    return stereo::naive::validate_inside_matches(aggregated, match.min_disp, match.validation);
}

namespace {

// Real-valued responses in [0, 1] (docs/asw.md, before the 8-bit rounding).
double real_response(double stimulus, const Params& params) {
    const double floor = 1.0 / params.diameter;
    const double s = std::min(1.0, std::max(stimulus, floor));
    return -std::log(s) / std::log(static_cast<double>(params.diameter));
}

struct RealWeights {
    const Params& params;
    double colour(int difference) const {
        return params.response == Response::log
                   ? real_response(static_cast<double>(difference) / params.colour_range, params)
                   : std::exp(-difference / kExpColourGamma);
    }
    double continuity(int jump) const {
        return params.response == Response::log
                   ? real_response(static_cast<double>(jump) / params.disparity_range, params)
                   : std::exp(-jump / kExpContinuityGamma);
    }
    double proximity(const Offset& o) const {
        const double distance = std::sqrt(static_cast<double>(o.dx * o.dx + o.dy * o.dy));
        const int radius = (params.diameter - 1) / 2;
        return params.response == Response::log ? real_response(distance / params.diameter, params)
                                                : std::exp(-distance / std::max(1, radius));
    }
};

std::vector<double> real_pass(const std::vector<double>& in, const Image& left, const Image& right,
                              int ndisp, int min_disp, const std::vector<Offset>& offsets,
                              const Params& params, const std::vector<std::int16_t>& labels) {
    const int width = left.width;
    const int height = left.height;
    const RealWeights weights{params};
    std::vector<double> out(in.size());
    for (int k = 0; k < ndisp; ++k) {
        const int d = min_disp + k;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                double num = 0.0;
                double den = 0.0;
                for (const Offset& o : offsets) {
                    const int qx = x + o.dx;
                    const int qy = y + o.dy;
                    if (!inside(qx, qy, width, height)) {
                        continue;
                    }
                    double w = weights.proximity(o) *
                               weights.colour(colour_difference(left, x, y, left, qx, qy));
                    if (params.continuity && !labels.empty()) {
                        w *= weights.continuity(
                            std::abs(labels[static_cast<std::size_t>(y) * width + x] -
                                     labels[static_cast<std::size_t>(qy) * width + qx]));
                    }
                    if (params.right_weights && inside(x - d, y, width, height) &&
                        inside(qx - d, qy, width, height)) {
                        w *= weights.colour(colour_difference(right, x - d, y, right, qx - d, qy));
                    }
                    num += w * in[(static_cast<std::size_t>(k) * height + qy) * width + qx];
                    den += w;
                }
                out[(static_cast<std::size_t>(k) * height + y) * width + x] =
                    den > 0.0 ? num / den
                              : in[(static_cast<std::size_t>(k) * height + y) * width + x];
            }
        }
    }
    return out;
}

std::vector<std::int16_t> real_winners(const std::vector<double>& volume, int width, int height,
                                       int ndisp, int min_disp) {
    std::vector<std::int16_t> winners(static_cast<std::size_t>(width) * height);
    const std::size_t plane = static_cast<std::size_t>(width) * height;
    for (std::size_t i = 0; i < plane; ++i) {
        // Only the disparities whose match lies inside the right image; none: min_disp (invalid).
        const int x = static_cast<int>(i % static_cast<std::size_t>(width));
        int best = -1;
        for (int k = 0; k < ndisp; ++k) {
            const int xr = x - (min_disp + k);
            const bool inside = xr >= 0 && xr < width;
            if (inside && (best < 0 || volume[k * plane + i] < volume[best * plane + i])) {
                best = k;
            }
        }
        winners[i] = static_cast<std::int16_t>(min_disp + std::max(best, 0));
    }
    return winners;
}

std::vector<double> real_aggregate(const std::vector<double>& cost, const Image& left,
                                   const Image& right, int ndisp, int min_disp,
                                   const Params& params, const std::vector<std::int16_t>& labels) {
    const std::vector<Offset> region = support_region(params);
    if (!params.separable) {
        return real_pass(cost, left, right, ndisp, min_disp, region, params, labels);
    }
    const std::vector<Offset> column = axis_offsets(region, true);
    const std::vector<Offset> row = axis_offsets(region, false);
    Params vertical_params = params;
    vertical_params.continuity = false;  // the vertical pass has no continuity factor
    const auto vertical =
        real_pass(cost, left, right, ndisp, min_disp, column, vertical_params, {});
    return real_pass(vertical, left, right, ndisp, min_disp, row, params, labels);
}

}  // namespace

DisparityMap match_floating(const Image& left, const Image& right, const MatchParams& match,
                            const Params& params) {
    validate(params, left.width, left.height);
    const Dsi cost = truncated_cost_volume(left, right, match, params);
    const std::vector<double> real_cost(cost.cells().begin(), cost.cells().end());
    Params first = params;
    first.continuity = false;
    auto aggregated =
        real_aggregate(real_cost, left, right, match.ndisp, match.min_disp, first, {});
    if (params.continuity) {
        const auto labels =
            real_winners(aggregated, left.width, left.height, match.ndisp, match.min_disp);
        aggregated =
            real_aggregate(real_cost, left, right, match.ndisp, match.min_disp, params, labels);
    }
    const auto winners =
        real_winners(aggregated, left.width, left.height, match.ndisp, match.min_disp);
    DisparityMap map(left.width, left.height);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            const std::size_t i = map.index(x, y);
            const int d = winners[i];
            if (x - d >= 0 && x - d < left.width && d >= 0 && d <= 255) {
                map.disparity[i] = static_cast<std::uint8_t>(d);
                map.valid[i] = 1;
            }
        }
    }
    return map;
}

}  // namespace stereo::asw
