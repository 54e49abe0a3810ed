// stereo_asw_aggregate: the separable adaptive-support-weight aggregation of two passes
// (stereo_top ASW = 1; model: stereo::asw::match with Params::separable, docs/asw.md), the
// stage between stereo_cost (RAW_BITS: the words of stereo_asw_column) and stereo_wta. Label k
// stands for d = m + k, m = cfg.min_disp; r = DIAMETER / 2; x - d is the label's right column.
//
//   vertical  Av(x, d) = round(16 sum_j Wv_j C_j / sum_j Wv_j) over the rows j of the
//             column stack inside the frame, Wv_j = vert_L[j] (x) (right column inside ?
//             vert_R[j] : 255), C_j = min(cost, TRUNCATION) (no minimum for TRUNCATION = 0),
//             the cost 31 x Hamming distance of the census codes (CODES = 1) or |dR| + |dG| +
//             |dB| (CODES = 0), COST_OUTSIDE where the right column lies outside the right image;
//   pass 1    A1(x1, d) = round(sum_dx W_dx Av(x1 + dx, d) / sum_dx W_dx) over the offsets whose
//             column lies in the frame, W_dx = near_L[dx] (x) (x1 - d and x1 - d + dx inside ?
//             near_R[dx] : 255), then ASW_NO_CANDIDATE where x1 - d lies outside; its winner
//             (smallest cost, ties to the smaller k, labels below cfg.ndisp) is x1's label;
//   pass 2    the same at x2 with W_dx = (far_L[dx] (x) continuity(|label(x2) - label(x2 +
//             dx)|)) (x) (... far_R[dx] : 255): the output, ASW_NO_CANDIDATE where x2 - d
//             lies outside.
// round(n / s) is floor((n + floor(s / 2)) / s), a restoring division of 14 quotient bits; (x)
// is fx_pkg::asw_combine. The words hand their right factors over with the right column
// (stereo_asw_column), so every weight is one combine per label and offset (stereo_asw_weights:
// two labels a multiplier).
//
// Pipelined in whole steps (a plain register would hand group g's values to group g + 1's
// clock; a ring of one entry per label group, stereo_group_ring, advanced like the Av ring,
// hands them to group g's next clock, one step later):
//   V = fx_pkg::ASW_VERTICAL_STEPS: the vertical pass' weights and the costs they weigh wait V
//       steps before their sums (no clock holds the response products and the adder tree);
//   S = fx_pkg::ASW_DIVIDE_STEPS: every pass' sums (num, den) wait one step in a ring, then the
//       division runs over S steps, ceil(14 / S) quotient rows each, its state in one more ring
//       per step (no clock holds the sums and a division, nor a whole division);
//   W = fx_pkg::ASW_WINNER_STEPS: pass 1's means wait W steps before its winner over the labels.
// Av(c) enters the history LATE = V + S steps after column c's weights; pass 1's label is final
// S + W steps after its sums.
//
// Stream positions (stage_table.hpp asw_near_steps, asw_far_steps): the input (x, yc) is the
// vertical pass' pixel; x1 is the pixel NEAR = r + 1 + LATE steps before it, x2 the one
// FAR = NEAR + r + 1 + S + W before (both follow the stream across row ends: their coordinates
// come from a shift register). Pass 1 reads Av of the columns x1 - r .. x1 + r and pass 2 those
// of x2 - r .. x2 + r, all divided at earlier steps: each label group keeps the last
// HISTORY = FAR + r - LATE columns' Av (x - 1 - LATE .. x - HISTORY - LATE) in a ring, and
// pass 2 reads the labels pass 1 gave x2 - r .. x2 + r at earlier steps.
// Output: (x2, yc) of S steps before and its labels' costs, divided by this step, through the
// stage's output register (G = 1), or the registered coordinates and this clock's group (G > 1,
// the stage contract of docs/rtl.md: stereo_wta's input ring holds the group until the next
// step): latency FAR + S + 1 = 2r + 3 + 3S + V + W steps.
// Time-multiplexed lanes (LANES < NDISP): the clock of group g computes labels [g*LANES +:
// LANES] of all three passes' sums and divisions; pass 1's winner runs over the groups (a
// register that group 0 restarts) and enters the label history at the step.
`default_nettype none
`include "stereo_assert.svh"

