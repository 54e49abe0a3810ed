// stereo_window3x3: the 3x3 neighbourhood of every disparity plane, for the CA rules.
//
// A two-row line buffer and two column registers hold, at the step of input pixel (x, y), the
// window centred on (x-1, y-1) (wrapping to the previous row at x = 0). window_data holds
// position (dx, dy) in {-1, 0, 1}^2 at slot (dy+1)*3 + (dx+1), each slot NDISP*BITS wide;
// in_frame[slot] says whether that position lies in the frame (outside positions must be read as
// zero padding). Combinational outputs; the rule modules register their results.
`default_nettype none

module stereo_window3x3 #(
    parameter int WIDTH = 64,  // longest row
    parameter int BITS  = 14,  // one DSI value
    parameter int NDISP = 16   // disparities in parallel
) (
    input  wire logic                          clk,
    input  wire logic                          ce,
    input  wire logic signed [15:0]            in_x,
    input  wire logic signed [15:0]            in_y,
    input  wire logic        [NDISP*BITS-1:0]  in_data,
    input  wire logic        [15:0]            cfg_width,
    input  wire logic        [15:0]            cfg_height,
    output      logic signed [15:0]            centre_x,
    output      logic signed [15:0]            centre_y,
    output      logic        [9*NDISP*BITS-1:0] window_data,
    output      logic        [8:0]             in_frame
);
  localparam int COLUMN = NDISP * BITS;

  logic [2*COLUMN-1:0] rows_above;  // row y-1 at slot 0, row y-2 at slot 1
  stereo_line_buffer #(
      .WIDTH(WIDTH),
      .DATA_BITS(COLUMN),
      .ROWS(2)
  ) line_buffer (
      .clk(clk),
      .ce(ce),
      .in_x(in_x),
      .cfg_width(cfg_width),
      .in_data(in_data),
      .rows_above(rows_above)
  );

  // The incoming column, rows y-2 (top) .. y (bottom), and the two columns before it.
  logic [3*COLUMN-1:0] column_new, column_1, column_2;  // slot 0 = top row
  assign column_new = {in_data, rows_above[0 +: COLUMN], rows_above[COLUMN +: COLUMN]};

  always_ff @(posedge clk) begin
    if (ce) begin
      column_1 <= column_new;
      column_2 <= column_1;
    end
  end

  // Centre = the column one step ago, one row up: (x-1, y-1).
  // Coordinates are 18-bit signed: 16-bit positions, the no-pixel code and the wrap fit.
  logic signed [17:0] cx, cy;
  always_comb begin
    cx = 18'(in_x) - 18'sd1;
    cy = 18'(in_y) - 18'sd1;
    if (cx < 18'sd0) begin
      cx = cx + $signed(18'(cfg_width));
      cy = cy - 18'sd1;
    end
  end
  assign centre_x = 16'(cx);
  assign centre_y = 16'(cy);

  // Which rows and columns of the window lie inside the frame; a slot is inside when both are.
  logic [2:0] row_inside, column_inside;
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      column_inside[k] = cx + 18'(k - 1) >= 18'sd0 && cx + 18'(k - 1) < $signed(18'(cfg_width));
      row_inside[k] = cy + 18'(k - 1) >= 18'sd0 && cy + 18'(k - 1) < $signed(18'(cfg_height));
    end
  end

  generate
    for (genvar dy = -1; dy <= 1; dy++) begin : g_row
      for (genvar dx = -1; dx <= 1; dx++) begin : g_column
        localparam int SLOT = (dy + 1) * 3 + (dx + 1);
        if (dx == -1) begin : g_left
          assign window_data[SLOT*COLUMN +: COLUMN] = column_2[(dy+1)*COLUMN +: COLUMN];
        end else if (dx == 0) begin : g_middle
          assign window_data[SLOT*COLUMN +: COLUMN] = column_1[(dy+1)*COLUMN +: COLUMN];
        end else begin : g_right
          assign window_data[SLOT*COLUMN +: COLUMN] = column_new[(dy+1)*COLUMN +: COLUMN];
        end
        assign in_frame[SLOT] = row_inside[dy+1] && column_inside[dx+1];
      end
    end
  endgenerate
endmodule

`default_nettype wire
