// Adaptive support weights with gestalt laws and a logarithmic response (thesis Sec. 3.4): an
// aggregator of the cost volume, bit-exact in fixed point. docs/asw.md gives the formulas, the
// bit widths and a worked example; docs/results-asw.md the measured accuracy.
//
// The aggregated cost of pixel p at disparity d is the weighted mean over the support region
// (offsets o of a circle of diameter w) of the costs C(p + o, d):
//   A(p, d) = 16 * sum_o W(p, o, d) C(p + o, d) / sum_o W(p, o, d), rounded,
// where the 8-bit support weight W is the rounded product of the gestalt responses: proximity
// (|o| / w), colour similarity in the left image (L(p) against L(p + o)), continuity (label of
// p against label of p + o in a preliminary map, so two passes) and colour similarity in the
// right image (R(p - d) against R(p + o - d)), each an 8-bit response from a table.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stereo/catalogue.hpp"
#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::asw {

// How a normalised stimulus S in [1/w, 1] becomes a response in [0, 1] (scaled to 0..255).
enum class Response {
    log,  // Weber-Fechner: -ln S / ln w (the thesis)
    exp,  // Yoon and Kweon's exponential: exp(-difference / gamma) (the ablation)
};

enum class Shape {
    circle,  // offsets with dx^2 + dy^2 <= r^2, r = (w - 1) / 2 (the thesis)
    square,  // the odd square of (nearly) the same pixel count (the ablation)
};

// "log" / "exp" and "circle" / "square", the names the CLI and the Python module take; throw
// std::invalid_argument naming the choices for anything else.
Response response_from_name(std::string_view name);
Shape shape_from_name(std::string_view name);

inline constexpr int kDefaultDiameter = 55;  // thesis Sec. 3.4
// The hardware configuration (stereo_top ASW = 1 at VGA, docs/results-asw.md "Hardware
// configuration"): the separable variant at this diameter with the census cost, chosen by the
// validated accuracy on every scene with ground truth against the core's resources.
inline constexpr int kHardwareDiameter = 11;
inline constexpr int kMinDiameter = 3;
inline constexpr int kMaxDiameter = 127;  // keeps every sum inside 32 bits (docs/asw.md)
inline constexpr int kResponseBits = 8;   // every response and the support weight: 0 .. 255
inline constexpr int kResponseMax = (1 << kResponseBits) - 1;
inline constexpr int kMaxColourDifference = 765;  // |dR| + |dG| + |dB|
inline constexpr int kOutputFracBits = 4;         // A(p, d) carries 4 fraction bits, like stage 2
// The matching cost is truncated before the aggregation, C' = min(C, T): Yoon and Kweon's T = 40
// (in units of |dR| + |dG| + |dB|), part of the ASW framework the thesis builds on (docs/asw.md,
// "The truncated cost"). 0 switches it off.
inline constexpr int kDefaultTruncation =
    catalogue::cost(catalogue::Cost::ad).asw_truncation;  // 40
// The default of Params::truncation: T follows the cost (truncation_for). Yoon and Kweon's T is
// in intensity steps and caps the outliers of a difference of intensities (ad, lcdm, zncc); the
// census cost is a Hamming distance, bounded and rank-based, whose every bit already saturates,
// and min(31 h, 40) would keep no more than h = 0, 1 apart: it is not truncated.
inline constexpr int kTruncationByCost = -1;
// `truncation` as the matcher applies it for `cost`: kTruncationByCost becomes 0 for census and
// kDefaultTruncation for every other cost; any other value is returned unchanged.
int truncation_for(int truncation, std::string_view cost);
// Exponential ablation: Yoon and Kweon's gamma_p is the window radius; these two are ours.
inline constexpr double kExpColourGamma = 14.0;     // in units of |dR| + |dG| + |dB|
inline constexpr double kExpContinuityGamma = 2.0;  // in disparity labels

struct Params {
    int diameter = kDefaultDiameter;  // w: odd, kMinDiameter .. kMaxDiameter
    Response response = Response::log;
    Shape shape = Shape::circle;
    bool continuity = true;     // second pass weighted by the first pass' disparities
    bool right_weights = true;  // colour similarity in the right image too (Yoon and Kweon)
    // The hardware-friendly variant: a vertical pass (no continuity factor, shared by both
    // passes of the two-pass scheme) then a horizontal pass (docs/asw.md).
    bool separable = false;
    // Stimulus normalisers (docs/asw.md): a colour difference of colour_range or more, a label
    // difference of disparity_range or more, is the largest stimulus (S = 1).
    int colour_range = 255;
    int disparity_range = 255;
    // kTruncationByCost (by the cost, truncation_for), 0 (not truncated) or 1 .. 765.
    int truncation = kTruncationByCost;
    int threads = 0;  // worker threads, 0 = every hardware thread (results do not depend on it)
    bool operator==(const Params&) const = default;
};

