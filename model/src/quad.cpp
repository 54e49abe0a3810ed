// Quad-camera matching (docs/quad.md): the three pair geometries and the certainty fusion.
#include "stereo/quad.hpp"
#include "stereo/catalogue.hpp"

#include <algorithm>
#include <cstdlib>
#include <future>
#include <stdexcept>
#include <string>
#include <utility>

#include "stereo/stages.hpp"
#include "stereo/stages/validate.hpp"

namespace stereo::quad {
namespace {

std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
           std::to_string(image.channels);
}

// The partner pixel of (x, y) at disparity d lies inside [lo, hi) on both axes.
bool partner_inside(Step s, int x, int y, int d, int width, int height, int reach) {
    const int xs = x - d * s.x;
    const int ys = y - d * s.y;
    return xs >= reach && xs < width - reach && ys >= reach && ys < height - reach;
}

// Stage 1 along the direction, through the cost plug-in (stages.hpp): plane k holds d =
// min_disp + k, kCostOutside where the partner pixel leaves the image. The plug-in's row() takes
// the partner row and column offset, so every pixel-pair cost (stereo/catalogue.hpp) runs along any
// direction.
Dsi direction_cost(Step s, const Image& reference, const Image& partner,
                   const MatchParams& params) {
    const int width = reference.width;
    const int height = reference.height;
    const auto cost = make_cost(params.cost);
    const PlanarImage ref = cost->prepare(reference);
    const PlanarImage par = cost->prepare(partner);
    Dsi dsi(width, height, params.ndisp);
    for (int k = 0; k < params.ndisp; ++k) {
        const int d = params.min_disp + k;
        const int shift = d * s.x;
        // The columns whose partner x - shift lies inside [0, width).
        const int x0 = std::clamp(shift, 0, width);
        const int x1 = std::clamp(width + shift, 0, width);
        const auto plane = dsi.plane(k);
        std::fill(plane.begin(), plane.end(), static_cast<Dsi::Value>(fx::kCostOutside));
        for (int y = 0; y < height; ++y) {
            const int ys = y - d * s.y;
            if (ys < 0 || ys >= height || x1 <= x0) {
                continue;
            }
            cost->row(ref, par, y, ys, x0, x1 - x0, shift,
                      &plane[static_cast<std::size_t>(y) * width + x0]);
        }
    }
    return dsi;
}

// Stage 6 over a final volume, plane by plane: winner, second cost, right-referenced winner of
// every partner pixel (the left pixels that see it, along the direction), then per pixel. The
// winner costs come along for fusion by cost.
PairMatch direction_validate(const Dsi& volume, Step s, int min_disp,
                             const ValidationParams& params, const InvalidBorder& border) {
    const int width = volume.width();
    const int height = volume.height();
    const int ndisp = volume.ndisp();
    const std::size_t size = volume.plane_size();
    std::vector<int> best(size, fx::kNoSecondCost + 1);
    std::vector<int> label(size, 0);
    for (int k = 0; k < ndisp; ++k) {
        const auto plane = volume.plane(k);
        for (std::size_t p = 0; p < size; ++p) {
            if (plane[p] < best[p]) {
                best[p] = plane[p];
                label[p] = k;
            }
        }
    }
    std::vector<int> second(size, fx::kNoSecondCost);
    for (int k = 0; k < ndisp; ++k) {
        const auto plane = volume.plane(k);
        for (std::size_t p = 0; p < size; ++p) {
            if (std::abs(k - label[p]) > 1 && plane[p] < second[p]) {
                second[p] = plane[p];
            }
        }
    }
    std::vector<int> right_best;
    std::vector<int> right_label;
    if (params.left_right) {
        right_best.assign(size, fx::kNoSecondCost + 1);
        right_label.assign(size, 0);
        for (int k = 0; k < ndisp; ++k) {
            const int d = min_disp + k;
            const auto plane = volume.plane(k);
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    if (!partner_inside(s, x, y, d, width, height, 0)) {
                        continue;
                    }
                    const std::size_t q =
                        static_cast<std::size_t>(y - d * s.y) * width + (x - d * s.x);
                    const int cost = plane[static_cast<std::size_t>(y) * width + x];
                    if (cost < right_best[q]) {
                        right_best[q] = cost;
                        right_label[q] = k;
                    }
                }
            }
        }
    }
    ValidatedDisparity out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = out.index(x, y);
            const int k1 = label[p];
            const int c1 = best[p];
            const int c2 = second[p];
            out.certainty[p] = static_cast<std::uint8_t>(validation::certainty(c1, c2));
            const int d = min_disp + k1;
            if (!border.window_inside(x, y, width, height) ||
                !partner_inside(s, x, y, d, width, height, border.reach)) {
                out.reason[p] = fx::kReasonBorder;
                continue;
            }
            if (params.uniqueness && !validation::unique(c1, c2, params.uniqueness_ratio)) {
                out.reason[p] = fx::kReasonUniqueness;
                continue;
            }
            if (params.left_right) {
                const std::size_t q = static_cast<std::size_t>(y - d * s.y) * width + (x - d * s.x);
                if (std::abs(k1 - right_label[q]) > params.lr_tolerance) {
                    out.reason[p] = fx::kReasonLeftRight;
                    continue;
                }
            }
            out.reason[p] = fx::kReasonValid;
            int offset = 0;
            if (params.subpixel && k1 > 0 && k1 < ndisp - 1) {
                offset = validation::subpixel_offset(volume.plane(k1 - 1)[p], c1,
                                                     volume.plane(k1 + 1)[p]);
            }
            out.fixed[p] = static_cast<std::int16_t>(fx::kSubpixelScale * d + offset);
        }
    }
    return {std::move(out), std::vector<std::uint16_t>(best.begin(), best.end())};
}

