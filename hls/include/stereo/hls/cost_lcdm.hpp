// cost_lcdm: the LCDM matching cost (thesis Sec. 3.5) as the `cost` stage with lcdm_measure, same
// interface, signed range and latency as the AD cost (model: the "lcdm" cost plug-in,
// docs/fixed-point.md "LCDM"; RTL: rtl/stereo_cost.sv with COST = 1, rtl/stereo_lcdm_convert.sv,
// rtl/stereo_lcdm_distance.sv).
//
// Each pixel is converted to its point (a, b) on the hue-saturation disc; the cost of two points
// is min(765, (isqrt(4 ((aL - aR)^2 + (bL - bR)^2)) * 765 + 1024) >> 11). The cosine comes from
// the generated quarter wave (lcdm_table.hpp).
#pragma once

#include <cstdint>

#include "stereo/hls/cost.hpp"
#include "stereo/hls/lcdm_table.hpp"
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

// The LCDM measure of `cost`: the delay lines carry points, compared by their distance.
struct lcdm_measure {
    using feature = LcdmPoint;
    static feature convert(const Rgb& p) { return lcdm_convert(p); }
    static cost_t distance(const LcdmPoint& p, const LcdmPoint& q) {
        return lcdm_distance_cost(p, q);
    }
};

template <int NDISP, int MAX_MIN_DISP>
using cost_lcdm = cost<NDISP, MAX_MIN_DISP, lcdm_measure>;

}  // namespace stereo::hls
