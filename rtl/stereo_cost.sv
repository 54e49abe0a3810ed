// stereo_cost: the matching cost over the signed disparity range d = m + k, k = 0 .. NDISP-1,
// m = cfg.min_disp (model: stereo::cost and the cost plug-ins, docs/fixed-point.md stages 1 and 6,
// "LCDM"). COST_AD: absolute differences over RGB; COST_LCDM: the LCDM cost (thesis Sec. 3.5),
// each incoming pixel first converted to its point on the hue-saturation disc
// (stereo_lcdm_convert), the per-label distance by stereo_lcdm_distance; COST_CENSUS: the census
// cost, in_left and in_right being census codes (stereo_census in front), the Hamming distance
// times CENSUS_WEIGHT.
// Below, "pixel" is what the delay lines carry: RGB or a census code (24 bits) or the LCDM point
// (22 bits).
//
// The right pixels pass through continuous delay lines (across row boundaries). For a negative m
// the left pixel must wait for right pixels that arrive later: it is delayed (with its
// coordinates) by K = max(0, -m) steps. The right sample of label k sits k + P positions behind
// the newest right pixel, P = max(m, 0): one multiplexer picks the right pixel P steps old from a
// pre-delay line of MAX_MIN_DISP, and the lanes' delay line holds its history (a lane reading a
// value picked under the previous frame's P reads a position before the frame, which is
// outside). The cost of label k is
//   |Lr - Rr(xr)| + |Lg - Rg(xr)| + |Lb - Rb(xr)|  (AD),  lcdm(L, R(xr))  (LCDM)  or
//   popcount(L ^ R(xr)) * CENSUS_WEIGHT  (census),  xr = x - m - k,
// or COST_OUTSIDE where xr lies outside [0, W): exactly where the tap holds a pixel of another
// row (or none), so nothing is ever cleared. cfg.min_disp must stay within +-MAX_MIN_DISP
// (stereo_top clamps it) and constant during a frame and its flush.
//
// LANES = NDISP (the all-parallel stage): NDISP distance units compute every label at the step
// from the selected right pixel and a history of NDISP - 1; out_data (all labels) is registered.
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): the register is in front of the
// arithmetic. The step registers the matched left pixel, its coordinates and the selected right
// pixel into a history of NDISP (label k's right pixel at entry k); during the clock of label
// group g (`group` from stereo_top, 0 .. G-1, G = NDISP / LANES; the step, ce, comes at G-1)
// LANES distance units compute labels [g*LANES +: LANES] combinationally from the head of the
// history, a ring of G words of LANES entries (stereo_group_ring: LUT or block RAM, no G:1
// multiplexer per lane), and out_data carries that group only (LANES costs). The stage's
// output is thus the same pixel's costs between two steps as with LANES = NDISP.
// CENSUS_CODES = 1 (census only; what stereo_top sets for its aggregation): each label's field
// carries the census code instead, the distance or CENSUS_CODE_OUTSIDE where xr lies outside,
// zero-extended to COST_BITS (stereo_aggregate's narrow line buffer, docs/rtl.md "Census codes").
// ROWS > 1 (census codes or AD; stereo_top RECOMPUTE_COSTS, docs/rtl.md "Lean memory"): the stage
// keeps a line buffer of ROWS - 1 rows of both images' census codes or RGB pixels (48 bits a
// column, whatever the label count) and the delay lines carry column stacks of ROWS of them (rows
// in_y - ROWS + 1 .. in_y of one column) instead of single ones; each label's field then holds
// ROWS codes (costs), row j (in_y - ROWS + 1 + j) at [j*COST_BITS +: COST_BITS], so the
// aggregation's vertical pass needs no per-label line buffer: memory grows with the width, not
// with the label count.
// RAW_BITS > 0 (the adaptive-support-weight core, stereo_top ASW = 1): the delay lines carry
// in_left_raw / in_right_raw (RAW_BITS each: a column of codes and its responses) instead of the
// pixels, no distance is computed (out_data is 0) and the stage hands on the raw words as it
// would the pixels it compares: out_left_raw, the left word of (out_x, out_y), and
// out_right_raw, lane l's right word (label group*LANES + l's right column x - m - k; G = 1: all
// labels), registered (G = 1) or of this clock's group (G > 1) like out_data.
// Latency: 1 + K pixel steps. Throughput: one pixel per ce.
`default_nettype none
`include "stereo_assert.svh"