// The final volume of a pair: the cost along the direction, the aggregation, the CA rules.
Dsi pair_volume(Pair pair, const Image& reference, const Image& partner,
                const MatchParams& params) {
    check_pair(reference, partner);
    validate_pair(pair, params, reference.width, reference.height);
    Dsi volume = aggregate(direction_cost(step(pair), reference, partner, params),
                           gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        volume = ca_rule2(ca_rule1(volume));
    }
    return volume;
}

// Pixel by pixel, the pair p that wins(pairs, p, q, i) against every other valid pair q (scanned
// in the order horizontal, vertical, diagonal, so that a strict comparison leaves ties to the
// earlier).
template <class Wins>
QuadResult fuse_maps(std::array<ValidatedDisparity, 3> pairs, Wins wins) {
    const int width = pairs[0].width;
    const int height = pairs[0].height;
    for (const auto& map : pairs) {
        if (map.width != width || map.height != height) {
            throw std::invalid_argument("the three pair maps must have one size");
        }
    }
    QuadResult result;
    result.fused = ValidatedDisparity(width, height);
    result.source.assign(static_cast<std::size_t>(width) * height, kSourceNone);
    for (std::size_t i = 0; i < result.source.size(); ++i) {
        int winner = -1;
        for (int p = 0; p < 3; ++p) {
            if (pairs[p].valid(i) && (winner < 0 || wins(pairs, p, winner, i))) {
                winner = p;
            }
        }
        if (winner < 0) {
            result.fused.reason[i] = pairs[0].reason[i];
            continue;
        }
        result.fused.fixed[i] = pairs[winner].fixed[i];
        result.fused.reason[i] = fx::kReasonValid;
        result.fused.certainty[i] = pairs[winner].certainty[i];
        result.source[i] = source_code(static_cast<Pair>(winner));
    }
    result.pairs = std::move(pairs);
    return result;
}

void check_views(const QuadViews& views) {
    const std::array<std::pair<const char*, const Image*>, 3> partners = {{
        {"horizontal", &views.horizontal},
        {"vertical", &views.vertical},
        {"diagonal", &views.diagonal},
    }};
    for (const auto& [label, image] : partners) {
        if (image->width != views.reference.width || image->height != views.reference.height ||
            image->channels != views.reference.channels) {
            throw std::invalid_argument(std::string("the ") + label + " view is " +
                                        size_text(*image) + " but the reference is " +
                                        size_text(views.reference) +
                                        " (the four views must have one size and channel count)");
        }
    }
}

}  // namespace

std::string_view name(Pair pair) {
    constexpr std::array<std::string_view, kPairs.size()> kNames = {"horizontal", "vertical",
                                                                    "diagonal"};
    const auto index = static_cast<std::size_t>(pair);
    return index < kNames.size() ? kNames[index] : kNames[0];
}

std::string_view name(FusionKey key) {
    return key == FusionKey::cost ? "cost" : "certainty";
}

FusionKey fusion_key(std::string_view name) {
    for (const FusionKey key : kFusionKeys) {
        if (name == quad::name(key)) {
            return key;
        }
    }
    throw std::invalid_argument("unknown fusion key '" + std::string(name) +
                                "' (certainty or cost)");
}

void validate_pair(Pair pair, const MatchParams& params, int width, int height) {
    validate_params(params);
    if (pair != Pair::horizontal) {
        catalogue::require_cost(params.cost, catalogue::CostUse::pixel_pair,
                                "the " + std::string(name(pair)) + " pair (pixel-pair costs)");
    }
    // The disparity range runs along the search axis: the width for the horizontal pair, the
    // height for the vertical pair, both for the diagonal.
    if (pair != Pair::vertical) {
        validate(params, width, height);
    }
    if (pair != Pair::horizontal) {
        try {
            validate(params, height, width);
        } catch (const std::invalid_argument& error) {
            // The check ran on the transposed size: say so, the numbers are the columns'.
            throw std::invalid_argument("the " + std::string(name(pair)) +
                                        " pair searches along the columns, checked as the "
                                        "transposed image (height " +
                                        std::to_string(height) + " as width): " + error.what());
        }
    }
}

