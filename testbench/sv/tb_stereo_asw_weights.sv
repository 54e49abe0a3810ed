// tb_stereo_asw_weights: stereo_asw_weights (two labels' support weights from one multiplier,
// fx_pkg::asw_combine_pair) against fx_pkg::asw_combine, the one-product definition, lane by lane.
// Every pair of factors (a, b) 0 .. 255 passes through every lane of a LANES-lane instance (odd
// LANES: the last lane's pair has a zero partner), each lane with a different b, and every tap
// masked once; prints "tb_stereo_asw_weights: PASS ..." and $finish, or the first mismatches and
// $fatal (a non-zero exit status).
`default_nettype none

module tb_stereo_asw_weights #(
    parameter int LANES = 3,
    parameter int TAPS = 2
);
  logic [8*TAPS-1:0] shared;
  logic [LANES*8*TAPS-1:0] lane_factors, weights;
  logic [TAPS-1:0] tap_inside;

  stereo_asw_weights #(.LANES(LANES), .TAPS(TAPS)) dut (.*);

  // Lane l, tap t of the vector for (a, b): b rotated by a different amount per lane and tap,
  // so a swapped lane or tap, or a carry from one half into the other, changes the weight.
  function automatic logic [7:0] factor_of(input int b, input int l, input int t);
    factor_of = 8'((b + 37 * l + 101 * t) % 256);
  endfunction

  initial begin
    int errors, checks;
    logic [7:0] expected;
    errors = 0;
    checks = 0;
    for (int a = 0; a < 256; a++) begin
      for (int b = 0; b < 256; b++) begin
        for (int t = 0; t < TAPS; t++) begin
          shared[t*8+:8] = 8'((a + 59 * t) % 256);
          for (int l = 0; l < LANES; l++) lane_factors[(l*TAPS+t)*8+:8] = factor_of(b, l, t);
        end
        tap_inside = TAPS'((a + b) % (1 << TAPS)) | TAPS'(1);  // tap 0 inside, the rest vary
        if (b == 255) tap_inside = '0;  // every tap outside once per a
        #1;
        for (int l = 0; l < LANES; l++) begin
          for (int t = 0; t < TAPS; t++) begin
            expected = tap_inside[t] ? fx_pkg::asw_combine(shared[t*8+:8], factor_of(b, l, t))
                                     : 8'd0;
            checks++;
            if (weights[(l*TAPS+t)*8+:8] !== expected) begin
              errors++;
              if (errors <= 10) begin
                $display("tb_stereo_asw_weights: lane %0d tap %0d a %0d b %0d: %0d, expected %0d",
                         l, t, shared[t*8+:8], factor_of(b, l, t), weights[(l*TAPS+t)*8+:8],
                         expected);
              end
            end
          end
        end
      end
    end
    if (errors != 0) $fatal(1, "tb_stereo_asw_weights: FAIL: %0d of %0d weights differ", errors, checks);
    $display("tb_stereo_asw_weights: PASS: %0d weights of %0d lanes, %0d taps", checks, LANES, TAPS);
    $finish;
  end
endmodule

`default_nettype wire
