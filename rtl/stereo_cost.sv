// stereo_cost: the matching cost for all labels at once, over the signed disparity range
// d = m + k, k = 0 .. NDISP-1, m = cfg_min_disp (model: stereo::cost and the cost plug-ins,
// docs/fixed-point.md stages 1 and 6, "LCDM"). COST = 0: absolute differences over RGB;
// COST = 1: the LCDM cost (thesis Sec. 3.5), each incoming pixel first converted to its point on
// the hue-saturation disc (stereo_lcdm_convert), the per-label distance by stereo_lcdm_distance.
// Below, "pixel" is what the delay lines carry: RGB (24 bits) or the LCDM point (22 bits).
//
// The right pixels pass through continuous delay lines (across row boundaries). For a negative m
// the left pixel must wait for right pixels that arrive later: it is delayed (with its
// coordinates) by K = max(0, -m) steps. The right sample of label k sits k + P positions behind
// the newest right pixel, P = max(m, 0): one multiplexer picks the right pixel P steps old from a
// pre-delay line of MAX_MIN_DISP, and the lanes' delay line of NDISP - 1 holds its history (a
// lane reading a value picked under the previous frame's P reads a position before the frame,
// which is outside). The cost of label k is
//   |Lr - Rr(xr)| + |Lg - Rg(xr)| + |Lb - Rb(xr)|  (AD)  or  lcdm(L, R(xr))  (LCDM),  xr = x - m - k,
// or COST_OUTSIDE where xr lies outside [0, W): exactly where the tap holds a pixel of another
// row (or none), so nothing is ever cleared. cfg_min_disp must stay within +-MAX_MIN_DISP
// (stereo_top clamps it) and constant during a frame and its flush.
// Latency: 1 + K pixel steps. Throughput: one pixel per ce.
`default_nettype none

module stereo_cost #(
    parameter int NDISP        = 16,                           // labels evaluated in parallel
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,  // largest |cfg_min_disp|
    parameter int COST         = 0                             // 0: AD over RGB, 1: LCDM
) (
    input  wire logic                               clk,
    input  wire logic                               rst,           // clears coordinates only
    input  wire logic                               ce,            // advance one pixel step
    input  wire fx_pkg::coord_t                     in_x,
    input  wire fx_pkg::coord_t                     in_y,
    input  wire logic [23:0]                        in_left,       // {R, G, B}
    input  wire logic [23:0]                        in_right,      // {R, G, B}
    input  wire fx_pkg::cfg_size_t                  cfg_width,
    input  wire fx_pkg::cfg_min_disp_t              cfg_min_disp,
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    output      logic [NDISP*fx_pkg::COST_BITS-1:0] out_data
);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int PIXEL_BITS = (COST == 1) ? 2 * fx_pkg::LCDM_COORD_BITS : fx_pkg::RGB_BITS;
  // Right pixels kept: the pre-delay line, and the lanes' history besides the selected pixel.
  localparam int PRE_DELAY = (MAX_MIN_DISP > 0) ? MAX_MIN_DISP : 1;
  localparam int HISTORY = (NDISP > 1) ? NDISP - 1 : 1;
  localparam int LEFT_DELAY = (MAX_MIN_DISP > 0) ? MAX_MIN_DISP : 1;  // left pixels kept
  localparam int SHIFT_BITS = $clog2(MAX_MIN_DISP + 1) + 1;

  initial begin
    assert (MAX_MIN_DISP >= 0 && MAX_MIN_DISP <= fx_pkg::MAX_MIN_DISPARITY);
    assert (COST == 0 || COST == 1);
  end

  // The pixels the delay lines carry.
  logic [PIXEL_BITS-1:0] new_left, new_right;
  generate
    if (COST == 1) begin : g_lcdm_points
      logic signed [fx_pkg::LCDM_COORD_BITS-1:0] left_a, left_b, right_a, right_b;
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
      assign new_left  = {left_a, left_b};
      assign new_right = {right_a, right_b};
    end else begin : g_rgb
      assign new_left  = in_left;
      assign new_right = in_right;
    end
  endgenerate

  // right_pre[i*PIXEL_BITS +: PIXEL_BITS] = the right pixel i + 1 steps before the newest.
  logic [PRE_DELAY*PIXEL_BITS-1:0] right_pre;
  // right_history[i*PIXEL_BITS +: PIXEL_BITS] = the selected right pixel i + 1 steps ago.
  logic [HISTORY*PIXEL_BITS-1:0] right_history;
  // The left pixel and its coordinates, i + 1 steps ago.
  logic [LEFT_DELAY*PIXEL_BITS-1:0] left_history;
  fx_pkg::coord_t left_x_history[LEFT_DELAY];
  fx_pkg::coord_t left_y_history[LEFT_DELAY];

  // K = max(0, -m) and P = max(m, 0), both within 0 .. MAX_MIN_DISP.
  logic [SHIFT_BITS-1:0] left_wait, right_skip;
  always_comb begin
    left_wait = '0;
    right_skip = '0;
    if (cfg_min_disp < 0) left_wait = SHIFT_BITS'(-cfg_min_disp);
    else right_skip = SHIFT_BITS'(cfg_min_disp);
  end

  // The right pixel P steps old.
  logic [PIXEL_BITS-1:0] right_selected;
  always_comb begin
    right_selected = new_right;
    for (int p = 1; p <= MAX_MIN_DISP; p++) begin
      if (32'(right_skip) == p) right_selected = right_pre[(p-1)*PIXEL_BITS +: PIXEL_BITS];
    end
  end

  // The left pixel matched at this step.
  logic [PIXEL_BITS-1:0] left_pixel;
  fx_pkg::coord_t left_x, left_y;
  always_comb begin
    left_pixel = new_left;
    left_x = in_x;
    left_y = in_y;
    for (int i = 1; i <= MAX_MIN_DISP; i++) begin
      if (32'(left_wait) == i) begin
        left_pixel = left_history[(i-1)*PIXEL_BITS +: PIXEL_BITS];
        left_x = left_x_history[i-1];
        left_y = left_y_history[i-1];
      end
    end
  end

  function automatic logic [COST_BITS-1:0] abs_diff_rgb(input logic [23:0] a, input logic [23:0] b);
    logic [8:0] dr, dg, db;
    dr = (a[23:16] >= b[23:16]) ? {1'b0, a[23:16] - b[23:16]} : {1'b0, b[23:16] - a[23:16]};
    dg = (a[15:8] >= b[15:8]) ? {1'b0, a[15:8] - b[15:8]} : {1'b0, b[15:8] - a[15:8]};
    db = (a[7:0] >= b[7:0]) ? {1'b0, a[7:0] - b[7:0]} : {1'b0, b[7:0] - a[7:0]};
    abs_diff_rgb = COST_BITS'(dr) + COST_BITS'(dg) + COST_BITS'(db);
  endfunction

  logic [NDISP*COST_BITS-1:0] cost_d;
  generate
    for (genvar k = 0; k < NDISP; k++) begin : g_label
      logic [PIXEL_BITS-1:0] right_pixel;
      logic signed [17:0] right_x;  // xr = x - m - k
      logic [COST_BITS-1:0] distance;
      always_comb begin
        // Tap k + P behind the newest right pixel: k behind the selected one.
        right_pixel = (k == 0) ? right_selected
                               : right_history[(k > 0 ? k - 1 : 0)*PIXEL_BITS +: PIXEL_BITS];
        right_x = 18'(left_x) - 18'(cfg_min_disp) - 18'(k);
      end
      if (COST == 1) begin : g_lcdm
        stereo_lcdm_distance lcdm (
            .in_left (left_pixel),
            .in_right(right_pixel),
            .out_cost(distance)
        );
      end else begin : g_ad
        assign distance = abs_diff_rgb(24'(left_pixel), 24'(right_pixel));  // PIXEL_BITS = 24 here
      end
      assign cost_d[k*COST_BITS +: COST_BITS] =
          (right_x < 18'sd0 || right_x >= $signed(18'(cfg_width)))
              ? COST_BITS'(fx_pkg::COST_OUTSIDE) : distance;
    end
  endgenerate

  generate
    if (HISTORY > 1) begin : g_shift
      always_ff @(posedge clk) begin
        if (ce) right_history <= {right_history[(HISTORY-1)*PIXEL_BITS-1:0], right_selected};
      end
    end else begin : g_single
      always_ff @(posedge clk) begin
        if (ce) right_history <= right_selected;
      end
    end
    if (PRE_DELAY > 1) begin : g_pre_shift
      always_ff @(posedge clk) begin
        if (ce) right_pre <= {right_pre[(PRE_DELAY-1)*PIXEL_BITS-1:0], new_right};
      end
    end else begin : g_pre_single
      always_ff @(posedge clk) begin
        if (ce) right_pre <= new_right;
      end
    end
    if (LEFT_DELAY > 1) begin : g_left_shift
      always_ff @(posedge clk) begin
        if (ce) left_history <= {left_history[(LEFT_DELAY-1)*PIXEL_BITS-1:0], new_left};
      end
    end else begin : g_left_single
      always_ff @(posedge clk) begin
        if (ce) left_history <= new_left;
      end
    end
  endgenerate

  // The coordinates of the delayed left pixels: "no pixel" after a reset, like every stage's.
  always_ff @(posedge clk) begin
    if (rst) begin
      for (int i = 0; i < LEFT_DELAY; i++) begin
        left_x_history[i] <= '0;
        left_y_history[i] <= fx_pkg::NO_PIXEL;
      end
    end else if (ce) begin
      left_x_history[0] <= in_x;
      left_y_history[0] <= in_y;
      for (int i = 1; i < LEFT_DELAY; i++) begin
        left_x_history[i] <= left_x_history[i-1];
        left_y_history[i] <= left_y_history[i-1];
      end
    end
  end

  always_ff @(posedge clk) begin
    if (ce) out_data <= cost_d;
  end

  stereo_coord_reg coordinates (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .in_x(left_x),
      .in_y(left_y),
      .out_x(out_x),
      .out_y(out_y)
  );
endmodule

`default_nettype wire
