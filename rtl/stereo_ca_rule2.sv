// stereo_ca_rule2: CA rule 2 (model: stereo::ca_rule2, docs/fixed-point.md stage 4).
//
// A cell with at least RULE2_MIN_COUNT of its 8 in-plane neighbours in_frame the frame that
// differ from it by less than half its value, 2|n - c| < c, becomes round(c / 1.3) =
// (c * DIV13_MUL + 2^(DIV13_SHIFT-1)) >> DIV13_SHIFT. With cfg_use_ca low every cell passes.
// Output pixel = input pixel moved back one row and one column. Latency: W + 3 pixel steps
// (the window's input register, the centre one row and one column back, the result register).
`default_nettype none

module stereo_ca_rule2 #(
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
    input  wire logic                                          cfg_use_ca,
    output      logic signed [15:0]                            out_x,
    output      logic signed [15:0]                            out_y,
    output      logic        [NDISP*fx_pkg::AGG_BITS-1:0]  out_data
);
  localparam int BITS = fx_pkg::AGG_BITS;
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
      always_comb begin
        logic [BITS-1:0] centre;
        logic [3:0] count;
        logic [31:0] product;
        centre = window[CENTRE*COLUMN + d*BITS +: BITS];
        count = '0;
        for (int slot = 0; slot < 9; slot++) begin
          // A neighbour outside the frame is zero padding, and zero never agrees.
          if (slot != CENTRE && in_frame[slot] &&
              agrees(window[slot*COLUMN + d*BITS +: BITS], centre)) begin
            count = count + 4'd1;
          end
        end
        product = 32'(centre) * 32'(fx_pkg::DIV13_MUL) + 32'(1 << (fx_pkg::DIV13_SHIFT - 1));
        result[d*BITS +: BITS] = (cfg_use_ca && $signed(32'(count)) >= fx_pkg::RULE2_MIN_COUNT)
                                     ? BITS'(product >> fx_pkg::DIV13_SHIFT) : centre;
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
