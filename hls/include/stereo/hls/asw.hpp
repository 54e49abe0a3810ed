// The separable adaptive-support-weight core as HLS kernels, one pixel per step (issue 46; model:
// stereo::asw::match with Params::separable, docs/asw.md; RTL: stereo_top ASW = 1,
// rtl/stereo_asw_column.sv, rtl/stereo_cost.sv RAW_BITS, rtl/stereo_asw_aggregate.sv).
//
//   [asw_census: census codes, RGB through] -> asw_column -> asw_cost -> asw_aggregate
//     -> wta (reach 0) -> validate_stage -> lr_check
//
// asw_column stacks the DIAMETER rows of the incoming column of both images and computes what
// does not depend on the disparity (the words, AswWord): the codes of the column (census codes,
// or the RGB pixels for the AD cost), the vertical factors against the centre row, and the
// horizontal factors of the centre row's pixels x - r - 1 (pass 1, "near") and x - 2r - 2 (pass
// 2, "far"). asw_cost carries the words through the cost stage's delay lines (lane k: right
// column x - m - k). asw_aggregate computes, for every label at once, the vertical weighted
// mean, keeps the last 3r + 2 columns' means in a ring, pass 1 at x - r - 1 with its winner
// entering a history of 2r + 1 labels, and pass 2 at x - 2r - 2 with the continuity factor of
// those labels. Every table is the model's (asw_tables.hpp, generated from
// stereo::asw::response_tables), every product stereo::asw::combine, every mean a restoring
// division of fx::kAggBits quotient bits. WTA and stage 6 are the pipeline's kernels with the
// border rule at reach 0; a label whose match lies outside the right image leaves the aggregation
// as kAswNoCandidate (all ones), which stage 6 never takes for C2 or a parabola point.
#pragma once

#include <cstdint>
#include <type_traits>

#include "stereo/asw.hpp"
#include "stereo/hls/asw_tables.hpp"
#include "stereo/hls/census.hpp"
#include "stereo/hls/cost.hpp"
#include "stereo/hls/line_buffer.hpp"
#include "stereo/hls/shift_register.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/stream.hpp"
#include "stereo/hls/top.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/hls/validate.hpp"
#include "stereo/hls/wta.hpp"

namespace stereo::hls {

using response_t = std::uint8_t;  // a response or weight: asw::kResponseBits
using asw_num_t = std::uint32_t;  // sum of weight x cost (or x mean) over at most 31 taps
using asw_den_t = std::uint16_t;  // sum of weights: at most 31 x 255
static_assert(holds_bits<response_t>(asw::kResponseBits));
static_assert(table::kAswMaxDiameter * asw::kResponseMax * fx::kAggMax < (std::int64_t{1} << 32));
static_assert(table::kAswMaxDiameter * asw::kResponseMax <= 0xFFFF);
// A label whose match lies outside the right image: all ones of an aggregated cost, above every
// one (rtl/fx_pkg.sv's ASW_NO_CANDIDATE); the same code as stage 6's "no second cost".
inline constexpr agg_t kAswNoCandidate = kNoCandidateCost;
static_assert(kAswNoCandidate > fx::kAggMax);

// The responses of diameter DIAMETER (the generated tables) and the rounded product.
template <int DIAMETER>
struct asw_responses {
    static_assert(DIAMETER % 2 == 1 && DIAMETER >= table::kAswMinDiameter &&
                  DIAMETER <= table::kAswMaxDiameter);
    static constexpr int kTable = (DIAMETER - table::kAswMinDiameter) / 2;
    static response_t colour(int difference) { return kAswColour[kTable][difference]; }
    static response_t continuity(int difference) { return kAswContinuity[kTable][difference]; }
    static response_t proximity(int distance) { return kAswProximity[kTable][distance]; }
};

inline response_t asw_combine(int a, int b) {
#pragma HLS INLINE
    return static_cast<response_t>(asw::combine(a, b));
}

// floor(((num << shift) + floor(den / 2)) / den) by a restoring division of fx::kAggBits rows:
// the quotient of a weighted mean is below 2^kAggBits (docs/asw.md, "Bit widths"). A zero
// denominator (no pixel) gives all ones, as the RTL's divider.
inline agg_t asw_mean(asw_num_t num, asw_den_t den, int shift) {
#pragma HLS INLINE
    constexpr int kBits = fx::kAggBits;
    const std::uint64_t dividend = (std::uint64_t{num} << shift) + (den >> 1);
    std::uint64_t partial = dividend >> kBits;
    agg_t quotient = 0;
    for (int i = kBits - 1; i >= 0; --i) {
        partial = (partial << 1) | ((dividend >> i) & 1U);
        if (partial >= den) {
            partial -= den;
            quotient = static_cast<agg_t>(quotient | (1U << i));
        }
    }
    return quotient;
}

// One image's pixel as the column stack keeps it: RGB (weights) and the code the cost compares
// (the census code, or the RGB pixel again for the AD cost).
struct AswPixel {
    Rgb rgb;
    Rgb code;
};

struct AswSample {
    AswPixel left;
    AswPixel right;
};

// One image's word of one column (rtl/stereo_asw_column.sv's out_left / out_right).
template <int DIAMETER>
struct AswWord {
    Rgb code[DIAMETER] = {};         // row yc - r + j's code
    response_t vert[DIAMETER] = {};  // row j against the centre (left: with the proximity)
    response_t near[DIAMETER] = {};  // offset i - r of pixel x - r - 1 (pass 1)
    response_t far[DIAMETER] = {};   // the same of pixel x - 2r - 2 (pass 2)
};

// The census codes of both images with their RGB pixels alongside (rtl/stereo_census.sv with the
// RGB through): census_transform, and the RGB of its window centre, row y - 2 of a two-row line
// buffer delayed two steps. Latency 2 W + 3, as census_transform.
template <int WIDTH>
class asw_census : public coord_output {
    static constexpr int kRadius = fx::kCensusRadius;

