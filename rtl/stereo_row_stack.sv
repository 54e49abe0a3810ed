// stereo_row_stack: the ROWS rows of one column of an image streamed in raster order, one pixel
// per pixel step (ce) at column in_x: column slot j holds row in_y - (ROWS-1) + j, the incoming
// pixel in_data last (slot ROWS-1) and the rows above it from a one-group stereo_line_buffer of
// ROWS-1 rows (read a step ahead). Rows above the image hold stale data: the users mask them by
// coordinates. The window rows of stereo_census (both lumas) and stereo_cost's recomputed rows
// (both RGB pixels, ROWS > 1).
`default_nettype none
`include "stereo_assert.svh"

module stereo_row_stack #(
    parameter int WIDTH     = 64,  // longest row
    parameter int DATA_BITS = 8,   // one pixel's data
    parameter int ROWS      = 2    // rows of the stack, the incoming one included
) (
    input  wire logic                      clk,
    input  wire logic                      ce,  // the pixel step
    input  wire fx_pkg::coord_t            in_x,  // column of this step, 0 .. cfg_width-1
    input  wire fx_pkg::cfg_size_t         cfg_width,
    input  wire logic [DATA_BITS-1:0]      in_data,
    output      logic [ROWS*DATA_BITS-1:0] column  // row in_y - (ROWS-1) + j at slot j
);
  `STEREO_ASSERT(rows_min, ROWS >= 2, "ROWS must be at least 2")

  logic [(ROWS-1)*DATA_BITS-1:0] rows_above;  // row in_y - 1 - k at slot k
  stereo_line_buffer #(
      .WIDTH(WIDTH),
      .DATA_BITS(DATA_BITS),
      .ROWS(ROWS - 1),
      .GROUPS(1)
  ) line_buffer (
      .clk(clk),
      .ce(ce),
      .in_x(in_x),
      .group(1'b0),
      .cfg_width(cfg_width),
      .in_data(in_data),
      .rows_above(rows_above)
  );
  always_comb begin
    for (int j = 0; j < ROWS - 1; j++) begin
      column[j*DATA_BITS +: DATA_BITS] = rows_above[(ROWS-2-j)*DATA_BITS +: DATA_BITS];
    end
    column[(ROWS-1)*DATA_BITS +: DATA_BITS] = in_data;
  end
endmodule

`default_nettype wire
