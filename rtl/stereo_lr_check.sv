// stereo_lr_check: certainty, uniqueness, the left-right consistency check and the output beat
// (model: stereo::ValidatingSelector, stereo::validation::certainty and ::unique,
// docs/fixed-point.md stage 6).
//
// Right-referenced winners along the DSI diagonal. The cost vector of left pixel x (stereo_wta's
// register, acc_*) meets right pixel xr = x - m - k at label k. NDISP accumulators of (cost,
// label) form a shift structure: accumulator j holds right pixel xr = x - m - j and takes
// (E(x, j), j) when E(x, j) is strictly below it (labels arrive in increasing k for one xr, so
// ties keep the smaller label), j < cfg.ndisp, x is a frame pixel and xr lies in [0, W) of x's
// row. Each step the entries move one place; the one leaving place NDISP - 1 is complete: kR of
// xr = x - m - (NDISP - 1), the smallest k minimising E(xr + m + k, k) over the labels whose left
// pixel is in the row. The last NDISP completed labels are kept (hist[i] = kR(xr - i)).
//
// The left results (stereo_validate's register, one pixel behind the accumulators' input) pass
// through a delay line of NDISP - 1 steps (a RAM ring); then kR(x - m - k1) = hist[k1]. At the
// delay line's input: the uniqueness test C1 (100 + U) >= C2 100, computed as C1 U >= 100
// (C2 - C1) (signed; no C2: unique), and the certainty floor(((C2 - C1) << 8) / (C2 + 1))
// (stereo_divider). At the line's output: the left-right test |k1 - kR| > T and the reason, the first failing of border,
// uniqueness, left-right; fixed is 0 where invalid.
//
// LANES = NDISP (G = 1): all NDISP accumulators update at the step; the divider is pipelined
// beside the first min(NDISP - 1, 3) places of the delay line (its rows split over up to four
// steps at no extra latency; at one label it stays combinational); the product C1 U is one
// multiplier.
// Time-multiplexed lanes (LANES < NDISP, G = NDISP / LANES, docs/rtl.md): the accumulators are a
// ring of G words of LANES entries (in RAM, stereo_group_ring) that advances one word at each
// clock that processes a group (`ce || group != G-1`); at group g its head word holds accumulators
// [g*LANES +: LANES], LANES lanes compare them (and the previous word's last entry, kept in a
// carry register) with labels [g*LANES +: LANES], acc_group, and the results enter at the tail.
// The costs are those of stereo_wta's input pixel (its input ring's head; the WTA keeps no cost
// vector register), one step ahead of LANES = NDISP, so the completed label, out of the last
// group at the step, is one step early: kR(x - m - k1) = hist[k1 + 1] of NDISP + 1. The divider
// iterates over the G clocks of the step (ceil(8 / G) rows per clock, the last rows at the step clock) and the product
// C1 U takes ceil(8 / G) bits of U per clock, so both are ready at the step as with G = 1.
// Latency: NDISP pixel steps (the delay line and the output register), which is the output
// register of stereo_top.
`default_nettype none
`include "stereo_assert.svh"

