// stereo_asw_weights: the support weights of one adaptive-support-weight pass for LANES labels
// (stereo_asw_aggregate): weight[l][t] = tap_inside[t] ? shared[t] (x) lane_factors[l][t] : 0,
// (x) = fx_pkg::asw_combine, for TAPS taps. The left image's factor of a tap is the same for
// every label (shared), the right one comes with each label's right column.
//
// Two lanes share one multiplier (fx_pkg::asw_combine_pair: {b1, b0} * a, the two products in
// the two halves), so a DSP block makes two weights: at LANES = 8 and 33 taps a pixel this
// halves the 264 multipliers of the combines (docs/results-asw.md "Resources of the ASW core").
// An odd last lane takes a pair with a zero factor. Combinational.
`default_nettype none
`include "stereo_assert.svh"

module stereo_asw_weights #(
    parameter int LANES = 2,  // labels
    parameter int TAPS  = 5   // taps of the pass (the diameter)
) (
    input  wire logic [8*TAPS-1:0]       shared,        // the left factor of tap t at [t*8 +: 8]
    input  wire logic [LANES*8*TAPS-1:0] lane_factors,  // lane l's right factors at [l*8*TAPS +: 8*TAPS]
    input  wire logic [TAPS-1:0]         tap_inside,    // taps inside the frame
    output      logic [LANES*8*TAPS-1:0] weights        // the same layout as lane_factors
);
  `STEREO_ASSERT(sizes, LANES >= 1 && TAPS >= 1, "LANES and TAPS must be at least 1")
  localparam int PAIRS = (LANES + 1) / 2;

  for (genvar q = 0; q < PAIRS; q++) begin : g_pair
    localparam int LOW = 2 * q;  // the pair's lanes: LOW and LOW + 1 (if any)
    localparam bit TWO = LOW + 1 < LANES;
    localparam int HIGH = TWO ? LOW + 1 : LOW;
    /* verilator lint_off UNUSEDSIGNAL */  // an odd last lane: no high half
    logic [8*TAPS-1:0] low_weights, high_weights;
    /* verilator lint_on UNUSEDSIGNAL */
    always_comb begin
      logic [15:0] both;
      for (int t = 0; t < TAPS; t++) begin
        both = fx_pkg::asw_combine_pair(shared[t*8+:8], lane_factors[LOW*8*TAPS+t*8+:8],
                                        TWO ? lane_factors[HIGH*8*TAPS+t*8+:8] : 8'd0);
        low_weights[t*8+:8] = tap_inside[t] ? both[7:0] : 8'd0;
        high_weights[t*8+:8] = tap_inside[t] ? both[15:8] : 8'd0;
      end
    end
    assign weights[LOW*8*TAPS+:8*TAPS] = low_weights;
    if (TWO) begin : g_high
      assign weights[HIGH*8*TAPS+:8*TAPS] = high_weights;
    end
  end
endmodule

`default_nettype wire
