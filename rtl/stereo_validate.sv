// stereo_validate: the second cost and the sub-pixel disparity of a pixel (model:
// stereo::ValidatingSelector and stereo::validation::subpixel_offset, docs/fixed-point.md
// stage 6), from stereo_wta's registered winner and cost vector.
//
//   C2 = min { E(k) : |k - k1| > 1, k < cfg.ndisp }: LANES = NDISP: a second comparator tree
//        whose leaves are masked by the winner; a masked leaf holds all ones = NO_SECOND_COST,
//        which is what the tree yields when no label lies away from the winner. LANES < NDISP
//        (time-multiplexed lanes, docs/rtl.md): stereo_wta computes C2 while it scans the label
//        groups (in_second); in_data is unused and this stage has no comparator tree. NDISP <= 2:
//        no label can lie away from the winner, so C2 is the constant NO_SECOND_COST (not even
//        registered: stereo_lr_check's certainty divider then folds into a shift).
//   fixed = 16 (m + k1) + offset, offset = sign(a - b) CORRECTION[p],
//        p = floor((16 |a - b| + den) / (2 den)), a = E(k1 - 1), b = E(k1 + 1),
//        den = a + b - 2 C1 > 0, when cfg.subpixel_en and 0 < k1 < cfg.ndisp - 1; else 0. Since
//        p <= 8 (den >= |a - b|), a 4-bit restoring division of 16 |a - b| + den by 2 den (four
//        subtractors) gives it; CORRECTION is the 9-entry table fx_pkg::subpixel_correction.
//        No offset where a or b is ASW_NO_CANDIDATE (the ASW core's excluded labels).
// Latency: 1 pixel step.
`default_nettype none
`include "stereo_assert.svh"

