// stereo_census: the census transform of both images (model: stereo::census::transform,
// docs/fixed-point.md "Census"), the stage in front of stereo_cost when stereo_top's COST is
// fx_pkg::COST_CENSUS.
//
// Each pixel's luma, (LUMA_R R + LUMA_G G + LUMA_B B + 2^(LUMA_SHIFT-1)) >> LUMA_SHIFT, is
// compared with the 24 other pixels of its 5x5 window: bit 23 - n of the code is set where the
// n-th of them (raster order, the centre skipped) lies in the frame and is darker than the
// centre; a position outside the frame counts as equal (bit clear). The stream of {left code,
// right code} replaces the RGB pixels in stereo_cost's delay lines (24 bits each, as RGB).
//
// Structure (as stereo_window3x3, at radius r = CENSUS_RADIUS = 2): an input register with the
// two lumas, a line buffer of 2r rows of both lumas, and 2r column registers; one step after
// input pixel (x, y) arrives they hold the window centred on (x - r, y - r) (wrapping to the
// previous row, twice at width 1), whose code enters the output register at that step. Which
// rows and columns of that window lie in the frame is computed from the incoming coordinates and
// registered beside the input, so the comparisons start from registers. A centre above the frame
// (the first r rows' worth of steps of a frame) leaves as "no pixel" coordinates, as after a
// reset: the stages after it see a pipeline that was r * W + r + 2 steps longer.
// Latency: r * W + r + 2 pixel steps (stage_table.hpp kCensusStage). Every step is a pixel step
// (ce); with time-multiplexed lanes the stage steps once per G clocks like the others.
// Reset clears the coordinates only; stale data is masked by them.
`default_nettype none
`include "stereo_assert.svh"

