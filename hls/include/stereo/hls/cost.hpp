// cost: the matching cost, all NDISP labels of one pixel per step, over the signed range d = m + k
// (model: stereo::cost and the cost plug-ins, docs/fixed-point.md stages 1 and 6; RTL:
// rtl/stereo_cost.sv). MEASURE says what the delay lines carry and how two of those are compared:
// ad_measure (RGB, absolute differences; below) or lcdm_measure (cost_lcdm.hpp: the point on the
// hue-saturation disc, the LCDM distance), like stereo_cost's COST parameter.
//
// The right pixels pass through continuous delay lines (across rows): one selection picks the
// right pixel P = max(m, 0) steps old from a pre-delay line of MAX_MIN_DISP, and the lanes'
// delay line of NDISP - 1 holds its history, so lane k reads the right pixel k + P positions
// behind the newest. For a negative m the left pixel and its coordinates wait K = max(0, -m)
// steps in a delay line of their own. Lane k is
//   |Lr - Rr(xr)| + |Lg - Rg(xr)| + |Lb - Rb(xr)|,  xr = x - m - k,
// or fx::kCostOutside where xr lies outside [0, W), decided from the coordinates alone, so no
// delay line is ever cleared between rows or frames (only the left coordinates, by reset()).
// Latency: 1 + K pixel steps.
#pragma once

#include "stereo/hls/shift_register.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

// The AD cost over RGB: the delay lines carry the pixels themselves.
struct ad_measure {
    using feature = Rgb;
    static feature convert(const Rgb& p) { return p; }
    static cost_t distance(const Rgb& a, const Rgb& b) {
#pragma HLS INLINE
        const auto diff = [](int p, int q) { return p >= q ? p - q : q - p; };
        return static_cast<cost_t>(diff(a.r, b.r) + diff(a.g, b.g) + diff(a.b, b.b));
    }
};

template <int NDISP, int MAX_MIN_DISP, class MEASURE = ad_measure>
class cost : public lane_output<cost_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    static_assert(MAX_MIN_DISP >= 0 && MAX_MIN_DISP <= fx::kMaxMinDisparity);
    using lane_output<cost_t, NDISP>::out_data_;
    using lane_output<cost_t, NDISP>::out_x_;
    using lane_output<cost_t, NDISP>::out_y_;

  public:
    cost() { reset(); }

    // The delayed left pixels' coordinates to "no pixel", as the stage's own.
    void reset() {
        coord_output::reset();
        for (int i = 0; i < kLeftDelay; ++i) {
            left_x_[i] = 0;
            left_y_[i] = kNoPixel;
        }
    }

    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right, int width,
              int min_disp) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = history_ complete
#pragma HLS ARRAY_PARTITION variable = pre_ complete
#pragma HLS ARRAY_PARTITION variable = left_ complete
#pragma HLS ARRAY_PARTITION variable = left_x_ complete
#pragma HLS ARRAY_PARTITION variable = left_y_ complete
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        const Feature new_left = MEASURE::convert(left);
        const Feature new_right = MEASURE::convert(right);
        const int wait = min_disp < 0 ? -min_disp : 0;  // K
        const int skip = min_disp > 0 ? min_disp : 0;   // P
        const Feature matched = wait == 0 ? new_left : left_[wait - 1];
        const coord_t x = wait == 0 ? in_x : left_x_[wait - 1];
        const coord_t y = wait == 0 ? in_y : left_y_[wait - 1];
        const Feature selected = skip == 0 ? new_right : pre_[skip - 1];
        for (int k = 0; k < NDISP; ++k) {
            const Feature& match = k == 0 ? selected : history_[k - 1];
            const int right_x = x - min_disp - k;
            out_data_[k] = right_x < 0 || right_x >= width ? static_cast<cost_t>(fx::kCostOutside)
                                                           : MEASURE::distance(matched, match);
        }
        shift_in(history_, selected);
        shift_in(pre_, new_right);
        shift_in(left_, new_left);
        shift_in(left_x_, in_x);
        shift_in(left_y_, in_y);
        out_x_ = x;
        out_y_ = y;
    }

  private:
    using Feature = typename MEASURE::feature;
    // The lanes' right history, the right pre-delay line, the left pixels kept.
    static constexpr int kHistory = NDISP > 1 ? NDISP - 1 : 1;
    static constexpr int kPreDelay = MAX_MIN_DISP > 0 ? MAX_MIN_DISP : 1;
    static constexpr int kLeftDelay = MAX_MIN_DISP > 0 ? MAX_MIN_DISP : 1;

    Feature history_[kHistory] = {};  // history_[i]: the selected right pixel i + 1 steps ago
    Feature pre_[kPreDelay] = {};     // pre_[i]: the right pixel i + 1 steps before the newest
    Feature left_[kLeftDelay] = {};   // left_[i]: the left pixel i + 1 steps ago, and its place
    coord_t left_x_[kLeftDelay] = {};
    coord_t left_y_[kLeftDelay] = {};
};

}  // namespace stereo::hls
