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
    return stereo::naive::validate_along(dsi, s.x, s.y, params.min_disp, params.validation,
                                         invalid_border(params).reach);
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