module stereo_lr_check #(
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP,  // labels compared per clock (divides NDISP)
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM (stereo_top)
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
    input  wire logic                                 clk,
    input  wire logic                                 rst,         // clears the delay line's coordinates
    input  wire logic                                 rst_output,  // clears the output's coordinates
    input  wire logic                                 ce,  // the pixel step (at group G-1)
    /* verilator lint_off UNUSEDSIGNAL */  // LANES = NDISP: always 0
    input  wire logic [((NDISP / LANES > 1) ? $clog2(NDISP / LANES) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    // The cost vector and its pixel: LANES = NDISP: stereo_wta's register (acc_data);
    // LANES < NDISP: stereo_wta's input, one step ahead, whose group of this clock is acc_group.
    input  wire fx_pkg::coord_t                       acc_x,
    input  wire fx_pkg::coord_t                       acc_y,
    /* verilator lint_off UNUSEDSIGNAL */  // one of the two, by LANES
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0]    acc_data,
    input  wire logic [LANES*fx_pkg::AGG_BITS-1:0]    acc_group,
    /* verilator lint_on UNUSEDSIGNAL */
    // The left result (stereo_validate's register): the pixel before acc_x in raster order.
    input  wire fx_pkg::coord_t                       in_x,
    input  wire fx_pkg::coord_t                       in_y,
    /* verilator lint_off UNUSEDSIGNAL */  // k1 < NDISP: the low LABEL_BITS bits
    input  wire logic [fx_pkg::DISP_BITS-1:0]         in_label,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic                                 in_border,
    input  wire logic [fx_pkg::AGG_BITS-1:0]          in_cost,
    input  wire logic [fx_pkg::AGG_BITS-1:0]          in_second,
    input  wire logic signed [fx_pkg::FIXED_BITS-1:0] in_fixed,
    /* verilator lint_off UNUSEDSIGNAL */  // reads all but radius, use_ca and subpixel_en
    input  wire fx_pkg::config_t                      cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    // The pixel entering the output register at this step.
    output      fx_pkg::coord_t                       next_x,
    output      fx_pkg::coord_t                       next_y,
    output      fx_pkg::coord_t                       out_x,
    output      fx_pkg::coord_t                       out_y,
    output      fx_pkg::out_beat_t                    out_beat
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int LABEL_BITS = (NDISP > 1) ? $clog2(NDISP) : 1;  // labels 0 .. NDISP-1
  localparam int GROUPS = NDISP / LANES;  // clocks per pixel step
  localparam int DELAY = NDISP - 1;  // delay line steps
  localparam int U_BITS = fx_pkg::CFG_UNIQUENESS_BITS;
  localparam int PRODUCT_BITS = BITS + U_BITS + 1;  // signed: C1 U < 2^22, |100 (C2 - C1)| < 2^21
  localparam logic [BITS-1:0] UNSET = {BITS{1'b1}};  // above every cost

  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")

  // The group of this clock; G = 1: 0 whatever the port carries (stage testbenches leave it open).
  /* verilator lint_off UNUSEDSIGNAL */  // G = 1: not needed
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  /* verilator lint_on UNUSEDSIGNAL */
  assign group_now = (GROUPS > 1) ? group : '0;

  // ---- right-referenced winners ---------------------------------------------------------------
  // Lane l of this clock's group takes label j = g*LANES + l: when x is a frame pixel, j is below
  // cfg.ndisp and xr = x - m - j lies in [0, W), i.e. diagonal >= l and diagonal - W < l.
  logic acc_in_frame;
  assign acc_in_frame = acc_x >= 0 && 32'(acc_x) < $signed(32'(cfg.width)) && acc_y >= 0 &&
                        32'(acc_y) < $signed(32'(cfg.height));
  logic signed [17:0] diagonal;  // xr of lane 0: x - m - g*LANES (18-bit signed arithmetic)
  logic signed [17:0] beyond;  // diagonal - W
  assign diagonal = 18'(acc_x) - 18'(cfg.min_disp) - 18'(32'(group_now) * LANES);
  assign beyond = diagonal - $signed(18'(cfg.width));
  logic [LANES-1:0] take;
  logic [LANES*BITS-1:0] lane_cost;  // E(x, g*LANES + l) at [l*BITS +: BITS]
  always_comb begin
    for (int l = 0; l < LANES; l++) begin
      take[l] = acc_in_frame && $signed(32'(group_now) * LANES + l) < $signed(32'(cfg.ndisp)) &&
                diagonal >= $signed(18'(l)) && beyond < $signed(18'(l));
    end
  end
  logic [LABEL_BITS-1:0] completed;  // kR leaving the accumulators at this step
  generate
    if (GROUPS > 1) begin : g_ring
      assign lane_cost = acc_group;  // stereo_wta's multiplexer
      // G words of LANES accumulators (cost, label), a ring in RAM (stereo_group_ring) that
      // advances at each clock that processes a group: at group g its head holds accumulators
      // [g*LANES +: LANES], and the advance stores the group's new accumulators.
      logic advance;
      assign advance = ce || 32'(group_now) != GROUPS - 1;
      logic [LANES*BITS-1:0] head_cost;
      logic [LANES*LABEL_BITS-1:0] head_label;
      logic [BITS-1:0] carry_cost;  // accumulator g*LANES - 1 (the previous word's last)
      logic [LABEL_BITS-1:0] carry_label;
      logic [LANES*BITS-1:0] new_cost;
      logic [LANES*LABEL_BITS-1:0] new_label;
      stereo_group_ring #(
          .BITS     (LANES * (BITS + LABEL_BITS)),
          .GROUPS   (GROUPS),
          .BLOCK_RAM(RING_BLOCK_RAM),
          .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) accumulators (
          .clk(clk),
          .advance(advance),
          .next_state({new_label, new_cost}),
          .head({head_label, head_cost})
      );
      always_comb begin
        for (int l = 0; l < LANES; l++) begin
          logic [BITS-1:0] previous_cost;  // accumulator j - 1 (accumulator 0: a fresh one)
          logic [LABEL_BITS-1:0] previous_label;
          if (l == 0) begin
            previous_cost = (group_now == '0) ? UNSET : carry_cost;
            previous_label = (group_now == '0) ? '0 : carry_label;
          end else begin
            previous_cost = head_cost[(l-1)*BITS +: BITS];
            previous_label = head_label[(l-1)*LABEL_BITS +: LABEL_BITS];
          end
          if (take[l] && lane_cost[l*BITS +: BITS] < previous_cost) begin
            new_cost[l*BITS +: BITS] = lane_cost[l*BITS +: BITS];
            new_label[l*LABEL_BITS +: LABEL_BITS] = LABEL_BITS'(32'(group_now) * LANES + l);
          end else begin
            new_cost[l*BITS +: BITS] = previous_cost;
            new_label[l*LABEL_BITS +: LABEL_BITS] = previous_label;
          end
        end
      end
      always_ff @(posedge clk) begin
        if (advance) begin
          carry_cost <= head_cost[(LANES-1)*BITS +: BITS];
          carry_label <= head_label[(LANES-1)*LABEL_BITS +: LABEL_BITS];
        end
      end
      assign completed = new_label[(LANES-1)*LABEL_BITS +: LABEL_BITS];
    end else begin : g_parallel
      assign lane_cost = acc_data;
      logic [BITS-1:0] acc_cost[NDISP];
      logic [LABEL_BITS-1:0] acc_label[NDISP];
      logic [BITS-1:0] next_cost[NDISP];
      logic [LABEL_BITS-1:0] next_label[NDISP];
      always_comb begin
        for (int j = 0; j < NDISP; j++) begin
          logic [BITS-1:0] cost;
          cost = lane_cost[j*BITS +: BITS];
          if (j == 0) begin
            next_cost[j] = take[j] ? cost : UNSET;
            next_label[j] = '0;
          end else if (take[j] && cost < acc_cost[j-1]) begin
            next_cost[j] = cost;
            next_label[j] = LABEL_BITS'(j);
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
        end
      end
      assign completed = next_label[NDISP-1];
    end
  endgenerate
  // hist[i]: kR completed i + 1 steps ago. With LANES < NDISP the accumulators run one step
  // ahead, so kR(x - m - k1) is hist[k1 + 1] of NDISP + 1 (AHEAD = 1).
  localparam int AHEAD = (GROUPS > 1) ? 1 : 0;
  logic [LABEL_BITS-1:0] hist[NDISP+AHEAD];
  always_ff @(posedge clk) begin
    if (ce) begin
      hist[0] <= completed;
      for (int i = 1; i < NDISP + AHEAD; i++) hist[i] <= hist[i-1];
    end
  end

  // ---- left results: certainty and uniqueness, then the delay line ----------------------------
  // G = 1: the divider's pipeline runs beside the delay line's first DIVIDER_STAGES - 1 places;
  // G > 1: it iterates over the step's clocks, done at the step. Its quotient then waits
  // CERTAINTY_DELAY more steps to leave with its pixel.
  localparam int DIVIDER_STAGES = (GROUPS > 1) ? 1 : (DELAY < 3 ? DELAY : 3) + 1;
  localparam int CERTAINTY_DELAY = DELAY - (DIVIDER_STAGES - 1);
  logic [fx_pkg::CERTAINTY_BITS-1:0] certainty;  // of the pixel DIVIDER_STAGES - 1 steps in
  stereo_divider #(
      .DIVISOR_BITS (BITS + 1),
      .QUOTIENT_BITS(fx_pkg::CERTAINTY_BITS),
      .STAGES       (DIVIDER_STAGES),
      .CLOCKS       (GROUPS)
  ) divider (
      .clk(clk),
      .ce(ce),
      .index(group_now),
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

  // Uniqueness: C1 (100 + U) >= 100 C2 <=> C1 U >= 100 (C2 - C1) (signed, exact).
  logic [PRODUCT_BITS-1:0] scaled_best;  // C1 U
  generate
    if (GROUPS > 1) begin : g_product_iterative
      // Horner over U's bits, most significant first, CHUNK bits per clock from group 0 on.
      localparam int CHUNK = (U_BITS + GROUPS - 1) / GROUPS;
      localparam int CHUNKS = (U_BITS + CHUNK - 1) / CHUNK;
      logic [CHUNKS*CHUNK-1:0] factor;
      logic [PRODUCT_BITS-1:0] partial;  // registered: the chunks of the clocks before
      logic [CHUNK-1:0] chunk;
      assign factor = (CHUNKS * CHUNK)'(cfg.uniqueness);
      always_comb begin
        chunk = '0;
        for (int c = 0; c < CHUNKS; c++) begin
          if (32'(group_now) == c) chunk = factor[(CHUNKS-1-c)*CHUNK +: CHUNK];
        end
        if (32'(group_now) >= CHUNKS) scaled_best = partial;
        else
          scaled_best = (((group_now == '0) ? '0 : partial) << CHUNK) +
                        PRODUCT_BITS'(in_cost) * PRODUCT_BITS'(chunk);
      end
      always_ff @(posedge clk) begin
        if (ce || 32'(group_now) != GROUPS - 1) partial <= scaled_best;
      end
    end else begin : g_product
      assign scaled_best = PRODUCT_BITS'(in_cost) * PRODUCT_BITS'(cfg.uniqueness);
    end
  endgenerate
  logic not_unique;
  always_comb begin
    logic signed [PRODUCT_BITS-1:0] scaled_margin;  // 100 (C2 - C1)
    scaled_margin = (PRODUCT_BITS'(in_second) - PRODUCT_BITS'(in_cost)) *
                    PRODUCT_BITS'(fx_pkg::UNIQUENESS_BASE);
    not_unique = cfg.uniqueness_en && in_second != BITS'(fx_pkg::NO_SECOND_COST) &&
                 $signed(scaled_best) >= scaled_margin;
  end

  // A left result in the delay line; its coordinates travel beside it in registers of their own
  // (reset to "no pixel"; the data has no reset).
  typedef struct packed {
    logic [LABEL_BITS-1:0] label;  // k1 < NDISP
    logic border;
    logic not_unique;
    logic signed [fx_pkg::FIXED_BITS-1:0] fixed;
  } result_t;
  localparam int RESULT_BITS = LABEL_BITS + 2 + fx_pkg::FIXED_BITS;
  result_t entering, leaving;
  fx_pkg::coord_t leaving_x, leaving_y;
  always_comb begin
    entering.label = LABEL_BITS'(in_label);
    entering.border = in_border;
    entering.not_unique = not_unique;
    entering.fixed = in_fixed;
  end

  generate
    if (DELAY > 0) begin : g_delay
      // DELAY steps of results and their coordinates, a ring in RAM (stereo_group_ring, one word
      // a step; block RAM on the iCE40, LUT RAM elsewhere from 8 steps on) instead of a shift
      // register. A RAM cannot be reset, so the "no pixel" that a reset (or the end-of-frame
      // clear) puts into the whole line comes from a count of the steps since: until DELAY
      // steps have entered, what leaves is not a pixel, as the cleared registers were.
      localparam int COUNT_BITS = $clog2(DELAY + 1);
      logic [COUNT_BITS-1:0] filled;  // steps entered since rst, up to DELAY
      logic [RESULT_BITS-1:0] head_result;
      fx_pkg::coord_t head_x, head_y;
      stereo_group_ring #(
          .BITS     (RESULT_BITS + 2 * fx_pkg::COORD_BITS),
          .GROUPS   (DELAY),
          .BLOCK_RAM(RING_BLOCK_RAM),
          .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) line (
          .clk(clk),
          .advance(ce),
          .next_state({entering, in_x, in_y}),
          .head({head_result, head_x, head_y})
      );
      always_ff @(posedge clk) begin
        if (rst) filled <= '0;
        else if (ce && 32'(filled) != DELAY) filled <= filled + 1'b1;
      end
      assign leaving = head_result;
      assign leaving_x = (32'(filled) == DELAY) ? head_x : '0;
      assign leaving_y = (32'(filled) == DELAY) ? head_y : fx_pkg::NO_PIXEL;
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
  logic [LABEL_BITS-1:0] right_label;  // kR(x - m - k1)
  always_comb begin
    right_label = '0;
    for (int i = 0; i < NDISP; i++) begin
      if (32'(leaving.label) == i) right_label = hist[i+AHEAD];
    end
  end
  fx_pkg::out_beat_t beat;
  always_comb begin
    logic [LABEL_BITS-1:0] distance;
    distance = (leaving.label >= right_label) ? leaving.label - right_label
                                              : right_label - leaving.label;
    beat.certainty = leaving_certainty;
    beat.pad = '0;
    if (!leaving.border) beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_BORDER);
    else if (leaving.not_unique) beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_UNIQUENESS);
    else if (cfg.lr_en && 32'(distance) > 32'(cfg.lr_tolerance))
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