module stereo_asw_aggregate #(
    parameter int NDISP    = 16,  // labels
    parameter int LANES    = NDISP,  // labels computed per clock (divides NDISP)
    parameter int DIAMETER = 5,   // the support diameter w (odd)
    parameter bit CODES    = 1'b1,  // 1: census codes (cost 31 x Hamming); 0: AD over RGB
    parameter int TRUNCATION = 0,  // the cost's cap before the aggregation, 0: none
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM
    parameter int RING_BLOCK_MIN_FILL = 50,  // stereo_group_ring BLOCK_MIN_FILL
    // stereo_top's SHIFT_ADD: anything but SHIFT_ADD_NONE builds the vertical pass' weight x
    // cost products of the census cost (TRUNCATION = 0) from shifts and adds (below)
    parameter fx_pkg::shift_add_e SHIFT_ADD = fx_pkg::SHIFT_ADD_NONE
) (
`include "stereo_stage_ports.svh"
    input  wire logic [48*DIAMETER-1:0]          in_left,   // stereo_asw_column's words
    input  wire logic [LANES*48*DIAMETER-1:0]    in_right,  // lane l: label group*LANES + l
    /* verilator lint_off UNUSEDSIGNAL */  // reads width, height, ndisp and min_disp only
    input  wire fx_pkg::config_t                 cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                  out_x,
    output      fx_pkg::coord_t                  out_y,
    output      logic [LANES*fx_pkg::AGG_BITS-1:0] out_data
);
  localparam int R = DIAMETER / 2;
  localparam int WORD = 48 * DIAMETER;
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int GROUPS = NDISP / LANES;
  localparam int STEPS = fx_pkg::ASW_DIVIDE_STEPS;  // S: steps from the sums to the mean
  localparam int VSTEPS = fx_pkg::ASW_VERTICAL_STEPS;  // V: from the vertical weights to sums
  localparam int WSTEPS = fx_pkg::ASW_WINNER_STEPS;  // W: from pass 1's means to its winner
  localparam int ROWS = (BITS + STEPS - 1) / STEPS;  // quotient rows a step
  // Positions (stage_table.hpp asw_near_steps, asw_far_steps): x1 = x - NEAR, x2 = x - FAR.
  // The horizontal passes' steps (H = fx_pkg::ASW_HORIZONTAL_STEPS, 0 .. 3): A, the factors;
  // B, the response products; C, the weight x mean products; D, the sums. A group delay of one
  // step after each of the first H of A, B, C; none after the others.
  localparam int HSTEPS = fx_pkg::ASW_HORIZONTAL_STEPS;
  localparam int FACTOR_DELAY = (HSTEPS >= 1) ? 1 : 0;
  localparam int WEIGHT_DELAY = (HSTEPS >= 2) ? 1 : 0;
  localparam int PRODUCT_DELAY = (HSTEPS >= 3) ? 1 : 0;
  localparam int PRODUCTS_AT = FACTOR_DELAY + WEIGHT_DELAY;  // step C, after step A
  localparam int NEAR = R + 1 + STEPS + VSTEPS;
  localparam int FAR = NEAR + R + 1 + HSTEPS + STEPS + WSTEPS;
  localparam int LATE = STEPS + VSTEPS;  // Av(c) enters the history LATE steps after column c
  // Av of columns x - 1 - LATE .. x - HISTORY - LATE (pass 2's oldest is read at step C)
  localparam int HISTORY = FAR + R - LATE + PRODUCTS_AT;
  localparam int OWN_LABEL = FAR - NEAR - HSTEPS - STEPS - WSTEPS;  // pass 1's label of x2
  // The sums' widths: weights below 2^8, costs below 2^10 (vertical) and means below 2^BITS.
  localparam int DEN_BITS = $clog2(255 * DIAMETER + 1);
  localparam int VNUM_BITS = $clog2(255 * 1023 * DIAMETER + 1);
  localparam int HNUM_BITS = $clog2(255 * ((1 << BITS) - 1) * DIAMETER + 1);
  localparam int VSUM_BITS = VNUM_BITS + DEN_BITS;  // a lane's {num, den}
  localparam int HSUM_BITS = 1 + HNUM_BITS + DEN_BITS;  // {outside, num, den}
  localparam int FACTOR_BITS = 9 * DIAMETER + LANES * (8 * DIAMETER + 1);
  localparam int PRODUCT_BITS = 1 + DEN_BITS + 22 * DIAMETER;  // {outside, den, 8 x 14 products}
  // A division between steps: {outside, partial remainder (17), quotient, dividend's low bits,
  // den (16)}.
  localparam int DIV_BITS = 1 + 17 + 2 * BITS + 16;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam logic [BITS-1:0] NO_CANDIDATE = BITS'(fx_pkg::ASW_NO_CANDIDATE);
  localparam int CENSUS_SHIFT = $clog2(fx_pkg::CENSUS_WEIGHT + 1);
  // The census cost is CENSUS_WEIGHT x h (h the Hamming distance, 5 bits) or, for a whole lane,
  // COST_OUTSIDE, so the vertical sum_j w_j c_j is CENSUS_WEIGHT x sum_j w_j h_j or COST_OUTSIDE
  // x sum_j w_j: products of 8 by 5 bits (five gated additions each) and two by constants, no
  // multiplier (DSP block) per label and row.
  localparam bit VERTICAL_SHIFT_ADD =
      CODES && TRUNCATION == 0 && SHIFT_ADD != fx_pkg::SHIFT_ADD_NONE;
  // This diameter's row of fx_pkg::ASW_CONTINUITY (what fx_pkg::asw_continuity reads), so a
  // look-up is a shifter over 256 entries, not over every diameter's (stereo_asw_column says why).
  localparam int CONTINUITY_ROW_BITS = fx_pkg::ASW_CONTINUITY_ENTRIES * 8;
  localparam logic [CONTINUITY_ROW_BITS-1:0] CONTINUITY_ROW =
      fx_pkg::ASW_CONTINUITY[((DIAMETER - fx_pkg::ASW_MIN_DIAMETER) / 2) * CONTINUITY_ROW_BITS +:
                             CONTINUITY_ROW_BITS];

  `STEREO_ASSERT(steps_range, STEPS >= 1 && STEPS <= BITS && (VSTEPS == 0 || VSTEPS == 1) &&
                     (WSTEPS == 0 || WSTEPS == 1) && HSTEPS >= 0 && HSTEPS <= 3,
                 "ASW_DIVIDE_STEPS must be 1 .. AGG_BITS, ASW_VERTICAL/WINNER_STEPS 0 or 1, ASW_HORIZONTAL_STEPS 0 .. 3")
  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")
  `STEREO_ASSERT(diameter_range,
                 DIAMETER % 2 == 1 && DIAMETER >= fx_pkg::ASW_MIN_DIAMETER &&
                     DIAMETER <= fx_pkg::ASW_MAX_DIAMETER,
                 "DIAMETER must be odd, ASW_MIN_DIAMETER .. ASW_MAX_DIAMETER")

  // ---- the words' fields (stereo_asw_column) ---------------------------------------------------
  function automatic logic [23:0] code_of(input logic [WORD-1:0] word, input int j);
    code_of = word[j*24+:24];
  endfunction
  function automatic logic [7:0] vert_of(input logic [WORD-1:0] word, input int j);
    vert_of = word[24*DIAMETER+j*8+:8];
  endfunction
  function automatic logic [7:0] near_of(input logic [WORD-1:0] word, input int i);
    near_of = word[32*DIAMETER+i*8+:8];
  endfunction
  function automatic logic [7:0] far_of(input logic [WORD-1:0] word, input int i);
    far_of = word[40*DIAMETER+i*8+:8];
  endfunction

  // ---- arithmetic -------------------------------------------------------------------------------
  function automatic logic [4:0] hamming(input logic [23:0] a, input logic [23:0] b);
    logic [4:0] sum;
    sum = '0;
    for (int i = 0; i < fx_pkg::CENSUS_BITS; i++) sum = sum + {4'd0, a[i] ^ b[i]};
    hamming = sum;
  endfunction
  // x * c for a constant c, as shifts and adds (a constant product takes a DSP block)
  function automatic logic [31:0] times_constant(input logic [31:0] x, input int c);
    logic [31:0] product;
    product = '0;
    for (int k = 0; k < 31; k++) if (c[k]) product = product + (x << k);
    times_constant = product;
  endfunction
  function automatic logic [9:0] matching_cost(input logic [23:0] a, input logic [23:0] b);
    logic [9:0] sum;
    logic [7:0] channel;
    sum = '0;
    if (CODES) begin
      // times CENSUS_WEIGHT as a shift and a subtraction (a constant product takes a DSP block)
      sum = {5'd0, hamming(a, b)};
      sum = 10'((sum << CENSUS_SHIFT) - sum * 10'((1 << CENSUS_SHIFT) - fx_pkg::CENSUS_WEIGHT));
    end else begin
      for (int c = 0; c < 3; c++) begin
        channel = (a[c*8+:8] >= b[c*8+:8]) ? a[c*8+:8] - b[c*8+:8] : b[c*8+:8] - a[c*8+:8];
        sum = sum + {2'd0, channel};
      end
    end
    matching_cost = sum;
  endfunction
  function automatic logic in_range(input logic signed [17:0] x, input fx_pkg::cfg_size_t width);
    in_range = x >= 18'sd0 && x < $signed(18'(width));
  endfunction

  // ---- positions --------------------------------------------------------------------------------
  // xs[p], ys[p]: the input pixel p steps ago (p = 1 .. FAR + H + S); x1 = xs[NEAR], x2 = xs[FAR].
  fx_pkg::coord_t xs[FAR+HSTEPS+STEPS+1], ys[FAR+HSTEPS+STEPS+1];
  always_comb begin
    xs[0] = in_x;
    ys[0] = in_y;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      for (int p = 1; p <= FAR + HSTEPS + STEPS; p++) begin
        xs[p] <= '0;
        ys[p] <= fx_pkg::NO_PIXEL;
      end
    end else if (ce) begin
      for (int p = 1; p <= FAR + HSTEPS + STEPS; p++) begin
        xs[p] <= xs[p-1];
        ys[p] <= ys[p-1];
      end
    end
  end

  // The labels of this clock: k = group * LANES + l.
  logic signed [17:0] base_k;
  assign base_k = 18'(32'(group) * LANES);

  // ---- the Av history of this clock's group ----------------------------------------------------
  // head[(l*HISTORY + p - 1)*BITS +: BITS]: lane l's Av of column x - p - LATE.
  localparam int RING_BITS = LANES * HISTORY * BITS;
  logic [RING_BITS-1:0] head, next_state;
  logic advance;
  assign advance = ce || 32'(group) != GROUPS - 1;
  stereo_group_ring #(
      .BITS(RING_BITS),
      .GROUPS(GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) history (
      .clk(clk),
      .advance(advance),
      .next_state(next_state),
      .head(head)
  );
  function automatic logic [BITS-1:0] av_at(input int l, input int p);
    av_at = head[(l*HISTORY+p-1)*BITS+:BITS];
  endfunction

  // ---- the sums of the last step, per pass: one ring entry per group ----------------------------
  logic [LANES*VSUM_BITS-1:0] vertical_sums, vertical_sums_q;
  logic [LANES*HSUM_BITS-1:0] pass1_sums, pass1_sums_q, pass2_sums, pass2_sums_q;
  stereo_group_ring #(
      .BITS(LANES * VSUM_BITS),
      .GROUPS(GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) vertical_ring (
      .clk(clk),
      .advance(advance),
      .next_state(vertical_sums),
      .head(vertical_sums_q)
  );
  stereo_group_ring #(
      .BITS(LANES * HSUM_BITS),
      .GROUPS(GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) pass1_ring (
      .clk(clk),
      .advance(advance),
      .next_state(pass1_sums),
      .head(pass1_sums_q)
  );
  stereo_group_ring #(
      .BITS(LANES * HSUM_BITS),
      .GROUPS(GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) pass2_ring (
      .clk(clk),
      .advance(advance),
      .next_state(pass2_sums),
      .head(pass2_sums_q)
  );
  // Means floor(((num << shift) + floor(den / 2)) / den), the quotient below 2^BITS (a weighted
  // mean of values below 2^BITS / 16 << 4, or below 2^BITS): BITS rows of long division, the
  // partial remainder below 2 den.
  // The division of the three passes (0 vertical, 1 and 2), one part a step: start with the
  // dividend of the last step's sums (ring above), then ROWS quotient rows a step, the state
  // between steps in a ring of its own; NO_CANDIDATE where a horizontal pass' match lies outside.
  function automatic logic [DIV_BITS-1:0] divide_start(input logic outside,
                                                       input logic [31:0] num,
                                                       input logic [15:0] den, input int shift);
    logic [35:0] dividend;
    dividend = (36'(num) << shift) + 36'(den[15:1]);
    divide_start = {outside, 17'(dividend >> BITS), BITS'(0), dividend[BITS-1:0], den};
  endfunction
  // The rows of quotient bits top .. bottom of a division's state (mean's rows).
  function automatic logic [DIV_BITS-1:0] divide_rows(input logic [DIV_BITS-1:0] state,
                                                      input int top, input int bottom);
    logic outside;
    logic [16:0] partial;
    logic [BITS-1:0] quotient, low;
    logic [15:0] den;
    {outside, partial, quotient, low, den} = state;
    for (int i = BITS - 1; i >= 0; i--) begin
      if (i <= top && i >= bottom) begin
        partial = {partial[15:0], low[i]};
        if (partial >= {1'b0, den}) begin
          partial = partial - {1'b0, den};
          quotient[i] = 1'b1;
        end
      end
    end
    divide_rows = {outside, partial, quotient, low, den};
  endfunction
  logic [3*LANES*DIV_BITS-1:0] division_start;  // [(pass*LANES + l)*DIV_BITS +: DIV_BITS]
  logic [3*LANES*BITS-1:0] division_result;  // [(pass*LANES + l)*BITS +: BITS]
  for (genvar q = 0; q < 3; q++) begin : g_divide
    // states[(s*LANES + l)*DIV_BITS +: DIV_BITS]: lane l after step s's rows
    logic [STEPS*LANES*DIV_BITS-1:0] states;
    for (genvar step = 0; step < STEPS; step++) begin : g_step
      localparam int TOP = BITS - 1 - step * ROWS;
      localparam int BOTTOM = (BITS - (step + 1) * ROWS > 0) ? BITS - (step + 1) * ROWS : 0;
      logic [LANES*DIV_BITS-1:0] incoming;
      if (step == 0) begin : g_first
        assign incoming = division_start[q*LANES*DIV_BITS+:LANES*DIV_BITS];
      end else begin : g_later
        stereo_group_ring #(
            .BITS(LANES * DIV_BITS),
            .GROUPS(GROUPS),
            .BLOCK_RAM(RING_BLOCK_RAM),
            .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
        ) partial_ring (
            .clk(clk),
            .advance(advance),
            .next_state(states[(step-1)*LANES*DIV_BITS+:LANES*DIV_BITS]),
            .head(incoming)
        );
      end
      for (genvar l = 0; l < LANES; l++) begin : g_lane
        assign states[(step*LANES+l)*DIV_BITS+:DIV_BITS] =
            divide_rows(incoming[l*DIV_BITS+:DIV_BITS], TOP, BOTTOM);
      end
    end
    for (genvar l = 0; l < LANES; l++) begin : g_result
      logic [DIV_BITS-1:0] done;
      assign done = states[((STEPS-1)*LANES+l)*DIV_BITS+:DIV_BITS];
      assign division_result[(q*LANES+l)*BITS+:BITS] =
          done[DIV_BITS-1] ? NO_CANDIDATE : done[16+BITS+:BITS];
    end
  end

  // ---- the vertical pass --------------------------------------------------------------------
  // Per lane (generate loops: every index below is a constant of the elaboration).
  // Rows of the column stack inside the frame (the same for every lane).
  logic [DIAMETER-1:0] row_inside;
  always_comb begin
    for (int j = 0; j < DIAMETER; j++) begin
      row_inside[j] = in_range(18'(in_y) - 18'(R) + 18'(j), cfg.height);
    end
  end
  logic [LANES*BITS-1:0] vertical;  // lane l's Av of column x - LATE (its division's last step)
  logic [LANES*8*DIAMETER-1:0] vertical_right, vertical_weights;  // lane l's factors, weights
  logic [8*DIAMETER-1:0] vertical_left;
  always_comb begin
    for (int j = 0; j < DIAMETER; j++) vertical_left[j*8+:8] = vert_of(in_left, j);
  end
  stereo_asw_weights #(.LANES(LANES), .TAPS(DIAMETER)) vertical_combine (
      .shared(vertical_left), .lane_factors(vertical_right), .tap_inside(row_inside),
      .weights(vertical_weights));
  // A lane's terms: {outside, the rows' costs (the Hamming distances with SHIFT_ADD), weights},
  // made at this step and summed VSTEPS steps later (a ring of one entry per group in between).
  localparam int TERM_COST_BITS = VERTICAL_SHIFT_ADD ? 5 : 10;
  localparam int VTERM_BITS = 1 + DIAMETER * (TERM_COST_BITS + 8);
  logic [LANES*VTERM_BITS-1:0] vertical_terms, vertical_terms_q;
  if (VSTEPS == 0) begin : g_terms_now
    assign vertical_terms_q = vertical_terms;
  end else begin : g_terms_ring
    stereo_group_ring #(
        .BITS(LANES * VTERM_BITS),
        .GROUPS(GROUPS),
        .BLOCK_RAM(RING_BLOCK_RAM),
        .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
    ) terms_ring (
        .clk(clk),
        .advance(advance),
        .next_state(vertical_terms),
        .head(vertical_terms_q)
    );
  end
  for (genvar l = 0; l < LANES; l++) begin : g_vertical
    logic [WORD-1:0] right_word;
    logic signed [17:0] right_x;
    logic outside;
    assign right_word = in_right[l*WORD+:WORD];
    assign right_x = 18'(in_x) - 18'(cfg.min_disp) - base_k - 18'(l);
    assign outside = !in_range(right_x, cfg.width);
    always_comb begin
      for (int j = 0; j < DIAMETER; j++) begin
        vertical_right[(l*DIAMETER+j)*8+:8] = outside ? 8'd255 : vert_of(right_word, j);
      end
    end
    always_comb begin
      logic [9:0] cost;
      logic [VTERM_BITS-1:0] terms;
      terms = '0;
      terms[VTERM_BITS-1] = outside;
      for (int j = 0; j < DIAMETER; j++) begin
        terms[j*8+:8] = vertical_weights[(l*DIAMETER+j)*8+:8];
        if (VERTICAL_SHIFT_ADD) begin
          cost = {5'd0, hamming(code_of(in_left, j), code_of(right_word, j))};
        end else begin
          cost = outside ? 10'(fx_pkg::COST_OUTSIDE)
                         : matching_cost(code_of(in_left, j), code_of(right_word, j));
          if (TRUNCATION > 0 && cost > 10'(TRUNCATION)) cost = 10'(TRUNCATION);
        end
        terms[8*DIAMETER+j*TERM_COST_BITS+:TERM_COST_BITS] = TERM_COST_BITS'(cost);
      end
      vertical_terms[l*VTERM_BITS+:VTERM_BITS] = terms;
    end
    always_comb begin
      logic [VTERM_BITS-1:0] terms;
      logic [31:0] num, weighted_h;
      logic [15:0] den;
      logic [9:0] cost;
      logic [4:0] h;
      logic [7:0] weight;
      logic [17:0] product;  // 8 x 10 bits
      terms = vertical_terms_q[l*VTERM_BITS+:VTERM_BITS];
      num = '0;
      den = '0;
      weighted_h = '0;
      for (int j = 0; j < DIAMETER; j++) begin
        weight = terms[j*8+:8];
        den = den + 16'(weight);
        if (VERTICAL_SHIFT_ADD) begin
          h = 5'(terms[8*DIAMETER+j*TERM_COST_BITS+:TERM_COST_BITS]);
          // gated by AND, not by `if`: the terms form one sum (Yosys: one $macc, mapped to an
          // adder tree), where conditional additions stay a chain (128 LUT levels at 640x480,
          // LANES = 4: docs/results-asw.md)
          for (int b = 0; b < 5; b++) weighted_h = weighted_h + ((32'(weight) << b) & {32{h[b]}});
        end else begin
          cost = 10'(terms[8*DIAMETER+j*TERM_COST_BITS+:TERM_COST_BITS]);
          product = 18'(weight) * 18'(cost);
          num = num + 32'(product);
        end
      end
      if (VERTICAL_SHIFT_ADD) begin
        num = terms[VTERM_BITS-1] ? times_constant(32'(den), fx_pkg::COST_OUTSIDE)
                                  : times_constant(weighted_h, fx_pkg::CENSUS_WEIGHT);
      end
      vertical_sums[l*VSUM_BITS+:VSUM_BITS] = {VNUM_BITS'(num), DEN_BITS'(den)};
    end
    // The last step's sums of this group start their division; Av of column x - LATE leaves it.
    assign division_start[l*DIV_BITS+:DIV_BITS] =
        divide_start(1'b0, 32'(vertical_sums_q[l*VSUM_BITS+DEN_BITS+:VNUM_BITS]),
                     16'(vertical_sums_q[l*VSUM_BITS+:DEN_BITS]), fx_pkg::AGG_FRAC_BITS);
    assign vertical[l*BITS+:BITS] = division_result[l*BITS+:BITS];
    // The new Av enters position 1; the older ones move one column back.
    assign next_state[(l*HISTORY)*BITS+:BITS] = vertical[l*BITS+:BITS];
    if (HISTORY > 1) begin : g_shift
      assign next_state[(l*HISTORY+1)*BITS+:(HISTORY-1)*BITS] =
          head[(l*HISTORY)*BITS+:(HISTORY-1)*BITS];
    end
  end

  // ---- the horizontal passes ------------------------------------------------------------------
  // Pass p (1, 2) at pixel `centre`, BACK steps back: column centre + dx is BACK - dx back. The
  // left factors do not depend on the label: computed once per pixel (pass 2's with the
  // continuity of the labels pass 1 gave), the right ones come with each lane's word.
  logic [DISP_BITS-1:0] labels[1:2*R+1];  // labels[p]: pass 1's label of x1 - p - S - W
  logic [LANES*BITS-1:0] pass1, pass2;
  for (genvar pass = 1; pass <= 2; pass++) begin : g_pass
    localparam int BACK = (pass == 1) ? NEAR : FAR;
    // -- step A: the factors (pass 2's left ones with the continuity), which taps and lanes lie
    //    inside; to step B through a group delay of FACTOR_DELAY steps.
    logic signed [17:0] centre;
    logic [FACTOR_BITS-1:0] factors, factors_q;  // {lanes' {outside, right factors}, inside, left}
    assign centre = 18'(xs[BACK]);
    always_comb begin
      logic [DISP_BITS-1:0] label_step;
      for (int i = 0; i < DIAMETER; i++) begin
        factors[8*DIAMETER+i] = in_range(centre + 18'(i - R), cfg.width);
        if (pass == 1) begin
          factors[i*8+:8] = near_of(in_left, i);
        end else begin
          label_step = (labels[OWN_LABEL] >= labels[OWN_LABEL-(i-R)])
                           ? labels[OWN_LABEL] - labels[OWN_LABEL-(i-R)]
                           : labels[OWN_LABEL-(i-R)] - labels[OWN_LABEL];
          factors[i*8+:8] = fx_pkg::asw_combine(
              far_of(in_left, i), CONTINUITY_ROW[32'(label_step)*8+:8]);
        end
      end
    end
    for (genvar l = 0; l < LANES; l++) begin : g_lane_factors
      logic [WORD-1:0] right_word;
      logic signed [17:0] right_x;
      logic outside;
      assign right_word = in_right[l*WORD+:WORD];
      assign right_x = centre - 18'(cfg.min_disp) - base_k - 18'(l);
      assign outside = !in_range(right_x, cfg.width);
      always_comb begin
        logic [8*DIAMETER:0] lane;  // {outside, right factors}
        lane[8*DIAMETER] = outside;
        for (int i = 0; i < DIAMETER; i++) begin
          if (outside || !in_range(right_x + 18'(i - R), cfg.width)) begin
            lane[i*8+:8] = 8'd255;
          end else if (pass == 1) begin
            lane[i*8+:8] = near_of(right_word, i);
          end else begin
            lane[i*8+:8] = far_of(right_word, i);
          end
        end
        factors[9*DIAMETER+l*(8*DIAMETER+1)+:8*DIAMETER+1] = lane;
      end
    end
    stereo_group_delay #(
        .BITS(FACTOR_BITS), .GROUPS(GROUPS), .STEPS(FACTOR_DELAY), .BLOCK_RAM(RING_BLOCK_RAM),
        .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
    ) factor_delay (.clk(clk), .advance(advance), .in_data(factors), .out_data(factors_q));
    // -- step B: the response products (weights); to step C through WEIGHT_DELAY steps.
    logic [LANES*8*DIAMETER-1:0] right_factors, weights;  // lane l's factors, weights
    logic [LANES-1:0] outside_b;
    for (genvar l = 0; l < LANES; l++) begin : g_lane_split
      localparam int AT = 9 * DIAMETER + l * (8 * DIAMETER + 1);
      assign right_factors[l*8*DIAMETER+:8*DIAMETER] = factors_q[AT+:8*DIAMETER];
      assign outside_b[l] = factors_q[AT+8*DIAMETER];
    end
    stereo_asw_weights #(.LANES(LANES), .TAPS(DIAMETER)) combine (
        .shared(factors_q[0+:8*DIAMETER]), .lane_factors(right_factors),
        .tap_inside(factors_q[8*DIAMETER+:DIAMETER]), .weights(weights));
    logic [LANES*(8*DIAMETER+1)-1:0] weighted, weighted_q;  // lane l: {outside, weights}
    for (genvar l = 0; l < LANES; l++) begin : g_lane_weights
      assign weighted[l*(8*DIAMETER+1)+:8*DIAMETER+1] =
          {outside_b[l], weights[l*8*DIAMETER+:8*DIAMETER]};
    end
    stereo_group_delay #(
        .BITS(LANES * (8 * DIAMETER + 1)), .GROUPS(GROUPS), .STEPS(WEIGHT_DELAY),
        .BLOCK_RAM(RING_BLOCK_RAM), .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
    ) weight_delay (.clk(clk), .advance(advance), .in_data(weighted), .out_data(weighted_q));
    // -- step C: weight x mean products (the means of the history, PRODUCTS_AT steps after step
    //    A) and the weights' sum; to step D through PRODUCT_DELAY steps.
    logic [LANES*PRODUCT_BITS-1:0] products, products_q;  // lane l: {outside, den, products}
    for (genvar l = 0; l < LANES; l++) begin : g_lane_products
      always_comb begin
        logic [8*DIAMETER:0] lane;
        logic [PRODUCT_BITS-1:0] out;
        logic [15:0] den;
        logic [7:0] weight;
        lane = weighted_q[l*(8*DIAMETER+1)+:8*DIAMETER+1];
        den = '0;
        for (int i = 0; i < DIAMETER; i++) begin
          weight = lane[i*8+:8];
          // column centre + dx is BACK - dx steps back at step A: history position
          // BACK - dx - LATE + PRODUCTS_AT here
          out[i*22+:22] = 22'(weight) * 22'(av_at(l, BACK - (i - R) - LATE + PRODUCTS_AT));
          den = den + 16'(weight);
        end
        out[22*DIAMETER+:DEN_BITS] = DEN_BITS'(den);
        out[PRODUCT_BITS-1] = lane[8*DIAMETER];
        products[l*PRODUCT_BITS+:PRODUCT_BITS] = out;
      end
    end
    stereo_group_delay #(
        .BITS(LANES * PRODUCT_BITS), .GROUPS(GROUPS), .STEPS(PRODUCT_DELAY),
        .BLOCK_RAM(RING_BLOCK_RAM), .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
    ) product_delay (.clk(clk), .advance(advance), .in_data(products), .out_data(products_q));
    // -- step D: the weighted sums.
    for (genvar l = 0; l < LANES; l++) begin : g_lane
      logic [HSUM_BITS-1:0] sums;
      always_comb begin
        logic [PRODUCT_BITS-1:0] lane;
        logic [31:0] num;
        lane = products_q[l*PRODUCT_BITS+:PRODUCT_BITS];
        num = '0;
        for (int i = 0; i < DIAMETER; i++) num = num + 32'(lane[i*22+:22]);
        sums = {lane[PRODUCT_BITS-1], HNUM_BITS'(num), lane[22*DIAMETER+:DEN_BITS]};
      end
      // This step's sums into the ring; the last step's start their division (pass1, pass2:
      // the means of the sums S steps ago).
      logic [HSUM_BITS-1:0] sums_q;
      if (pass == 1) begin : g_first
        assign pass1_sums[l*HSUM_BITS+:HSUM_BITS] = sums;
        assign sums_q = pass1_sums_q[l*HSUM_BITS+:HSUM_BITS];
      end else begin : g_second
        assign pass2_sums[l*HSUM_BITS+:HSUM_BITS] = sums;
        assign sums_q = pass2_sums_q[l*HSUM_BITS+:HSUM_BITS];
      end
      assign division_start[(pass*LANES+l)*DIV_BITS+:DIV_BITS] =
          divide_start(sums_q[HSUM_BITS-1], 32'(sums_q[DEN_BITS+:HNUM_BITS]),
                       16'(sums_q[0+:DEN_BITS]), 0);
      if (pass == 1) begin : g_first_mean
        assign pass1[l*BITS+:BITS] = division_result[(LANES+l)*BITS+:BITS];
      end else begin : g_second_mean
        assign pass2[l*BITS+:BITS] = division_result[(2*LANES+l)*BITS+:BITS];
      end
    end
  end

  // ---- pass 1's winner over the groups (x1 of S + W steps ago), the label history -------------
  // Each lane's mean with one bit more, labels >= cfg.ndisp as 2^BITS (above every mean): made at
  // the division's last step and, W = 1, kept a step in a ring of one entry per group.
  localparam int LEAF_BITS = BITS + 1;
  logic [LANES*LEAF_BITS-1:0] pass1_leaves, pass1_leaves_q;
  always_comb begin
    for (int l = 0; l < LANES; l++) begin
      pass1_leaves[l*LEAF_BITS+:LEAF_BITS] = (32'(base_k) + l < 32'(cfg.ndisp))
                                                 ? {1'b0, pass1[l*BITS+:BITS]}
                                                 : {1'b1, BITS'(0)};
    end
  end
  if (WSTEPS == 0) begin : g_winner_now
    assign pass1_leaves_q = pass1_leaves;
  end else begin : g_winner_ring
    stereo_group_ring #(
        .BITS(LANES * LEAF_BITS),
        .GROUPS(GROUPS),
        .BLOCK_RAM(RING_BLOCK_RAM),
        .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
    ) means_ring (
        .clk(clk),
        .advance(advance),
        .next_state(pass1_leaves),
        .head(pass1_leaves_q)
    );
  end
  // The group's smallest leaf by a tree of pairs (the left one on equal values: ties to the
  // smaller label; with no label below cfg.ndisp, lane 0 at 2^BITS); leaves past LANES are
  // all ones, above every lane.
  localparam int LEAVES = 1 << $clog2(LANES);
  logic [BITS:0] group_cost, merged_cost, running_cost;
  logic [DISP_BITS-1:0] group_label, merged_label, running_label;
  always_comb begin
    logic [LEAF_BITS-1:0] value[LEAVES];
    logic [DISP_BITS-1:0] lane[LEAVES];
    for (int l = 0; l < LEAVES; l++) begin
      value[l] = (l < LANES) ? pass1_leaves_q[((l < LANES) ? l : 0)*LEAF_BITS+:LEAF_BITS] : '1;
      lane[l] = DISP_BITS'(l);
    end
    for (int span = 1; span < LEAVES; span = span * 2) begin
      for (int l = 0; l + span < LEAVES; l = l + 2 * span) begin
        if (value[l+span] < value[l]) begin
          value[l] = value[l+span];
          lane[l] = lane[l+span];
        end
      end
    end
    group_cost = value[0];
    group_label = DISP_BITS'(base_k) + lane[0];
  end
  always_comb begin
    if (32'(group) == 0 || group_cost < running_cost) begin
      merged_cost = group_cost;
      merged_label = group_label;
    end else begin
      merged_cost = running_cost;
      merged_label = running_label;
    end
  end
  always_ff @(posedge clk) begin
    if (advance) begin
      running_cost <= merged_cost;
      running_label <= merged_label;
    end
    if (ce) begin
      labels[1] <= merged_label;
      for (int p = 2; p <= 2 * R + 1; p++) labels[p] <= labels[p-1];
    end
  end

  // The output register (G = 1), or the coordinates only (G > 1: stereo_wta's input ring holds
  // this clock's group until the next step, where the all-parallel stage has this register).
  stereo_stage_output #(.BITS(LANES * BITS), .REGISTERED(GROUPS == 1)) outputs (
      .in_x(xs[FAR+HSTEPS+STEPS]), .in_y(ys[FAR+HSTEPS+STEPS]), .in_data(pass2), .*);
endmodule

`default_nettype wire
