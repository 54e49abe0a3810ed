// The quad-camera references, written from the definitions in docs/quad.md and
// docs/fixed-point.md: direct loops, bounds checks in the innermost loops, nothing shared with
// model/src/quad.cpp but the public stage definitions of stereo::naive.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "stereo/catalogue.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/quad.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::quad::naive {
namespace {

bool inside(int x, int y, int width, int height, int margin) {
    return x >= margin && y >= margin && x < width - margin && y < height - margin;
}

// One reference pixel against one partner pixel, both inside, by the cost's definition.
int pixel_cost(const MatchParams& params, const Image& reference, int x, int y,
               const Image& partner, int xs, int ys, const Image& reference_grey,
               const Image& partner_grey) {
    switch (catalogue::cost(params.cost).id) {
        case catalogue::Cost::census:
            return census::naive::pixel_cost(reference_grey, x, y, partner_grey, xs, ys);
        case catalogue::Cost::lcdm:
            return lcdm::naive::pixel_cost(reference, x, y, partner, xs, ys, lcdm::kDarkFloor);
        case catalogue::Cost::ad:
            break;
        case catalogue::Cost::zncc:  // not a pixel-pair cost: refused by validate_pair
            throw std::invalid_argument("the naive pair matcher has no zncc cost");
    }
    int sum = 0;
    for (int c = 0; c < 3; ++c) {
        const int channel = reference.channels == 3 ? c : 0;
        sum += std::abs(reference.at(x, y, channel) - partner.at(xs, ys, channel));
    }
    return sum;
}

Dsi cost(Step s, const Image& reference, const Image& partner, const MatchParams& params) {
    if (catalogue::cost(params.cost).id == catalogue::Cost::lcdm &&
        (reference.channels != 3 || partner.channels != 3)) {
        throw std::invalid_argument("the lcdm cost needs colour images");
    }
    const Image reference_grey = edge_frontend::naive::luma(reference);
    const Image partner_grey = edge_frontend::naive::luma(partner);
    Dsi dsi(reference.width, reference.height, params.ndisp);
    for (int y = 0; y < reference.height; ++y) {
        for (int x = 0; x < reference.width; ++x) {
            for (int k = 0; k < params.ndisp; ++k) {
                const int d = params.min_disp + k;
                const int xs = x - d * s.x;
                const int ys = y - d * s.y;
                dsi.at(x, y, k) =
                    inside(xs, ys, reference.width, reference.height, 0)
                        ? static_cast<Dsi::Value>(pixel_cost(params, reference, x, y, partner, xs,
                                                             ys, reference_grey, partner_grey))
                        : static_cast<Dsi::Value>(fx::kCostMax);
            }
        }
    }
    return dsi;
}

// The final volume of a pair by stereo::naive's stages.
Dsi final_volume(Pair pair, const Image& reference, const Image& partner,
                 const MatchParams& params) {
    check_pair(reference, partner);
    validate_pair(pair, params, reference.width, reference.height);
    Dsi dsi = stereo::naive::aggregate(cost(step(pair), reference, partner, params),
                                       gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        dsi = stereo::naive::ca_rule2(stereo::naive::ca_rule1(dsi));
    }
    return dsi;
}

ValidatedDisparity validate(Pair pair, const Dsi& dsi, const MatchParams& params) {
    const Step s = step(pair);
    return stereo::naive::validate_along(dsi, s.x, s.y, params.min_disp, params.validation,
                                         invalid_border(params).reach);
}

}  // namespace

ValidatedDisparity match_pair(Pair pair, const Image& reference, const Image& partner,
                              const MatchParams& params) {
    return validate(pair, final_volume(pair, reference, partner, params), params);
}

PairMatch match_pair_with_cost(Pair pair, const Image& reference, const Image& partner,
                               const MatchParams& params) {
    const Dsi dsi = final_volume(pair, reference, partner, params);
    PairMatch out{validate(pair, dsi, params), {}};
    // C1: the smallest cost of the pixel's column (the first minimum's value; which label holds
    // it does not matter for the value).
    for (int y = 0; y < dsi.height(); ++y) {
        for (int x = 0; x < dsi.width(); ++x) {
            int c1 = dsi.at(x, y, 0);
            for (int k = 1; k < dsi.ndisp(); ++k) {
                c1 = std::min(c1, static_cast<int>(dsi.at(x, y, k)));
            }
            out.cost.push_back(static_cast<std::uint16_t>(c1));
        }
    }
    return out;
}

namespace {

// The largest key wins; `key(p, i)` is 0 for an invalid pair.
template <class Key>
QuadResult fuse_by_key(std::array<ValidatedDisparity, 3> pairs, Key key) {
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
            long long best_key = 0;
            int best_pair = -1;
            for (int p = 0; p < 3; ++p) {
                const long long k = pairs[p].reason[i] == fx::kReasonValid ? key(p, i) : 0;
                if (k > best_key) {
                    best_key = k;
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

}  // namespace

QuadResult fuse(std::array<ValidatedDisparity, 3> pairs) {
    // Key: 1 + 3 * certainty + priority (horizontal 2, vertical 1, diagonal 0): the largest key
    // wins, equal certainties by priority.
    const auto key = [&pairs](int p, std::size_t i) {
        return 1 + 3LL * pairs[p].certainty[i] + (2 - p);
    };
    return fuse_by_key(pairs, key);
}

QuadResult fuse_by_cost(std::array<PairMatch, 3> pairs) {
    for (const PairMatch& pair : pairs) {
        if (pair.cost.size() != pair.map.fixed.size()) {
            throw std::invalid_argument("a pair's winner costs do not cover its map");
        }
    }
    // Key: 1 + 3 * (kAggMax - cost) + priority (horizontal 2, vertical 1, diagonal 0).
    const auto key = [&pairs](int p, std::size_t i) {
        return 1 + 3LL * (fx::kAggMax - pairs[p].cost[i]) + (2 - p);
    };
    return fuse_by_key({pairs[0].map, pairs[1].map, pairs[2].map}, key);
}

QuadResult match_quad(const QuadViews& views, const MatchParams& params, FusionKey key) {
    validate_quad(views, params);
    if (key == FusionKey::cost) {
        return naive::fuse_by_cost(
            {naive::match_pair_with_cost(Pair::horizontal, views.reference, views.horizontal,
                                         params),
             naive::match_pair_with_cost(Pair::vertical, views.reference, views.vertical, params),
             naive::match_pair_with_cost(Pair::diagonal, views.reference, views.diagonal, params)});
    }
    return naive::fuse(
        {naive::match_pair(Pair::horizontal, views.reference, views.horizontal, params),
         naive::match_pair(Pair::vertical, views.reference, views.vertical, params),
         naive::match_pair(Pair::diagonal, views.reference, views.diagonal, params)});
}

}  // namespace stereo::quad::naive