  public:
    void reset() {
        census_.reset();
        coord_output::reset();
    }

    const AswSample& out() const { return out_; }

    void step(coord_t in_x, coord_t in_y, const Rgb& left, const Rgb& right, int width,
              int height) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = delay_ complete dim = 0
        // This step's centre is 2 W + 2 pixels back: row y - 2 at column x, two steps ago.
        const Rgb leaving[2] = {delay_[kRadius - 1][0], delay_[kRadius - 1][1]};
        for (int i = kRadius - 1; i > 0; --i) {
            delay_[i][0] = delay_[i - 1][0];
            delay_[i][1] = delay_[i - 1][1];
        }
        delay_[0][0] = rows_.above(kRadius - 1)[0];
        delay_[0][1] = rows_.above(kRadius - 1)[1];
        const Rgb incoming[2] = {left, right};
        rows_.step(in_x, width, incoming);
        census_.step(in_x, in_y, left, right, width, height);
        out_.left = {leaving[0], census_.out_left()};
        out_.right = {leaving[1], census_.out_right()};
        out_x_ = census_.out_x();
        out_y_ = census_.out_y();
    }

  private:
    census_transform<WIDTH> census_;
    line_buffer<WIDTH, Rgb, kRadius, 2> rows_;  // {left, right} RGB of rows y-1, y-2
    Rgb delay_[kRadius][2] = {};                // row y - 2's pixels of the last steps
    AswSample out_;
};

// The column stack and the words (rtl/stereo_asw_column.sv). Output: (x, yc = y - r), "no
// pixel" while yc < 0, and both images' words, registered (the RTL's column is combinational and
// the cost stage registers its words: here the column has the register, latency r W + 1).
template <int WIDTH, int DIAMETER>
class asw_column : public coord_output {
    static constexpr int R = DIAMETER / 2;
    static constexpr int kNear = R + 1;         // pass 1's pixel x - kNear
    static constexpr int kHistory = 2 * R + 1;  // centre-row pixels x - 1 .. x - kHistory
    using Tables = asw_responses<DIAMETER>;

  public:
    using Word = AswWord<DIAMETER>;

    const Word& out_left() const { return out_word_[0]; }
    const Word& out_right() const { return out_word_[1]; }

