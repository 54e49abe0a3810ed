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
`default_nettype none

module stereo_divider #(
    parameter int DIVISOR_BITS  = 15,  // the dividend has as many bits and is below the divisor
    parameter int QUOTIENT_BITS = 8,
    parameter int STAGES        = 1
) (
    input  wire logic                     clk,
    input  wire logic                     ce,
    input  wire logic [DIVISOR_BITS-1:0]  dividend,
    input  wire logic [DIVISOR_BITS-1:0]  divisor,
    output      logic [QUOTIENT_BITS-1:0] quotient
);
  localparam int ROWS = (QUOTIENT_BITS + STAGES - 1) / STAGES;  // rows per segment

  initial assert (STAGES >= 1 && STAGES <= QUOTIENT_BITS);

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
    remainder = in[REMAINDER_LSB+:DIVISOR_BITS+1];
    den = in[DIVISOR_LSB+:DIVISOR_BITS];
    q = in[Q_LSB+:QUOTIENT_BITS];
    for (int r = first_row; r < first_row + ROWS; r++) begin
      if (r < QUOTIENT_BITS) begin
        remainder = {remainder[DIVISOR_BITS-1:0], 1'b0};
        if (remainder >= {1'b0, den}) begin
          remainder = remainder - {1'b0, den};
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
    if (STAGES == 1) begin : g_combinational
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
