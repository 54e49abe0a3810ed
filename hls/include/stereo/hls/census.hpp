// census: the census transform of both images in front of the cost stage, and census_measure,
// the cost stage's measure for it (model: the "census" cost plug-in, stereo::census::transform,
// docs/fixed-point.md "Census"; RTL: rtl/stereo_census.sv and rtl/stereo_cost.sv with COST = 2).
//
// Each pixel's luma (fx::kLumaR/G/B, fx::kLumaShift) is compared with the other 24 of its 5x5
// window: bit 23 - n of the code is set where the n-th of them (raster order, the centre
// skipped) lies in the frame and is darker than the centre. The codes travel through the cost
// stage's delay lines packed into an Rgb (r = bits 23..16, g = 15..8, b = 7..0); census_measure
// compares two of them by the Hamming distance times fx::kCensusWeight.
//
// At the step of input pixel (x, y) the window is the line buffer's 4 rows above and the input
// at column x, and the 4 columns before it: it is centred on (x - 2, y - 2), wrapping to the
// previous row (twice at width 1). Its code enters the output register at that step; a centre
// above the frame leaves as "no pixel". Latency: 2 W + 3 pixel steps (the RTL's stage has an
// input register more: table::kCensusStage).
#pragma once

#include <bit>
#include <cstdint>
#include <type_traits>

#include "stereo/hls/line_buffer.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

// BT.601 integer luma of one pixel.
inline pixel_t census_luma(const Rgb& p) {
#pragma HLS INLINE
    const int sum = fx::kLumaR * p.r + fx::kLumaG * p.g + fx::kLumaB * p.b;
    return static_cast<pixel_t>((sum + (1 << (fx::kLumaShift - 1))) >> fx::kLumaShift);
}

template <int WIDTH>
class census_transform : public coord_output {
    static constexpr int kRadius = fx::kCensusRadius;
    static constexpr int kSide = 2 * kRadius + 1;
    static_assert(fx::kCensusBits == kSide * kSide - 1 && fx::kCensusBits <= 24);

  public:
    const Rgb& out_left() const { return out_left_; }
    const Rgb& out_right() const { return out_right_; }

    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right, int width,
              int height) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = history_ complete dim = 0
        // The newest column: rows y-4 .. y at column x, {left, right} lumas (slot j: row y-4+j).
        pixel_t column[kSide][2];
#pragma HLS ARRAY_PARTITION variable = column complete dim = 0
        for (int j = 0; j + 1 < kSide; ++j) {
            const auto& above = rows_.above(kSide - 2 - j);
            column[j][0] = above[0];
            column[j][1] = above[1];
        }
        const pixel_t new_lumas[2] = {census_luma(left), census_luma(right)};
        column[kSide - 1][0] = new_lumas[0];
        column[kSide - 1][1] = new_lumas[1];

        // The centre, wrapping to the previous row up to kRadius times.
        int cx = in_x - kRadius;
        int cy = in_y - kRadius;
        for (int wrap = 0; wrap < kRadius; ++wrap) {
            if (cx < 0) {
                cx += width;
                --cy;
            }
        }
        // Window column dx is history_[kRadius - dx - 1], or the newest column at dx = kRadius.
        const auto luma_at = [&](int dx, int dy, int image) {
            return dx == kRadius ? column[dy + kRadius][image]
                                 : history_[kRadius - dx - 1][dy + kRadius][image];
        };
        std::uint32_t codes[2] = {0, 0};
        for (int image = 0; image < 2; ++image) {
            const int centre = luma_at(0, 0, image);
            for (int dy = -kRadius; dy <= kRadius; ++dy) {
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    if (dx == 0 && dy == 0) {
                        continue;
                    }
                    const bool inside = inside_frame(cx + dx, cy + dy, width, height);
                    codes[image] =
                        (codes[image] << 1) | (inside && luma_at(dx, dy, image) < centre ? 1U : 0U);
                }
            }
        }
        const bool real = in_y != kNoPixel && cy >= 0;
        out_x_ = real ? static_cast<coord_t>(cx) : coord_t{0};
        out_y_ = real ? static_cast<coord_t>(cy) : kNoPixel;
        out_left_ = unpack(codes[0]);
        out_right_ = unpack(codes[1]);

        for (int c = kSide - 2; c > 0; --c) {
            for (int j = 0; j < kSide; ++j) {
                history_[c][j][0] = history_[c - 1][j][0];
                history_[c][j][1] = history_[c - 1][j][1];
            }
        }
        for (int j = 0; j < kSide; ++j) {
            history_[0][j][0] = column[j][0];
            history_[0][j][1] = column[j][1];
        }
        rows_.step(in_x, width, new_lumas);
    }

  private:
    static bool inside_frame(int x, int y, int width, int height) {
        return x >= 0 && x < width && y >= 0 && y < height;
    }
    static Rgb unpack(std::uint32_t code) {
        return {static_cast<pixel_t>(code >> 16), static_cast<pixel_t>(code >> 8),
                static_cast<pixel_t>(code)};
    }

    line_buffer<WIDTH, pixel_t, kSide - 1, 2> rows_;  // {left, right} lumas of 4 rows
    pixel_t history_[kSide - 1][kSide][2] = {};       // the 4 columns before the newest
    Rgb out_left_;
    Rgb out_right_;
};

// The census cost: the delay lines carry the codes.
struct census_measure {
    using feature = Rgb;
    static feature convert(const Rgb& code) { return code; }
    static cost_t distance(const Rgb& a, const Rgb& b) {
#pragma HLS INLINE
        const auto bits = [](const Rgb& c) {
            return (std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b;
        };
        return static_cast<cost_t>(std::popcount(bits(a) ^ bits(b)) * fx::kCensusWeight);
    }
};

template <class MEASURE>
inline constexpr bool kIsCensus = std::is_same_v<MEASURE, census_measure>;

}  // namespace stereo::hls