    void step(coord_t in_x, coord_t in_y, const AswSample& in, int width) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = centre_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = near_history_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = out_word_ complete dim = 0
        // Slot j: row yc - r + j of column x (slot 2r the incoming row).
        AswSample column[DIAMETER];
#pragma HLS ARRAY_PARTITION variable = column complete
        for (int j = 0; j < 2 * R; ++j) {
            column[j] = rows_.above(2 * R - 1 - j)[0];
        }
        column[2 * R] = in;
        response_t near_now[2][DIAMETER] = {};
#pragma HLS ARRAY_PARTITION variable = near_now complete dim = 0
        for (int side = 0; side < 2; ++side) {
            const auto pixel = [&](int j) -> const AswPixel& {
                return side == 0 ? column[j].left : column[j].right;
            };
            const Rgb& centre = pixel(R).rgb;
            Word& word = out_word_[side];
            for (int j = 0; j < DIAMETER; ++j) {
                const int distance = j >= R ? j - R : R - j;
                const response_t colour =
                    Tables::colour(ad_measure::distance(pixel(j).rgb, centre));
                word.code[j] = pixel(j).code;
                word.vert[j] =
                    side == 0 ? asw_combine(Tables::proximity(distance), colour) : colour;
            }
            // Pass 1's pixel x - kNear and its neighbour x - kNear + (i - r), from the history.
            for (int i = 0; i < DIAMETER; ++i) {
                const int distance = i >= R ? i - R : R - i;
                const response_t colour = Tables::colour(ad_measure::distance(
                    centre_[side][kNear - 1 - (i - R)], centre_[side][kNear - 1]));
                near_now[side][i] =
                    side == 0 ? asw_combine(Tables::proximity(distance), colour) : colour;
                word.near[i] = near_now[side][i];
                word.far[i] = near_history_[side][kNear - 1][i];
            }
        }
        out_x_ = in_x;
        out_y_ = in_y < R ? kNoPixel : to_coord(in_y - R);

        for (int side = 0; side < 2; ++side) {
            for (int p = kHistory - 1; p > 0; --p) {
                centre_[side][p] = centre_[side][p - 1];
            }
            centre_[side][0] = side == 0 ? column[R].left.rgb : column[R].right.rgb;
            for (int p = kNear - 1; p > 0; --p) {
                for (int i = 0; i < DIAMETER; ++i) {
                    near_history_[side][p][i] = near_history_[side][p - 1][i];
                }
            }
            for (int i = 0; i < DIAMETER; ++i) {
                near_history_[side][0][i] = near_now[side][i];
            }
        }
        const AswSample incoming[1] = {in};
        rows_.step(in_x, width, incoming);
    }

  private:
    line_buffer<WIDTH, AswSample, 2 * R, 1> rows_;      // rows y-1 .. y-2r of both images
    Rgb centre_[2][kHistory] = {};                      // [side][p-1]: centre row, column x - p
    response_t near_history_[2][kNear][DIAMETER] = {};  // near words of the last kNear steps
    Word out_word_[2];
};

// The cost stage's delay lines carrying the words (rtl/stereo_cost.sv with RAW_BITS; hls
// cost.hpp): lane k gets the right word of column x - m - k, the left word waits
// K = max(0, -m) steps with its coordinates. Latency 1 + K.
template <int NDISP, int MAX_MIN_DISP, int DIAMETER>
class asw_cost : public coord_output {
  public:
    using Word = AswWord<DIAMETER>;
    using Lanes = Word[NDISP];

    asw_cost() { reset(); }

    void reset() {
        coord_output::reset();
        delays_.reset();
    }

    const Word& out_left() const { return out_left_; }
    const Lanes& out_right() const { return out_right_; }

    void step(coord_t in_x, coord_t in_y, const Word& left, const Word& right, int min_disp) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = out_right_ complete
        const auto aligned = delays_.align(in_x, in_y, left, right, min_disp);
        out_left_ = aligned.left;
        out_x_ = aligned.x;
        out_y_ = aligned.y;
        for (int k = 0; k < NDISP; ++k) {
            out_right_[k] = delays_.lane(aligned, k);
        }
        delays_.advance(aligned, in_x, in_y, left, right);
    }

  private:
    label_delays<Word, NDISP, MAX_MIN_DISP> delays_;
    Word out_left_;
    Lanes out_right_ = {};
};