Image transpose(const Image& image) {
    Image out(image.height, image.width, image.channels);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                out.at(y, x, c) = image.at(x, y, c);
            }
        }
    }
    return out;
}

ValidatedDisparity transpose(const ValidatedDisparity& map) {
    ValidatedDisparity out(map.height, map.width);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t from = map.index(x, y);
            const std::size_t to = out.index(y, x);
            out.fixed[to] = map.fixed[from];
            out.reason[to] = map.reason[from];
            out.certainty[to] = map.certainty[from];
        }
    }
    return out;
}

ValidatedDisparity match_pair_volume(Pair pair, const Image& reference, const Image& partner,
                                     const MatchParams& params) {
    return direction_validate(pair_volume(pair, reference, partner, params), step(pair),
                              params.min_disp, params.validation, invalid_border(params))
        .map;
}

PairMatch match_pair_with_cost(Pair pair, const Image& reference, const Image& partner,
                               const MatchParams& params) {
    check_pair(reference, partner);
    validate_pair(pair, params, reference.width, reference.height);
    switch (pair) {
        case Pair::horizontal:
            return match_validated_with_costs(reference, partner, params);
        case Pair::vertical: {
            const PairMatch columns =
                match_validated_with_costs(transpose(reference), transpose(partner), params);
            // The costs transposed back like the map: column-major of the transposed frame.
            std::vector<std::uint16_t> cost(columns.cost.size());
            for (int y = 0; y < reference.height; ++y) {
                for (int x = 0; x < reference.width; ++x) {
                    cost[static_cast<std::size_t>(y) * reference.width + x] =
                        columns.cost[static_cast<std::size_t>(x) * reference.height + y];
                }
            }
            return {transpose(columns.map), std::move(cost)};
        }
        case Pair::diagonal:
            return direction_validate(pair_volume(pair, reference, partner, params), step(pair),
                                      params.min_disp, params.validation, invalid_border(params));
    }
    throw std::invalid_argument("unknown pair");
}

ValidatedDisparity match_pair(Pair pair, const Image& reference, const Image& partner,
                              const MatchParams& params) {
    // The winner costs come for free from the streaming selector (and the diagonal's volume).
    return match_pair_with_cost(pair, reference, partner, params).map;
}

QuadResult fuse(std::array<ValidatedDisparity, 3> pairs) {
    return fuse_maps(std::move(pairs), [](const auto& maps, int p, int q, std::size_t i) {
        return maps[p].certainty[i] > maps[q].certainty[i];
    });
}

QuadResult fuse_by_cost(std::array<PairMatch, 3> pairs) {
    std::array<ValidatedDisparity, 3> maps;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        if (pairs[p].cost.size() != pairs[p].map.fixed.size()) {
            throw std::invalid_argument("a pair's winner costs do not cover its map");
        }
        maps[p] = std::move(pairs[p].map);
    }
    // Only the maps move: the costs stay in `pairs` for the comparison.
    return fuse_maps(std::move(maps), [&pairs](const auto&, int p, int q, std::size_t i) {
        return pairs[p].cost[i] < pairs[q].cost[i];
    });
}

void validate_quad(const QuadViews& views, const MatchParams& params) {
    check_views(views);
    for (const Pair pair : kPairs) {
        validate_pair(pair, params, views.reference.width, views.reference.height);
    }
}

namespace {

// The three pairs, one thread each when `threads`: match(pair, partner) for each.
template <class Match>
auto match_three(const QuadViews& views, bool threads, Match match) {
    using Output = decltype(match(Pair::horizontal, views.horizontal));
    const std::array<const Image*, 3> partners = {&views.horizontal, &views.vertical,
                                                  &views.diagonal};
    std::array<Output, 3> outputs;
    if (!threads) {
        for (const Pair pair : kPairs) {
            const auto p = static_cast<std::size_t>(pair);
            outputs[p] = match(pair, *partners[p]);
        }
        return outputs;
    }
    std::array<std::future<Output>, 3> jobs;
    for (const Pair pair : kPairs) {
        const auto p = static_cast<std::size_t>(pair);
        jobs[p] = std::async(std::launch::async, [&match, pair, partner = partners[p]] {
            return match(pair, *partner);
        });
    }
    for (std::size_t p = 0; p < jobs.size(); ++p) {
        outputs[p] = jobs[p].get();
    }
    return outputs;
}

}  // namespace

QuadResult match_quad(const QuadViews& views, const MatchParams& params, bool threads,
                      FusionKey key) {
    validate_quad(views, params);
    if (key == FusionKey::cost) {
        return fuse_by_cost(match_three(views, threads, [&](Pair pair, const Image& partner) {
            return match_pair_with_cost(pair, views.reference, partner, params);
        }));
    }
    return fuse(match_three(views, threads, [&](Pair pair, const Image& partner) {
        return match_pair(pair, views.reference, partner, params);
    }));
}

}  // namespace stereo::quad
