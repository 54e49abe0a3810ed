// stereo_weighted_sum: sum over i of tap i times kernel weight i, for WINDOW taps (the 1-D
// pass of the separable aggregation, used for its vertical and its horizontal pass). Exact in
// SUM_BITS; combinational.
// RUNTIME_KERNEL = 1: generic multipliers by the weights of `kernel`. RUNTIME_KERNEL = 0: the
// model's default kernel for WINDOW (fx_pkg::default_tap; LEVEL_KERNEL = 1: the hierarchical
// levels' kernel, fx_pkg::constant_tap), which is symmetric (k[i] = k[2R-i],
// checked in stereo_aggregate): mirrored taps are added before the one constant product they
// share, R + 1 products instead of 2R + 1. SHIFT_ADD = 1 (constant kernel only) builds each
// constant product from shifts, additions and subtractions, one per nonzero digit of the tap's
// canonical signed-digit form (46 = 64 - 16 - 2: three terms where its binary form has four), so
// that no multiplier or DSP block is inferred; SHIFT_ADD = 0 leaves the products to the tools.
`default_nettype none
`include "stereo_assert.svh"

module stereo_weighted_sum #(
    parameter int WINDOW         = 5,
    parameter int IN_BITS        = 10,
    parameter int SUM_BITS       = 20,
    parameter bit RUNTIME_KERNEL = 1'b1,
    parameter bit LEVEL_KERNEL   = 1'b0,
    parameter bit SHIFT_ADD      = 1'b0
) (
    input  wire logic [WINDOW*IN_BITS-1:0]          taps,
    /* verilator lint_off UNUSEDSIGNAL */  // ignored with RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0] kernel,
    /* verilator lint_on UNUSEDSIGNAL */
    output      logic [SUM_BITS-1:0]                sum
);
  localparam int R = WINDOW / 2;
  localparam int TAP_BITS = fx_pkg::TAP_BITS;

  // Taps i and WINDOW - 1 - i are paired around the centre tap R.
  `STEREO_ASSERT(window_odd, WINDOW >= 1 && WINDOW % 2 == 1, "WINDOW must be odd")

  // Digit `position` (-1, 0 or 1) of the canonical signed-digit form of `value` >= 0: no two
  // adjacent digits nonzero, the fewest nonzero digits of any signed-digit form.
  function automatic int csd_digit(input int value, input int position);
    int rest, digit;
    rest = value;
    digit = 0;
    for (int b = 0; b <= position; b++) begin
      if (rest % 2 != 0) digit = 2 - rest % 4;  // 1 when rest = 1 mod 4, -1 when 3 mod 4
      else digit = 0;
      rest = (rest - digit) / 2;
    end
    csd_digit = digit;
  endfunction

  function automatic int constant_tap(input int i);
    constant_tap = fx_pkg::constant_tap(LEVEL_KERNEL, WINDOW, i);
  endfunction

  // x times the constant `tap`, modulo 2^SUM_BITS (exact where the true sum fits SUM_BITS).
  function automatic logic [SUM_BITS-1:0] times_tap(input logic [SUM_BITS-1:0] x, input int tap);
    times_tap = '0;
    if (SHIFT_ADD) begin
      for (int b = 0; b <= TAP_BITS; b++) begin
        if (csd_digit(tap, b) > 0) times_tap = times_tap + (x << b);
        else if (csd_digit(tap, b) < 0) times_tap = times_tap - (x << b);
      end
    end else begin
      times_tap = x * SUM_BITS'(tap);
    end
  endfunction
  always_comb begin
    if (RUNTIME_KERNEL) begin
      sum = '0;
      for (int i = 0; i < WINDOW; i++) begin
        sum = sum + SUM_BITS'(taps[i*IN_BITS +: IN_BITS]) *
                    SUM_BITS'(kernel[i*TAP_BITS +: TAP_BITS]);
      end
    end else begin
      sum = times_tap(SUM_BITS'(taps[R*IN_BITS +: IN_BITS]), constant_tap(R));
      for (int i = 0; i < R; i++) begin
        sum = sum + times_tap(SUM_BITS'(taps[i*IN_BITS +: IN_BITS]) +
                              SUM_BITS'(taps[(2*R-i)*IN_BITS +: IN_BITS]),
                              constant_tap(i));
      end
    end
  end
endmodule

`default_nettype wire