// The two-pass separable aggregation, every label at once (rtl/stereo_asw_aggregate.sv with
// LANES = NDISP, before it was pipelined in whole steps: the RTL's vertical sums wait
// fx_pkg::ASW_VERTICAL_STEPS steps, its divisions take fx_pkg::ASW_DIVIDE_STEPS and pass 1's
// winner fx_pkg::ASW_WINNER_STEPS more, so its passes sit further back, stage_table.hpp
// asw_near_steps and asw_far_steps; here those registers are the HLS tool's retiming). Input: (x,
// yc) with the left word and the right words of the lanes. Output: pass 2's means of (x2, yc), x2 =
// x - 2r - 2 (following the stream across row ends), through the output register: latency 2r + 3.
// MEASURE compares two codes (ad_measure or census_measure).
template <int NDISP, int DIAMETER, class MEASURE>
class asw_aggregate : public lane_output<agg_t, NDISP> {
    static_assert(NDISP >= 1 && NDISP <= fx::kMaxDisparities);
    static constexpr int R = DIAMETER / 2;
    static constexpr int kNear = R + 1;         // x1 = x - kNear
    static constexpr int kFar = 2 * R + 2;      // x2 = x - kFar
    static constexpr int kHistory = 3 * R + 2;  // means of columns x - 1 .. x - kHistory
    static constexpr int kLabels = 2 * R + 1;   // pass 1's labels of x1 - 1 .. x1 - kLabels
    using Tables = asw_responses<DIAMETER>;
    using lane_output<agg_t, NDISP>::out_data_;
    using lane_output<agg_t, NDISP>::out_x_;
    using lane_output<agg_t, NDISP>::out_y_;

  public:
    using Word = AswWord<DIAMETER>;
    using Lanes = Word[NDISP];

    // The positions' coordinates and the output's to "no pixel".
    void reset() {
        lane_output<agg_t, NDISP>::reset();
        for (int p = 0; p < kFar; ++p) {
            xs_[p] = 0;
            ys_[p] = kNoPixel;
        }
    }

    // truncation: the cost's cap before the aggregation (0: none; asw::truncation_for).
    void step(coord_t in_x, coord_t in_y, const Word& left, const Lanes& right, int width,
              int height, int ndisp, int min_disp, int truncation) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = xs_ complete
#pragma HLS ARRAY_PARTITION variable = ys_ complete
#pragma HLS ARRAY_PARTITION variable = means_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = labels_ complete
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        const auto in_range = [](int v, int size) { return v >= 0 && v < size; };

        // ---- the vertical pass of column x --------------------------------------------------
        agg_t vertical[NDISP];
#pragma HLS ARRAY_PARTITION variable = vertical complete
        bool row_inside[DIAMETER];
#pragma HLS ARRAY_PARTITION variable = row_inside complete
        for (int j = 0; j < DIAMETER; ++j) {
            row_inside[j] = in_range(in_y - R + j, height);
        }
        for (int k = 0; k < NDISP; ++k) {
            const bool outside = !in_range(in_x - min_disp - k, width);
            asw_num_t num = 0;
            asw_den_t den = 0;
            for (int j = 0; j < DIAMETER; ++j) {
                const int right_factor = outside ? asw::kResponseMax : right[k].vert[j];
                const int weight = row_inside[j] ? asw_combine(left.vert[j], right_factor) : 0;
                int cost =
                    outside ? fx::kCostOutside : MEASURE::distance(left.code[j], right[k].code[j]);
                if (truncation > 0 && cost > truncation) {
                    cost = truncation;
                }
                num += static_cast<asw_num_t>(weight * cost);
                den = static_cast<asw_den_t>(den + weight);
            }
            vertical[k] = asw_mean(num, den, asw::kOutputFracBits);
        }

        // ---- pass 1 at x1 and its winner ------------------------------------------------------
        const int x1 = xs_[kNear - 1];
        agg_t pass1[NDISP];
#pragma HLS ARRAY_PARTITION variable = pass1 complete
        horizontal(x1, kNear, left.near, right, width, min_disp, false, pass1);
        // Costs with one bit more: labels >= ndisp count 2^kAggBits, above every cell.
        int best_cost = 1 << fx::kAggBits;
        int best_label = 0;
        for (int k = 0; k < NDISP; ++k) {
            if (k < ndisp && pass1[k] < best_cost) {
                best_cost = pass1[k];
                best_label = k;
            }
        }

        // ---- pass 2 at x2 with the continuity of pass 1's labels ----------------------------
        response_t far_left[DIAMETER];
#pragma HLS ARRAY_PARTITION variable = far_left complete
        for (int i = 0; i < DIAMETER; ++i) {
            const int own = labels_[kNear - 1];
            const int other = labels_[kNear - 1 - (i - R)];
            const int step = own >= other ? own - other : other - own;
            far_left[i] = asw_combine(left.far[i], Tables::continuity(step));
        }
        horizontal(xs_[kFar - 1], kFar, far_left, right, width, min_disp, true, out_data_);
        out_x_ = xs_[kFar - 1];
        out_y_ = ys_[kFar - 1];

