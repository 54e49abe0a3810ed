// stereo_ca_rule1: CA rule 1 (model: stereo::ca_rule1, docs/fixed-point.md stage 3).
//
// A cell whose d-1 or d+1 neighbour (d+1 < cfg_ndisp) differs from it by less than half its
// value, 2|n - c| < c, becomes round(sum of its 3x3 in-plane neighbourhood / 9), with zero
// padding outside the frame and the division done as (sum * MEAN9_MUL + 2^(MEAN9_SHIFT-1)) >>
// MEAN9_SHIFT. With cfg_use_ca low every cell passes unchanged.
// Output pixel = input pixel moved back one row and one column. Latency: W + 3 pixel steps
// (the window's input register, the centre one row and one column back, the result register).
`default_nettype none

module stereo_ca_rule1 #(
    parameter int WIDTH = 64,  // longest row
    parameter int NDISP = 16   // disparities in parallel
) (
    input  wire logic                                          clk,
    input  wire logic                                          rst,  // clears coordinates only
    input  wire logic                                          ce,
    input  wire logic signed [15:0]                            in_x,
    input  wire logic signed [15:0]                            in_y,
    input  wire logic        [NDISP*fx_pkg::AGG_BITS-1:0]  in_data,
    input  wire logic        [15:0]                            cfg_width,
    input  wire logic        [15:0]                            cfg_height,
    input  wire logic        [8:0]                             cfg_ndisp,
    input  wire logic                                          cfg_use_ca,
    output      logic signed [15:0]                            out_x,
    output      logic signed [15:0]                            out_y,
    output      logic        [NDISP*fx_pkg::AGG_BITS-1:0]  out_data
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int SUM_BITS = fx_pkg::CA_SUM_BITS;
  localparam int COLUMN = NDISP * BITS;
  localparam int CENTRE = 4;  // slot of (0, 0)
  localparam logic signed [15:0] NO_PIXEL = -16'sd32768;

  logic signed [15:0] centre_x, centre_y;
  logic [9*COLUMN-1:0] window;
  logic [8:0] in_frame;
  stereo_window3x3 #(
      .WIDTH(WIDTH),
      .BITS (BITS),
      .NDISP(NDISP)
  ) neighbourhood (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .in_x(in_x),
      .in_y(in_y),
      .in_data(in_data),
      .cfg_width(cfg_width),
      .cfg_height(cfg_height),
      .centre_x(centre_x),
      .centre_y(centre_y),
      .window_data(window),
      .in_frame(in_frame)
  );

  // 2|n - c| < c  <=>  c < 2n < 3c, exactly in integers: two comparisons instead of a
  // subtraction, an absolute value and a comparison (3c is shared by all neighbours).
  function automatic logic agrees(input logic [BITS-1:0] neighbour, input logic [BITS-1:0] centre);
    logic [BITS+1:0] twice_neighbour, centre_wide;
    twice_neighbour = {1'b0, neighbour, 1'b0};
    centre_wide = {2'b0, centre};
    agrees = centre_wide < twice_neighbour && twice_neighbour < centre_wide + {1'b0, centre, 1'b0};
  endfunction

  logic [COLUMN-1:0] result;
  generate
    for (genvar d = 0; d < NDISP; d++) begin : g_disparity
      logic [BITS-1:0] centre;
      logic below_agrees, above_agrees;
      assign centre = window[CENTRE*COLUMN + d*BITS +: BITS];
      if (d > 0) begin : g_below
        assign below_agrees = agrees(window[CENTRE*COLUMN + (d-1)*BITS +: BITS], centre);
      end else begin : g_no_below
        assign below_agrees = 1'b0;
      end
      if (d + 1 < NDISP) begin : g_above
        assign above_agrees = d + 1 < $signed(32'(cfg_ndisp)) &&
                              agrees(window[CENTRE*COLUMN + (d+1)*BITS +: BITS], centre);
      end else begin : g_no_above
        assign above_agrees = 1'b0;
      end
      always_comb begin
        logic [SUM_BITS-1:0] sum;
        logic [31:0] product;
        sum = '0;
        for (int slot = 0; slot < 9; slot++) begin
          if (in_frame[slot]) sum = sum + SUM_BITS'(window[slot*COLUMN + d*BITS +: BITS]);
        end
        product = 32'(sum) * 32'(fx_pkg::MEAN9_MUL) + 32'(1 << (fx_pkg::MEAN9_SHIFT - 1));
        result[d*BITS +: BITS] = (cfg_use_ca && (below_agrees || above_agrees))
                                     ? BITS'(product >> fx_pkg::MEAN9_SHIFT) : centre;
      end
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) out_data <= result;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      out_x <= '0;
      out_y <= NO_PIXEL;
    end else if (ce) begin
      out_x <= centre_x;
      out_y <= centre_y;
    end
  end
endmodule

`default_nettype wire
