// The ZNCC cost (the thesis' rival in Sec. 3.5.3, over a 15x15 window): the zero-mean normalised
// cross-correlation of the luma windows around the left and the right pixel, as the cost
// (1 - ZNCC) * kCostMax / 2 in [0, fx::kCostMax]. ZNCC is itself a window measure, so the plug-in
// computes the whole window in row() and is meant to run with aggregation window 1 and no CA
// (`--cost zncc --window 1 --no-ca`); docs/fixed-point.md, "ZNCC", gives the integer definition:
//
//   the window: the pixels (x+i, y+j), |i|, |j| <= kRadius, whose left and right pixels
//   (x+i, y+j) and (x+i-d, yr+j) both lie inside the images (N of them)
//   num = N*Slr - Sl*Sr;  vl = N*Sll - Sl^2;  vr = N*Srr - Sr^2          (64-bit, exact)
//   den = isqrt(vl * vr)                                                   (floor, 64-bit)
//   cost = den == 0 ? kFlatCost : clamp(((den - num) * kCostMax + den) / (2 den), 0, kCostMax)
#pragma once

#include <cstdint>

#include "stereo/constants.hpp"

namespace stereo::zncc {

inline constexpr int kRadius = 7;  // 15x15, as in the thesis
inline constexpr int kWindow = 2 * kRadius + 1;
// A flat window has no correlation: the middle of the range, round(kCostMax / 2).
inline constexpr int kFlatCost = (fx::kCostMax + 1) / 2;
// The largest vl (and vr): N^2 times the largest variance of 8-bit values, 127.5^2.
inline constexpr std::int64_t kVarianceMax = static_cast<std::int64_t>(kWindow) * kWindow *
                                             kWindow * kWindow * fx::kPixelMax * fx::kPixelMax / 4;
static_assert(kVarianceMax < (1LL << 31), "vl * vr must fit 63 bits");

// Floor of the square root of a 64-bit value.
std::uint64_t isqrt64(std::uint64_t value);
// The cost from the five window sums (definition above).
int cost_from_sums(std::int64_t n, std::int64_t sl, std::int64_t sr, std::int64_t sll,
                   std::int64_t srr, std::int64_t slr);

}  // namespace stereo::zncc
