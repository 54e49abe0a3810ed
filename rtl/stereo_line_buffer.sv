// stereo_line_buffer: the ROWS previous image rows at the column being streamed in.
//
// One RAM word per column holds that column of the last ROWS rows. At the step of column x the
// buffer shows rows_above = {row y-ROWS, ..., row y-2, row y-1} at column x (row y-1 in the
// low bits), and stores {rows_above minus its oldest row, in_data}. The RAM is read one step
// ahead (address of the next column), so its registered output is ready when that column
// arrives. Read and write addresses differ whenever the width exceeds 1; at width 1 the next
// column is the one being written, so the word being stored is passed straight through.
// Rows above the image hold stale data: the stages mask them by coordinates.
`default_nettype none

module stereo_line_buffer #(
    parameter int WIDTH     = 64,  // longest row
    parameter int DATA_BITS = 8,   // one pixel's data
    parameter int ROWS      = 2    // rows kept
) (
    input  wire logic                        clk,
    input  wire logic                        ce,         // advance one pixel step
    input  wire logic signed [15:0]          in_x,       // column of this step, 0 .. cfg_width-1
    input  wire logic        [15:0]          cfg_width,
    input  wire logic        [DATA_BITS-1:0] in_data,
    output      logic   [ROWS*DATA_BITS-1:0] rows_above  // row y-1-k at [k*DATA_BITS +: DATA_BITS]
);
  localparam int ADDR_BITS = (WIDTH > 1) ? $clog2(WIDTH) : 1;

  logic [ROWS*DATA_BITS-1:0] memory[WIDTH];
  logic [ROWS*DATA_BITS-1:0] stored;
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
      rows_above <= (cfg_width == 16'd1) ? stored : memory[read_address];
    end
  end
endmodule

`default_nettype wire
