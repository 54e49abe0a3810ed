// stereo_cost: absolute-difference matching cost over RGB for all disparities at once
// (model: stereo::cost, docs/fixed-point.md stage 1).
//
// The right pixels of the current row pass through a delay line, so that at the step of left
// pixel x the line holds R(x-1) .. R(x-NDISP+1). Cost of disparity d:
//   |Lr - Rr(x-d)| + |Lg - Rg(x-d)| + |Lb - Rb(x-d)|,  or COST_OUTSIDE where x - d < 0.
// Latency: 1 pixel step. Throughput: one pixel per ce.
`default_nettype none

module stereo_cost #(
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
  localparam int HISTORY = (NDISP > 1) ? NDISP - 1 : 1;  // right pixels kept besides the current

  // right_history[i*24 +: 24] = R(x - 1 - i) during the step of pixel x (same row or masked).
  logic [HISTORY*24-1:0] right_history;
  logic [NDISP*COST_BITS-1:0] cost_d;

  function automatic logic [COST_BITS-1:0] abs_diff_rgb(input logic [23:0] a, input logic [23:0] b);
    logic [8:0] dr, dg, db;
    dr = (a[23:16] >= b[23:16]) ? {1'b0, a[23:16] - b[23:16]} : {1'b0, b[23:16] - a[23:16]};
    dg = (a[15:8] >= b[15:8]) ? {1'b0, a[15:8] - b[15:8]} : {1'b0, b[15:8] - a[15:8]};
    db = (a[7:0] >= b[7:0]) ? {1'b0, a[7:0] - b[7:0]} : {1'b0, b[7:0] - a[7:0]};
    abs_diff_rgb = COST_BITS'(dr) + COST_BITS'(dg) + COST_BITS'(db);
  endfunction

  generate
    for (genvar d = 0; d < NDISP; d++) begin : g_disparity
      logic [23:0] right_pixel;
      if (d == 0) begin : g_current
        assign right_pixel = in_right;
      end else begin : g_delayed
        assign right_pixel = right_history[(d-1)*24 +: 24];
      end
      assign cost_d[d*COST_BITS +: COST_BITS] =
          (18'(in_x) < 18'sd0 + 18'(d)) ? COST_BITS'(fx_pkg::COST_OUTSIDE) : abs_diff_rgb(in_left, right_pixel);
    end
  endgenerate

  generate
    if (HISTORY > 1) begin : g_shift
      always_ff @(posedge clk) begin
        if (ce) right_history <= {right_history[(HISTORY-1)*24-1:0], in_right};
      end
    end else begin : g_single
      always_ff @(posedge clk) begin
        if (ce) right_history <= in_right;
      end
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) out_data <= cost_d;
  end

  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
