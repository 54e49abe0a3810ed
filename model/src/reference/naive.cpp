// Deliberately plain: every value is computed straight from its definition in
// docs/fixed-point.md, with bounds checks in the innermost loops and integer division instead
// of multiply-and-shift. Slow, and meant to be.
#include <cmath>
#include <cstdlib>

#include "cells.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/reference.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::naive {
using reference::for_each_cell;
namespace {

// Zero padding: samples outside the plane read as 0.
int sample(const Dsi& dsi, int x, int y, int d) {
    if (x < 0 || y < 0 || x >= dsi.width() || y >= dsi.height()) {
        return 0;
    }
    return dsi.at(x, y, d);
}

bool differs_by_less_than_half(int neighbour, int centre) {
    // |n - c| < c / 2, in exact integers.
    return fx::agrees(neighbour, centre);
}

}  // namespace

Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp) {
    check_pair(left, right);
    return reference::pixel_cost_volume(
        left, ndisp, min_disp, fx::kCostMax, [&](int x, int y, int right_x) {
            int sum = 0;
            for (int c = 0; c < 3; ++c) {
                // A grey image has one channel; reading channel 0 three times matches (g,g,g).
                const int channel = left.channels == 3 ? c : 0;
                sum += std::abs(left.at(x, y, channel) - right.at(right_x, y, channel));
            }
            return sum;
        });
}

Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel) {
    const int radius = static_cast<int>(kernel.size()) / 2;
    const std::int64_t divisor = std::int64_t{1} << fx::kAggShift;
    Dsi out(cost.width(), cost.height(), cost.ndisp());
    for (int d = 0; d < cost.ndisp(); ++d) {
        for (int y = 0; y < cost.height(); ++y) {
            for (int x = 0; x < cost.width(); ++x) {
                std::int64_t sum = 0;
                for (int j = -radius; j <= radius; ++j) {
                    for (int i = -radius; i <= radius; ++i) {
                        const std::int64_t weight =
                            std::int64_t{kernel[i + radius]} * kernel[j + radius];
                        sum += weight * sample(cost, x + i, y + j, d);
                    }
                }
                // Round half up: floor(sum / 2^shift + 1/2).
                out.at(x, y, d) = static_cast<Dsi::Value>((2 * sum + divisor) / (2 * divisor));
            }
        }
    }
    return out;
}

Dsi ca_rule1(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    for_each_cell(dsi.width(), dsi.height(), dsi.ndisp(), [&](int x, int y, int d) {
        const int centre = dsi.at(x, y, d);
        bool fire = false;
        if (d - 1 >= 0 && differs_by_less_than_half(dsi.at(x, y, d - 1), centre)) {
            fire = true;
        }
        if (d + 1 < dsi.ndisp() && differs_by_less_than_half(dsi.at(x, y, d + 1), centre)) {
            fire = true;
        }
        if (!fire) {
            out.at(x, y, d) = static_cast<Dsi::Value>(centre);
            return;
        }
        int sum = 0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                sum += sample(dsi, x + i, y + j, d);
            }
        }
        out.at(x, y, d) = static_cast<Dsi::Value>((2 * sum + 9) / 18);  // round(sum / 9)
    });
    return out;
}

Dsi ca_rule2(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    for_each_cell(dsi.width(), dsi.height(), dsi.ndisp(), [&](int x, int y, int d) {
        const int centre = dsi.at(x, y, d);
        int count = 0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                if (i == 0 && j == 0) {
                    continue;
                }
                if (differs_by_less_than_half(sample(dsi, x + i, y + j, d), centre)) {
                    ++count;
                }
            }
        }
        out.at(x, y, d) = static_cast<Dsi::Value>(count >= 7 ? (20 * centre + 13) / 26
                                                             : centre);  // round(centre / 1.3)
    });
    return out;
}

DisparityMap wta(const Dsi& dsi, const InvalidBorder& border) {
    DisparityMap map(dsi.width(), dsi.height());
    for (int y = 0; y < dsi.height(); ++y) {
        for (int x = 0; x < dsi.width(); ++x) {
            int best = 0;
            for (int d = 1; d < dsi.ndisp(); ++d) {
                if (dsi.at(x, y, d) < dsi.at(x, y, best)) {
                    best = d;
                }
            }
            const int r = border.reach;
            const bool inside = x >= r && y >= r && x < dsi.width() - r && y < dsi.height() - r;
            if (!inside || x - best < r) {
                continue;
            }
            map.disparity[map.index(x, y)] = static_cast<std::uint8_t>(best);
            map.valid[map.index(x, y)] = 1;
        }
    }
    return map;
}

Dsi cost_volume(const std::string& name, const Image& left, const Image& right, int ndisp,
                int min_disp) {
    switch (catalogue::cost(name).id) {  // throws on an unknown name
        case catalogue::Cost::ad:
            return naive::cost(left, right, ndisp, min_disp);
        case catalogue::Cost::census:
            return census::naive::cost(left, right, ndisp, min_disp);
        case catalogue::Cost::lcdm:
            return lcdm::naive::cost(left, right, ndisp, lcdm::kDarkFloor, min_disp);
        case catalogue::Cost::zncc:
            return zncc::naive::cost(left, right, ndisp, min_disp);
    }
    throw std::logic_error("naive::cost_volume: a catalogue cost without a naive reference");
}