// One offset of the support region with its proximity response.
struct Offset {
    int dx = 0;
    int dy = 0;
    std::uint8_t proximity = 0;
};

// The support region in raster order (dy, then dx). The separable variant's two 1-D regions
// are the offsets of this list with dx == 0 and with dy == 0.
std::vector<Offset> support_region(const Params& params);
// The separable variant's 1-D regions: the offsets of `region` with dx == 0 (vertical) or
// dy == 0 (horizontal), the centre in both.
std::vector<Offset> axis_offsets(const std::vector<Offset>& region, bool vertical);

// Responses indexed by stimulus: colour by |dR| + |dG| + |dB| (0 .. 765), continuity by the
// label difference (0 .. 255), proximity by the squared distance dx^2 + dy^2.
struct ResponseTables {
    std::vector<std::uint8_t> colour;
    std::vector<std::uint8_t> continuity;
    std::vector<std::uint8_t> proximity;
};
ResponseTables response_tables(const Params& params);

// (a * b + 128) >> 8 for two 8-bit responses, the only way weights are combined: a rounded
// product in units of 1/256 (a shift in hardware, not a division by 255), so each factor
// below 255 costs at most one count more than the exact product.
constexpr int combine(int a, int b) {
    return (a * b + 128) >> kResponseBits;
}

// |dR| + |dG| + |dB| of two pixels; grey pixels count as (g, g, g).
int colour_difference(const Image& a, int ax, int ay, const Image& b, int bx, int by);

// Throws std::invalid_argument (one line) for an even, too small or too large diameter, a
// support region that does not fit the image, or normalisers outside [1, 765] / [1, 255].
void validate(const Params& params, int width, int height);

// Throws std::invalid_argument (one line naming `core`) unless `params` asks for what the
// hardware ASW cores compute: the separable variant at the default responses, at any diameter
// and thread count, and at any truncation where `takes_truncation`.
void check_hardware_variant(const Params& params, std::string_view core, bool takes_truncation);

// How far the support region reaches from its centre (the invalid border).
int reach(const Params& params);

// The aggregated volume (plane k: d = min_disp + k) of `cost`, weighted by `left`, `right` and,
// with params.continuity, by `labels` (a preliminary label map, width x height, labels k).
Dsi aggregate(const Dsi& cost, const Image& left, const Image& right, int min_disp,
              const Params& params, const std::vector<std::int16_t>& labels);

// min(C, truncation) for every cell, in place; truncation 0 leaves the volume as it is. The cells
// whose match lies outside the right image (fx::kCostOutside) are capped too: under truncation T
// is the cost of no match, and a neighbour that has no partner at d is no evidence against d
// (docs/asw.md, "The truncated cost"). The pixel's own outside match is invalid anyway.
void truncate_cost(Dsi& cost, int truncation);

// Takes every pixel's own outside matches out of the search: the aggregated cell of (x, y, d)
// becomes kNoCandidate where x - d lies outside the right image (d = min_disp + k). Each pixel
// then wins among the disparities it can have, and the output is dense wherever one exists
// (docs/asw.md, "Border and validity").
void exclude_outside_matches(Dsi& aggregated, int min_disp);

// Winner takes all with stage 6 (match.min_disp, match.validation) over an aggregated volume
// whose outside matches are excluded: the last step of match() and match_naive(). No invalid
// border: the support region is clipped, so every cell has its cost.
ValidatedDisparity select_validated(const Dsi& aggregated, const MatchParams& match);

// The whole matcher: cost (match.cost, truncated by truncation_for(params.truncation,
// match.cost)), pass 1 without continuity,
// its winners (outside matches excluded) as the preliminary map, pass 2 with continuity (when
// on), outside matches excluded again, then stage 6 (match.min_disp, match.validation). The
// support region is clipped at the image border, so a pixel is invalid only where none of its
// matches lies inside the right image (0 <= x - d < width). match.window, sigma and use_ca are
// not read.
ValidatedDisparity match(const Image& left, const Image& right, const MatchParams& match,
                         const Params& params);

// Independent references: the same integers from the definitions, one pixel and one
// disparity at a time (naive), and the real-valued algorithm with exact logarithms (floating).
Dsi aggregate_naive(const Dsi& cost, const Image& left, const Image& right, int min_disp,
                    const Params& params, const std::vector<std::int16_t>& labels);
ValidatedDisparity match_naive(const Image& left, const Image& right, const MatchParams& match,
                               const Params& params);
DisparityMap match_floating(const Image& left, const Image& right, const MatchParams& match,
                            const Params& params);

}  // namespace stereo::asw
