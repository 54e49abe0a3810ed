// window3x3: the 3x3 neighbourhood of every disparity plane, for the CA rules
// (RTL: rtl/stereo_window3x3.sv).
//
// A two-row line buffer and two column registers hold, at the step of input pixel (x, y), the
// window centred on (x-1, y-1) (wrapping to the previous row at x = 0). Slot (dy+1)*3 + (dx+1)
// holds position (dx, dy); in_frame says whether that position lies in the frame, because the
// rules must read positions outside it as zero padding (the registers hold stale data there).
#pragma once

#include "stereo/hls/line_buffer.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int WIDTH, typename T, int NDISP>
class window3x3 {
  public:
    using Lanes = T[NDISP];
    static constexpr int kCentre = 4;  // slot of (0, 0)

    // The window seen at the step of input (in_x, in_y): its centre, the values of its nine
    // positions and whether each lies in the frame. Combinational; changes nothing.
    void look(coord_t in_x, coord_t in_y, const Lanes& in, int width, int height, coord_t& centre_x,
              coord_t& centre_y, T (&value)[9][NDISP], bool (&in_frame)[9]) const {
#pragma HLS INLINE
#pragma HLS ARRAY_PARTITION variable = column_1_ complete dim = 0
#pragma HLS ARRAY_PARTITION variable = column_2_ complete dim = 0
        int cx = in_x - 1;
        int cy = in_y - 1;
        if (cx < 0) {
            cx += width;
            cy -= 1;
        }
        centre_x = to_coord(cx);
        centre_y = to_coord(cy);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int slot = (dy + 1) * 3 + (dx + 1);
                in_frame[slot] = inside(cx + dx, cy + dy, width, height);
                for (int d = 0; d < NDISP; ++d) {
                    value[slot][d] = dx < 0    ? column_2_[dy + 1][d]
                                     : dx == 0 ? column_1_[dy + 1][d]
                                               : newest(dy + 1, in)[d];
                }
            }
        }
    }

    void step(coord_t in_x, int width, const Lanes& in) {
#pragma HLS INLINE
        for (int row = 0; row < 3; ++row) {
            for (int d = 0; d < NDISP; ++d) {
                column_2_[row][d] = column_1_[row][d];
                column_1_[row][d] = newest(row, in)[d];
            }
        }
        rows_.step(in_x, width, in);
    }

  private:
    // The incoming column, rows y-2 (row 0) .. y (row 2).
    const Lanes& newest(int row, const Lanes& in) const {
        return row == 2 ? in : rows_.above(1 - row);
    }

    line_buffer<WIDTH, T, 2, NDISP> rows_;
    T column_1_[3][NDISP] = {};  // the column one step ago, row 0 = top
    T column_2_[3][NDISP] = {};  // two steps ago
};

}  // namespace stereo::hls