        // ---- the histories move on ----------------------------------------------------------
        for (int p = kHistory - 1; p > 0; --p) {
            for (int k = 0; k < NDISP; ++k) {
                means_[p][k] = means_[p - 1][k];
            }
        }
        for (int k = 0; k < NDISP; ++k) {
            means_[0][k] = vertical[k];
        }
        for (int p = kLabels - 1; p > 0; --p) {
            labels_[p] = labels_[p - 1];
        }
        labels_[0] = static_cast<disparity_t>(best_label);
        for (int p = kFar - 1; p > 0; --p) {
            xs_[p] = xs_[p - 1];
            ys_[p] = ys_[p - 1];
        }
        xs_[0] = in_x;
        ys_[0] = in_y;
    }

  private:
    // A horizontal pass at pixel `centre`, `back` steps behind the input (its column
    // centre + dx is back - dx steps back in the ring): the left factors of the pixel (pass 2's
    // with the continuity), the right ones from each lane's word (near or far), 255 where the
    // right pixel or its neighbour lies outside the right image; kAswNoCandidate where the
    // label's match lies outside.
    void horizontal(int centre, int back, const response_t (&left)[DIAMETER], const Lanes& right,
                    int width, int min_disp, bool far, agg_t (&out)[NDISP]) const {
#pragma HLS INLINE
        const auto in_range = [](int v, int size) { return v >= 0 && v < size; };
        bool column_inside[DIAMETER];
#pragma HLS ARRAY_PARTITION variable = column_inside complete
        for (int i = 0; i < DIAMETER; ++i) {
            column_inside[i] = in_range(centre + i - R, width);
        }
        for (int k = 0; k < NDISP; ++k) {
            const int right_x = centre - min_disp - k;
            const bool outside = !in_range(right_x, width);
            asw_num_t num = 0;
            asw_den_t den = 0;
            for (int i = 0; i < DIAMETER; ++i) {
                const int right_factor = outside || !in_range(right_x + i - R, width)
                                             ? asw::kResponseMax
                                             : (far ? right[k].far[i] : right[k].near[i]);
                const int weight = column_inside[i] ? asw_combine(left[i], right_factor) : 0;
                num += static_cast<asw_num_t>(weight) * means_[back - (i - R) - 1][k];
                den = static_cast<asw_den_t>(den + weight);
            }
            out[k] = outside ? kAswNoCandidate : asw_mean(num, den, 0);
        }
    }

    coord_t xs_[kFar] = {};  // xs_[p - 1]: the input's x p steps ago
    coord_t ys_[kFar] = {};
    agg_t means_[kHistory][NDISP] = {};  // means_[p - 1][k]: the vertical mean of column x - p
    disparity_t labels_[kLabels] = {};   // labels_[p - 1]: pass 1's label of x1 - p
};

// The census stage of an AD core: nothing.
struct no_asw_census {
    void reset() {}
};

// Runtime configuration of one frame (the RTL's cfg_* ports the ASW core reads).
struct AswConfig {
    int width = 0;       // 1 .. WIDTH
    int height = 0;      // 1 .. HEIGHT
    int ndisp = 1;       // labels 0 .. ndisp - 1, 1 .. NDISP
    int min_disp = 0;    // d = min_disp + label, |min_disp| <= MAX_MIN_DISP
    int truncation = 0;  // the cost's cap, 0: none (asw::truncation_for)
    bool uniqueness = false;
    int uniqueness_ratio = 0;
    bool left_right = false;
    int lr_tolerance = 0;
    bool subpixel = false;
};

// Pixel steps from a pixel entering the core to its result in the output register: the census
// stage 2 W + 3 (census only), the column stack r W + 1, the cost stage 1 + K, the aggregation
// 2 r + 3, WTA 1, validate 1, lr_check NDISP.
template <int NDISP, int DIAMETER, class MEASURE>
constexpr int asw_pipeline_delay(int width, int min_disp = 0) {
    constexpr int R = DIAMETER / 2;
    const int census = kIsCensus<MEASURE> ? 2 * width + 3 : 0;
    const int wait = min_disp < 0 ? -min_disp : 0;
    return census + (R * width + 1) + (1 + wait) + (2 * R + 3) + 1 + 1 + NDISP;
}