module stereo_census #(
    parameter int WIDTH = 64,  // longest row
    // 1: out_left_rgb / out_right_rgb carry the RGB pixels of the centre beside its codes (the
    // adaptive-support-weight core weighs by colour): r rows of both RGB pixels more memory.
    parameter bit RGB_THROUGH = 1'b0
) (
    input  wire logic            clk,
    input  wire logic            rst,  // clears coordinates only
    input  wire logic            ce,   // the pixel step
    input  wire fx_pkg::coord_t  in_x,
    input  wire fx_pkg::coord_t  in_y,
    input  wire logic [23:0]     in_left,   // {R, G, B}
    input  wire logic [23:0]     in_right,  // {R, G, B}
    /* verilator lint_off UNUSEDSIGNAL */  // reads width and height only
    input  wire fx_pkg::config_t   cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output fx_pkg::coord_t       out_x,
    output fx_pkg::coord_t       out_y,
    output logic [23:0]          out_left,   // census code of the left image at (out_x, out_y)
    output logic [23:0]          out_right,  // ... of the right image
    output logic [23:0]          out_left_rgb,   // RGB_THROUGH: the left pixel (out_x, out_y)
    output logic [23:0]          out_right_rgb   // ... the right one (else 0)
);
  localparam int RADIUS = fx_pkg::CENSUS_RADIUS;
  localparam int SIDE = 2 * RADIUS + 1;
  localparam int LUMA_BITS = fx_pkg::PIXEL_BITS;
  localparam int PAIR_BITS = 2 * LUMA_BITS;  // {left luma, right luma}
  localparam int COLUMN_BITS = SIDE * PAIR_BITS;

  `STEREO_ASSERT(census_bits, fx_pkg::CENSUS_BITS == SIDE * SIDE - 1 && fx_pkg::CENSUS_BITS <= 24,
                 "CENSUS_BITS must be the window's pixels but the centre, at most 24")

  localparam int SUM_BITS = LUMA_BITS + fx_pkg::LUMA_SHIFT;  // 255 * 256 + 128 fits
  // v * WEIGHT as a sum of shifted copies of v, one per set bit of the constant weight: adders,
  // never a multiplier or a DSP block.
  function automatic logic [SUM_BITS-1:0] times(input logic [LUMA_BITS-1:0] v, input int weight);
    times = '0;
    for (int b = 0; b < SUM_BITS; b++) begin
      if (((weight >> b) & 1) == 1) times = times + (SUM_BITS'(v) << b);
    end
  endfunction
  function automatic logic [LUMA_BITS-1:0] luma(input logic [23:0] rgb);
    /* verilator lint_off UNUSEDSIGNAL */  // the fraction below the shift
    logic [SUM_BITS-1:0] sum;
    /* verilator lint_on UNUSEDSIGNAL */
    sum = times(rgb[23:16], fx_pkg::LUMA_R) + times(rgb[15:8], fx_pkg::LUMA_G) +
          times(rgb[7:0], fx_pkg::LUMA_B) + SUM_BITS'(1 << (fx_pkg::LUMA_SHIFT - 1));
    luma = sum[SUM_BITS-1:fx_pkg::LUMA_SHIFT];
  endfunction

  // ---- geometry of the window the incoming pixel completes ----------------------------------
  // Its centre (x - r, y - r), wrapping to the previous row; up to r times, as a frame narrower
  // than r wraps more than once (at r = 2: width 1).
  logic signed [17:0] cx, cy;
  stereo_window_centre #(.RADIUS(RADIUS)) window_centre (
      .in_x(in_x), .in_y(in_y), .cfg_width(cfg.width), .centre_x(cx), .centre_y(cy));
  logic [SIDE-1:0] row_inside, column_inside;
  stereo_border_flags #(
      .OFFSET_LO(-RADIUS),
      .OFFSET_HI(RADIUS)
  ) column_flags (
      .position(cx),
      .limit(cfg.width),
      .in_frame(column_inside)
  );
  stereo_border_flags #(
      .OFFSET_LO(-RADIUS),
      .OFFSET_HI(RADIUS)
  ) row_flags (
      .position(cy),
      .limit(cfg.height),
      .in_frame(row_inside)
  );

  // ---- input register ------------------------------------------------------------------------
  fx_pkg::coord_t x_q;  // addresses the line buffer
  fx_pkg::coord_t centre_x_q, centre_y_q;
  logic centre_real_q;  // the centre lies in a row >= 0 (and the input was a pixel)
  logic [SIDE-1:0] row_inside_q, column_inside_q;
  logic [PAIR_BITS-1:0] luma_q;
  always_ff @(posedge clk) begin
    if (rst) begin
      centre_real_q <= 1'b0;
    end else if (ce) begin
      centre_real_q <= in_y != fx_pkg::NO_PIXEL && cy >= 18'sd0;
    end
  end
  always_ff @(posedge clk) begin
    if (ce) begin
      x_q <= in_x;
      centre_x_q <= 16'(cx);
      centre_y_q <= 16'(cy);
      row_inside_q <= row_inside;
      column_inside_q <= column_inside;
      luma_q <= {luma(in_left), luma(in_right)};
    end
  end

  // ---- the window ---------------------------------------------------------------------------
  // columns[c] = the column c steps before the newest (c = 0: the registered pixel's); row slot j
  // of a column is row y - (SIDE-1) + j, so slot j is window row dy = j - r.
  logic [COLUMN_BITS-1:0] column_new;  // the registered pixel and the SIDE-1 rows above it
  stereo_row_stack #(.WIDTH(WIDTH), .DATA_BITS(PAIR_BITS), .ROWS(SIDE)) row_stack (
      .clk(clk), .ce(ce), .in_x(x_q), .cfg_width(cfg.width), .in_data(luma_q), .column(column_new));
  logic [COLUMN_BITS-1:0] column_history[SIDE-1];  // columns 1 .. SIDE-1
  logic [COLUMN_BITS-1:0] columns[SIDE];
  always_comb begin
    columns[0] = column_new;
    for (int c = 1; c < SIDE; c++) columns[c] = column_history[c-1];
  end
  always_ff @(posedge clk) begin
    if (ce) begin
      column_history[0] <= column_new;
      for (int c = 1; c < SIDE - 1; c++) column_history[c] <= column_history[c-1];
    end
  end

  // ---- the codes -----------------------------------------------------------------------------
  // Window position (dx, dy) is row slot dy + r of column r - dx; in the frame where its row and
  // column are.
  logic [23:0] code_left, code_right;
  always_comb begin
    logic [LUMA_BITS-1:0] centre_left, centre_right, left, right;
    logic in_window;
    int bit_index;
    centre_left = columns[RADIUS][RADIUS*PAIR_BITS+LUMA_BITS+:LUMA_BITS];
    centre_right = columns[RADIUS][RADIUS*PAIR_BITS+:LUMA_BITS];
    code_left = '0;
    code_right = '0;
    bit_index = fx_pkg::CENSUS_BITS - 1;
    for (int dy = -RADIUS; dy <= RADIUS; dy++) begin
      for (int dx = -RADIUS; dx <= RADIUS; dx++) begin
        if (dx != 0 || dy != 0) begin
          left = columns[RADIUS-dx][(dy+RADIUS)*PAIR_BITS+LUMA_BITS+:LUMA_BITS];
          right = columns[RADIUS-dx][(dy+RADIUS)*PAIR_BITS+:LUMA_BITS];
          in_window = row_inside_q[dy+RADIUS] && column_inside_q[dx+RADIUS];
          code_left[bit_index] = in_window && left < centre_left;
          code_right[bit_index] = in_window && right < centre_right;
          bit_index--;
        end
      end
    end
  end

  // ---- the centre's RGB pixels (RGB_THROUGH) --------------------------------------------------
  // Row slot 0 of an r + 1-row stack of the registered pixels is row y - r of column x; r column
  // registers more make it the centre (x - r, y - r).
  generate
    if (RGB_THROUGH) begin : g_rgb_through
      localparam int RGB_PAIR_BITS = 2 * fx_pkg::RGB_BITS;  // {left, right}
      logic [RGB_PAIR_BITS-1:0] rgb_q;
      /* verilator lint_off UNUSEDSIGNAL */  // rows y - r + 1 .. y: only row y - r is read
      logic [(RADIUS+1)*RGB_PAIR_BITS-1:0] rgb_column;
      /* verilator lint_on UNUSEDSIGNAL */
      logic [RGB_PAIR_BITS-1:0] rgb_history[RADIUS];  // row y - r of columns x - 1 .. x - r
      always_ff @(posedge clk) begin
        if (ce) rgb_q <= {in_left, in_right};
      end
      stereo_row_stack #(.WIDTH(WIDTH), .DATA_BITS(RGB_PAIR_BITS), .ROWS(RADIUS + 1)) rgb_rows (
          .clk(clk), .ce(ce), .in_x(x_q), .cfg_width(cfg.width), .in_data(rgb_q),
          .column(rgb_column));
      always_ff @(posedge clk) begin
        if (ce) begin
          rgb_history[0] <= rgb_column[0+:RGB_PAIR_BITS];
          for (int c = 1; c < RADIUS; c++) rgb_history[c] <= rgb_history[c-1];
        end
      end
      always_ff @(posedge clk) begin
        if (ce) {out_left_rgb, out_right_rgb} <= rgb_history[RADIUS-1];
      end
    end else begin : g_no_rgb
      assign out_left_rgb = '0;
      assign out_right_rgb = '0;
    end
  endgenerate

  // ---- the output register -------------------------------------------------------------------
  always_ff @(posedge clk) begin
    if (rst) begin
      out_x <= '0;
      out_y <= fx_pkg::NO_PIXEL;
    end else if (ce) begin
      out_x <= centre_real_q ? centre_x_q : '0;
      out_y <= centre_real_q ? centre_y_q : fx_pkg::NO_PIXEL;
    end
  end
  always_ff @(posedge clk) begin
    if (ce) begin
      out_left <= code_left;
      out_right <= code_right;
    end
  end
endmodule

`default_nettype wire
