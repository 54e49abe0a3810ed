// cost_lcdm: the LCDM matching cost (thesis Sec. 3.5), all NDISP disparities of one pixel per
// step, a drop-in for `cost` with the same interface and latency (model: the "lcdm" cost plug-in,
// docs/fixed-point.md "LCDM"; RTL: rtl/stereo_cost_lcdm.sv with rtl/stereo_lcdm_convert.sv).
//
// The left and the right pixel of each step are converted to their points (a, b) on the
// hue-saturation disc; the right points of the row pass through a delay line. Lane d is
//   min(765, (isqrt(4 ((aL - aR)^2 + (bL - bR)^2)) * 765 + 1024) >> 11), or kCostOutside where
// x - d < 0. The cosine comes from the generated quarter wave (lcdm_table.hpp).
#pragma once

#include <cstdint>

#include "stereo/hls/lcdm_table.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::hls {

struct LcdmPoint {
    std::int16_t a = 0;  // 11 significant bits, signed
    std::int16_t b = 0;
};

// cos(2 pi h / kHueCount) * 2^kTrigBits from the quarter wave, by the cosine's symmetries.
inline int lcdm_cosine(int h) {
#pragma HLS INLINE
    constexpr int q = lcdm::kHueQuarter;
    if (h <= q) {
        return kLcdmQuarterCos[h];
    }
    if (h <= 2 * q) {
        return -kLcdmQuarterCos[2 * q - h];
    }
    if (h <= 3 * q) {
        return -kLcdmQuarterCos[h - 2 * q];
    }
    return kLcdmQuarterCos[lcdm::kHueCount - h];
}

// One RGB pixel to its point: the two divisions (saturation, hue index) and the table.
inline LcdmPoint lcdm_convert(const Rgb& p) {
#pragma HLS INLINE
    const int r = p.r;
    const int g = p.g;
    const int b = p.b;
    const int mx = r >= g ? (r >= b ? r : b) : (g >= b ? g : b);
    const int mn = r <= g ? (r <= b ? r : b) : (g <= b ? g : b);
    const int c = mx - mn;
    if (c == 0) {
        return {};
    }
    const int l2 = mx + mn;
    const int side = l2 < lcdm::kLightSum - l2 ? l2 : lcdm::kLightSum - l2;
    const int den = side > lcdm::kDarkFloor ? side : lcdm::kDarkFloor;
    const int s = (2 * c * lcdm::kRadius + den) / (2 * den);
    const int t =
        mx == r ? (g >= b ? g - b : 6 * c + g - b) : (mx == g ? 2 * c + b - r : 4 * c + r - g);
    int h = (2 * lcdm::kHueSteps * t + c) / (2 * c);
    h = h == lcdm::kHueCount ? 0 : h;
    const int h_sin = h >= lcdm::kHueQuarter ? h - lcdm::kHueQuarter : h + 3 * lcdm::kHueQuarter;
    const int half = 1 << (lcdm::kTrigBits - 1);
    return {static_cast<std::int16_t>((s * lcdm_cosine(h) + half) >> lcdm::kTrigBits),
            static_cast<std::int16_t>((s * lcdm_cosine(h_sin) + half) >> lcdm::kTrigBits)};
}

// Floor of the square root, digit by digit (as the RTL).
inline int lcdm_isqrt(std::uint32_t value) {
#pragma HLS INLINE
    std::uint32_t remainder = 0;
    std::uint32_t root = 0;
    for (int i = lcdm::kDistBits - 1; i >= 0; --i) {
#pragma HLS UNROLL
        remainder = (remainder << 2) | ((value >> (2 * i)) & 3U);
        const std::uint32_t trial = (root << 2) | 1U;
        if (remainder >= trial) {
            remainder -= trial;
            root = (root << 1) | 1U;
        } else {
            root <<= 1;
        }
    }
    return static_cast<int>(root);
}

inline cost_t lcdm_distance_cost(const LcdmPoint& p, const LcdmPoint& q) {
#pragma HLS INLINE
    const int da = p.a - q.a;
    const int db = p.b - q.b;
    const auto q4 = static_cast<std::uint32_t>(4 * (da * da + db * db));
    const int scaled =
        (lcdm_isqrt(q4) * fx::kCostMax + 2 * lcdm::kRadius) >> (lcdm::kRadiusBits + 2);
    return static_cast<cost_t>(scaled < fx::kCostMax ? scaled : fx::kCostMax);
}

template <int NDISP>
class cost_lcdm : public lane_output<cost_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    using lane_output<cost_t, NDISP>::out_data_;
    using lane_output<cost_t, NDISP>::out_x_;
    using lane_output<cost_t, NDISP>::out_y_;

  public:
    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = history_ complete
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        const LcdmPoint l = lcdm_convert(left);
        const LcdmPoint r = lcdm_convert(right);
        for (int d = 0; d < NDISP; ++d) {
            const LcdmPoint& match = d == 0 ? r : history_[d - 1];
            out_data_[d] =
                in_x - d < 0 ? static_cast<cost_t>(fx::kCostOutside) : lcdm_distance_cost(l, match);
        }
        for (int i = kHistory - 1; i > 0; --i) {
            history_[i] = history_[i - 1];
        }
        history_[0] = r;
        out_x_ = in_x;
        out_y_ = in_y;
    }

  private:
    static constexpr int kHistory = NDISP > 1 ? NDISP - 1 : 1;
    LcdmPoint history_[kHistory] = {};  // history_[i] = right point (x-1-i) at the step of x
};

}  // namespace stereo::hls
