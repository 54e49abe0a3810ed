// stereo_divider: restoring division of a fraction, quotient = floor((dividend << QUOTIENT_BITS)
// / divisor) for dividend < divisor (then the quotient fits QUOTIENT_BITS). Stage 6 computes the
// certainty floor(((C2 - C1) << 8) / (C2 + 1)) with it (stereo::validation::certainty).
//
// QUOTIENT_BITS rows of one subtractor each: row i doubles the partial remainder and subtracts
// the divisor where it fits, which sets quotient bit QUOTIENT_BITS - 1 - i. The remainder stays
// below the divisor, so it needs one bit more than the divisor only while doubled.
//
// STAGES splits the rows into that many combinational segments of ceil(QUOTIENT_BITS / STAGES)
// rows with a register (enabled by ce) between segments: the quotient of the operands presented
// at one ce appears STAGES - 1 ce steps later. STAGES = 1 is purely combinational (clk and ce
// unused; the user registers the quotient).
//
// CLOCKS > 1 (with STAGES = 1): iterative over the CLOCKS clocks of a pixel step (the clocks of
// label groups index = 0 .. CLOCKS-1 of stereo_top's time-multiplexed lanes, the step, ce, at
// index CLOCKS-1; the operands hold still from one step to the next). Each clock that processes
// a group (ce || index != CLOCKS-1) applies the next ceil(QUOTIENT_BITS / CLOCKS) rows to a
// state register (index 0 starts from the operands); the quotient is complete, combinationally,
// at the step clock. One segment of rows instead of QUOTIENT_BITS rows.
`default_nettype none
`include "stereo_assert.svh"

