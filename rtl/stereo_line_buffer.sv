// stereo_line_buffer: the ROWS previous image rows at the column being streamed in.
//
// One RAM word per column holds that column of the last ROWS rows. At the step of column x the
// buffer shows rows_above = {row y-ROWS, ..., row y-2, row y-1} at column x (row y-1 in the
// low bits), and stores {rows_above minus its oldest row, in_data}. The RAM is read one step
// ahead (address of the next column), so its registered output is ready when that column
// arrives. The RAM has one write port and one registered read port with a clock enable and no
// logic between the RAM and its output register, so synthesis maps it to block RAM (checked
// in the synthesis reports, docs/synthesis.md). Read and write addresses differ whenever the
// width exceeds 1; at width 1 the next column is the one being written, so the word being
// stored is taken from a bypass register instead of the RAM.
// Rows above the image hold stale data: the stages mask them by coordinates.
//
// GROUPS > 1 (time-multiplexed lanes, docs/rtl.md): a pixel step takes GROUPS clocks, and at the
// clock of label group g (`group`) the buffer shows and stores group g of the column: in_data and
// rows_above are one group wide, and the RAM has GROUPS words per column (address x*GROUPS + g),
// so one read per clock returns one group. `ce` then means "advance": a clock of a group below
// GROUPS-1, or the step itself (the stage passes ce || group != GROUPS-1). At group g the RAM
// reads group g+1 of the same column, at the last group (the step) group 0 of the next column;
// its output register holds the last group while the step waits. Read and write addresses
// always differ (no bypass needed, whatever the width).
`default_nettype none

module stereo_line_buffer #(
    parameter int WIDTH     = 64,  // longest row
    parameter int DATA_BITS = 8,   // one pixel's data
    parameter int ROWS      = 2,   // rows kept
    parameter int GROUPS    = 1    // label groups per column, one per clock (see above)
) (
    input  wire logic                      clk,
    input  wire logic                      ce,         // advance one pixel step (one group)
    input  wire fx_pkg::coord_t            in_x,       // column of this step, 0 .. cfg_width-1
    /* verilator lint_off UNUSEDSIGNAL */  // GROUPS = 1: always 0
    input  wire logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group,  // label group now
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::cfg_size_t         cfg_width,
    input  wire logic [DATA_BITS-1:0]      in_data,
    output      logic [ROWS*DATA_BITS-1:0] rows_above  // row y-1-k at [k*DATA_BITS +: DATA_BITS]
);
  localparam int DEPTH = WIDTH * GROUPS;
  localparam int ADDR_BITS = (DEPTH > 1) ? $clog2(DEPTH) : 1;
  localparam int WORD_BITS = ROWS * DATA_BITS;

  logic [WORD_BITS-1:0] memory[DEPTH];
  logic [WORD_BITS-1:0] stored;
  logic [WORD_BITS-1:0] memory_q;  // the RAM's output register
  logic [WORD_BITS-1:0] bypass_q;  // the word stored at the previous step (width 1)
  logic width_is_one;
  logic [ADDR_BITS-1:0] write_address;
  logic [ADDR_BITS-1:0] read_address;

  // in_x is the last column of the row (or outside it): in_x + 1 >= cfg_width, with in_x read as
  // an unsigned 32-bit number as the address arithmetic below did before (one subtraction in
  // stereo_border_flags instead of two 32-bit adders; the same truth for every 16-bit in_x).
  logic next_inside;
  logic row_end;
  stereo_border_flags #(
      .OFFSET_LO(1),
      .OFFSET_HI(1)
  ) next_column (
      .position(18'(in_x)),
      .limit(cfg_width),
      .in_frame(next_inside)
  );
  assign row_end = !next_inside;

  generate
    if (GROUPS > 1) begin : g_grouped_address
      always_comb begin
        write_address = ADDR_BITS'(32'(in_x) * GROUPS + 32'(group));
        if (32'(group) + 1 < GROUPS) read_address = write_address + 1'b1;
        else if (row_end) read_address = '0;
        else read_address = ADDR_BITS'((32'(in_x) + 1) * GROUPS);
      end
    end else begin : g_address
      always_comb begin
        write_address = ADDR_BITS'(in_x);
        read_address = row_end ? '0 : ADDR_BITS'(in_x + 16'sd1);
      end
    end
  endgenerate

  generate
    if (ROWS > 1) begin : g_shift
      assign stored = {rows_above[(ROWS-1)*DATA_BITS-1:0], in_data};
    end else begin : g_single
      assign stored = in_data;
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) begin
      memory[write_address] <= stored;
      memory_q <= memory[read_address];
    end
  end

  generate
    if (GROUPS > 1) begin : g_no_bypass
      assign bypass_q = '0;
      assign width_is_one = 1'b0;
    end else begin : g_bypass
      always_ff @(posedge clk) begin
        if (ce) begin
          bypass_q <= stored;
          width_is_one <= cfg_width == 16'd1;
        end
      end
    end
  endgenerate
  assign rows_above = width_is_one ? bypass_q : memory_q;
endmodule

`default_nettype wire
