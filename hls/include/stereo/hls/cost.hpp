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

// The delay lines of a cost stage (rtl/stereo_cost.sv), for minimum disparity m: the left pixel
// waits K = max(0, -m) steps with its coordinates, and lane k meets the right pixel of column
// x - m - k, the right stream delayed P = max(0, m) steps and then k more.
template <typename Word, int NDISP, int MAX_MIN_DISP>
class label_delays {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    static_assert(MAX_MIN_DISP >= 0 && MAX_MIN_DISP <= fx::kMaxMinDisparity);

  public:
    // This step's left pixel (after its wait), its place, and lane 0's right pixel.
    struct Aligned {
        Word left;
        coord_t x;
        coord_t y;
        Word selected;
    };

    label_delays() { reset(); }

    // The waiting left pixels' coordinates to "no pixel", as the stage's own.
    void reset() {
        for (int i = 0; i < kLeftDelay; ++i) {
            left_x_[i] = 0;
            left_y_[i] = kNoPixel;
        }
    }

    Aligned align(coord_t in_x, coord_t in_y, const Word& left, const Word& right,
                  int min_disp) const {
#pragma HLS INLINE
        const int wait = min_disp < 0 ? -min_disp : 0;  // K
        const int skip = min_disp > 0 ? min_disp : 0;   // P
        return {wait == 0 ? left : left_[wait - 1], wait == 0 ? in_x : left_x_[wait - 1],
                wait == 0 ? in_y : left_y_[wait - 1], skip == 0 ? right : pre_[skip - 1]};
    }

    // Lane k's right pixel of this step.
    const Word& lane(const Aligned& aligned, int k) const {
        return k == 0 ? aligned.selected : history_[k - 1];
    }

    // Every line one step on, with this step's input.
    void advance(const Aligned& aligned, coord_t in_x, coord_t in_y, const Word& left,
                 const Word& right) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = history_ complete
#pragma HLS ARRAY_PARTITION variable = pre_ complete
#pragma HLS ARRAY_PARTITION variable = left_ complete
#pragma HLS ARRAY_PARTITION variable = left_x_ complete
#pragma HLS ARRAY_PARTITION variable = left_y_ complete
        shift_in(history_, aligned.selected);
        shift_in(pre_, right);
        shift_in(left_, left);
        shift_in(left_x_, in_x);
        shift_in(left_y_, in_y);
    }

  private:
    static constexpr int kHistory = NDISP > 1 ? NDISP - 1 : 1;
    static constexpr int kPreDelay = MAX_MIN_DISP > 0 ? MAX_MIN_DISP : 1;
    static constexpr int kLeftDelay = MAX_MIN_DISP > 0 ? MAX_MIN_DISP : 1;

    Word history_[kHistory] = {};  // history_[i]: the selected right pixel i + 1 steps ago
    Word pre_[kPreDelay] = {};     // pre_[i]: the right pixel i + 1 steps before the newest
    Word left_[kLeftDelay] = {};   // left_[i]: the left pixel i + 1 steps ago, and its place
    coord_t left_x_[kLeftDelay] = {};
    coord_t left_y_[kLeftDelay] = {};
};

template <int NDISP, int MAX_MIN_DISP, class MEASURE = ad_measure>
class cost : public lane_output<cost_t, NDISP> {
    using lane_output<cost_t, NDISP>::out_data_;
    using lane_output<cost_t, NDISP>::out_x_;
    using lane_output<cost_t, NDISP>::out_y_;

  public:
    cost() { reset(); }

    void reset() {
        coord_output::reset();
        delays_.reset();
    }

    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right, int width,
              int min_disp) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        const Feature new_left = MEASURE::convert(left);
        const Feature new_right = MEASURE::convert(right);
        const auto aligned = delays_.align(in_x, in_y, new_left, new_right, min_disp);
        for (int k = 0; k < NDISP; ++k) {
            const int right_x = aligned.x - min_disp - k;
            out_data_[k] = right_x < 0 || right_x >= width
                               ? static_cast<cost_t>(fx::kCostOutside)
                               : MEASURE::distance(aligned.left, delays_.lane(aligned, k));
        }
        delays_.advance(aligned, in_x, in_y, new_left, new_right);
        out_x_ = aligned.x;
        out_y_ = aligned.y;
    }

  private:
    using Feature = typename MEASURE::feature;
    label_delays<Feature, NDISP, MAX_MIN_DISP> delays_;
};

}  // namespace stereo::hls
