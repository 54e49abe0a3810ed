// stereo_window3x3: the 3x3 neighbourhood of every disparity plane, for the CA rules.
//
// An input register, a two-row line buffer and two column registers hold, one step after input
// pixel (x, y) arrives, the window centred on (x-1, y-1) (wrapping to the previous row at x = 0).
// window_data holds position (dx, dy) in {-1, 0, 1}^2 at slot (dy+1)*3 + (dx+1), each slot
// NDISP*BITS wide; in_frame[slot] says whether that position lies in the frame (outside positions
// must be read as zero padding). Every output comes from a register (window_data partly through
// the line buffer's RAM output register); the rule modules register their results.
//
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): at the clock of label group g (`group`;
// the step, ce, comes at group G-1, G = NDISP / LANES) window_data holds labels [g*LANES +:
// LANES] of the window: in_data is the producer's result of this clock's group (it hands on
// one group per clock, unregistered), delayed by 2G group clocks in a RAM ring (stereo_group_ring;
// where the all-parallel stage has the producer's output register and this input register, two
// steps), the line buffer has G words per column, and the two column registers of the G groups circulate in a ring of G
// slots that advances one slot per group (ce || group != G-1), its head being the group of the
// clock; the ring is a RAM (stereo_group_ring), not G registers. next_centre is the centre value of label (g+1)*LANES (the next group's first, not yet
// advanced), for rule 1's d+1 across the group boundary.
`default_nettype none
`include "stereo_assert.svh"

module stereo_window3x3 #(
    parameter int WIDTH = 64,  // longest row
    parameter int BITS  = 14,  // one DSI value
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP,  // labels per clock (divides NDISP)
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
`include "stereo_stage_ports.svh"
    // G = 1: the pixel's NDISP values; G > 1: the producer's result of this clock's group.
    input  wire logic [LANES*BITS-1:0]   in_data,
    input  wire fx_pkg::cfg_size_t       cfg_width,
    input  wire fx_pkg::cfg_size_t       cfg_height,
    output      fx_pkg::coord_t          centre_x,
    output      fx_pkg::coord_t          centre_y,
    output      logic [9*LANES*BITS-1:0] window_data,  // this clock's group
    output      logic [BITS-1:0]         next_centre,  // centre of label (group+1)*LANES; 0 if G = 1
    output      logic [8:0]              in_frame
);
  localparam int GROUPS = NDISP / LANES;
  localparam int COLUMN = LANES * BITS;  // one group of one position

  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")

  // The group of this clock; G = 1: 0 whatever the port carries.
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  assign group_now = (GROUPS > 1) ? group : '0;
  // A clock that processes a group: every group below the last, and the last at the step.
  logic advance;
  assign advance = ce || 32'(group_now) != GROUPS - 1;

  // ---- input register --------------------------------------------------------------------
  // The incoming pixel is registered first, and the geometry of the window it completes (its
  // centre and which of its positions lie in the frame) is computed from the incoming
  // coordinates and registered beside it. The rules then start from registers: the coordinate
  // arithmetic no longer runs in front of their comparisons and sums (the critical path before,
  // docs/synthesis.md). Cost: one pixel step of latency.
  fx_pkg::coord_t x_q;  // addresses the line buffer; the geometry is registered below
  always_ff @(posedge clk) begin
    if (ce) x_q <= in_x;
  end
  logic [COLUMN-1:0] data_q;  // this clock's group of the registered pixel
  generate
    if (GROUPS > 1) begin : g_input_ring
      // The group the producer computed 2G advances ago: the pixel whose coordinates x_q holds.
      // In flip-flops that would be the producer's G-1 assembly and G output words and this
      // stage's G input words; here 2G words of RAM (block RAM on the iCE40).
      stereo_group_ring #(
          .BITS     (COLUMN),
          .GROUPS   (2 * GROUPS),
          .BLOCK_RAM(RING_BLOCK_RAM),
          .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) input_ring (
          .clk(clk),
          .advance(advance),
          .next_state(in_data),
          .head(data_q)
      );
    end else begin : g_input_register
      always_ff @(posedge clk) begin
        if (ce) data_q <= in_data;
      end
    end
  endgenerate

  logic [2*COLUMN-1:0] rows_above;  // rows y-1 (slot 0) and y-2 (slot 1) of the registered pixel
  stereo_line_buffer #(
      .WIDTH(WIDTH),
      .DATA_BITS(COLUMN),
      .ROWS(2),
      .GROUPS(GROUPS)
  ) line_buffer (
      .clk(clk),
      .ce(advance),
      .in_x(x_q),
      .group(group_now),
      .cfg_width(cfg_width),
      .in_data(data_q),
      .rows_above(rows_above)
  );

  // The registered column, rows y-2 (top) .. y (bottom), and the two columns before it (one
  // group's, from the ring below).
  logic [3*COLUMN-1:0] column_new, column_1, column_2;  // slot 0 = top row
  assign column_new = {data_q, rows_above[0 +: COLUMN], rows_above[COLUMN +: COLUMN]};

  // {column_2, column_1} of the group of this clock, the head of stereo_group_ring (G = 1: one
  // register, stepped with ce); the advance stores the group's next columns.
  logic [6*COLUMN-1:0] columns_q;
  stereo_group_ring #(
      .BITS     (6 * COLUMN),
      .GROUPS   (GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) column_ring (
      .clk(clk),
      .advance(advance),
      .next_state({column_1, column_new}),
      .head(columns_q)
  );
  assign column_1 = columns_q[0+:3*COLUMN];
  assign column_2 = columns_q[3*COLUMN+:3*COLUMN];
  generate
    if (GROUPS > 1) begin : g_next_centre
      // The next group's column_1 middle row, first lane, in a register ring of its own (the
      // RAM ring shows only the head): one value per group, rule 1 only (rule 2 leaves it
      // unused and synthesis removes it).
      logic [BITS-1:0] centre_ring[GROUPS];
      always_ff @(posedge clk) begin
        if (advance) begin
          for (int k = 0; k + 1 < GROUPS; k++) centre_ring[k] <= centre_ring[k+1];
          centre_ring[GROUPS-1] <= column_new[COLUMN+:BITS];
        end
      end
      assign next_centre = centre_ring[1];
    end else begin : g_no_next_centre
      assign next_centre = '0;
    end
  endgenerate

  // Centre of the window the incoming pixel completes: (x-1, y-1), wrapping to the previous row.
  // Coordinates are 18-bit signed: 16-bit positions, the no-pixel code and the wrap fit.
  logic signed [17:0] cx, cy;
  stereo_window_centre #(.RADIUS(1)) window_centre (
      .in_x(in_x), .in_y(in_y), .cfg_width(cfg_width), .centre_x(cx), .centre_y(cy));
  // Which rows and columns of that window lie inside the frame (one subtraction each, not two
  // comparisons per position: stereo_border_flags).
  logic [2:0] row_inside, column_inside;
  stereo_border_flags #(
      .OFFSET_LO(-1),
      .OFFSET_HI(1)
  ) column_flags (
      .position(cx),
      .limit(cfg_width),
      .in_frame(column_inside)
  );
  stereo_border_flags #(
      .OFFSET_LO(-1),
      .OFFSET_HI(1)
  ) row_flags (
      .position(cy),
      .limit(cfg_height),
      .in_frame(row_inside)
  );

  logic [2:0] row_inside_q, column_inside_q;
  always_ff @(posedge clk) begin
    if (rst) begin
      centre_x <= '0;
      centre_y <= fx_pkg::NO_PIXEL;
      row_inside_q <= '0;
      column_inside_q <= '0;
    end else if (ce) begin
      centre_x <= 16'(cx);
      centre_y <= 16'(cy);
      row_inside_q <= row_inside;
      column_inside_q <= column_inside;
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
        assign in_frame[SLOT] = row_inside_q[dy+1] && column_inside_q[dx+1];
      end
    end
  endgenerate
endmodule

`default_nettype wire
