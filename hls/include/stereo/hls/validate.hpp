// validate_stage and lr_check: stage 6, one pixel per step (model: stereo::ValidatingSelector and
// stereo::validation, docs/fixed-point.md stage 6; RTL: rtl/stereo_validate.sv,
// rtl/stereo_lr_check.sv, rtl/stereo_divider.sv).
//
// validate_stage (latency 1): C2 = min { E(k) : |k - k1| > 1, k < ndisp } by a masked comparator
// tree (a masked lane holds fx::kNoSecondCost, which is the result when no lane is left), and the
// fixed disparity 16 (m + k1) + offset, the sub-pixel offset counted on a ladder of the eight
// thresholds 16 |a - b| >= (2t - 1) den (no divider); no offset where a neighbour is no
// candidate (kNoCandidateCost, the ASW core's; rtl/stereo_validate.sv).
//
// lr_check (latency NDISP): the right-referenced winners along the DSI diagonal in NDISP
// (cost, label) accumulators that move one place per step (accumulator j holds right pixel
// xr = x - m - j of the cost vector's pixel x; the entry leaving place NDISP - 1 is complete);
// the certainty by restoring division and the uniqueness test as a left result enters a delay
// line of NDISP - 1 steps; at its end kR(x - m - k1) is completed entry k1 of the last NDISP, the
// left-right test and the reason, then the output register.
#pragma once

#include "stereo/hls/shift_register.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/hls/wta.hpp"

namespace stereo::hls {

// An aggregated cost that is no candidate: the ASW core's label whose match lies outside the right
// image (asw.hpp, rtl/fx_pkg.sv's ASW_NO_CANDIDATE), all ones of kAggBits, above every cost. No
// other aggregation reaches it. Stage 6 draws no parabola through such a neighbour (the model's
// rule, ValidatingSelector), and as a C2 candidate it equals "no second cost".
inline constexpr agg_t kNoCandidateCost = (1 << fx::kAggBits) - 1;
static_assert(kNoCandidateCost > fx::kAggMax && kNoCandidateCost == fx::kNoSecondCost);

template <int NDISP>
class validate_stage : public coord_output, public winner_output {
    static constexpr int kLeaves = tree_leaves(NDISP);
    static constexpr int kSteps = fx::kSubpixelScale / 2;  // largest |offset|
    static_assert(fx::kNoSecondCost == (1 << fx::kAggBits) - 1);

  public:
    void step(const wta<NDISP>& in, int ndisp, int min_disp, bool subpixel) {
#pragma HLS INLINE
        const int k1 = in.out_label();
        agg_t value[kLeaves];
#pragma HLS ARRAY_PARTITION variable = value complete
        for (int k = 0; k < kLeaves; ++k) {
            const bool away = k < k1 - 1 || k > k1 + 1;
            value[k] = k < NDISP && k < ndisp && away ? in.out_data()[k]
                                                      : static_cast<agg_t>(fx::kNoSecondCost);
        }
        for (int nodes = kLeaves / 2; nodes >= 1; nodes /= 2) {
            for (int n = 0; n < nodes; ++n) {
                value[n] = value[2 * n] <= value[2 * n + 1] ? value[2 * n] : value[2 * n + 1];
            }
        }
        const int before = in.out_before();
        const int after = in.out_after();
        const int difference = before >= after ? before - after : after - before;
        const int denominator = before + after - 2 * in.out_cost();
        int steps = 0;
        for (int t = 1; t <= kSteps; ++t) {
            steps += (difference << fx::kSubpixelBits) >= (2 * t - 1) * denominator ? 1 : 0;
        }
        int fixed = (min_disp + k1) * fx::kSubpixelScale;
        // The calibrated correction of the vertex: a 9-entry ROM (constants.hpp).
        const int corrected = fx::kSubpixelCorrection[static_cast<std::size_t>(steps)];
        const bool candidates = before != kNoCandidateCost && after != kNoCandidateCost;
        if (subpixel && k1 > 0 && k1 + 1 < ndisp && denominator != 0 && candidates) {
            fixed += before >= after ? corrected : -corrected;
        }
        out_label_ = static_cast<disparity_t>(k1);
        out_border_ = in.out_border();
        out_cost_ = in.out_cost();
        out_second_ = value[0];
        out_fixed_ = static_cast<fixed_t>(fixed);
        out_x_ = in.out_x();
        out_y_ = in.out_y();
    }

    agg_t out_second() const {
        return out_second_;
    }
    fixed_t out_fixed() const {
        return out_fixed_;
    }

  private:
    agg_t out_second_ = 0;
    fixed_t out_fixed_ = 0;
};

// floor((dividend << QUOTIENT_BITS) / divisor) for dividend < divisor: QUOTIENT_BITS rows of one
// subtraction each (RTL: stereo_divider).
template <int QUOTIENT_BITS>
constexpr int restoring_quotient(int dividend, int divisor) {
    int remainder = dividend;
    int quotient = 0;
    for (int i = QUOTIENT_BITS - 1; i >= 0; --i) {
        remainder <<= 1;
        if (remainder >= divisor) {
            remainder -= divisor;
            quotient |= 1 << i;
        }
    }
    return quotient;
}

template <int NDISP>
class lr_check : public coord_output {
    static constexpr int kDelay = NDISP - 1;
    static constexpr int kLine = kDelay > 0 ? kDelay : 1;
    static constexpr agg_t kUnset = (1 << fx::kAggBits) - 1;  // above every cost

