// stereo_cost_lcdm: the LCDM matching cost (thesis Sec. 3.5) for all disparities at once, a
// drop-in for stereo_cost with the same ports and latency (model: the "lcdm" cost plug-in,
// docs/fixed-point.md "LCDM").
//
// Each incoming left and right pixel is converted to its point (a, b) on the hue-saturation disc
// (stereo_lcdm_convert); the right points of the current row pass through a delay line as the
// right pixels do in stereo_cost. Cost of disparity d:
//   min(765, (isqrt(4 ((aL - aR)^2 + (bL - bR)^2)) * 765 + 1024) >> 11),  or COST_OUTSIDE
// where x - d < 0. Latency: 1 pixel step. Throughput: one pixel per ce.
`default_nettype none

module stereo_cost_lcdm #(
    parameter int NDISP = 16  // disparities evaluated in parallel
) (
    input  wire logic                               clk,
    input  wire logic                               rst,       // clears coordinates only
    input  wire logic                               ce,        // advance one pixel step
    input  wire fx_pkg::coord_t                     in_x,
    input  wire fx_pkg::coord_t                     in_y,
    input  wire logic [23:0]                        in_left,   // {R, G, B}
    input  wire logic [23:0]                        in_right,  // {R, G, B}
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    output      logic [NDISP*fx_pkg::COST_BITS-1:0] out_data
);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int COORD_BITS = fx_pkg::LCDM_COORD_BITS;
  localparam int POINT_BITS = 2 * COORD_BITS;  // {a, b}
  localparam int SQ_BITS = fx_pkg::LCDM_DIST_SQ_BITS;  // 4 (da^2 + db^2) <= 2^23
  localparam int ROOT_BITS = SQ_BITS / 2;
  localparam int HISTORY = (NDISP > 1) ? NDISP - 1 : 1;  // right points kept besides the current

  logic signed [COORD_BITS-1:0] left_a, left_b, right_a, right_b;
  stereo_lcdm_convert convert_left (
      .in_rgb(in_left),
      .out_a (left_a),
      .out_b (left_b)
  );
  stereo_lcdm_convert convert_right (
      .in_rgb(in_right),
      .out_a (right_a),
      .out_b (right_b)
  );
  logic [POINT_BITS-1:0] left_point, right_point;
  assign left_point = {left_a, left_b};
  assign right_point = {right_a, right_b};

  // Floor of the square root, digit by digit (no multiplier).
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

  function automatic logic [COST_BITS-1:0] lcdm_cost(input logic [POINT_BITS-1:0] p,
                                                     input logic [POINT_BITS-1:0] q);
    logic signed [SQ_BITS-1:0] da, db, squares;
    logic [ROOT_BITS+COST_BITS-1:0] scaled;
    da = SQ_BITS'($signed(p[POINT_BITS-1:COORD_BITS])) - SQ_BITS'($signed(q[POINT_BITS-1:COORD_BITS]));
    db = SQ_BITS'($signed(p[COORD_BITS-1:0])) - SQ_BITS'($signed(q[COORD_BITS-1:0]));
    squares = da * da + db * db;  // <= 2^21, so 4 squares fits SQ_BITS
    scaled = ((ROOT_BITS + COST_BITS)'(isqrt($unsigned(squares <<< 2))) *
                  (ROOT_BITS + COST_BITS)'(fx_pkg::COST_MAX) +
              (ROOT_BITS + COST_BITS)'(2 * fx_pkg::LCDM_RADIUS)) >> (fx_pkg::LCDM_RADIUS_BITS + 2);
    lcdm_cost = (scaled > (ROOT_BITS + COST_BITS)'(fx_pkg::COST_MAX)) ?
        COST_BITS'(fx_pkg::COST_MAX) : scaled[COST_BITS-1:0];
  endfunction

  // right_history[i*POINT_BITS +: POINT_BITS] = right point (x - 1 - i) during the step of x.
  logic [HISTORY*POINT_BITS-1:0] right_history;
  logic [NDISP*COST_BITS-1:0] cost_d;

  generate
    for (genvar d = 0; d < NDISP; d++) begin : g_disparity
      logic [POINT_BITS-1:0] right_pixel;
      if (d == 0) begin : g_current
        assign right_pixel = right_point;
      end else begin : g_delayed
        assign right_pixel = right_history[(d-1)*POINT_BITS +: POINT_BITS];
      end
      assign cost_d[d*COST_BITS +: COST_BITS] =
          (18'(in_x) < 18'sd0 + 18'(d)) ? COST_BITS'(fx_pkg::COST_OUTSIDE) : lcdm_cost(left_point, right_pixel);
    end
  endgenerate

  generate
    if (HISTORY > 1) begin : g_shift
      always_ff @(posedge clk) begin
        if (ce) right_history <= {right_history[(HISTORY-1)*POINT_BITS-1:0], right_point};
      end
    end else begin : g_single
      always_ff @(posedge clk) begin
        if (ce) right_history <= right_point;
      end
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) out_data <= cost_d;
  end

  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
