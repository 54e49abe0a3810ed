// stereo_divider: restoring division of a fraction, quotient = floor((dividend << QUOTIENT_BITS)
// / divisor) for dividend < divisor (then the quotient fits QUOTIENT_BITS). Stage 6 computes the
// certainty floor(((C2 - C1) << 8) / (C2 + 1)) with it (stereo::validation::certainty).
//
// QUOTIENT_BITS rows of one subtractor each, combinational (the user registers the quotient):
// row i doubles the partial remainder and subtracts the divisor where it fits, which sets
// quotient bit QUOTIENT_BITS - 1 - i. The remainder stays below the divisor, so it needs one bit
// more than the divisor only while doubled.
`default_nettype none

module stereo_divider #(
    parameter int DIVISOR_BITS  = 15,  // the dividend has as many bits and is below the divisor
    parameter int QUOTIENT_BITS = 8
) (
    input  wire logic [DIVISOR_BITS-1:0]  dividend,
    input  wire logic [DIVISOR_BITS-1:0]  divisor,
    output      logic [QUOTIENT_BITS-1:0] quotient
);
  always_comb begin
    logic [DIVISOR_BITS:0] remainder;
    remainder = {1'b0, dividend};
    quotient = '0;
    for (int i = QUOTIENT_BITS - 1; i >= 0; i--) begin
      remainder = {remainder[DIVISOR_BITS-1:0], 1'b0};
      if (remainder >= {1'b0, divisor}) begin
        remainder = remainder - {1'b0, divisor};
        quotient[i] = 1'b1;
      end
    end
  end
endmodule

`default_nettype wire
