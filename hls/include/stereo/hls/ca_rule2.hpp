// ca_rule2: CA rule 2 on the 3x3 window of every plane, one pixel per step
// (model: stereo::ca_rule2, docs/fixed-point.md stage 4; RTL: rtl/stereo_ca_rule2.sv).
//
// A cell with at least fx::kRule2MinCount of its 8 in-plane neighbours inside the frame agreeing
// with it, 2|n - c| < c, becomes round(c / 1.3) = (c * fx::kDiv13Mul + 2^(fx::kDiv13Shift-1)) >>
// fx::kDiv13Shift; the others pass. With use_ca false every cell passes. Output pixel = input
// pixel moved back one row and one column. Latency: W + 2 pixel steps.
#pragma once

#include "stereo/hls/ca_rule1.hpp"  // agrees()
#include "stereo/hls/types.hpp"
#include "stereo/hls/window3x3.hpp"

namespace stereo::hls {

template <int WIDTH, int NDISP>
class ca_rule2 {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);

  public:
    using value_type = agg_t;
    static constexpr int kLanes = NDISP;
    using Lanes = agg_t[NDISP];

    void reset() {
        out_x_ = 0;
        out_y_ = kNoPixel;
    }

    void step(coord_t in_x, coord_t in_y, const Lanes& in, int width, int height, bool use_ca) {
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
            int count = 0;
            for (int slot = 0; slot < 9; ++slot) {
                // A neighbour outside the frame is zero padding, and zero never agrees.
                if (slot != kCentre && in_frame[slot] && agrees(window[slot][d], centre)) {
                    ++count;
                }
            }
            // round(centre / 1.3) by the constants header's own multiply-and-shift.
            out_data_[d] = use_ca && count >= fx::kRule2MinCount
                               ? static_cast<agg_t>(fx::div13(static_cast<product_t>(centre)))
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
