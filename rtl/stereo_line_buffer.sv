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
`default_nettype none

module stereo_line_buffer #(
    parameter int WIDTH     = 64,  // longest row
    parameter int DATA_BITS = 8,   // one pixel's data
    parameter int ROWS      = 2    // rows kept
) (
    input  wire logic                      clk,
    input  wire logic                      ce,         // advance one pixel step
    input  wire fx_pkg::coord_t            in_x,       // column of this step, 0 .. cfg_width-1
    input  wire fx_pkg::cfg_size_t         cfg_width,
    input  wire logic [DATA_BITS-1:0]      in_data,
    output      logic [ROWS*DATA_BITS-1:0] rows_above  // row y-1-k at [k*DATA_BITS +: DATA_BITS]
);
  localparam int ADDR_BITS = (WIDTH > 1) ? $clog2(WIDTH) : 1;
  localparam int WORD_BITS = ROWS * DATA_BITS;

  logic [WORD_BITS-1:0] memory[WIDTH];
  logic [WORD_BITS-1:0] stored;
  logic [WORD_BITS-1:0] memory_q;  // the RAM's output register
  logic [WORD_BITS-1:0] bypass_q;  // the word stored at the previous step (width 1)
  logic width_is_one;
  logic [ADDR_BITS-1:0] write_address;
  logic [ADDR_BITS-1:0] read_address;

  always_comb begin
    write_address = ADDR_BITS'(in_x);
    read_address = (32'(in_x) + 1 >= 32'(cfg_width)) ? '0 : ADDR_BITS'(in_x + 16'sd1);
  end

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

  always_ff @(posedge clk) begin
    if (ce) begin
      bypass_q <= stored;
      width_is_one <= cfg_width == 16'd1;
    end
  end
  assign rows_above = width_is_one ? bypass_q : memory_q;
endmodule

`default_nettype wire
