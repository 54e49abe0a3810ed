// ca_rule1: CA rule 1 on the 3x3 window of every plane, one pixel per step
// (model: stereo::ca_rule1, docs/fixed-point.md stage 3; RTL: rtl/stereo_ca_rule1.sv).
//
// A cell whose d-1 or d+1 neighbour (d+1 < ndisp) agrees with it, 2|n - c| < c, becomes the
// rounded mean of its 3x3 in-plane neighbourhood (zero padding outside the frame),
// (sum * fx::kMean9Mul + 2^(fx::kMean9Shift-1)) >> fx::kMean9Shift; the others pass. With
// use_ca false every cell passes. Output pixel = input pixel moved back one row and one column.
// Latency: W + 2 pixel steps.
#pragma once

#include "stereo/hls/types.hpp"
#include "stereo/hls/window3x3.hpp"

namespace stereo::hls {

// 2|n - c| < c, exact ("n differs from c by less than half of c").
inline bool agrees(agg_t neighbour, agg_t centre) {
    const int difference = neighbour >= centre ? neighbour - centre : centre - neighbour;
    return 2 * difference < centre;
}

template <int WIDTH, int NDISP>
class ca_rule1 {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);

  public:
    using value_type = agg_t;
    static constexpr int kLanes = NDISP;
    using Lanes = agg_t[NDISP];

    void reset() {
        out_x_ = 0;
        out_y_ = kNoPixel;
    }

    void step(coord_t in_x, coord_t in_y, const Lanes& in, int width, int height, int ndisp,
              bool use_ca) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        coord_t centre_x = 0;
        coord_t centre_y = 0;
        agg_t window[9][NDISP];
        bool in_frame[9];
#pragma HLS ARRAY_PARTITION variable = window complete dim = 0
#pragma HLS ARRAY_PARTITION variable = in_frame complete
        window_.look(in_x, in_y, in, width, height, centre_x, centre_y, window, in_frame);
        constexpr int kCentre = window3x3<WIDTH, agg_t, NDISP>::kCentre;
        for (int d = 0; d < NDISP; ++d) {
            const agg_t centre = window[kCentre][d];
            const bool below = d > 0 && agrees(window[kCentre][d - 1], centre);
            const bool above =
                d + 1 < NDISP && d + 1 < ndisp && agrees(window[kCentre][d + 1], centre);
            ca_sum_t sum = 0;
            for (int slot = 0; slot < 9; ++slot) {
                if (in_frame[slot]) {
                    sum += window[slot][d];
                }
            }
            // round(sum / 9) by the constants header's own multiply-and-shift.
            out_data_[d] = use_ca && (below || above)
                               ? static_cast<agg_t>(fx::mean9(static_cast<product_t>(sum)))
                               : centre;
        }
        out_x_ = centre_x;
        out_y_ = centre_y;
        window_.step(in_x, width, in);
    }

    coord_t out_x() const {
        return out_x_;
    }
    coord_t out_y() const {
        return out_y_;
    }
    const Lanes& out_data() const {
        return out_data_;
    }

  private:
    window3x3<WIDTH, agg_t, NDISP> window_;
    Lanes out_data_ = {};
    coord_t out_x_ = 0;
    coord_t out_y_ = kNoPixel;
};

}  // namespace stereo::hls
