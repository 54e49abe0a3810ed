// The luminosity-compensated dissimilarity measure (LCDM, thesis Sec. 3.5): HSL lightness is
// dropped and a colour becomes the point S e^{iH} of the hue-saturation disc; the cost of two
// pixels is the distance of their points, scaled so that two opposite fully saturated colours
// (distance 2) cost fx::kCostMax. docs/fixed-point.md, "LCDM", specifies every step to the bit:
//
//   mx, mn = max, min of (R, G, B);  C = mx - mn;  L2 = mx + mn
//   den   = max(min(L2, 2*255 - L2), kDarkFloor)        HSL saturation denominator, floored
//   s     = (2 C kRadius + den) / (2 den)                 saturation in [0, kRadius]
//   t     = hexagonal hue times C in [0, 6C]              (sector of mx, 0..5)
//   h     = ((2 kHueSteps t + C) / (2C)) mod kHueCount    hue index, kHueSteps per 60 degrees
//   a, b  = (s * cos_table[h] + half) >> kTrigBits, same with sin_table    (0, 0) when C == 0
//   cost  = min(kCostMax, (isqrt(4 (da^2 + db^2)) * kCostMax + 2 kRadius) >> (kRadiusBits + 2))
//
// The floor of the denominator is the handling of nearly black and nearly white pixels, where
// HSL saturation C / den is unstable (one count of noise on a black pixel is a fully saturated
// colour): below kDarkFloor the saturation falls off linearly with the chroma instead.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/image.hpp"

namespace stereo::lcdm {

// Saturation 1 is kRadius (coordinates a, b are signed, |a|, |b| <= kRadius).
inline constexpr int kRadiusBits = 9;
inline constexpr int kRadius = 1 << kRadiusBits;  // 512
// Hue resolution: kHueSteps indices per 60-degree sector of the hexagonal HSL hue.
inline constexpr int kHueSteps = 256;
inline constexpr int kHueCount = 6 * kHueSteps;    // 1536 entries per table
inline constexpr int kHueQuarter = kHueCount / 4;  // 384
static_assert(kHueCount % 4 == 0);
// cos / sin table entries are round(2^kTrigBits * cos(2 pi h / kHueCount)), built from the
// quarter wave h = 0 .. kHueQuarter by the symmetries of the cosine (as the RTL does).
inline constexpr int kTrigBits = 12;
// Floor of the saturation denominator min(L2, 510 - L2) (chosen in docs/results-illumination.md
// by the mean over the four Middlebury 2003 pairs and the lightness sweep, not one scene).
inline constexpr int kDarkFloor = 8;
inline constexpr int kLightSum = 2 * fx::kPixelMax;  // 510: L2 of white

// Widths (docs/fixed-point.md): a, b in kCoordBits signed bits; the squared distance in
// kDistSqBits unsigned bits (4 (da^2 + db^2) <= 2^23); isqrt of it in kDistBits.
inline constexpr int kCoordBits = kRadiusBits + 2;  // [-512, 512]
inline constexpr int kDistSqBits = 2 * (kRadiusBits + 1) + 4;
inline constexpr int kDistBits = kRadiusBits + 3;
static_assert(4LL * 2 * (2 * kRadius) * (2 * kRadius) < (1LL << kDistSqBits));
static_assert(2897LL * 2897 > 4LL * 2 * (2 * kRadius) * (2 * kRadius) && 2896 < (1 << kDistBits));
static_assert(2896LL * fx::kCostMax + 2 * kRadius < (1LL << 31));
static_assert(kDarkFloor >= 1 && kDarkFloor <= fx::kPixelMax);
static_assert(static_cast<long long>(kRadius) * (1 << kTrigBits) < (1LL << 31));

// A colour on the hue-saturation disc.
struct Chroma {
    std::int16_t a = 0;  // S cos H, kRadius = 1
    std::int16_t b = 0;  // S sin H
    bool operator==(const Chroma&) const = default;
};

// round(2^kTrigBits cos(2 pi k / kHueCount)) for k = 0 .. kHueQuarter (the stored quarter wave).
int quarter_cos(int k);
// The two tables, kHueCount entries each (cos, sin), computed once.
const std::array<std::int16_t, kHueCount>& cos_table();
const std::array<std::int16_t, kHueCount>& sin_table();

// The fixed-point conversion of one 8-bit RGB pixel, with the denominator floor `dark_floor`.
Chroma chroma(int r, int g, int b, int dark_floor = kDarkFloor);
// Floor of the square root of q (q < 2^kDistSqBits).
int isqrt(std::uint32_t q);
// The cost of two converted pixels.
int cost(Chroma left, Chroma right);

// Throws std::invalid_argument (one line) unless `image` has three channels.
void require_colour(const Image& image);

namespace floating {
// The exact-trigonometry reference: HSL hue in radians and saturation C / den (same floor) in
// double precision, the complex difference |S1 e^{iH1} - S2 e^{iH2}| * kCostMax / 2, clamped.
double cost(int r1, int g1, int b1, int r2, int g2, int b2, int dark_floor = kDarkFloor);
}  // namespace floating

}  // namespace stereo::lcdm
