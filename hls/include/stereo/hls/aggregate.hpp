// aggregate: Gaussian-weighted window sum of every disparity plane, one pixel per step
// (model: stereo::aggregate, docs/fixed-point.md stage 2; RTL: rtl/stereo_aggregate.sv).
//
// Separable and exact. Vertical pass: a line buffer of WINDOW-1 rows gives, with the incoming
// row, the WINDOW costs of one column, and V = sum_j k[j] C (full precision) is registered.
// Horizontal pass: the last WINDOW vertical sums of the row give T = sum_i k[i] V, and one
// rounding shift A = (T + 2^(kAggShift-1)) >> kAggShift. Taps whose row or column lies outside
// the frame read 0 (zero padding), decided from the coordinates.
// Output pixel = input pixel moved back R rows and R columns, R = WINDOW/2 (wrapping to earlier
// rows). Latency: R*W + R + 2 pixel steps (W = runtime width).
#pragma once

#include "stereo/hls/line_buffer.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int WIDTH, int NDISP, int WINDOW>
class aggregate : public lane_output<agg_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    static_assert(WINDOW % 2 == 1 && WINDOW >= fx::kMinWindow && WINDOW <= fx::kMaxWindow);
    static constexpr int R = WINDOW / 2;
    static constexpr int kRows = R > 0 ? 2 * R : 1;  // rows buffered, columns of history

    using lane_output<agg_t, NDISP>::out_data_;
    using lane_output<agg_t, NDISP>::out_x_;
    using lane_output<agg_t, NDISP>::out_y_;

  public:
    using InLanes = cost_t[NDISP];
    using Kernel = tap_t[WINDOW];

    // Clears the coordinates only ("no pixel"), like the RTL's reset; data stays.
    void reset() {
        vertical_x_ = 0;
        vertical_y_ = kNoPixel;
        lane_output<agg_t, NDISP>::reset();
    }

    void step(coord_t in_x, coord_t in_y, const InLanes& in, int width, int height,
              const Kernel& kernel) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = vertical_q_ complete
#pragma HLS ARRAY_PARTITION variable = history_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        // ---- horizontal pass, on the registered vertical sums --------------------------------
        // Centre: R columns behind the newest vertical sum, wrapping to earlier rows (more than
        // one when the frame is narrower than R).
        int centre_x = vertical_x_ - R;
        int centre_y = vertical_y_;
        for (int wrap = 0; wrap < (R > 0 ? R : 1); ++wrap) {
            if (centre_x < 0) {
                centre_x += width;
                centre_y -= 1;
            }
        }
        bool column_inside[WINDOW];
#pragma HLS ARRAY_PARTITION variable = column_inside complete
        for (int i = 0; i < WINDOW; ++i) {
            const int column = centre_x - R + i;
            column_inside[i] = column >= 0 && column < width;
        }
        for (int d = 0; d < NDISP; ++d) {
            wsum_t sum = 0;
            for (int i = 0; i < WINDOW; ++i) {
                // Tap i covers column centre_x - R + i: 2R - i columns behind the newest.
                const vsum_t v = i == 2 * R ? vertical_q_[d] : history_[kRows - 1 - i][d];
                if (column_inside[i]) {
                    sum += static_cast<wsum_t>(v) * kernel[i];
                }
            }
            out_data_[d] =
                static_cast<agg_t>((sum + (wsum_t{1} << (fx::kAggShift - 1))) >> fx::kAggShift);
        }
        out_x_ = to_coord(centre_x);
        out_y_ = to_coord(centre_y);
        if constexpr (R > 0) {
            for (int k = kRows - 1; k > 0; --k) {
                for (int d = 0; d < NDISP; ++d) {
                    history_[k][d] = history_[k - 1][d];
                }
            }
            for (int d = 0; d < NDISP; ++d) {
                history_[0][d] = vertical_q_[d];
            }
        }

        // ---- vertical pass, on the incoming column and the line buffer -----------------------
        bool row_inside[WINDOW];
#pragma HLS ARRAY_PARTITION variable = row_inside complete
        for (int j = 0; j < WINDOW; ++j) {
            const int row = in_y - 2 * R + j;
            row_inside[j] = row >= 0 && row < height;
        }
        for (int d = 0; d < NDISP; ++d) {
            vsum_t sum = 0;
            for (int j = 0; j < WINDOW; ++j) {
                // Tap j covers row in_y - 2R + j: the row 2R - j above the incoming one.
                const cost_t c = j == 2 * R ? in[d] : rows_.above(2 * R - 1 - j)[d];
                if (row_inside[j]) {
                    sum += static_cast<vsum_t>(c) * kernel[j];
                }
            }
            vertical_q_[d] = sum;
        }
        vertical_x_ = in_x;
        vertical_y_ = to_coord(in_y - R);  // centre row of the vertical window
        if constexpr (R > 0) {
            rows_.step(in_x, width, in);
        }
    }

  private:
    line_buffer<WIDTH, cost_t, kRows, NDISP> rows_;  // row in_y-1-k at above(k)
    vsum_t vertical_q_[NDISP] = {};                  // V of column vertical_x_
    coord_t vertical_x_ = 0;
    coord_t vertical_y_ = kNoPixel;
    vsum_t history_[kRows][NDISP] = {};  // V of column vertical_x_ - 1 - k (same row or masked)
};

}  // namespace stereo::hls
