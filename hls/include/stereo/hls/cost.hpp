// cost: absolute-difference matching cost over RGB, all NDISP disparities of one pixel per step
// (model: stereo::cost, docs/fixed-point.md stage 1; RTL: rtl/stereo_cost.sv).
//
// The right pixels of the row pass through a delay line, so that at the step of left pixel x it
// holds R(x-1) .. R(x-NDISP+1). Lane d is
//   |Lr - Rr(x-d)| + |Lg - Rg(x-d)| + |Lb - Rb(x-d)|,  or fx::kCostOutside where x - d < 0,
// decided from the coordinate alone, so the delay line is never cleared between rows or frames.
// Latency: 1 pixel step (the output register).
#pragma once

#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int NDISP>
class cost : public lane_output<cost_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    using lane_output<cost_t, NDISP>::out_data_;
    using lane_output<cost_t, NDISP>::out_x_;
    using lane_output<cost_t, NDISP>::out_y_;

  public:
    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = history_ complete
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        for (int d = 0; d < NDISP; ++d) {
            const Rgb& match = d == 0 ? right : history_[d - 1];
            out_data_[d] =
                in_x - d < 0 ? static_cast<cost_t>(fx::kCostOutside) : rgb_cost(left, match);
        }
        for (int i = kHistory - 1; i > 0; --i) {
            history_[i] = history_[i - 1];
        }
        history_[0] = right;
        out_x_ = in_x;
        out_y_ = in_y;
    }

  private:
    static constexpr int kHistory = NDISP > 1 ? NDISP - 1 : 1;  // right pixels besides this one

    static cost_t rgb_cost(const Rgb& a, const Rgb& b) {
        const auto diff = [](int p, int q) { return p >= q ? p - q : q - p; };
        return static_cast<cost_t>(diff(a.r, b.r) + diff(a.g, b.g) + diff(a.b, b.b));
    }

    Rgb history_[kHistory] = {};  // history_[i] = R(x-1-i) at the step of pixel x
};

}  // namespace stereo::hls
