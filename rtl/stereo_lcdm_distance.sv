// stereo_lcdm_distance: the LCDM cost of two points on the hue-saturation disc (model:
// stereo::lcdm, docs/fixed-point.md "LCDM"):
//   min(765, (isqrt(4 ((aL - aR)^2 + (bL - bR)^2)) * 765 + 1024) >> 11).
// Combinational: two squares, a digit-by-digit square root (no multiplier), one constant product.
`default_nettype none

module stereo_lcdm_distance (
    input  wire logic [2*fx_pkg::LCDM_COORD_BITS-1:0] in_left,   // {a, b}, signed each
    input  wire logic [2*fx_pkg::LCDM_COORD_BITS-1:0] in_right,  // {a, b}, signed each
    output      logic [       fx_pkg::COST_BITS-1:0] out_cost
);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int COORD_BITS = fx_pkg::LCDM_COORD_BITS;
  localparam int SQ_BITS = fx_pkg::LCDM_DIST_SQ_BITS;  // 4 (da^2 + db^2) <= 2^23
  localparam int ROOT_BITS = SQ_BITS / 2;
  localparam int SCALED_BITS = ROOT_BITS + COST_BITS;

  // Floor of the square root, digit by digit.
  function automatic logic [ROOT_BITS-1:0] isqrt(input logic [SQ_BITS-1:0] value);
    logic [ROOT_BITS+1:0] remainder, trial;
    logic [ROOT_BITS-1:0] root;
    remainder = '0;
    root = '0;
    for (int i = ROOT_BITS - 1; i >= 0; i--) begin
      remainder = {remainder[ROOT_BITS-1:0], value[2*i+1-:2]};
      trial = {root, 2'b01};
      if (remainder >= trial) begin
        remainder = remainder - trial;
        root = {root[ROOT_BITS-2:0], 1'b1};
      end else begin
        root = {root[ROOT_BITS-2:0], 1'b0};
      end
    end
    isqrt = root;
  endfunction

  logic signed [SQ_BITS-1:0] da, db, squares;
  logic [SCALED_BITS-1:0] scaled;
  always_comb begin
    da = SQ_BITS'($signed(in_left[2*COORD_BITS-1:COORD_BITS])) -
         SQ_BITS'($signed(in_right[2*COORD_BITS-1:COORD_BITS]));
    db = SQ_BITS'($signed(in_left[COORD_BITS-1:0])) - SQ_BITS'($signed(in_right[COORD_BITS-1:0]));
    squares = da * da + db * db;  // <= 2^21, so 4 squares fits SQ_BITS
    scaled = (SCALED_BITS'(isqrt($unsigned(squares <<< 2))) * SCALED_BITS'(fx_pkg::COST_MAX) +
              SCALED_BITS'(2 * fx_pkg::LCDM_RADIUS)) >> (fx_pkg::LCDM_RADIUS_BITS + 2);
    out_cost = (scaled > SCALED_BITS'(fx_pkg::COST_MAX)) ? COST_BITS'(fx_pkg::COST_MAX)
                                                         : scaled[COST_BITS-1:0];
  end
endmodule

`default_nettype wire