module stereo_validate #(
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP  // labels per clock upstream (< NDISP: C2 comes as in_second)
) (
    input  wire logic                               clk,
    input  wire logic                               rst,  // clears coordinates only
    input  wire logic                               ce,
    input  wire fx_pkg::coord_t                     in_x,
    input  wire fx_pkg::coord_t                     in_y,
    input  wire logic [fx_pkg::DISP_BITS-1:0]       in_label,   // k1
    input  wire logic                               in_border,  // the border rule holds
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_cost,    // C1
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_before,  // E(k1 - 1)
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_after,   // E(k1 + 1)
    /* verilator lint_off UNUSEDSIGNAL */  // LANES < NDISP: in_data; LANES = NDISP: in_second
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0]  in_data,    // E(0 .. NDISP-1)
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_second,  // C2 from stereo_wta
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_off UNUSEDSIGNAL */  // reads ndisp, min_disp and subpixel_en only
    input  wire fx_pkg::config_t                    cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]       out_label,
    output      logic                               out_border,
    output      logic [fx_pkg::AGG_BITS-1:0]        out_cost,    // C1
    output      logic [fx_pkg::AGG_BITS-1:0]        out_second,  // C2
    output      logic signed [fx_pkg::FIXED_BITS-1:0] out_fixed  // 16 d + offset
);
  localparam int BITS = fx_pkg::AGG_BITS;

  // A masked leaf of the comparator tree (all ones) is "no second cost".
  `STEREO_ASSERT(no_second_cost_all_ones, fx_pkg::NO_SECOND_COST == (1 << BITS) - 1,
                 "NO_SECOND_COST must be all ones in AGG_BITS")

  // ---- C2: the minimum over labels away from the winner --------------------------------------
  logic [BITS-1:0] second;
  generate
    if (NDISP <= 2) begin : g_no_second
      // No label lies away from the winner: C2 is a constant (no register, so that stage 6's
      // certainty divider folds into a shift).
      assign second = BITS'(fx_pkg::NO_SECOND_COST);
    end else if (LANES < NDISP) begin : g_streamed
      assign second = in_second;
    end else begin : g_tree
      localparam int LEVELS = (NDISP > 1) ? $clog2(NDISP) : 1;
      localparam int LEAVES = 1 << LEVELS;
      localparam int NODES = 2 * LEAVES - 1;
      logic [NODES*BITS-1:0] node  /*verilator split_var*/;
      for (genvar k = 0; k < LEAVES; k++) begin : g_leaf
        if (k < NDISP) begin : g_label
          logic away;  // |k - k1| > 1
          assign away = (k + 1 < $signed(32'(in_label))) || (k > $signed(32'(in_label)) + 1);
          assign node[(LEAVES-1+k)*BITS +: BITS] =
              // A shift, not a part-select: Verilator's lint of several tops at once (different
              // NDISP) checks this select against another instance's width.
              (away && k < $signed(32'(cfg.ndisp))) ? BITS'(in_data >> (k * BITS))
                                                     : BITS'(fx_pkg::NO_SECOND_COST);
        end else begin : g_padding
          assign node[(LEAVES-1+k)*BITS +: BITS] = BITS'(fx_pkg::NO_SECOND_COST);
        end
      end
      for (genvar n = 0; n < LEAVES - 1; n++) begin : g_node
        assign node[n*BITS +: BITS] =
            (node[(2*n+1)*BITS +: BITS] <= node[(2*n+2)*BITS +: BITS])
                ? node[(2*n+1)*BITS +: BITS] : node[(2*n+2)*BITS +: BITS];
      end
      assign second = node[0 +: BITS];
    end
  endgenerate

  // ---- sub-pixel offset: a 4-bit restoring division -------------------------------------------
  // steps = floor(n / (2 den)), n = 16 |a - b| + den, is at most 8 (den >= |a - b|): four rows of
  // long division, row r (3 .. 0) bringing down bit r of n into the partial remainder (below
  // 2 den before, so below 4 den after) and taking 2 den from it where it fits (steps bit r).
  localparam int NUM_BITS = BITS + fx_pkg::SUBPIXEL_BITS + 2;  // n < 17 * 2^15
  localparam int ROW_BITS = BITS + 3;  // 2 (2 den) <= 8 (2^14 - 1)
  logic signed [fx_pkg::FIXED_BITS-1:0] fixed;
  always_comb begin
    logic [BITS+1:0] forward;           // a - b, two's complement
    logic a_below_b;
    logic [BITS:0] difference;          // |a - b|
    logic [BITS+1:0] denominator;       // a + b - 2 C1 >= 0
    logic [NUM_BITS-1:0] numerator;     // n
    logic [ROW_BITS-1:0] partial, twice_denominator;
    logic [ROW_BITS:0] difference_row;
    logic [fx_pkg::SUBPIXEL_BITS-1:0] steps;
    logic refine;
    // a - b with its borrow: the borrow says b > a (one subtractor instead of a comparator).
    forward = {2'b00, in_before} - {2'b00, in_after};
    a_below_b = forward[BITS+1];
    difference = a_below_b ? (BITS + 1)'(in_after - in_before) : forward[BITS:0];
    denominator = (BITS + 2)'(in_before) + (BITS + 2)'(in_after) - {1'b0, in_cost, 1'b0};
    numerator = (NUM_BITS'(difference) << fx_pkg::SUBPIXEL_BITS) + NUM_BITS'(denominator);
    twice_denominator = ROW_BITS'(denominator) << 1;
    partial = ROW_BITS'(numerator >> fx_pkg::SUBPIXEL_BITS);
    steps = '0;
    difference_row = '0;
    for (int r = fx_pkg::SUBPIXEL_BITS - 1; r >= 0; r--) begin
      partial = {partial[ROW_BITS-2:0], numerator[r]};
      difference_row = {1'b0, partial} - {1'b0, twice_denominator};
      if (!difference_row[ROW_BITS]) begin  // partial >= 2 den: the subtractor's borrow
        partial = difference_row[ROW_BITS-1:0];
        steps[r] = 1'b1;
      end
    end
    // NDISP <= 2: no label has both neighbours (0 < k1 < cfg.ndisp - 1 <= 1 is empty), so the
    // offset is never applied and the division above folds away (it was the one- and two-label
    // cores' critical path).
    // A neighbour that is no candidate (ASW_NO_CANDIDATE: the adaptive-support-weight core's
    // outside matches) is no parabola point; no other stage's cost reaches that value.
    refine = NDISP > 2 && cfg.subpixel_en && in_label != '0 &&
             32'(in_label) + 1 < 32'(cfg.ndisp) && denominator != '0 &&
             in_before != BITS'(fx_pkg::ASW_NO_CANDIDATE) &&
             in_after != BITS'(fx_pkg::ASW_NO_CANDIDATE);
    fixed = (fx_pkg::FIXED_BITS'(cfg.min_disp) + fx_pkg::FIXED_BITS'(in_label))
            <<< fx_pkg::SUBPIXEL_BITS;
    // The calibrated correction of the vertex (fx_pkg::subpixel_correction, a 9-entry table).
    steps = fx_pkg::subpixel_correction(steps);
    if (refine) begin
      if (!a_below_b) fixed = fixed + fx_pkg::FIXED_BITS'(steps);
      else fixed = fixed - fx_pkg::FIXED_BITS'(steps);
    end
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_label <= in_label;
      out_border <= in_border;
      out_cost <= in_cost;
      out_fixed <= fixed;
    end
  end
  // The coordinates and C2 (NDISP <= 2: a constant, not registered).
  stereo_stage_output #(.BITS(fx_pkg::AGG_BITS), .REGISTERED(NDISP > 2)) outputs (
      .in_data(second), .out_data(out_second), .*);
endmodule

`default_nettype wire
