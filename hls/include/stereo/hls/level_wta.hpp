// level_wta: the winner of a hierarchical level's COLS x ROWS candidates, one pixel per step
// (model: stereo::hierarchical::match_level's WinnerTakesAll with stereo::tie_key,
// docs/hierarchical.md "The levels in hardware"; RTL: rtl/stereo_level_wta.sv and the TIE_RANK
// table of rtl/stereo_hier_level.sv).
//
// The smallest cost wins; among equal costs the candidate of the smallest tie key
// (|v - pv|, |d - pd|, v, d). Relative to the base that order is the same for every pixel, so each
// label k = j * COLS + i has a constant rank (kTieRank, at compile time) with
//   REFINE = 0 (the quarter level): d = i, v = V_MIN + j, preferred (0, 0);
//   REFINE = 1 (half and full):     d = i, v = j, preferred the 3x3 centre (1, 1).
// The ranks are distinct, so the winner is the smallest {cost, rank}: one comparison per pair of
// labels in the tree. Out comes the winner's label (not its rank). Latency: 1 pixel step.
#pragma once

#include <array>
#include <cstdint>

#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int COLS, int ROWS, bool REFINE, int V_MIN>
class level_wta : public coord_output {
    static constexpr int kLabels = COLS * ROWS;
    static_assert(kLabels >= 2 && kLabels <= fx::kMaxDisparities);
    static_assert(!REFINE || (COLS == 3 && ROWS == 3), "a refinement level has a 3x3 grid");
    static constexpr int kLeaves = tree_leaves(kLabels);

    static constexpr int magnitude(int value) { return value < 0 ? -value : value; }
    // stereo::tie_key's order of labels a and b, relative to the base.
    static constexpr bool key_less(int a, int b) {
        const int preferred = REFINE ? 1 : 0;  // pd = pv
        const int da = a % COLS;
        const int db = b % COLS;
        const int va = (REFINE ? 0 : V_MIN) + a / COLS;
        const int vb = (REFINE ? 0 : V_MIN) + b / COLS;
        if (magnitude(va - preferred) != magnitude(vb - preferred)) {
            return magnitude(va - preferred) < magnitude(vb - preferred);
        }
        if (magnitude(da - preferred) != magnitude(db - preferred)) {
            return magnitude(da - preferred) < magnitude(db - preferred);
        }
        return va != vb ? va < vb : da < db;
    }
    // The rank of every label: how many labels have a smaller key.
    static constexpr std::array<std::uint16_t, kLabels> tie_ranks() {
        std::array<std::uint16_t, kLabels> rank{};
        for (int k = 0; k < kLabels; ++k) {
            for (int m = 0; m < kLabels; ++m) {
                rank[static_cast<std::size_t>(k)] += key_less(m, k) ? 1 : 0;
            }
        }
        return rank;
    }

  public:
    using Lanes = agg_t[kLabels];
    static constexpr std::array<std::uint16_t, kLabels> kTieRank = tie_ranks();

    void step(coord_t in_x, coord_t in_y, const Lanes& in) {
#pragma HLS INLINE
        agg_t cost[kLeaves];
        std::uint16_t rank[kLeaves];
        std::uint16_t label[kLeaves];
#pragma HLS ARRAY_PARTITION variable = cost complete
#pragma HLS ARRAY_PARTITION variable = rank complete
#pragma HLS ARRAY_PARTITION variable = label complete
        for (int k = 0; k < kLeaves; ++k) {
            // Padding leaves carry a rank above every label's: they never win.
            cost[k] = k < kLabels ? in[k] : static_cast<agg_t>(fx::kAggMax);
            rank[k] = k < kLabels ? kTieRank[static_cast<std::size_t>(k)] : kLabels;
            label[k] = static_cast<std::uint16_t>(k);
        }
        // One tree level per pass, in place, as wta: node n takes children 2n and 2n+1.
        for (int nodes = kLeaves / 2; nodes >= 1; nodes /= 2) {
            for (int n = 0; n < nodes; ++n) {
                const int a = 2 * n;
                const int b = 2 * n + 1;
                const bool take_a = cost[a] < cost[b] || (cost[a] == cost[b] && rank[a] < rank[b]);
                const int winner = take_a ? a : b;
                cost[n] = cost[winner];
                rank[n] = rank[winner];
                label[n] = label[winner];
            }
        }
        out_label_ = label[0];
        out_cost_ = cost[0];
        out_x_ = in_x;
        out_y_ = in_y;
    }

    int out_label() const {
        return out_label_;
    }  // k = j * COLS + i of the winner
    agg_t out_cost() const {
        return out_cost_;
    }

  private:
    std::uint16_t out_label_ = 0;
    agg_t out_cost_ = 0;
};

}  // namespace stereo::hls
