// ca_rule<WIDTH, NDISP, RULE, SEGMENT>: the shared skeleton of CA rules 1 and 2 (RTL:
// rtl/stereo_ca_plane.sv): the 3x3 in-plane window of every plane (window3x3), the per-cell
// update of RULE, the result and coordinate registers; one pixel per step. Output pixel = input
// pixel moved back one row and one column. Latency: W + 2 pixel steps.
//
//   RULE 1 (model stereo::ca_rule1, docs/fixed-point.md stage 3): a cell whose d-1 or d+1
//          neighbour (d+1 < ndisp) agrees with it becomes the rounded mean of its 3x3 in-plane
//          neighbourhood (zero padding outside the frame), fx::mean9. The labels form runs of
//          SEGMENT (all NDISP by default) and d-1, d+1 stay inside the run of d: a hierarchical
//          level's candidate rows, CaNeighbours::horizontal (RTL: stereo_ca_plane's SEGMENT).
//   RULE 2 (model stereo::ca_rule2, stage 4): a cell with at least fx::kRule2MinCount of its 8
//          in-plane neighbours inside the frame agreeing with it becomes round(c / 1.3),
//          fx::div13.
// "Agrees" is fx::agrees (stage_table.hpp), 2|n - c| < c. With use_ca false every cell passes.
#pragma once

#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/hls/window3x3.hpp"
#include "stereo/stage_table.hpp"

namespace stereo::hls {

using fx::agrees;

template <int WIDTH, int NDISP, int RULE, int SEGMENT = NDISP>
class ca_rule : public lane_output<agg_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    static_assert(RULE == 1 || RULE == 2);
    static_assert(SEGMENT >= 1 && NDISP % SEGMENT == 0);
    using lane_output<agg_t, NDISP>::out_data_;
    using lane_output<agg_t, NDISP>::out_x_;
    using lane_output<agg_t, NDISP>::out_y_;

  public:
    using typename lane_output<agg_t, NDISP>::Lanes;

    // ndisp matters to rule 1 only (rule 2 does not look across planes).
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
        for (int d = 0; d < NDISP; ++d) {
            out_data_[d] = use_ca ? update(window, in_frame, d, ndisp) : window[kCentre][d];
        }
        out_x_ = centre_x;
        out_y_ = centre_y;
        window_.step(in_x, width, in);
    }

  private:
    static constexpr int kCentre = window3x3<WIDTH, agg_t, NDISP>::kCentre;

    // The new value of cell d with CA on.
    static agg_t update(const agg_t (&window)[9][NDISP], const bool (&in_frame)[9], int d,
                        int ndisp) {
        const agg_t centre = window[kCentre][d];
        if constexpr (RULE == 1) {
            // d % SEGMENT: the label's place in its run (d itself for the 1-D pipeline).
            const bool below = d % SEGMENT > 0 && agrees(window[kCentre][d - 1], centre);
            const bool above = (d + 1) % SEGMENT != 0 && d + 1 < NDISP && d + 1 < ndisp &&
                               agrees(window[kCentre][d + 1], centre);
            ca_sum_t sum = 0;
            for (int slot = 0; slot < 9; ++slot) {
                if (in_frame[slot]) {
                    sum += window[slot][d];
                }
            }
            // round(sum / 9) by the constants header's own multiply-and-shift.
            return below || above ? static_cast<agg_t>(fx::mean9(static_cast<product_t>(sum)))
                                  : centre;
        } else {
            int count = 0;
            for (int slot = 0; slot < 9; ++slot) {
                // A neighbour outside the frame is zero padding, and zero never agrees.
                if (slot != kCentre && in_frame[slot] && agrees(window[slot][d], centre)) {
                    ++count;
                }
            }
            // round(centre / 1.3) by the constants header's own multiply-and-shift.
            return count >= fx::kRule2MinCount
                       ? static_cast<agg_t>(fx::div13(static_cast<product_t>(centre)))
                       : centre;
        }
    }

    window3x3<WIDTH, agg_t, NDISP> window_;
};

// The two stages of the pipeline (stereo_hls_top); a hierarchical level's rule 1 has runs of
// SEGMENT = COLS labels (hier_level.hpp).
template <int WIDTH, int NDISP, int SEGMENT = NDISP>
using ca_rule1 = ca_rule<WIDTH, NDISP, 1, SEGMENT>;
template <int WIDTH, int NDISP>
using ca_rule2 = ca_rule<WIDTH, NDISP, 2>;

}  // namespace stereo::hls
