// stereo_asw_column: the d-independent half of the separable adaptive-support-weight core
// (stereo_top ASW = 1; model: stereo::asw, docs/asw.md "The hardware-friendly variant"). For
// the incoming pixel (x, y) of both images it stacks the DIAMETER rows y - 2r .. y of column x
// (r = DIAMETER / 2; the centre row yc = y - r) and computes, per image, the words the cost
// stage's delay lines carry (stereo_cost RAW_BITS = WORD_BITS) to the aggregation
// (stereo_asw_aggregate):
//   codes[j]  row yc - r + j's census code (CODES = 1) or RGB pixel (CODES = 0, the AD cost),
//             at [j*24 +: 24], j = 0 .. DIAMETER-1;
//   vert[j]   the vertical pass' weight of row j against the centre: left image
//             prox(|j - r|) (x) colour(L_j, L_c), right image colour(R_j, R_c) (the right
//             factor of label d is that of the right column x - d), at [24 D + j*8 +: 8];
//   near[i]   the horizontal weight of offset dx = i - r of pixel x - NEAR of the centre row
//             (NEAR = r + 1 + S + V, stereo_asw_aggregate; left: prox(|dx|) (x) colour, right:
//             colour) for the first horizontal pass, at [32 D + i*8 +: 8];
//   far[i]    the same of pixel x - FAR for the second pass (near, GAP = FAR - NEAR =
//             r + 1 + H + S + W steps later), at [40 D + i*8 +: 8];
// colour(a, b) = fx_pkg::asw_colour(DIAMETER, |dR| + |dG| + |dB|), (x) = fx_pkg::asw_combine (with
// the constant proximity: asw_combine_constant, shifts and adds).
// The aggregation masks rows and columns outside the frame and right columns outside the right
// image; nothing here knows the frame's edges, so words of pixels near them carry stale
// neighbours, never read.
// The coordinates go on as (x, yc), "no pixel" while yc < 0. Combinational (the cost stage
// registers the words): latency 0 steps; the rows of the stack are r * W steps, counted as the
// stage's latency in stage_table.hpp.
`default_nettype none
`include "stereo_assert.svh"

