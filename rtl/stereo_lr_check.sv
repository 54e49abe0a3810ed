// stereo_lr_check: certainty, uniqueness, the left-right consistency check and the output beat
// (model: stereo::ValidatingSelector, stereo::validation::certainty and ::unique,
// docs/fixed-point.md stage 6).
//
// Right-referenced winners along the DSI diagonal. The cost vector of left pixel x (stereo_wta's
// register, acc_*) meets right pixel xr = x - m - k at label k. NDISP accumulators of (cost,
// label) form a shift structure: accumulator j holds right pixel xr = x - m - j and takes
// (E(x, j), j) when E(x, j) is strictly below it (labels arrive in increasing k for one xr, so
// ties keep the smaller label), j < cfg_ndisp, x is a frame pixel and xr lies in [0, W) of x's
// row. Each step the entries move one place; the one leaving place NDISP - 1 is complete: kR of
// xr = x - m - (NDISP - 1), the smallest k minimising E(xr + m + k, k) over the labels whose left
// pixel is in the row. The last NDISP completed labels are kept (hist[i] = kR(xr - i)).
//
// The left results (stereo_validate's register, one pixel behind the accumulators' input) pass
// through a delay line of NDISP - 1 steps; then kR(x - m - k1) = hist[k1]. At the delay line's
// input: the uniqueness test C1 (100 + U) >= C2 100 (no C2: unique) and the certainty
// floor(((C2 - C1) << 8) / (C2 + 1)), whose divider (stereo_divider) is pipelined beside the
// first min(NDISP - 1, 3) places of the delay line, so its rows are split over up to four steps
// at no extra latency (at one label the division stays combinational). At the line's output: the
// left-right test |k1 - kR| > T and the reason, the first failing of border, uniqueness,
// left-right; fixed is 0 where invalid.
// Latency: NDISP pixel steps (the delay line and the output register), which is the output
// register of stereo_top.
`default_nettype none

module stereo_lr_check #(
    parameter int NDISP = 16  // labels in parallel
) (
    input  wire logic                                 clk,
    input  wire logic                                 rst,         // clears the delay line's coordinates
    input  wire logic                                 rst_output,  // clears the output's coordinates
    input  wire logic                                 ce,
    // The cost vector and its pixel (stereo_wta's register).
    input  wire fx_pkg::coord_t                       acc_x,
    input  wire fx_pkg::coord_t                       acc_y,
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0]    acc_data,
    // The left result (stereo_validate's register): the pixel before acc_x in raster order.
    input  wire fx_pkg::coord_t                       in_x,
    input  wire fx_pkg::coord_t                       in_y,
    input  wire logic [fx_pkg::DISP_BITS-1:0]         in_label,
    input  wire logic                                 in_border,
    input  wire logic [fx_pkg::AGG_BITS-1:0]          in_cost,
    input  wire logic [fx_pkg::AGG_BITS-1:0]          in_second,
    input  wire logic signed [fx_pkg::FIXED_BITS-1:0] in_fixed,
    input  wire fx_pkg::cfg_size_t                    cfg_width,
    input  wire fx_pkg::cfg_size_t                    cfg_height,
    input  wire fx_pkg::cfg_ndisp_t                   cfg_ndisp,
    input  wire fx_pkg::cfg_min_disp_t                cfg_min_disp,
    input  wire logic                                 cfg_uniqueness_en,
    input  wire fx_pkg::cfg_uniqueness_t              cfg_uniqueness,
    input  wire logic                                 cfg_lr_en,
    input  wire fx_pkg::cfg_lr_tolerance_t            cfg_lr_tolerance,
    // The pixel entering the output register at this step.
    output      fx_pkg::coord_t                       next_x,
    output      fx_pkg::coord_t                       next_y,
    output      fx_pkg::coord_t                       out_x,
    output      fx_pkg::coord_t                       out_y,
    output      fx_pkg::out_beat_t                    out_beat
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int DELAY = NDISP - 1;  // delay line steps
  localparam int PRODUCT_BITS = BITS + 10;  // C1 * (100 + 255) < 2^23, C2 * 100 < 2^21
  localparam logic [BITS-1:0] UNSET = {BITS{1'b1}};  // above every cost

  // ---- right-referenced winners ---------------------------------------------------------------
  logic [BITS-1:0] acc_cost[NDISP];
  logic [DISP_BITS-1:0] acc_label[NDISP];
  logic [BITS-1:0] next_cost[NDISP];
  logic [DISP_BITS-1:0] next_label[NDISP];
  logic [DISP_BITS-1:0] hist[NDISP];  // hist[i]: kR completed i + 1 steps ago
  logic acc_in_frame;
  assign acc_in_frame = acc_x >= 0 && 32'(acc_x) < $signed(32'(cfg_width)) && acc_y >= 0 &&
                        32'(acc_y) < $signed(32'(cfg_height));
  always_comb begin
    for (int j = 0; j < NDISP; j++) begin
      logic signed [17:0] right_x;  // xr = x - m - j
      logic take;
      logic [BITS-1:0] cost;
      right_x = 18'(acc_x) - 18'(cfg_min_disp) - 18'(j);
      take = acc_in_frame && j < $signed(32'(cfg_ndisp)) && right_x >= 18'sd0 &&
             right_x < $signed(18'(cfg_width));
      cost = acc_data[j*BITS +: BITS];
      if (j == 0) begin
        next_cost[j] = take ? cost : UNSET;
        next_label[j] = '0;
      end else if (take && cost < acc_cost[j-1]) begin
        next_cost[j] = cost;
        next_label[j] = DISP_BITS'(j);
      end else begin
        next_cost[j] = acc_cost[j-1];
        next_label[j] = acc_label[j-1];
      end
    end
  end
  always_ff @(posedge clk) begin
    if (ce) begin
      for (int j = 0; j < NDISP; j++) begin
        acc_cost[j] <= next_cost[j];
        acc_label[j] <= next_label[j];
      end
      hist[0] <= next_label[NDISP-1];
      for (int i = 1; i < NDISP; i++) hist[i] <= hist[i-1];
    end
  end

  // ---- left results: certainty and uniqueness, then the delay line ----------------------------
  // The divider's pipeline runs beside the delay line's first DIVIDER_STAGES - 1 places; its
  // quotient then waits CERTAINTY_DELAY more steps to leave with its pixel.
  localparam int DIVIDER_STAGES = (DELAY < 3 ? DELAY : 3) + 1;
  localparam int CERTAINTY_DELAY = DELAY - (DIVIDER_STAGES - 1);
  logic [fx_pkg::CERTAINTY_BITS-1:0] certainty;  // of the pixel DIVIDER_STAGES - 1 steps in
  stereo_divider #(
      .DIVISOR_BITS (BITS + 1),
      .QUOTIENT_BITS(fx_pkg::CERTAINTY_BITS),
      .STAGES       (DIVIDER_STAGES)
  ) divider (
      .clk(clk),
      .ce(ce),
      .dividend((BITS + 1)'(in_second - in_cost)),
      .divisor((BITS + 1)'(in_second) + (BITS + 1)'(1)),
      .quotient(certainty)
  );
  logic [fx_pkg::CERTAINTY_BITS-1:0] leaving_certainty;
  generate
    if (CERTAINTY_DELAY > 0) begin : g_certainty_delay
      logic [fx_pkg::CERTAINTY_BITS-1:0] certainty_line[CERTAINTY_DELAY];
      always_ff @(posedge clk) begin
        if (ce) begin
          certainty_line[0] <= certainty;
          for (int i = 1; i < CERTAINTY_DELAY; i++) certainty_line[i] <= certainty_line[i-1];
        end
      end
      assign leaving_certainty = certainty_line[CERTAINTY_DELAY-1];
    end else begin : g_certainty_direct
      assign leaving_certainty = certainty;
    end
  endgenerate
  logic not_unique;
  always_comb begin
    logic [PRODUCT_BITS-1:0] scaled_best, scaled_second;
    scaled_best = PRODUCT_BITS'(in_cost) *
                  (PRODUCT_BITS'(fx_pkg::UNIQUENESS_BASE) + PRODUCT_BITS'(cfg_uniqueness));
    scaled_second = PRODUCT_BITS'(in_second) * PRODUCT_BITS'(fx_pkg::UNIQUENESS_BASE);
    not_unique = cfg_uniqueness_en && in_second != BITS'(fx_pkg::NO_SECOND_COST) &&
                 scaled_best >= scaled_second;
  end

  // A left result in the delay line; its coordinates travel beside it in registers of their own
  // (reset to "no pixel"; the data has no reset).
  typedef struct packed {
    logic [DISP_BITS-1:0] label;
    logic border;
    logic not_unique;
    logic signed [fx_pkg::FIXED_BITS-1:0] fixed;
  } result_t;
  localparam int RESULT_BITS = DISP_BITS + 2 + fx_pkg::FIXED_BITS;
  result_t entering, leaving;
  fx_pkg::coord_t leaving_x, leaving_y;
  always_comb begin
    entering.label = in_label;
    entering.border = in_border;
    entering.not_unique = not_unique;
    entering.fixed = in_fixed;
  end

  generate
    if (DELAY > 0) begin : g_delay
      // One flat vector, entry i at [i*RESULT_BITS +: RESULT_BITS] (Yosys 0.23 loses an
      // unpacked array of structs).
      logic [DELAY*RESULT_BITS-1:0] line;
      fx_pkg::coord_t line_x[DELAY];
      fx_pkg::coord_t line_y[DELAY];
      if (DELAY > 1) begin : g_shift
        always_ff @(posedge clk) begin
          if (ce) line <= {line[(DELAY-1)*RESULT_BITS-1:0], entering};
        end
      end else begin : g_single
        always_ff @(posedge clk) begin
          if (ce) line <= entering;
        end
      end
      always_ff @(posedge clk) begin
        if (rst) begin
          for (int i = 0; i < DELAY; i++) begin
            line_x[i] <= '0;
            line_y[i] <= fx_pkg::NO_PIXEL;
          end
        end else if (ce) begin
          line_x[0] <= in_x;
          line_y[0] <= in_y;
          for (int i = 1; i < DELAY; i++) begin
            line_x[i] <= line_x[i-1];
            line_y[i] <= line_y[i-1];
          end
        end
      end
      assign leaving = line[(DELAY-1)*RESULT_BITS +: RESULT_BITS];
      assign leaving_x = line_x[DELAY-1];
      assign leaving_y = line_y[DELAY-1];
    end else begin : g_direct
      assign leaving = entering;
      assign leaving_x = in_x;
      assign leaving_y = in_y;
      // One label: no delay line, whose coordinates rst would clear.
      /* verilator lint_off UNUSEDSIGNAL */
      logic unused_rst;
      /* verilator lint_on UNUSEDSIGNAL */
      assign unused_rst = rst;
    end
  endgenerate

  // ---- the left-right test and the output register ---------------------------------------------
  logic [DISP_BITS-1:0] right_label;  // kR(x - m - k1)
  always_comb begin
    right_label = '0;
    for (int i = 0; i < NDISP; i++) begin
      if (32'(leaving.label) == i) right_label = hist[i];
    end
  end
  fx_pkg::out_beat_t beat;
  always_comb begin
    logic [DISP_BITS-1:0] distance;
    distance = (leaving.label >= right_label) ? leaving.label - right_label
                                              : right_label - leaving.label;
    beat.certainty = leaving_certainty;
    beat.pad = '0;
    if (!leaving.border) beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_BORDER);
    else if (leaving.not_unique) beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_UNIQUENESS);
    else if (cfg_lr_en && 32'(distance) > 32'(cfg_lr_tolerance))
      beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_LEFT_RIGHT);
    else beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_VALID);
    beat.fixed = (beat.reason == fx_pkg::REASON_BITS'(fx_pkg::REASON_VALID)) ? leaving.fixed : '0;
  end
  assign next_x = leaving_x;
  assign next_y = leaving_y;

  always_ff @(posedge clk) begin
    if (ce) out_beat <= beat;
  end
  stereo_coord_reg coordinates (
      .clk(clk),
      .rst(rst_output),
      .ce(ce),
      .in_x(leaving_x),
      .in_y(leaving_y),
      .out_x(out_x),
      .out_y(out_y)
  );
endmodule

`default_nettype wire