module stereo_cost #(
    parameter int NDISP        = 16,                           // labels
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,  // largest |cfg.min_disp|
    parameter fx_pkg::cost_e COST = fx_pkg::COST_AD,  // COST_AD, COST_LCDM or COST_CENSUS
    parameter int LANES        = NDISP,  // labels computed per clock (divides NDISP)
    parameter bit CENSUS_CODES = 1'b0,  // census: the code (distance or outside) per label
    // Rows of codes (AD: costs) per label, above 1 only with CENSUS_CODES or COST_AD: the
    // aggregation's vertical window, recomputed from a line buffer of the image rows (above);
    // WIDTH sizes that buffer.
    parameter int ROWS  = 1,
    parameter int WIDTH = 64,  // longest row (ROWS > 1 only)
    // LANES < NDISP: the right history's ring (stereo_group_ring BLOCK_RAM, BLOCK_MIN_FILL)
    parameter bit RING_BLOCK_RAM = 1'b0,
    parameter int RING_BLOCK_MIN_FILL = 50,
    // > 0: the delay lines carry the raw words of that many bits (above); ROWS must be 1.
    parameter int RAW_BITS = 0
) (
`include "stereo_stage_ports.svh"
    /* verilator lint_off UNUSEDSIGNAL */  // RAW_BITS > 0: the raw words instead
    input  wire logic [23:0]                        in_left,       // {R, G, B} or census code
    input  wire logic [23:0]                        in_right,      // {R, G, B} or census code
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_off UNUSEDSIGNAL */  // reads width and min_disp only
    input  wire fx_pkg::config_t                    cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    // The row out_y takes at this step (the coordinate register's input): the aggregation
    // computes its row flags a step ahead from it (stereo_aggregate in_next_y).
    output      fx_pkg::coord_t                     out_next_y,
    // LANES = NDISP: all labels, registered; else labels [group*LANES +: LANES], combinational.
    // Label l's field is ROWS * COST_BITS wide (ROWS > 1: one code per row, above).
    output      logic [LANES*ROWS*fx_pkg::COST_BITS-1:0] out_data,
    // RAW_BITS > 0 only (else unused, and 0): the words the delay lines carry.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire logic [((RAW_BITS > 0) ? RAW_BITS : 1)-1:0]          in_left_raw,
    input  wire logic [((RAW_BITS > 0) ? RAW_BITS : 1)-1:0]          in_right_raw,
    /* verilator lint_on UNUSEDSIGNAL */
    output      logic [((RAW_BITS > 0) ? RAW_BITS : 1)-1:0]          out_left_raw,
    output      logic [LANES*((RAW_BITS > 0) ? RAW_BITS : 1)-1:0]    out_right_raw
);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int PIXEL_BITS = (RAW_BITS > 0) ? RAW_BITS
                             : (COST == fx_pkg::COST_LCDM) ? 2 * fx_pkg::LCDM_COORD_BITS
                             : ROWS * fx_pkg::RGB_BITS;
  localparam int LANE_BITS = ROWS * COST_BITS;  // one label's output field
  localparam int GROUPS = NDISP / LANES;  // clocks per pixel step
  localparam int CENSUS_SHIFT = $clog2(fx_pkg::CENSUS_WEIGHT + 1);
  localparam int CENSUS_BELOW = (1 << CENSUS_SHIFT) - fx_pkg::CENSUS_WEIGHT;
  // What a label whose right pixel lies outside [0, W) gets.
  localparam logic [COST_BITS-1:0] OUTSIDE = (COST == fx_pkg::COST_CENSUS && CENSUS_CODES)
      ? COST_BITS'(fx_pkg::CENSUS_CODE_OUTSIDE) : COST_BITS'(fx_pkg::COST_OUTSIDE);
  // Right pixels kept: the pre-delay line, and the lanes' history (LANES = NDISP: NDISP - 1
  // besides the selected pixel; else a ring of NDISP, below).
  localparam int PRE_DELAY = (MAX_MIN_DISP > 0) ? MAX_MIN_DISP : 1;
  localparam int LEFT_DELAY = (MAX_MIN_DISP > 0) ? MAX_MIN_DISP : 1;  // left pixels kept
  localparam int SHIFT_BITS = $clog2(MAX_MIN_DISP + 1) + 1;

  `STEREO_ASSERT(max_min_disp_range,
                 MAX_MIN_DISP >= 0 && MAX_MIN_DISP <= fx_pkg::MAX_MIN_DISPARITY,
                 "MAX_MIN_DISP must be 0 .. MAX_MIN_DISPARITY")
  `STEREO_ASSERT(cost_known,
                 COST == fx_pkg::COST_AD || COST == fx_pkg::COST_LCDM ||
                     COST == fx_pkg::COST_CENSUS,
                 "COST must be COST_AD, COST_LCDM or COST_CENSUS")
  `STEREO_ASSERT(census_codes_cost, !CENSUS_CODES || COST == fx_pkg::COST_CENSUS,
                 "CENSUS_CODES = 1 needs COST = COST_CENSUS")
  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")
  // Row stacks: census codes (CENSUS_CODES) or RGB (AD); not LCDM, whose points are computed
  // in front of the delay lines.
  `STEREO_ASSERT(rows_cost, ROWS >= 1 && (ROWS == 1 || CENSUS_CODES || COST == fx_pkg::COST_AD),
                 "ROWS must be at least 1, and 1 unless the stage carries census codes or AD")
  `STEREO_ASSERT(raw_rows, RAW_BITS >= 0 && (RAW_BITS == 0 || ROWS == 1),
                 "RAW_BITS must be at least 0, and ROWS 1 when it is above 0")

  // The pixels the delay lines carry.
  logic [PIXEL_BITS-1:0] new_left, new_right;
  generate
    if (RAW_BITS > 0) begin : g_raw_words
      assign new_left  = in_left_raw;
      assign new_right = in_right_raw;
    end else if (COST == fx_pkg::COST_LCDM) begin : g_lcdm_points
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
    end else if (ROWS > 1) begin : g_row_stacks
      // Rows in_y - ROWS + 1 .. in_y of both codes (RGB) at column in_x, from a line buffer (read
      // a step ahead); row j is in_y - ROWS + 1 + j, the incoming one last.
      localparam int PAIR_BITS = 2 * fx_pkg::RGB_BITS;  // {right, left}
      logic [ROWS*PAIR_BITS-1:0] stacked;  // row in_y - ROWS + 1 + j at slot j
      stereo_row_stack #(.WIDTH(WIDTH), .DATA_BITS(PAIR_BITS), .ROWS(ROWS)) code_rows (
          .clk(clk), .ce(ce), .in_x(in_x), .cfg_width(cfg.width), .in_data({in_right, in_left}),
          .column(stacked));
      for (genvar j = 0; j < ROWS; j++) begin : g_row
        assign new_left[j*24 +: 24] = stacked[j*PAIR_BITS +: 24];
        assign new_right[j*24 +: 24] = stacked[j*PAIR_BITS + 24 +: 24];
      end
    end else begin : g_rgb  // or the census codes
      assign new_left  = in_left;
      assign new_right = in_right;
    end
  endgenerate

  // right_pre[i*PIXEL_BITS +: PIXEL_BITS] = the right pixel i + 1 steps before the newest.
  logic [PRE_DELAY*PIXEL_BITS-1:0] right_pre;
  // The left pixel and its coordinates, i + 1 steps ago.
  logic [LEFT_DELAY*PIXEL_BITS-1:0] left_history;
  fx_pkg::coord_t left_x_history[LEFT_DELAY];
  fx_pkg::coord_t left_y_history[LEFT_DELAY];

  // K = max(0, -m) and P = max(m, 0), both within 0 .. MAX_MIN_DISP.
  logic [SHIFT_BITS-1:0] left_wait, right_skip;
  always_comb begin
    left_wait = '0;
    right_skip = '0;
    if (cfg.min_disp < 0) left_wait = SHIFT_BITS'(-cfg.min_disp);
    else right_skip = SHIFT_BITS'(cfg.min_disp);
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

  function automatic logic [COST_BITS-1:0] census_count(input logic [23:0] a,
                                                        input logic [23:0] b);
    logic [23:0] differ;
    differ = a ^ b;
    census_count = '0;
    for (int i = 0; i < fx_pkg::CENSUS_BITS; i++) census_count = census_count + COST_BITS'(differ[i]);
  endfunction

  function automatic logic [COST_BITS-1:0] census_distance(input logic [23:0] a,
                                                           input logic [23:0] b);
    logic [COST_BITS-1:0] count;
    count = census_count(a, b);
    // count * CENSUS_WEIGHT as count * 2^k - count * (2^k - CENSUS_WEIGHT), 2^k the power of two
    // above the weight (31 = 32 - 1: a shift and a subtraction), so no multiplier or DSP block.
    census_distance = (count << CENSUS_SHIFT) - count * COST_BITS'(CENSUS_BELOW);
  endfunction

  // What the LANES distance units compare: the left pixel, each lane's right pixel, and each
  // lane's xr + l (lane l's xr is lane_base_x - l).
  logic [PIXEL_BITS-1:0] lane_left;
  logic [LANES*PIXEL_BITS-1:0] lane_right;
  logic signed [17:0] lane_base_x;
  generate
    if (GROUPS > 1) begin : g_lanes
      // The pixels of the last step: the left pixel, and the selected right pixel (label 0's
      // right pixel, entry 0 of the history; label k's at entry k).
      logic [PIXEL_BITS-1:0] left_q, right_q;
      always_ff @(posedge clk) begin
        if (ce) begin
          left_q <= left_pixel;
          right_q <= right_selected;
        end
      end
      assign lane_left = left_q;
      // xr = x - m - k with the registered coordinates, k = group*LANES + l.
      assign lane_base_x = 18'(out_x) - 18'(cfg.min_disp) - 18'(32'(group) * LANES);
      // The history as a ring of G words of LANES entries (stereo_group_ring, block or LUT RAM):
      // the word at the head in the clock of group g holds entries [g*LANES +: LANES], so the
      // lanes read it without a multiplexer. At each advance the head's word moves one entry up
      // (the entries of the next step) and takes the previous group's last entry (`carry`) as its
      // first; the first entry of group 0 is the next step's right pixel, which is not there yet:
      // it is right_q, put in when group 0 is read. A reset in the middle of a round rotates the
      // ring against the group count, which only moves entries registered before the reset
      // (pixels before any frame pixel of their row, outside for every label).
      localparam int WORD_BITS = LANES * PIXEL_BITS;
      logic [WORD_BITS-1:0] head, word, next_word;
      logic [PIXEL_BITS-1:0] carry;  // the last entry of the group read at the previous advance
      logic advance;  // a clock that processes a group
      assign advance = ce || 32'(group) != GROUPS - 1;
      always_comb begin
        word = head;
        if (32'(group) == 0) word[0+:PIXEL_BITS] = right_q;
      end
      assign lane_right = word;
      if (LANES > 1) begin : g_shift_word
        assign next_word = {word[0+:(LANES-1)*PIXEL_BITS], carry};
      end else begin : g_one_entry
        assign next_word = carry;
      end
      always_ff @(posedge clk) begin
        if (advance) carry <= word[(LANES-1)*PIXEL_BITS+:PIXEL_BITS];
      end
      stereo_group_ring #(
          .BITS(WORD_BITS),
          .GROUPS(GROUPS),
          .BLOCK_RAM(RING_BLOCK_RAM),
          .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) history_ring (
          .clk(clk),
          .advance(advance),
          .next_state(next_word),
          .head(head)
      );
    end else begin : g_parallel
      assign lane_left = left_pixel;
      assign lane_base_x = 18'(left_x) - 18'(cfg.min_disp);
      // Tap k + P behind the newest right pixel: k behind the selected one.
      if (NDISP > 1) begin : g_history
        // right_history[i*PIXEL_BITS +: PIXEL_BITS] = the selected right pixel i + 1 steps ago.
        logic [(NDISP-1)*PIXEL_BITS-1:0] right_history;
        stereo_shift_reg #(
            .BITS (PIXEL_BITS),
            .DEPTH(NDISP - 1)
        ) right_delay (
            .in_data(right_selected),
            .history(right_history),
            .*
        );
        assign lane_right = {right_history, right_selected};
      end else begin : g_selected
        assign lane_right = right_selected;
      end
    end
  endgenerate

  /* verilator lint_off UNUSEDSIGNAL */  // RAW_BITS > 0: not handed on
  logic [LANES*LANE_BITS-1:0] cost_d;
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    for (genvar l = 0; l < LANES; l++) begin : g_label
      logic signed [17:0] right_x;  // xr
      logic [LANE_BITS-1:0] distance;
      assign right_x = lane_base_x - 18'(l);
      if (RAW_BITS > 0) begin : g_raw  // the words are handed on, not compared
        assign distance = '0;
      end else if (ROWS > 1 && CENSUS_CODES) begin : g_census_rows  // one code per row
        for (genvar j = 0; j < ROWS; j++) begin : g_row
          assign distance[j*COST_BITS +: COST_BITS] =
              census_count(lane_left[j*24 +: 24], lane_right[l*PIXEL_BITS + j*24 +: 24]);
        end
      end else if (ROWS > 1) begin : g_ad_rows  // COST_AD: one cost per row
        for (genvar j = 0; j < ROWS; j++) begin : g_row
          assign distance[j*COST_BITS +: COST_BITS] =
              abs_diff_rgb(lane_left[j*24 +: 24], lane_right[l*PIXEL_BITS + j*24 +: 24]);
        end
      end else if (COST == fx_pkg::COST_LCDM) begin : g_lcdm
        stereo_lcdm_distance lcdm (
            .in_left (lane_left),
            .in_right(lane_right[l*PIXEL_BITS +: PIXEL_BITS]),
            .out_cost(distance)
        );
      end else if (COST == fx_pkg::COST_CENSUS && CENSUS_CODES) begin : g_census_code
        assign distance =
            census_count(24'(lane_left), 24'(lane_right[l*PIXEL_BITS +: PIXEL_BITS]));
      end else if (COST == fx_pkg::COST_CENSUS) begin : g_census  // PIXEL_BITS = 24
        assign distance =
            census_distance(24'(lane_left), 24'(lane_right[l*PIXEL_BITS +: PIXEL_BITS]));
      end else begin : g_ad  // PIXEL_BITS = 24 here
        assign distance = abs_diff_rgb(24'(lane_left), 24'(lane_right[l*PIXEL_BITS +: PIXEL_BITS]));
      end
      // Outside: every row's field (a column is outside for all its rows).
      assign cost_d[l*LANE_BITS +: LANE_BITS] =
          (right_x < 18'sd0 || right_x >= $signed(18'(cfg.width))) ? {ROWS{OUTSIDE}} : distance;
    end
  endgenerate

  stereo_shift_reg #(
      .BITS (PIXEL_BITS),
      .DEPTH(PRE_DELAY)
  ) right_pre_delay (
      .in_data(new_right),
      .history(right_pre),
      .*
  );
  stereo_shift_reg #(
      .BITS (PIXEL_BITS),
      .DEPTH(LEFT_DELAY)
  ) left_delay (
      .in_data(new_left),
      .history(left_history),
      .*
  );

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

  assign out_next_y = left_y;
  // G > 1: this clock's group of the registered pixel; G = 1: the output register.
  generate
    if (RAW_BITS > 0) begin : g_raw_outputs
      logic [(LANES+1)*PIXEL_BITS-1:0] raw_out;
      stereo_stage_output #(.BITS((LANES + 1) * PIXEL_BITS), .REGISTERED(GROUPS == 1)) outputs (
          .in_x(left_x), .in_y(left_y), .in_data({lane_left, lane_right}), .out_data(raw_out),
          .*);
      assign {out_left_raw, out_right_raw} = raw_out;
      assign out_data = '0;
    end else begin : g_cost_outputs
      stereo_stage_output #(.BITS(LANES * LANE_BITS), .REGISTERED(GROUPS == 1)) outputs (
          .in_x(left_x), .in_y(left_y), .in_data(cost_d), .*);
      assign out_left_raw = '0;
      assign out_right_raw = '0;
    end
  endgenerate

endmodule

`default_nettype wire
