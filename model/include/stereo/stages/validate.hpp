// Stage 6, validation and sub-pixel refinement (docs/fixed-point.md): the integer arithmetic of
// one pixel, shared by the model's selector, the HLS kernel and the testbenches, and the
// selector that runs it over the 1-D search.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/stages.hpp"
#include "stereo/validated.hpp"
#include "stereo/validation_params.hpp"

namespace stereo::validation {

// The winner's cost c1 is not unique enough when c1 * (100 + ratio) >= c2 * 100, c2 the best
// cost outside the winner and its two neighbours (fx::kNoSecondCost when there is none: then
// the winner is unique).
constexpr bool unique(int c1, int c2, int ratio) {
    return c2 == fx::kNoSecondCost ||
           static_cast<std::int32_t>(c1) * (fx::kUniquenessBase + ratio) <
               static_cast<std::int32_t>(c2) * fx::kUniquenessBase;
}

// floor((c2 - c1) * 256 / (c2 + 1)): 0 when the second-best cost equals the winner's, towards
// 255 as the winner stands out. c1 <= c2.
constexpr int certainty(int c1, int c2) {
    return static_cast<int>((static_cast<std::uint32_t>(c2 - c1) << fx::kCertaintyBits) /
                            static_cast<std::uint32_t>(c2 + 1));
}

// The vertex of the parabola through (-1, before), (0, centre), (1, after), in 1/16 pixel:
// round(8 * (before - after) / (before + after - 2 * centre)), halves away from zero; 0 when the
// costs are flat. centre <= before, after (it is the minimum), so the offset is in [-8, 8].
constexpr int parabola_offset(int before, int centre, int after) {
    const int denominator = before + after - 2 * centre;
    if (denominator <= 0) {
        return 0;
    }
    const int numerator = before - after;
    const int magnitude = numerator >= 0 ? numerator : -numerator;
    const int steps = (fx::kSubpixelScale * magnitude + denominator) / (2 * denominator);
    return numerator >= 0 ? steps : -steps;
}

// Stage 6's sub-pixel offset: the parabola's vertex through the calibrated correction
// (fx::kSubpixelCorrection), in [-8, 8]. With centre the minimum |vertex| <= 8; the index is
// clamped all the same, so that a caller breaking that cannot read past the table.
constexpr int subpixel_offset(int before, int centre, int after) {
    const int parabola = parabola_offset(before, centre, after);
    const auto index = std::min(static_cast<std::size_t>(parabola >= 0 ? parabola : -parabola),
                                fx::kSubpixelCorrection.size() - 1);
    const int corrected = fx::kSubpixelCorrection[index];
    return parabola >= 0 ? corrected : -corrected;
}

}  // namespace stereo::validation

namespace stereo {

// A cell that is no candidate at all: above every cost, so it never wins while a real candidate
// exists, and the selector never takes it for the second cost or a parabola point. The ASW
// matcher writes it where a pixel's own match lies outside the right image (docs/asw.md).
inline constexpr CostValue kNoCandidate = std::numeric_limits<CostValue>::max();
static_assert(fx::kNoSecondCost < kNoCandidate);

// Winner takes all over the 1-D search (labels k = 0 .. ndisp-1, d = min_disp + k, ties to the
// smaller k) with stage 6: certainty, uniqueness, left-right check and sub-pixel refinement.
// Keeps per pixel the four smallest (cost, k), the costs next to the winner and, for the
// left-right check, the right-referenced winner of every right pixel.
class ValidatingSelector final : public Selector {
  public:
    ValidatingSelector(int width, int height, int ndisp, int min_disp,
                       const ValidationParams& params, const InvalidBorder& border);
    void update(const CostValue* plane, int i, int j) override;
    ValidatedDisparity result() const;
    // The winner's final cost C1 of every pixel, raster order.
    std::vector<std::uint16_t> winner_costs() const;

  private:
    static constexpr int kKept = 4;  // enough for the best outside the winner's neighbours
    // A kept candidate as one ordered key, cost << 16 | k: planes arrive in increasing k, so
    // comparing keys compares costs with ties to the smaller k, and keeping the list sorted is a
    // branchless min/max network the compiler vectorises across pixels.
    using Key = std::uint32_t;
    static constexpr Key key(CostValue cost, int k) {
        return static_cast<Key>(cost) << 16 | static_cast<Key>(k);
    }
    static constexpr CostValue key_cost(Key key) { return static_cast<CostValue>(key >> 16); }
    static constexpr int key_label(Key key) { return static_cast<int>(key & 0xFFFFU); }
    static void update_kept(std::size_t size, int k, const CostValue* __restrict costs,
                            Key* __restrict slot0, Key* __restrict slot1, Key* __restrict slot2,
                            Key* __restrict slot3, CostValue* __restrict before,
                            CostValue* __restrict after, CostValue* __restrict previous);
    // Right pixel r meets the left pixel r + d at label k: keeps its smallest cost and label.
    static void update_right(std::size_t size, std::uint16_t label,
                             const CostValue* __restrict costs, CostValue* __restrict right_cost,
                             std::uint16_t* __restrict right_label);
    int width_;
    int height_;
    int ndisp_;
    int min_disp_;
    ValidationParams params_;
    InvalidBorder border_;
    std::size_t size_;
    std::vector<Key> kept_;              // kKept planes of size_ keys, ascending per pixel
    std::vector<CostValue> before_;      // cost at winner - 1
    std::vector<CostValue> after_;       // cost at winner + 1
    std::vector<CostValue> previous_;    // the previous plane
    std::vector<CostValue> right_cost_;  // left-right: best cost per right pixel
    std::vector<std::uint16_t> right_label_;
};

}  // namespace stereo