module stereo_divider #(
    parameter int DIVISOR_BITS  = 15,  // the dividend has as many bits and is below the divisor
    parameter int QUOTIENT_BITS = 8,
    parameter int STAGES        = 1,
    parameter int CLOCKS        = 1   // > 1: iterative over the clocks of a step
) (
    input  wire logic                     clk,
    input  wire logic                     ce,
    /* verilator lint_off UNUSEDSIGNAL */  // CLOCKS = 1: unused
    input  wire logic [((CLOCKS > 1) ? $clog2(CLOCKS) : 1)-1:0] index,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic [DIVISOR_BITS-1:0]  dividend,
    input  wire logic [DIVISOR_BITS-1:0]  divisor,
    output      logic [QUOTIENT_BITS-1:0] quotient
);
  // Rows per segment (CLOCKS > 1: per clock).
  localparam int ROWS = (CLOCKS > 1) ? (QUOTIENT_BITS + CLOCKS - 1) / CLOCKS
                                     : (QUOTIENT_BITS + STAGES - 1) / STAGES;
  localparam int BUSY_CLOCKS = (QUOTIENT_BITS + ROWS - 1) / ROWS;  // CLOCKS > 1: clocks with rows

  `STEREO_ASSERT(stages_clocks,
                 STAGES >= 1 && STAGES <= QUOTIENT_BITS && CLOCKS >= 1 &&
                     (CLOCKS == 1 || STAGES == 1),
                 "STAGES must be 1 .. QUOTIENT_BITS and CLOCKS at least 1, one of them 1")

  // The division's state between rows, one packed vector (Yosys 0.23 parses no functions of
  // struct type): {remainder (< divisor), divisor, quotient bits so far}.
  localparam int STATE_BITS = 2 * DIVISOR_BITS + 1 + QUOTIENT_BITS;
  localparam int Q_LSB = 0;
  localparam int DIVISOR_LSB = QUOTIENT_BITS;
  localparam int REMAINDER_LSB = QUOTIENT_BITS + DIVISOR_BITS;

  // Rows first_row .. first_row + ROWS - 1 (those below QUOTIENT_BITS) applied to `in`.
  function automatic logic [STATE_BITS-1:0] rows_of(logic [STATE_BITS-1:0] in, int first_row);
    logic [DIVISOR_BITS:0] remainder;
    logic [DIVISOR_BITS-1:0] den;
    logic [QUOTIENT_BITS-1:0] q;
    logic [DIVISOR_BITS+1:0] difference;  // one subtractor: its borrow is the comparison
    remainder = in[REMAINDER_LSB+:DIVISOR_BITS+1];
    difference = '0;
    den = in[DIVISOR_LSB+:DIVISOR_BITS];
    q = in[Q_LSB+:QUOTIENT_BITS];
    for (int r = first_row; r < first_row + ROWS; r++) begin
      if (r < QUOTIENT_BITS) begin
        remainder = {remainder[DIVISOR_BITS-1:0], 1'b0};
        difference = {1'b0, remainder} - {2'b00, den};
        if (!difference[DIVISOR_BITS+1]) begin  // remainder >= den
          remainder = difference[DIVISOR_BITS:0];
          q[QUOTIENT_BITS-1-r] = 1'b1;
        end
      end
    end
    rows_of = {remainder, den, q};
  endfunction

  logic [STATE_BITS-1:0] start;
  assign start = {1'b0, dividend, divisor, {QUOTIENT_BITS{1'b0}}};

  logic [STATE_BITS-1:0] done;
  assign quotient = done[Q_LSB+:QUOTIENT_BITS];
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused;
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    if (CLOCKS > 1) begin : g_iterative
      // The quotient shifts in from the right, so a row's bit position needs no decoder.
      logic [STATE_BITS-1:0] state;  // after the rows of the clocks before
      always_comb begin
        logic [DIVISOR_BITS:0] remainder;
        logic [QUOTIENT_BITS-1:0] q;
        logic [DIVISOR_BITS+1:0] difference;  // one subtractor: its borrow is the comparison
        remainder = (index == '0) ? start[REMAINDER_LSB+:DIVISOR_BITS+1]
                                  : state[REMAINDER_LSB+:DIVISOR_BITS+1];
        q = (index == '0) ? start[Q_LSB+:QUOTIENT_BITS] : state[Q_LSB+:QUOTIENT_BITS];
        difference = '0;
        if (32'(index) < BUSY_CLOCKS) begin
          for (int r = 0; r < ROWS; r++) begin
            // Rows past QUOTIENT_BITS (the last busy clock's spare rows) do nothing.
            if (32'(index) * ROWS + r < QUOTIENT_BITS) begin
              remainder = {remainder[DIVISOR_BITS-1:0], 1'b0};
              difference = {1'b0, remainder} - {2'b00, divisor};
              if (!difference[DIVISOR_BITS+1]) begin  // remainder >= divisor
                remainder = difference[DIVISOR_BITS:0];
                q = {q[QUOTIENT_BITS-2:0], 1'b1};
              end else begin
                q = {q[QUOTIENT_BITS-2:0], 1'b0};
              end
            end
          end
        end
        done = {remainder, divisor, q};
      end
      always_ff @(posedge clk) begin
        if (ce || 32'(index) != CLOCKS - 1) state <= done;  // a clock that processes a group
      end
      assign unused = ^{done[STATE_BITS-1:QUOTIENT_BITS], state[DIVISOR_LSB+:DIVISOR_BITS],
                        start[DIVISOR_LSB+:DIVISOR_BITS]};
    end else if (STAGES == 1) begin : g_combinational
      assign done = rows_of(start, 0);
      assign unused = ^{clk, ce, done[STATE_BITS-1:QUOTIENT_BITS]};
    end else begin : g_pipelined
      logic [STATE_BITS-1:0] held[STAGES-1];  // held[s]: after segment s, registered
      always_ff @(posedge clk) begin
        if (ce) begin
          held[0] <= rows_of(start, 0);
          for (int s = 1; s < STAGES - 1; s++) held[s] <= rows_of(held[s-1], s * ROWS);
        end
      end
      assign done = rows_of(held[STAGES-2], (STAGES - 1) * ROWS);
      assign unused = ^done[STATE_BITS-1:QUOTIENT_BITS];
    end
  endgenerate
endmodule

`default_nettype wire