    struct Entry {
        coord_t x = 0;
        coord_t y = kNoPixel;
        disparity_t label = 0;
        bool border = false;
        bool not_unique = false;
        certainty_t certainty = 0;
        fixed_t fixed = 0;
    };

  public:
    // Coordinates of the delay line and of the output to "no pixel".
    void reset() {
        coord_output::reset();
        for (int i = 0; i < kLine; ++i) {
            line_[i].x = 0;
            line_[i].y = kNoPixel;
        }
    }

    // `acc`: the cost vector of pixel p (the WTA's register); `left`: the left result of pixel
    // p - 1 (validate's register). Returns nothing; the output register is out_*().
    void step(const wta<NDISP>& acc, const validate_stage<NDISP>& left, int width, int height,
              int ndisp, int min_disp, bool uniqueness, int ratio, bool left_right, int tolerance) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = cost_ complete
#pragma HLS ARRAY_PARTITION variable = label_ complete
#pragma HLS ARRAY_PARTITION variable = hist_ complete
#pragma HLS ARRAY_PARTITION variable = line_ complete
        // The delay line's end: the left-right test and the output register.
        const Entry leaving = kDelay > 0 ? line_[kLine - 1] : entering(left, uniqueness, ratio);
        const int right_label = hist_[leaving.label < NDISP ? leaving.label : 0];
        const int distance = leaving.label >= right_label ? leaving.label - right_label
                                                          : right_label - leaving.label;
        reason_t reason = fx::kReasonValid;
        if (!leaving.border) {
            reason = fx::kReasonBorder;
        } else if (leaving.not_unique) {
            reason = fx::kReasonUniqueness;
        } else if (left_right && distance > tolerance) {
            reason = fx::kReasonLeftRight;
        }
        out_.reason = reason;
        out_.fixed = reason == fx::kReasonValid ? leaving.fixed : static_cast<fixed_t>(0);
        out_.certainty = leaving.certainty;
        out_x_ = leaving.x;
        out_y_ = leaving.y;

        // The delay line moves on.
        if (kDelay > 0) {
            shift_in(line_, entering(left, uniqueness, ratio));
        }

        // The accumulators along the diagonal, and the completed winner.
        const int x = acc.out_x();
        const int y = acc.out_y();
        const bool in_frame = inside(x, y, width, height);
        disparity_t completed = 0;
        for (int j = NDISP - 1; j >= 0; --j) {  // from the end: place j reads j - 1's old entry
            const int right_x = x - min_disp - j;
            const bool take = in_frame && j < ndisp && right_x >= 0 && right_x < width;
            const agg_t value = acc.out_data()[j];
            agg_t cost = kUnset;
            disparity_t label = 0;
            if (j == 0) {
                cost = take ? value : kUnset;
            } else if (take && value < cost_[j - 1]) {
                cost = value;
                label = static_cast<disparity_t>(j);
            } else {
                cost = cost_[j - 1];
                label = label_[j - 1];
            }
            if (j == NDISP - 1) {
                completed = label;
            }
            cost_[j] = cost;
            label_[j] = label;
        }
        shift_in(hist_, completed);
    }

    const Validated& out() const {
        return out_;
    }

  private:
    static Entry entering(const validate_stage<NDISP>& left, bool uniqueness, int ratio) {
        Entry e;
        const int c1 = left.out_cost();
        const int c2 = left.out_second();
        e.x = left.out_x();
        e.y = left.out_y();
        e.label = left.out_label();
        e.border = left.out_border();
        e.certainty =
            static_cast<certainty_t>(restoring_quotient<fx::kCertaintyBits>(c2 - c1, c2 + 1));
        e.not_unique = uniqueness && c2 != fx::kNoSecondCost &&
                       c1 * (fx::kUniquenessBase + ratio) >= c2 * fx::kUniquenessBase;
        e.fixed = left.out_fixed();
        return e;
    }

    agg_t cost_[NDISP] = {};
    disparity_t label_[NDISP] = {};
    disparity_t hist_[NDISP] = {};  // hist_[i]: the winner completed i + 1 steps ago
    Entry line_[kLine];
    Validated out_;
};

// The last three stages of every core (RTL: stereo_wta, stereo_validate, stereo_lr_check): the
// winner of the aggregated lanes, stage 6, and the left-right check whose register is the core's
// output register. Config has the stage 6 fields of FrameConfig / AswConfig.
template <int NDISP>
class winner_stages {
  public:
    void reset() { reset_stages(wta_, validate_, lr_check_); }

    // radius, use_ca: the CA border rule of the winner (0, false: none).
    template <class Config>
    void step_winner(coord_t in_x, coord_t in_y, const agg_t (&lanes)[NDISP], const Config& cfg,
                     int radius, bool use_ca) {
#pragma HLS INLINE
        lr_check_.step(wta_, validate_, cfg.width, cfg.height, cfg.ndisp, cfg.min_disp,
                       cfg.uniqueness, cfg.uniqueness_ratio, cfg.left_right, cfg.lr_tolerance);
        validate_.step(wta_, cfg.ndisp, cfg.min_disp, cfg.subpixel);
        wta_.step(in_x, in_y, lanes, cfg.width, cfg.height, cfg.ndisp, radius, use_ca,
                  cfg.min_disp);
    }

    coord_t out_x() const {
        return lr_check_.out_x();
    }
    coord_t out_y() const {
        return lr_check_.out_y();
    }
    const Validated& out() const {
        return lr_check_.out();
    }

  private:
    wta<NDISP> wta_;
    validate_stage<NDISP> validate_;
    lr_check<NDISP> lr_check_;
};

}  // namespace stereo::hls
