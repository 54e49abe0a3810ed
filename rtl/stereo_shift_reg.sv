// stereo_shift_reg: the last DEPTH values of in_data, shifted in at each pixel step (ce);
// history[i*BITS +: BITS] is the value taken i + 1 steps ago. No reset: like a stage's data
// register, what it holds before a frame's pixels arrive is never read as a pixel (docs/rtl.md).
`default_nettype none

module stereo_shift_reg #(
    parameter int BITS  = 8,
    parameter int DEPTH = 2
) (
    input  wire logic                  clk,
    input  wire logic                  ce,
    input  wire logic [BITS-1:0]       in_data,
    output      logic [DEPTH*BITS-1:0] history
);
  generate
    if (DEPTH > 1) begin : g_shift
      always_ff @(posedge clk) begin
        if (ce) history <= {history[(DEPTH-1)*BITS-1:0], in_data};
      end
    end else begin : g_single
      always_ff @(posedge clk) begin
        if (ce) history <= in_data;
      end
    end
  endgenerate
endmodule

`default_nettype wire
