// stereo_downscale: one level of the hierarchical search's pyramid (docs/hierarchical.md,
// "Down-scaling"): the area mean of every FACTOR x FACTOR block of a pixel stream, each channel
// rounded half up, (sum + FACTOR^2/2) / FACTOR^2, bit-exact with
// stereo::hierarchical::downscale_area. A frame of cfg_width x cfg_height gives
// floor(cfg_width/FACTOR) x floor(cfg_height/FACTOR) blocks; the pixels past the last whole block
// of a row or a column are dropped, as the model drops them.
//
// One input pixel per step (ce). Along a row, a register sums the block's FACTOR pixels; at the
// block's last column that row sum is added into the column sum of the block, one RAM word per
// block column (WIDTH / FACTOR words of CHANNELS sums). At the block's last row the sum is
// complete and the mean leaves on out_pixel, with out_valid high for one clock and the block's
// coordinates. The RAM word of a block is read at the block's first column (registered read:
// block RAM), so it is ready at its last column, where it is written: one read and one write per
// FACTOR steps, never at the same step. The first row of a block overwrites the word, so nothing
// from an earlier frame or an abandoned one (reset) is ever added. Reset clears out_valid only.
`default_nettype none
`include "stereo_assert.svh"

module stereo_downscale #(
    parameter int WIDTH    = 64,  // longest input row
    parameter int FACTOR   = 2,   // 2 or 4 (a power of two)
    parameter int CHANNELS = 3    // 8-bit channels per pixel
) (
    input  wire logic                    clk,
    input  wire logic                    rst,         // clears out_valid
    input  wire logic                    ce,          // one input pixel
    input  wire fx_pkg::coord_t          in_x,        // its column, 0 .. cfg_width-1
    input  wire fx_pkg::coord_t          in_y,        // its row, 0 .. cfg_height-1
    input  wire fx_pkg::cfg_size_t       cfg_width,
    input  wire fx_pkg::cfg_size_t       cfg_height,
    input  wire logic [CHANNELS*8-1:0]   in_pixel,    // channel c at [c*8 +: 8]
    output      logic                    out_valid,   // one clock: a block completed
    output      fx_pkg::coord_t          out_x,       // the block's column, in_x / FACTOR
    output      fx_pkg::coord_t          out_y,       // the block's row, in_y / FACTOR
    output      logic [CHANNELS*8-1:0]   out_pixel    // the block's mean
);
  localparam int SHIFT = $clog2(FACTOR);
  localparam int BLOCKS = (WIDTH / FACTOR > 0) ? WIDTH / FACTOR : 1;
  localparam int ADDR_BITS = (BLOCKS > 1) ? $clog2(BLOCKS) : 1;
  localparam int ROW_BITS = 8 + SHIFT;  // one channel's sum over a block row
  localparam int SUM_BITS = 8 + 2 * SHIFT;  // ... over the whole block

  `STEREO_ASSERT(factor_power_of_two, FACTOR >= 2 && (1 << SHIFT) == FACTOR,
                 "FACTOR must be a power of two, at least 2")
  `STEREO_ASSERT(width_holds_a_block, WIDTH >= FACTOR, "WIDTH must hold at least one block")

  // Where the pixel lies in its block, and whether the block is a whole one of the frame.
  logic [SHIFT-1:0] phase_x, phase_y;
  logic first_column, last_column, last_row, whole_block;
  logic [15:0] block_x, block_y;
  assign phase_x = in_x[SHIFT-1:0];
  assign phase_y = in_y[SHIFT-1:0];
  assign first_column = phase_x == '0;
  assign last_column = phase_x == SHIFT'(FACTOR - 1);
  assign last_row = phase_y == SHIFT'(FACTOR - 1);
  assign block_x = 16'(in_x >>> SHIFT);
  assign block_y = 16'(in_y >>> SHIFT);
  assign whole_block = !in_x[15] && !in_y[15] && block_x < (cfg_width >> SHIFT) &&
                       block_y < (cfg_height >> SHIFT);

  // The row sum of the block so far (this pixel excluded), and with this pixel.
  logic [CHANNELS*ROW_BITS-1:0] row_sum_q, row_sum;
  always_comb begin
    for (int c = 0; c < CHANNELS; c++) begin
      row_sum[c*ROW_BITS+:ROW_BITS] =
          (first_column ? '0 : row_sum_q[c*ROW_BITS+:ROW_BITS]) + ROW_BITS'(in_pixel[c*8+:8]);
    end
  end

  // The block columns' sums over the rows so far.
  logic [CHANNELS*SUM_BITS-1:0] column_sums[BLOCKS];
  logic [CHANNELS*SUM_BITS-1:0] column_sum_q;  // the RAM's output register
  logic [CHANNELS*SUM_BITS-1:0] column_sum;  // with this block row added
  logic [ADDR_BITS-1:0] address;
  assign address = ADDR_BITS'(block_x);
  always_comb begin
    for (int c = 0; c < CHANNELS; c++) begin
      column_sum[c*SUM_BITS+:SUM_BITS] =
          (phase_y == '0 ? '0 : column_sum_q[c*SUM_BITS+:SUM_BITS]) +
          SUM_BITS'(row_sum[c*ROW_BITS+:ROW_BITS]);
    end
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      row_sum_q <= row_sum;
      if (first_column && whole_block) column_sum_q <= column_sums[address];
      if (last_column && whole_block) column_sums[address] <= column_sum;
    end
  end

  // The mean of a completed block, rounded half up.
  always_ff @(posedge clk) begin
    out_valid <= !rst && ce && whole_block && last_column && last_row;
    if (ce && whole_block && last_column && last_row) begin
      out_x <= $signed(block_x);
      out_y <= $signed(block_y);
      for (int c = 0; c < CHANNELS; c++) begin
        out_pixel[c*8+:8] <= 8'((column_sum[c*SUM_BITS+:SUM_BITS] +
                                 SUM_BITS'(FACTOR * FACTOR / 2)) >> (2 * SHIFT));
      end
    end
  end
endmodule

`default_nettype wire
