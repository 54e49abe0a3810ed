// Quad-camera matching and certainty fusion (thesis Sec. 3.2, docs/quad.md): four cameras on
// the corners of a square, the upper-left image the reference; a horizontal, a vertical and a
// diagonal pair, each matched with the Sec. 3.1 pipeline and stage 6, fused pixel by pixel by
// the stage-6 certainty (docs/fixed-point.md "Quad fusion").
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::quad {

// The partner of a pair, seen from the reference: reference pixel (x, y) matches partner pixel
// (x - d * step.x, y - d * step.y) at disparity d.
enum class Pair : std::uint8_t { horizontal = 0, vertical = 1, diagonal = 2 };
inline constexpr std::array<Pair, 3> kPairs = {Pair::horizontal, Pair::vertical, Pair::diagonal};

struct Step {
    int x = 0;
    int y = 0;
};
constexpr Step step(Pair pair) {
    switch (pair) {
        case Pair::horizontal:
            return {1, 0};
        case Pair::vertical:
            return {0, 1};
        case Pair::diagonal:
            return {1, 1};
    }
    return {1, 0};
}
std::string_view name(Pair pair);  // "horizontal", "vertical", "diagonal"

// The costs every pair geometry takes are the catalogue's pixel-pair costs
// (catalogue::cost_names(catalogue::CostUse::pixel_pair)): those of one pixel against one pixel
// (census compares two per-image codes), which read the same along any direction. ZNCC's window
// mask depends on the horizontal search, so it stays with the horizontal pair.

// The source map's values: which pair a fused pixel comes from (0: none was valid).
inline constexpr std::uint8_t kSourceNone = 0;
constexpr std::uint8_t source_code(Pair pair) {
    return static_cast<std::uint8_t>(pair) + 1;
}

// Throws std::invalid_argument (one line) when `params` cannot run on a pair of this size along
// this direction: stereo::validate along the search axis (both axes for the diagonal), and a
// cost that is not a pixel-pair cost for the vertical and diagonal pairs.
void validate_pair(Pair pair, const MatchParams& params, int width, int height);

// One pair through the Sec. 3.1 pipeline and stage 6 along its direction. Horizontal:
// stereo::match_validated. Vertical: both images transposed, the horizontal pipeline, the result
// transposed back. Diagonal: match_pair_volume. All stages but the cost sampling, the border
// rule and the left-right check are isotropic (docs/quad.md), so the three are the same
// algorithm along three directions.
ValidatedDisparity match_pair(Pair pair, const Image& reference, const Image& partner,
                              const MatchParams& params);

// Any pair through a whole final volume: cost sampled along the direction, the model's
// aggregation and CA stages on the volume, stage 6 with the border rule and the left-right
// check along the direction. Equals match_pair for every pair (tests); the diagonal uses it.
ValidatedDisparity match_pair_volume(Pair pair, const Image& reference, const Image& partner,
                                     const MatchParams& params);

// What fusion compares among the pairs valid at a pixel (docs/quad.md, "The fusion key"):
// certainty: stage 6's certainty, the largest wins (the default: the thesis fuses by certainty);
// cost: the winner's final aggregated cost C1, the smallest wins (each pair's
// best explanation of the same reference window, compared on one scale: the residual, as
// multi-baseline matchers choose among partner views). Equal keys go to the earlier pair.
enum class FusionKey : std::uint8_t { certainty = 0, cost = 1 };
inline constexpr std::array<FusionKey, 2> kFusionKeys = {FusionKey::certainty, FusionKey::cost};
std::string_view name(FusionKey key);  // "certainty", "cost"
// The key of a name; throws std::invalid_argument naming both choices for any other.
FusionKey fusion_key(std::string_view name);

// One pair's stage-6 output and, per pixel, the final cost of the winning label (C1, 0 ..
// fx::kAggMax; every pixel, border pixels too): what fusion by cost compares.
using PairMatch = CostedDisparity;

struct QuadResult {
    ValidatedDisparity fused;                 // the winning pair's disparity, reason and certainty
    std::vector<std::uint8_t> source;         // kSourceNone or source_code(winning pair), per pixel
    std::array<ValidatedDisparity, 3> pairs;  // indexed by Pair
};

// Fusion by maximum certainty among the pairs valid at a pixel; ties go to the earlier pair
// (horizontal, vertical, diagonal). Where no pair is valid: fixed 0, certainty 0, source
// kSourceNone and the horizontal pair's reason. Throws std::invalid_argument on unequal sizes.
QuadResult fuse(std::array<ValidatedDisparity, 3> pairs);
// Fusion by the smallest winner cost among the valid pairs, ties to the earlier pair; otherwise as
// fuse (the fused certainty is the winning pair's). Throws std::invalid_argument on unequal sizes.
QuadResult fuse_by_cost(std::array<PairMatch, 3> pairs);

// match_pair with the winner costs: the horizontal and vertical pairs through the streaming
// pipeline (match_validated_with_costs), the diagonal through its volume.
PairMatch match_pair_with_cost(Pair pair, const Image& reference, const Image& partner,
                               const MatchParams& params);

struct QuadViews {
    const Image& reference;   // upper left
    const Image& horizontal;  // upper right
    const Image& vertical;    // lower left
    const Image& diagonal;    // lower right
};

// Throws std::invalid_argument naming the view when the four views differ in size or channels,
// or (validate_pair) when the parameters do not fit one of the three pairs.
void validate_quad(const QuadViews& views, const MatchParams& params);

// The three pairs (one thread each when `threads`), then fuse by `key` (by cost, every pair runs
// through match_pair_with_cost).
QuadResult match_quad(const QuadViews& views, const MatchParams& params, bool threads = true,
                      FusionKey key = FusionKey::certainty);

// Transposes (x, y) -> (y, x), every channel; for ValidatedDisparity every field.
Image transpose(const Image& image);
ValidatedDisparity transpose(const ValidatedDisparity& map);

}  // namespace stereo::quad

namespace stereo::quad::naive {

// Independent references: the cost along the direction by direct loops, stereo::naive's
// aggregation and CA rules, stage 6 by its definition per pixel (parabola in double precision),
// and the fusion as the largest (certainty, priority) key or the smallest (cost, rank) key.
// Slow; tests only.
ValidatedDisparity match_pair(Pair pair, const Image& reference, const Image& partner,
                              const MatchParams& params);
PairMatch match_pair_with_cost(Pair pair, const Image& reference, const Image& partner,
                               const MatchParams& params);
QuadResult fuse(std::array<ValidatedDisparity, 3> pairs);
QuadResult fuse_by_cost(std::array<PairMatch, 3> pairs);
QuadResult match_quad(const QuadViews& views, const MatchParams& params,
                      FusionKey key = FusionKey::certainty);

}  // namespace stereo::quad::naive
