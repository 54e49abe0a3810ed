// stereo_stage_output: the output registers of a stage (docs/rtl.md, "The stage contract"). The
// coordinates are registered at each pixel step (stereo_coord_reg: reset marks "no pixel"). The
// data, REGISTERED = 1: taken at each pixel step, with no reset (what it holds before a frame's
// pixels arrive is never read as a pixel); REGISTERED = 0: in_data itself, for a stage whose
// groups (G > 1) go on combinationally, the consumer's input ring registering them, or for a
// value that is constant.
`default_nettype none

module stereo_stage_output #(
    parameter int BITS       = 8,
    parameter bit REGISTERED = 1'b1
) (
    input  wire logic            clk,
    input  wire logic            rst,
    input  wire logic            ce,
    input  wire fx_pkg::coord_t  in_x,
    input  wire fx_pkg::coord_t  in_y,
    input  wire logic [BITS-1:0] in_data,
    output      fx_pkg::coord_t  out_x,
    output      fx_pkg::coord_t  out_y,
    output      logic [BITS-1:0] out_data
);
  stereo_coord_reg coordinates (.*);
  generate
    if (REGISTERED) begin : g_register
      always_ff @(posedge clk) begin
        if (ce) out_data <= in_data;
      end
    end else begin : g_pass
      assign out_data = in_data;
    end
  endgenerate
endmodule

`default_nettype wire
