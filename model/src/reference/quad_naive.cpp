// The quad-camera references, written from the definitions in docs/quad.md and
// docs/fixed-point.md: direct loops, bounds checks in the innermost loops, nothing shared with
// model/src/quad.cpp but the public stage definitions of stereo::naive.
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "stereo/quad.hpp"
#include "stereo/reference.hpp"

namespace stereo::quad::naive {
namespace {

bool inside(int x, int y, int width, int height, int margin) {
    return x >= margin && y >= margin && x < width - margin && y < height - margin;
}

Dsi cost(Step s, const Image& reference, const Image& partner, int ndisp, int min_disp) {
    Dsi dsi(reference.width, reference.height, ndisp);
    for (int y = 0; y < reference.height; ++y) {
        for (int x = 0; x < reference.width; ++x) {
            for (int k = 0; k < ndisp; ++k) {
                const int d = min_disp + k;
                const int xs = x - d * s.x;
                const int ys = y - d * s.y;
                if (!inside(xs, ys, reference.width, reference.height, 0)) {
                    dsi.at(x, y, k) = fx::kCostMax;
                    continue;
                }
                int sum = 0;
                for (int c = 0; c < 3; ++c) {
                    const int channel = reference.channels == 3 ? c : 0;
                    sum += std::abs(reference.at(x, y, channel) - partner.at(xs, ys, channel));
                }
                dsi.at(x, y, k) = static_cast<Dsi::Value>(sum);
            }
        }
    }
    return dsi;
}

// The first label with the smallest cost among those `accept` takes; -1 when none.
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

ValidatedDisparity validate(const Dsi& dsi, Step s, int min_disp, const ValidationParams& params,
                            int reach) {
    const int width = dsi.width();
    const int height = dsi.height();
    const int ndisp = dsi.ndisp();
    ValidatedDisparity out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const auto cost = [&](int k) { return static_cast<int>(dsi.at(x, y, k)); };
            const int winner = first_minimum(
                ndisp, [](int) { return true; }, cost);
            const int second = first_minimum(
                ndisp, [&](int k) { return k < winner - 1 || k > winner + 1; }, cost);
            const std::int64_t c1 = cost(winner);
            const std::int64_t c2 = second < 0 ? fx::kNoSecondCost : cost(second);
            const std::size_t q = out.index(x, y);
            out.certainty[q] = static_cast<std::uint8_t>((c2 - c1) * 256 / (c2 + 1));
            const int d = min_disp + winner;
            const int xs = x - d * s.x;
            const int ys = y - d * s.y;
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
                // that see it, (xs + d' * step.x, ys + d' * step.y).
                const int right_winner = first_minimum(
                    ndisp,
                    [&](int k) {
                        const int dd = min_disp + k;
                        return inside(xs + dd * s.x, ys + dd * s.y, width, height, 0);
                    },
                    [&](int k) {
                        const int dd = min_disp + k;
                        return static_cast<int>(dsi.at(xs + dd * s.x, ys + dd * s.y, k));
                    });
                if (std::abs(winner - right_winner) > params.lr_tolerance) {
                    out.reason[q] = fx::kReasonLeftRight;
                    continue;
                }
            }
            out.reason[q] = fx::kReasonValid;
            double offset = 0.0;
            if (params.subpixel && winner > 0 && winner < ndisp - 1) {
                const double before = cost(winner - 1);
                const double after = cost(winner + 1);
                const double curvature = before + after - 2.0 * static_cast<double>(c1);
                if (curvature > 0) {
                    offset = std::round(8.0 * (before - after) / curvature);
                }
            }
            out.fixed[q] = static_cast<std::int16_t>(16 * d + static_cast<int>(offset));
        }
    }
    return out;
}

}  // namespace

ValidatedDisparity match_pair(Pair pair, const Image& reference, const Image& partner,
                              const MatchParams& params) {
    check_pair(reference, partner);
    validate_pair(pair, params, reference.width, reference.height);
    const Step s = step(pair);
    Dsi dsi = stereo::naive::aggregate(cost(s, reference, partner, params.ndisp, params.min_disp),
                                       gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        dsi = stereo::naive::ca_rule2(stereo::naive::ca_rule1(dsi));
    }
    return validate(dsi, s, params.min_disp, params.validation, invalid_border(params).reach);
}

QuadResult fuse(std::array<ValidatedDisparity, 3> pairs) {
    const int width = pairs[0].width;
    const int height = pairs[0].height;
    if (pairs[1].width != width || pairs[2].width != width || pairs[1].height != height ||
        pairs[2].height != height) {
        throw std::invalid_argument("the three pair maps must have one size");
    }
    QuadResult result;
    result.fused = ValidatedDisparity(width, height);
    result.source.assign(static_cast<std::size_t>(width) * height, kSourceNone);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = result.fused.index(x, y);
            // Key: 0 for an invalid pair, else 1 + 3 * certainty + priority (horizontal 2,
            // vertical 1, diagonal 0): the largest key wins, equal certainties by priority.
            int best_key = 0;
            int best_pair = -1;
            for (int p = 2; p >= 0; --p) {
                const int key = pairs[p].reason[i] == fx::kReasonValid
                                    ? 1 + 3 * pairs[p].certainty[i] + (2 - p)
                                    : 0;
                if (key > best_key) {
                    best_key = key;
                    best_pair = p;
                }
            }
            if (best_pair < 0) {
                result.fused.reason[i] = pairs[0].reason[i];
                result.fused.certainty[i] = 0;
                continue;
            }
            result.fused.fixed[i] = pairs[best_pair].fixed[i];
            result.fused.reason[i] = fx::kReasonValid;
            result.fused.certainty[i] = pairs[best_pair].certainty[i];
            result.source[i] = static_cast<std::uint8_t>(best_pair + 1);
        }
    }
    result.pairs = std::move(pairs);
    return result;
}

QuadResult match_quad(const QuadViews& views, const MatchParams& params) {
    validate_quad(views, params);
    return naive::fuse(
        {naive::match_pair(Pair::horizontal, views.reference, views.horizontal, params),
         naive::match_pair(Pair::vertical, views.reference, views.vertical, params),
         naive::match_pair(Pair::diagonal, views.reference, views.diagonal, params)});
}

}  // namespace stereo::quad::naive
