// line_buffer: the ROWS previous rows of a stream at the column being stepped
// (RTL: rtl/stereo_line_buffer.sv).
//
// One memory word per column holds that column of the last ROWS rows, all LANES values of each.
// At the step of column x, above(k) is row y-1-k at column x, and the word stored back at x is
// {this step's input, above(0), ..., above(ROWS-2)}: the oldest row drops out. The memory is
// read one step ahead (the next column, or column 0 after the row's last) into the `above_`
// register, so one read and one write per step on different addresses: a simple dual-port
// block RAM at II=1. Rows above the frame hold stale data (previous frame, flush, priming): the
// stages mask them by coordinates, so the memory is never cleared.
#pragma once

#include "stereo/hls/types.hpp"

namespace stereo::hls {

template <int WIDTH, typename T, int ROWS, int LANES>
class line_buffer {
    static_assert(WIDTH >= 1 && WIDTH <= kMaxFrameSide);
    static_assert(ROWS >= 1 && LANES >= 1);

  public:
    using Lanes = T[LANES];

    // Row y-1-k at the column of the coming step (registered: read at the previous step).
    const Lanes& above(int k) const { return above_[k]; }

    // One pixel step at column in_x (0 .. width-1) of a width-wide frame.
    void step(coord_t in_x, int width, const Lanes& in) {
#pragma HLS INLINE
#pragma HLS BIND_STORAGE variable = memory_ type = ram_2p impl = bram
#pragma HLS ARRAY_PARTITION variable = memory_ complete dim = 2
#pragma HLS ARRAY_PARTITION variable = memory_ complete dim = 3
#pragma HLS ARRAY_PARTITION variable = above_ complete dim = 0
// The word written at column x is read back W steps later; the read of this step is always at
// another column (width > 1), so no dependence between neighbouring steps.
#pragma HLS DEPENDENCE variable = memory_ inter false
        T stored[ROWS][LANES];
#pragma HLS ARRAY_PARTITION variable = stored complete dim = 0
        for (int d = 0; d < LANES; ++d) {
            stored[0][d] = in[d];
        }
        for (int k = 1; k < ROWS; ++k) {
            for (int d = 0; d < LANES; ++d) {
                stored[k][d] = above_[k - 1][d];
            }
        }
        const int write_x = in_x;
        const int read_x = in_x + 1 >= width ? 0 : in_x + 1;
        // At width 1 the next column is the one being written: pass the word straight through.
        for (int k = 0; k < ROWS; ++k) {
            for (int d = 0; d < LANES; ++d) {
                above_[k][d] = width == 1 ? stored[k][d] : memory_[read_x][k][d];
            }
        }
        for (int k = 0; k < ROWS; ++k) {
            for (int d = 0; d < LANES; ++d) {
                memory_[write_x][k][d] = stored[k][d];
            }
        }
    }

  private:
    T memory_[WIDTH][ROWS][LANES] = {};
    T above_[ROWS][LANES] = {};
};

}  // namespace stereo::hls
