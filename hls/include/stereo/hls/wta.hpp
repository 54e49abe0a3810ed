// wta: winner takes all and the validity flag, one pixel per step
// (model: stereo::wta, docs/fixed-point.md stage 5; RTL: rtl/stereo_wta.sv).
//
// A comparator tree over the NDISP lanes finds the smallest value; on equal values the left
// (smaller d) input wins, so ties go to the smallest d. Lanes d >= ndisp take no part. The pixel
// is valid when its window stays inside the frame and its winner's right-image samples do too:
//   reach <= x < W - reach,  reach <= y < H - reach,  x - d >= reach,
// reach = radius + (use_ca ? 1 : 0). Invalid pixels output fx::kInvalidDisparity.
// Latency: 1 pixel step.
#pragma once

#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int NDISP>
class wta : public coord_output {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);

    static constexpr int leaves(int n) {
        int count = 1;
        while (count < n) {
            count *= 2;
        }
        return count;
    }
    static constexpr int kLeaves = leaves(NDISP);
    // Absent labels carry a code above any aggregate: they never win.
    static constexpr agg_t kAbsent = (1 << fx::kAggBits) - 1;
    static_assert(kAbsent > fx::kAggMax);

  public:
    using Lanes = agg_t[NDISP];

    void step(coord_t in_x, coord_t in_y, const Lanes& in, int width, int height, int ndisp,
              int radius, bool use_ca) {
#pragma HLS INLINE
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
        const bool valid = in_x >= reach && in_x < width - reach && in_y >= reach &&
                           in_y < height - reach && in_x - winner >= reach;
        out_disparity_ = static_cast<disparity_t>(valid ? winner : fx::kInvalidDisparity);
        out_valid_ = valid;
        out_x_ = in_x;
        out_y_ = in_y;
    }

    disparity_t out_disparity() const {
        return out_disparity_;
    }
    bool out_valid() const {
        return out_valid_;
    }

  private:
    disparity_t out_disparity_ = 0;
    bool out_valid_ = false;
};

}  // namespace stereo::hls