namespace {

// The final volume of the pipeline, stage by stage.
Dsi final_volume(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    // Qualified calls: argument-dependent lookup would also find the optimised stereo:: stages.
    Dsi dsi = naive::aggregate(
        naive::cost_volume(params.cost, left, right, params.ndisp, params.min_disp),
        gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        dsi = naive::ca_rule2(naive::ca_rule1(dsi));
    }
    return dsi;
}

// First label of the smallest cost among labels k with accept(k).
template <typename Accept, typename CostOf>
int first_minimum(int ndisp, Accept accept, CostOf cost_of) {
    int best = -1;
    for (int k = 0; k < ndisp; ++k) {
        if (accept(k) && (best < 0 || cost_of(k) < cost_of(best))) {
            best = k;
        }
    }
    return best;
}

}  // namespace

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    if (params.min_disp != 0 || params.validation != ValidationParams{}) {
        return to_label_map(naive::match_validated(left, right, params));
    }
    return naive::wta(final_volume(left, right, params), invalid_border(params));
}

namespace {

// Stage 6 along (step_x, step_y). With only_inside_matches, label k of pixel (x, y) is a
// candidate only where its partner pixel (x - d step_x, y - d step_y) lies inside the image (the
// ASW matcher's rule, docs/asw.md "Border and validity"); otherwise every label is one.
ValidatedDisparity stage_six(const Dsi& dsi, int step_x, int step_y, int min_disp,
                             const ValidationParams& params, int reach, bool only_inside_matches) {
    const auto inside = [](int x, int y, int width, int height, int margin) {
        return x >= margin && y >= margin && x < width - margin && y < height - margin;
    };
    const int width = dsi.width();
    const int height = dsi.height();
    const int ndisp = dsi.ndisp();
    ValidatedDisparity out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const auto cost = [&](int k) { return static_cast<int>(dsi.at(x, y, k)); };
            const auto candidate = [&](int k) {
                const int dd = min_disp + k;
                return !only_inside_matches ||
                       inside(x - dd * step_x, y - dd * step_y, width, height, 0);
            };
            const int winner = first_minimum(ndisp, candidate, cost);
            if (winner < 0) {
                continue;  // no candidate at all: invalid (border), certainty 0, disparity 0
            }
            const int second = first_minimum(
                ndisp, [&](int k) { return candidate(k) && (k < winner - 1 || k > winner + 1); },
                cost);
            const std::int64_t c1 = cost(winner);
            const std::int64_t c2 = second < 0 ? fx::kNoSecondCost : cost(second);
            const std::size_t q = out.index(x, y);
            out.certainty[q] = static_cast<std::uint8_t>((c2 - c1) * 256 / (c2 + 1));
            const int d = min_disp + winner;
            const int xs = x - d * step_x;
            const int ys = y - d * step_y;
            if (!inside(x, y, width, height, reach) || !inside(xs, ys, width, height, reach)) {
                out.reason[q] = fx::kReasonBorder;
                continue;
            }
            if (params.uniqueness && second >= 0 &&
                c1 * (100 + params.uniqueness_ratio) >= c2 * 100) {
                out.reason[q] = fx::kReasonUniqueness;
                continue;
            }
            if (params.left_right) {
                // The partner pixel's own winner: the first minimum over the reference pixels
                // that see it, (xs + d' * step.x, ys + d' * step.y) (each of those cells has its
                // partner, xs, inside: a candidate under either rule).
                const int right_winner = first_minimum(
                    ndisp,
                    [&](int k) {
                        const int dd = min_disp + k;
                        return inside(xs + dd * step_x, ys + dd * step_y, width, height, 0);
                    },
                    [&](int k) {
                        const int dd = min_disp + k;
                        return static_cast<int>(dsi.at(xs + dd * step_x, ys + dd * step_y, k));
                    });
                if (std::abs(winner - right_winner) > params.lr_tolerance) {
                    out.reason[q] = fx::kReasonLeftRight;
                    continue;
                }
            }
            out.reason[q] = fx::kReasonValid;
            double offset = 0.0;
            // A neighbour that is no candidate is no parabola point: the offset stays 0.
            if (params.subpixel && winner > 0 && winner < ndisp - 1 && candidate(winner - 1) &&
                candidate(winner + 1)) {
                const double before = cost(winner - 1);
                const double after = cost(winner + 1);
                const double curvature = before + after - 2.0 * static_cast<double>(c1);
                if (curvature > 0) {
                    // The parabola's vertex in 1/16 pixel, halves away from zero (std::round).
                    offset = std::round(8.0 * (before - after) / curvature);
                    // Then the calibrated correction of the vertex (constants.hpp).
                    const auto steps = static_cast<std::size_t>(std::abs(offset));
                    offset = std::copysign(fx::kSubpixelCorrection.at(steps), offset);
                }
            }
            out.fixed[q] = static_cast<std::int16_t>(16 * d + static_cast<int>(offset));
        }
    }
    return out;
}

}  // namespace

ValidatedDisparity validate_along(const Dsi& dsi, int step_x, int step_y, int min_disp,
                                  const ValidationParams& params, int reach) {
    return stage_six(dsi, step_x, step_y, min_disp, params, reach, false);
}

ValidatedDisparity validate(const Dsi& dsi, int min_disp, const ValidationParams& params,
                            const InvalidBorder& border) {
    return validate_along(dsi, 1, 0, min_disp, params, border.reach);
}

ValidatedDisparity validate_inside_matches(const Dsi& dsi, int min_disp,
                                           const ValidationParams& params) {
    return stage_six(dsi, 1, 0, min_disp, params, 0, true);
}

ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params) {
    return naive::validate(final_volume(left, right, params), params.min_disp, params.validation,
                           invalid_border(params));
}

}  // namespace stereo::naive
