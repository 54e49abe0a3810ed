// wta: winner takes all and the border rule, one pixel per step (model: stereo::wta and the
// winner of stereo::ValidatingSelector, docs/fixed-point.md stages 5 and 6; RTL:
// rtl/stereo_wta.sv).
//
// A comparator tree over the NDISP lanes finds the smallest value; on equal values the left
// (smaller k) input wins, so ties go to the smallest label. Lanes k >= ndisp take no part. Label
// k stands for d = min_disp + k; the pixel passes the border rule when
//   reach <= x < W - reach,  reach <= y < H - reach,  reach <= x - d < W - reach,
// reach = radius + (use_ca ? 1 : 0). Registered for stage 6: the winner k1 whatever the border
// says, C1, the costs at k1 - 1 and k1 + 1, the border flag and the cost vector.
// Latency: 1 pixel step.
#pragma once

#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int NDISP>
class wta : public lane_output<agg_t, NDISP>, public winner_output {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    using lane_output<agg_t, NDISP>::out_data_;
    using lane_output<agg_t, NDISP>::out_x_;
    using lane_output<agg_t, NDISP>::out_y_;

    static constexpr int kLeaves = tree_leaves(NDISP);
    // Absent labels carry a code above any aggregate: they never win.
    static constexpr agg_t kAbsent = (1 << fx::kAggBits) - 1;
    static_assert(kAbsent > fx::kAggMax);

  public:
    using Lanes = agg_t[NDISP];

    void step(coord_t in_x, coord_t in_y, const Lanes& in, int width, int height, int ndisp,
              int radius, bool use_ca, int min_disp) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        agg_t value[kLeaves];
        disparity_t label[kLeaves];
#pragma HLS ARRAY_PARTITION variable = value complete
#pragma HLS ARRAY_PARTITION variable = label complete
        for (int d = 0; d < kLeaves; ++d) {
            value[d] = d < NDISP && d < ndisp ? in[d] : kAbsent;
            label[d] = static_cast<disparity_t>(d);
        }
        // One tree level per pass, in place: node n takes children 2n and 2n+1, which no
        // earlier node of the level has overwritten. Left wins ties.
        for (int nodes = kLeaves / 2; nodes >= 1; nodes /= 2) {
            for (int n = 0; n < nodes; ++n) {
                const bool take_left = value[2 * n] <= value[2 * n + 1];
                value[n] = take_left ? value[2 * n] : value[2 * n + 1];
                label[n] = take_left ? label[2 * n] : label[2 * n + 1];
            }
        }
        const int winner = label[0];
        const int reach = radius + (use_ca ? 1 : 0);
        const int right_x = in_x - min_disp - winner;
        out_border_ = in_x >= reach && in_x < width - reach && in_y >= reach &&
                      in_y < height - reach && right_x >= reach && right_x < width - reach;
        out_label_ = static_cast<disparity_t>(winner);
        out_cost_ = value[0];
        out_before_ = winner > 0 ? in[winner - 1] : 0;
        out_after_ = winner + 1 < NDISP ? in[winner + 1] : 0;
        for (int k = 0; k < NDISP; ++k) {
            out_data_[k] = in[k];
        }
        out_x_ = in_x;
        out_y_ = in_y;
    }

    agg_t out_before() const {
        return out_before_;
    }
    agg_t out_after() const {
        return out_after_;
    }
    // Stage 5's view: the winner where the border rule holds, else fx::kInvalidDisparity.
    disparity_t out_disparity() const {
        return out_border_ ? out_label_ : static_cast<disparity_t>(fx::kInvalidDisparity);
    }
    bool out_valid() const {
        return out_border_;
    }

  private:
    agg_t out_before_ = 0;
    agg_t out_after_ = 0;
};

}  // namespace stereo::hls
