// Fixed-width types, stream beats and the frame configuration of the HLS kernels.
//
// Every width comes from stereo::fx (model/include/stereo/constants.hpp, docs/fixed-point.md);
// nothing is re-typed here. Each value is held in the smallest standard unsigned integer at
// least that wide, checked by the static_asserts below, so the kernels compile with plain g++
// and no vendor header. A synthesis build that wants the exact widths in its RAMs can change
// these aliases (and only these) to ap_uint<N> of the named width.
#pragma once

#include <cstdint>
#include <limits>
#include <type_traits>

#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"

namespace stereo::hls {

using pixel_t = std::uint8_t;      // one colour channel: fx::kPixelBits
using cost_t = std::uint16_t;      // C, stage 1: fx::kCostBits (10)
using tap_t = std::uint16_t;       // one kernel tap, 0 .. fx::kKernelSum (9 bits)
using vsum_t = std::uint32_t;      // V, vertical pass: fx::kVerticalSumBits (18)
using wsum_t = std::uint32_t;      // T, window sum: fx::kWindowSumBits (26)
using agg_t = std::uint16_t;       // A, B, E (stages 2-4): fx::kAggBits (14)
using ca_sum_t = std::uint32_t;    // 3x3 sum of rule 1: fx::kCaSumBits (17)
using product_t = std::uint32_t;   // mean9 / div13 products: 32 bits
using disparity_t = std::uint8_t;  // fx::kDisparityBits
using ndisp_t = std::uint16_t;     // a label count 1 .. fx::kMaxDisparities (9 bits)
using coord_t = std::int16_t;      // pixel coordinates, signed 16 bits as in the RTL
using status_t = std::uint8_t;     // sticky error bits of one frame (see top.hpp)
using fixed_t = std::int16_t;      // signed disparity x 16: fx::kFixedDisparityBits
using certainty_t = std::uint8_t;  // fx::kCertaintyBits
using reason_t = std::uint8_t;     // fx::kReasonBits

template <typename T>
constexpr bool holds_bits(int bits) {
    return std::numeric_limits<T>::digits >= bits;
}

static_assert(holds_bits<pixel_t>(fx::kPixelBits));
static_assert(holds_bits<cost_t>(fx::kCostBits));
static_assert(fx::kKernelSum <= std::numeric_limits<tap_t>::max());
static_assert(static_cast<std::int64_t>(fx::kCostMax) * fx::kKernelSum <
                  (std::int64_t{1} << fx::kVerticalSumBits),
              "a vertical sum must fit kVerticalSumBits");
static_assert(holds_bits<vsum_t>(fx::kVerticalSumBits));
static_assert(holds_bits<wsum_t>(fx::kWindowSumBits));
static_assert(holds_bits<agg_t>(fx::kAggBits));
static_assert(holds_bits<ca_sum_t>(fx::kCaSumBits));
static_assert(holds_bits<product_t>(32));
static_assert(holds_bits<disparity_t>(fx::kDisparityBits));
static_assert(fx::kMaxDisparities <= std::numeric_limits<ndisp_t>::max());
static_assert(std::numeric_limits<fixed_t>::digits + 1 >= fx::kFixedDisparityBits);
static_assert(holds_bits<certainty_t>(fx::kCertaintyBits));
static_assert(holds_bits<reason_t>(fx::kReasonBits));

// Coordinates of "no pixel" and the largest frame side: the stage table's (stage_table.hpp).
inline constexpr coord_t kNoPixel = table::kNoPixel;
inline constexpr int kMaxFrameSide = table::kMaxFrameSide;
static_assert(holds_bits<std::make_unsigned_t<coord_t>>(table::kCoordBits));

// Wraps like the RTL's 16-bit coordinate registers (conversion to a signed type is modular
// in C++20).
inline coord_t to_coord(int value) {
    return static_cast<coord_t>(value);
}

// Leaves of a comparator tree over n lanes: the next power of two (wta, validate_stage).
constexpr int tree_leaves(int n) {
    int count = 1;
    while (count < n) {
        count *= 2;
    }
    return count;
}

inline bool inside(int x, int y, int width, int height) {
    return x >= 0 && x < width && y >= 0 && y < height;
}

struct Rgb {
    pixel_t r = 0;
    pixel_t g = 0;
    pixel_t b = 0;
};

// One input beat: a pixel pair in raster order. sof marks the frame's first pixel (the RTL's
// s_axis_tuser), eol each row's last (s_axis_tlast).
struct InputBeat {
    Rgb left;
    Rgb right;
    bool sof = false;
    bool eol = false;
};

// Stage 6's output for one pixel, the RTL's out_beat_t (stage_table.hpp): the signed disparity
// x 16 (0 where invalid), why it is invalid (fx::kReason*), the certainty (every pixel).
struct Validated {
    fixed_t fixed = 0;
    reason_t reason = fx::kReasonBorder;
    certainty_t certainty = 0;
};

// One output beat per input pixel.
struct OutputBeat {
    Validated result;
    bool sof = false;
    bool eol = false;
};

// Runtime configuration of one frame, the RTL's cfg_* ports. A window smaller than WINDOW is
// centred in the WINDOW taps of `kernel` with zeros around it; `radius` is its half side (it
// sets the validity border only).
template <int WINDOW>
struct FrameConfig {
    int width = 0;              // 1 .. WIDTH
    int height = 0;             // 1 .. HEIGHT
    int ndisp = 1;              // labels 0 .. ndisp-1, 1 .. NDISP
    int radius = 0;             // 0 .. WINDOW/2
    tap_t kernel[WINDOW] = {};  // non-negative, summing to fx::kKernelSum
    bool use_ca = true;         // apply CA rules 1 and 2
    // Stage 6 (docs/fixed-point.md): d = min_disp + label, |min_disp| <= the top's MAX_MIN_DISP.
    int min_disp = 0;
    bool uniqueness = false;   // invalid when C1 (100 + ratio) >= C2 100
    int uniqueness_ratio = 0;  // 0 .. fx::kMaxUniqueness
    bool left_right = false;   // invalid when |k1 - kR(x - d)| > lr_tolerance
    int lr_tolerance = 0;      // 0 .. fx::kMaxLrTolerance
    bool subpixel = false;     // parabola through the costs at k1 - 1, k1, k1 + 1
};

}  // namespace stereo::hls