module stereo_asw_column #(
    parameter int WIDTH    = 64,  // longest row
    parameter int DIAMETER = 5,   // the support diameter w (odd, fx_pkg::ASW_MIN/MAX_DIAMETER)
    parameter bit CODES    = 1'b1  // 1: census codes beside the RGB pixels; 0: AD, RGB only
) (
    input  wire logic                  clk,
    input  wire logic                  ce,  // the pixel step
    input  wire fx_pkg::coord_t        in_x,
    input  wire fx_pkg::coord_t        in_y,
    /* verilator lint_off UNUSEDSIGNAL */  // CODES = 0: the codes are the RGB pixels
    input  wire logic [23:0]           in_left_code,
    input  wire logic [23:0]           in_right_code,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic [23:0]           in_left_rgb,
    input  wire logic [23:0]           in_right_rgb,
    input  wire fx_pkg::cfg_size_t     cfg_width,
    output      fx_pkg::coord_t        out_x,
    output      fx_pkg::coord_t        out_y,
    output      logic [48*DIAMETER-1:0] out_left,  // one image's word (above)
    output      logic [48*DIAMETER-1:0] out_right
);
  localparam int WORD_BITS = 48 * DIAMETER;
  localparam int R = DIAMETER / 2;
  localparam int IMAGE_BITS = CODES ? 48 : 24;  // {code, RGB} or RGB, per image and row
  localparam int ROW_BITS = 2 * IMAGE_BITS;  // {right, left}
  // pixel x - NEAR: the first horizontal pass, x - FAR the second (stereo_asw_aggregate's
  // positions: stage_table.hpp asw_near_steps, asw_far_steps)
  localparam int NEAR = R + 1 + fx_pkg::ASW_DIVIDE_STEPS + fx_pkg::ASW_VERTICAL_STEPS;
  localparam int GAP = R + 1 + fx_pkg::ASW_HORIZONTAL_STEPS + fx_pkg::ASW_DIVIDE_STEPS +
                      fx_pkg::ASW_WINNER_STEPS;  // FAR - NEAR
  localparam int HISTORY = NEAR + R;  // centre-row pixels kept, x - 1 .. x - HISTORY

  `STEREO_ASSERT(diameter_range,
                 DIAMETER % 2 == 1 && DIAMETER >= fx_pkg::ASW_MIN_DIAMETER &&
                     DIAMETER <= fx_pkg::ASW_MAX_DIAMETER,
                 "DIAMETER must be odd, ASW_MIN_DIAMETER .. ASW_MAX_DIAMETER")

  function automatic int colour_difference(input logic [23:0] a, input logic [23:0] b);
    int sum;
    logic [7:0] channel;
    sum = 0;
    for (int c = 0; c < 3; c++) begin
      channel = (a[c*8+:8] >= b[c*8+:8]) ? a[c*8+:8] - b[c*8+:8] : b[c*8+:8] - a[c*8+:8];
      sum = sum + 32'(channel);
    end
    colour_difference = sum;
  endfunction
  // This diameter's row of fx_pkg::ASW_COLOUR (what fx_pkg::asw_colour reads), as a ROM: a
  // look-up in the package's constant vector (every diameter's table) left Yosys a shifter over
  // 91,920 bits per look-up, and one over this diameter's 6,128 bits still took it minutes per
  // look-up to map; a memory that is never written maps as a ROM.
  localparam int COLOUR_ROW_BITS = fx_pkg::ASW_COLOUR_ENTRIES * 8;
  localparam logic [COLOUR_ROW_BITS-1:0] COLOUR_ROW =
      fx_pkg::ASW_COLOUR[((DIAMETER - fx_pkg::ASW_MIN_DIAMETER) / 2) * COLOUR_ROW_BITS +:
                         COLOUR_ROW_BITS];
  logic [7:0] colour_rom[fx_pkg::ASW_COLOUR_ENTRIES];
  initial begin
    for (int i = 0; i < fx_pkg::ASW_COLOUR_ENTRIES; i++) colour_rom[i] = COLOUR_ROW[i*8+:8];
  end
  function automatic logic [7:0] response(input logic [23:0] a, input logic [23:0] b);
    response = colour_rom[colour_difference(a, b)];
  endfunction

  // ---- the column stack: row yc - r + j at slot j --------------------------------------------
  logic [ROW_BITS-1:0] in_row;
  generate
    if (CODES) begin : g_codes
      assign in_row = {in_right_code, in_right_rgb, in_left_code, in_left_rgb};
    end else begin : g_rgb
      assign in_row = {in_right_rgb, in_left_rgb};
    end
  endgenerate
  logic [DIAMETER*ROW_BITS-1:0] column;
  stereo_row_stack #(.WIDTH(WIDTH), .DATA_BITS(ROW_BITS), .ROWS(DIAMETER)) rows (
      .clk(clk), .ce(ce), .in_x(in_x), .cfg_width(cfg_width), .in_data(in_row), .column(column));

  // The RGB pixel and code of image `side` (0 left, 1 right) in row slot j.
  function automatic logic [23:0] rgb_at(input int side, input int j);
    rgb_at = column[j*ROW_BITS + side*IMAGE_BITS +: 24];
  endfunction
  function automatic logic [23:0] code_at(input int side, input int j);
    code_at = column[j*ROW_BITS + side*IMAGE_BITS + IMAGE_BITS - 24 +: 24];
  endfunction

  // ---- the centre row's pixels of the last HISTORY columns, per image --------------------------
  logic [23:0] centre_history[2][HISTORY];  // [side][p-1]: column x - p
  always_ff @(posedge clk) begin
    if (ce) begin
      for (int side = 0; side < 2; side++) begin
        centre_history[side][0] <= rgb_at(side, R);
        for (int p = 1; p < HISTORY; p++) centre_history[side][p] <= centre_history[side][p-1];
      end
    end
  end

  // ---- the words ------------------------------------------------------------------------------
  // near[i] of pixel x - NEAR: its neighbour x - NEAR + dx is column x - (NEAR - dx).
  logic [8*DIAMETER-1:0] near_now[2];
  always_comb begin
    for (int side = 0; side < 2; side++) begin
      for (int i = 0; i < DIAMETER; i++) begin
        near_now[side][i*8+:8] = response(centre_history[side][NEAR-1-(i-R)],
                                          centre_history[side][NEAR-1]);
        if (side == 0) begin
          near_now[side][i*8+:8] = fx_pkg::asw_combine_constant(
              32'(fx_pkg::asw_proximity(DIAMETER, (i >= R) ? i - R : R - i)),
              near_now[side][i*8+:8]);
        end
      end
    end
  end
  // far = near, GAP steps later.
  logic [8*DIAMETER-1:0] near_history[2][GAP];
  always_ff @(posedge clk) begin
    if (ce) begin
      for (int side = 0; side < 2; side++) begin
        near_history[side][0] <= near_now[side];
        for (int p = 1; p < GAP; p++) near_history[side][p] <= near_history[side][p-1];
      end
    end
  end

  logic [WORD_BITS-1:0] word[2];
  always_comb begin
    for (int side = 0; side < 2; side++) begin
      for (int j = 0; j < DIAMETER; j++) begin
        word[side][j*24+:24] = code_at(side, j);
        word[side][24*DIAMETER+j*8+:8] = response(rgb_at(side, j), rgb_at(side, R));
        if (side == 0) begin
          word[side][24*DIAMETER+j*8+:8] = fx_pkg::asw_combine_constant(
              32'(fx_pkg::asw_proximity(DIAMETER, (j >= R) ? j - R : R - j)),
              word[side][24*DIAMETER+j*8+:8]);
        end
      end
      word[side][32*DIAMETER+:8*DIAMETER] = near_now[side];
      word[side][40*DIAMETER+:8*DIAMETER] = near_history[side][GAP-1];
    end
  end
  assign out_left = word[0];
  assign out_right = word[1];

  assign out_x = in_x;
  assign out_y = (in_y < $signed(16'(R))) ? fx_pkg::NO_PIXEL : in_y - $signed(16'(R));
endmodule

`default_nettype wire
