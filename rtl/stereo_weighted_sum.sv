// stereo_weighted_sum: sum over i of tap i times kernel weight i, for WINDOW taps (the 1-D
// pass of the separable aggregation, used for its vertical and its horizontal pass). Exact in
// SUM_BITS; combinational.
// RUNTIME_KERNEL = 1: generic multipliers by the weights of `kernel`. RUNTIME_KERNEL = 0: the
// model's default kernel for WINDOW (fx_pkg::default_tap), which is symmetric (k[i] = k[2R-i],
// checked in stereo_aggregate): mirrored taps are added before the one constant product they
// share, R + 1 products instead of 2R + 1.
`default_nettype none

module stereo_weighted_sum #(
    parameter int WINDOW         = 5,
    parameter int IN_BITS        = 10,
    parameter int SUM_BITS       = 20,
    parameter bit RUNTIME_KERNEL = 1'b1
) (
    input  wire logic [WINDOW*IN_BITS-1:0]          taps,
    /* verilator lint_off UNUSEDSIGNAL */  // ignored with RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0] kernel,
    /* verilator lint_on UNUSEDSIGNAL */
    output      logic [SUM_BITS-1:0]                sum
);
  localparam int R = WINDOW / 2;
  localparam int TAP_BITS = fx_pkg::TAP_BITS;
  always_comb begin
    if (RUNTIME_KERNEL) begin
      sum = '0;
      for (int i = 0; i < WINDOW; i++) begin
        sum = sum + SUM_BITS'(taps[i*IN_BITS +: IN_BITS]) *
                    SUM_BITS'(kernel[i*TAP_BITS +: TAP_BITS]);
      end
    end else begin
      sum = SUM_BITS'(taps[R*IN_BITS +: IN_BITS]) * SUM_BITS'(fx_pkg::default_tap(WINDOW, R));
      for (int i = 0; i < R; i++) begin
        sum = sum + (SUM_BITS'(taps[i*IN_BITS +: IN_BITS]) +
                     SUM_BITS'(taps[(2*R-i)*IN_BITS +: IN_BITS])) *
                    SUM_BITS'(fx_pkg::default_tap(WINDOW, i));
      end
    end
  end
endmodule

`default_nettype wire
