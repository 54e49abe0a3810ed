// stereo_coord_reg: the coordinate register of a stage's output, the contract of every stage
// (docs/rtl.md): (out_x, out_y) take (in_x, in_y) on each pixel step (ce); reset marks "no pixel"
// (fx_pkg::NO_PIXEL, far outside any frame), so nothing still in flight is taken for a frame
// pixel. The stage's data register beside it has no reset.
`default_nettype none

module stereo_coord_reg (
    input  wire logic           clk,
    input  wire logic           rst,
    input  wire logic           ce,
    input  wire fx_pkg::coord_t in_x,
    input  wire fx_pkg::coord_t in_y,
    output      fx_pkg::coord_t out_x,
    output      fx_pkg::coord_t out_y
);
  always_ff @(posedge clk) begin
    if (rst) begin
      out_x <= '0;
      out_y <= fx_pkg::NO_PIXEL;
    end else if (ce) begin
      out_x <= in_x;
      out_y <= in_y;
    end
  end
endmodule

`default_nettype wire
