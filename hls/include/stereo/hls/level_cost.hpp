// level_cost: stage 1 of a hierarchical level, the census costs of a pixel's COLS x ROWS 2-D
// candidates, one pixel per step (model: stereo::cost_plane over a CandidateGrid with the census
// cost, docs/hierarchical.md "The levels in hardware"; RTL: rtl/stereo_level_cost.sv).
//
// For the pixel (x, y) and its base (bd, bv), candidate (i, j), label k = j * COLS + i, costs
//   popcount(L(x, y) ^ R(x - bd - i, y + bv + j)) * fx::kCensusWeight   (census_measure)
// or fx::kCostOutside where that right pixel lies outside the frame on any side (a 2-D candidate
// can leave it above and below too, not only on the left as in the 1-D cost stage).
//
// Memory: the census codes of the last SLOTS = V_MAX - V_MIN + 2 rows of both images, row r in
// slot r mod SLOTS. (The RTL splits each right row into power-of-two banks by column so that the
// COLS neighbouring columns come out of one-port memories in one read; here the cyclic partition
// pragma asks the tool for the same.) SLOTS is one more than the rows a step reads, so the row
// being written is never one being read.
//
// Timing, as the RTL: the codes of (in_x, in_y) (census_transform's output: raster order, then
// flush rows below the frame) are written at their step. The pixel requested at a step,
// (req_x, req_y) = (the previous step's in_x, its in_y - V_MAX), is the one whose last right pixel
// (x, y + V_MAX) arrived at the step before; the caller gives its base with that step. The step
// reads the codes and the outside flags of its candidates into registers; the next computes the
// costs into the output register. Latency: 2 pixel steps after (x, y + V_MAX) arrived.
// Nothing is cleared between frames: a row is written before any real pixel reads it.
#pragma once

#include "stereo/hls/census.hpp"
#include "stereo/hls/stage_output.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int WIDTH, int COLS, int ROWS, int V_MIN, int V_MAX>
class level_cost : public lane_output<cost_t, COLS * ROWS> {
    static constexpr int kLabels = COLS * ROWS;
    static constexpr int kSlots = V_MAX - V_MIN + 2;
    static_assert(WIDTH >= 1 && WIDTH <= kMaxFrameSide);
    static_assert(COLS >= 1 && ROWS >= 1 && ROWS <= V_MAX - V_MIN + 1);
    static_assert(V_MIN <= -1 && V_MAX >= 0 && V_MAX - V_MIN <= 126,
                  "the vertical offsets V_MIN .. V_MAX contain -1 and 0 and fit a byte");
    static_assert(kLabels <= fx::kMaxDisparities);
    using lane_output<cost_t, kLabels>::out_data_;
    using lane_output<cost_t, kLabels>::out_x_;
    using lane_output<cost_t, kLabels>::out_y_;

  public:
    // Clears the coordinates only ("no pixel"), like the RTL's reset; codes stay.
    void reset() {
        previous_x_ = 0;
        previous_y_ = kNoPixel;
        read_x_ = 0;
        read_y_ = kNoPixel;
        lane_output<cost_t, kLabels>::reset();
    }

    // The pixel whose costs the coming step reads (combinational from the registers): its base
    // is the caller's in_base_d / in_base_v of that step.
    coord_t req_x() const { return previous_x_; }
    coord_t req_y() const {
        return previous_y_ == kNoPixel ? kNoPixel : to_coord(previous_y_ - V_MAX);
    }

    // One pixel step: the census codes of (in_x, in_y), and the base (>= 0, any sign) of the
    // requested pixel (req_x(), req_y()).
    void step(coord_t in_x, coord_t in_y, const Rgb& left_code, const Rgb& right_code, int width,
              int height, int in_base_d, int in_base_v) {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = right_ complete dim = 1
#pragma HLS ARRAY_PARTITION variable = right_ cyclic factor = COLS dim = 2
#pragma HLS ARRAY_PARTITION variable = read_right_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = read_outside_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = out_data_ complete
        // ---- the costs of the pixel read at the step before ----------------------------------
        for (int j = 0; j < ROWS; ++j) {
            for (int i = 0; i < COLS; ++i) {
                out_data_[j * COLS + i] =
                    read_outside_[j][i] ? static_cast<cost_t>(fx::kCostOutside)
                                        : census_measure::distance(read_left_, read_right_[j][i]);
            }
        }
        out_x_ = read_x_;
        out_y_ = read_y_;

        // ---- the requested pixel's codes, before this step's write ---------------------------
        const int x = req_x();
        const int y = req_y();
        const bool real = y != kNoPixel;
        const int pixel_slot = slot_of(real ? y : 0);
        read_left_ = left_[pixel_slot][column_index(x)];
        for (int j = 0; j < ROWS; ++j) {
            const int row = y + in_base_v + j;
            const bool row_outside = !real || row < 0 || row >= height;
            for (int i = 0; i < COLS; ++i) {
                const int column = x - in_base_d - i;
                read_outside_[j][i] = row_outside || column < 0 || column >= width;
                read_right_[j][i] = right_[slot_of(real ? row : 0)][column_index(column)];
            }
        }
        read_x_ = req_x();
        read_y_ = req_y();

        // ---- this step's codes ---------------------------------------------------------------
        if (in_y != kNoPixel && inside(in_x, in_y, width, height)) {
            left_[slot_of(in_y)][in_x] = left_code;
            right_[slot_of(in_y)][in_x] = right_code;
        }
        previous_x_ = in_x;
        previous_y_ = in_y;
    }

  private:
    // The slot of a row: its residue mod kSlots (the RTL adds a bias instead of a signed mod).
    static int slot_of(int row) {
        const int residue = row % kSlots;
        return residue < 0 ? residue + kSlots : residue;
    }
    // A column outside the memory reads column 0: its candidate is outside, its code unused.
    static int column_index(int column) {
        return column >= 0 && column < WIDTH ? column : 0;
    }

    Rgb left_[kSlots][WIDTH] = {};   // census codes of the left rows (only the pixel's row read)
    Rgb right_[kSlots][WIDTH] = {};  // census codes of the right rows
    coord_t previous_x_ = 0;         // the previous step's input
    coord_t previous_y_ = kNoPixel;
    Rgb read_left_;  // the registers of the read: the requested pixel and its candidates
    Rgb read_right_[ROWS][COLS] = {};
    bool read_outside_[ROWS][COLS] = {};
    coord_t read_x_ = 0;
    coord_t read_y_ = kNoPixel;
};

}  // namespace stereo::hls