template <int NDISP, int DIAMETER, class MEASURE>
constexpr int asw_frame_steps(int width, int height, int min_disp = 0) {
    return width * height + asw_pipeline_delay<NDISP, DIAMETER, MEASURE>(width, min_disp) - 1;
}

// The stages of stereo_top ASW = 1. Large (the column stack is WIDTH columns of DIAMETER - 1
// rows): a static object in a synthesis top, a heap object in C-simulation hosts. MEASURE:
// ad_measure (RGB codes) or census_measure (the census stage in front).
template <int WIDTH, int HEIGHT, int NDISP, int DIAMETER, int MAX_MIN_DISP, class MEASURE>
class asw_pipeline : public winner_stages<NDISP> {
    static_assert(WIDTH >= 1 && WIDTH <= kMaxFrameSide && HEIGHT >= 1 && HEIGHT <= kMaxFrameSide);
    static_assert(std::is_same_v<MEASURE, ad_measure> || kIsCensus<MEASURE>,
                  "the ASW core compares AD or census codes");

  public:
    void reset() {
        winner_stages<NDISP>::reset();
        reset_stages(census_, column_, cost_, aggregate_);
    }

    // One pixel step of every stage, the last first (each reads its upstream register as it was
    // before this step).
    void step(coord_t x, coord_t y, const Rgb& left, const Rgb& right, const AswConfig& cfg) {
#pragma HLS INLINE
        this->step_winner(aggregate_.out_x(), aggregate_.out_y(), aggregate_.out_data(), cfg, 0,
                          false);
        aggregate_.step(cost_.out_x(), cost_.out_y(), cost_.out_left(), cost_.out_right(),
                        cfg.width, cfg.height, cfg.ndisp, cfg.min_disp, cfg.truncation);
        cost_.step(column_.out_x(), column_.out_y(), column_.out_left(), column_.out_right(),
                   cfg.min_disp);
        if constexpr (kIsCensus<MEASURE>) {
            column_.step(census_.out_x(), census_.out_y(), census_.out(), cfg.width);
            census_.step(x, y, left, right, cfg.width, cfg.height);
        } else {
            column_.step(x, y, AswSample{{left, left}, {right, right}}, cfg.width);
        }
    }

  private:
    std::conditional_t<kIsCensus<MEASURE>, asw_census<WIDTH>, no_asw_census> census_;
    asw_column<WIDTH, DIAMETER> column_;
    asw_cost<NDISP, MAX_MIN_DISP, DIAMETER> cost_;
    asw_aggregate<NDISP, DIAMETER, MEASURE> aggregate_;
};

// The configuration as the stages use it (sanitise_common, and the truncation to the cost's
// range), with kStatusConfigClamped set when anything was clamped.
template <int WIDTH, int HEIGHT, int NDISP, int MAX_MIN_DISP>
AswConfig sanitise_asw(const AswConfig& requested, status_t& status) {
#pragma HLS INLINE
    AswConfig cfg = requested;
    sanitise_common<WIDTH, HEIGHT, NDISP, MAX_MIN_DISP>(cfg, status);
    clamp_config(cfg.truncation, 0, fx::kCostMax, status);
    return cfg;
}

// One frame through the ASW core: cfg.width * cfg.height beats from `in`, as many to `out`, in
// raster order (stereo_hls_top's framing and flush). Returns the status bits.
template <int WIDTH, int HEIGHT, int NDISP, int DIAMETER, int MAX_MIN_DISP, class MEASURE>
status_t stereo_hls_asw_top(
    stream<InputBeat>& in, stream<OutputBeat>& out, const AswConfig& requested,
    asw_pipeline<WIDTH, HEIGHT, NDISP, DIAMETER, MAX_MIN_DISP, MEASURE>& state) {
#pragma HLS INLINE
    constexpr int kMaxSteps =
        asw_frame_steps<NDISP, DIAMETER, MEASURE>(WIDTH, HEIGHT, -MAX_MIN_DISP);
    status_t status = 0;
    const AswConfig cfg = sanitise_asw<WIDTH, HEIGHT, NDISP, MAX_MIN_DISP>(requested, status);
    state.reset();
    const int steps =
        asw_frame_steps<NDISP, DIAMETER, MEASURE>(cfg.width, cfg.height, cfg.min_disp);
    stream_frame<kMaxSteps>(in, out, cfg, state, steps, status);
    return status;
}

}  // namespace stereo::hls
