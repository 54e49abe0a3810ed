// stereo_fifo: a first-word-fall-through FIFO of DEPTH words of BITS bits: one memory with a write
// port and a registered read port (block RAM), and an output register that holds the oldest word
// (out_valid). A word written into an empty FIFO shows on the output two clocks later. in_ready is
// low while DEPTH words wait in the memory (the output register holds one more). Reset empties it.
`default_nettype none
`include "stereo_assert.svh"

module stereo_fifo #(
    parameter int BITS  = 8,
    parameter int DEPTH = 16
) (
    input  wire logic            clk,
    input  wire logic            rst,
    input  wire logic            in_valid,  // written when in_ready
    input  wire logic [BITS-1:0] in_data,
    output      logic            in_ready,
    output      logic            out_valid,
    output      logic [BITS-1:0] out_data,
    input  wire logic            out_take   // the output word is taken (with out_valid)
);
  localparam int ADDR_BITS = (DEPTH > 1) ? $clog2(DEPTH) : 1;
  `STEREO_ASSERT(depth_positive, DEPTH >= 2 && BITS >= 1, "DEPTH must be at least 2, BITS at least 1")

  logic [BITS-1:0] mem[DEPTH];
  logic [ADDR_BITS-1:0] write_at, read_at;
  logic [ADDR_BITS:0] stored;  // words in the memory, the output register's not counted
  logic write, read;
  assign in_ready = 32'(stored) < DEPTH;
  assign write = in_valid && in_ready;
  assign read = stored != 0 && (!out_valid || out_take);  // refill the output register

  function automatic logic [ADDR_BITS-1:0] next_address(input logic [ADDR_BITS-1:0] address);
    next_address = (32'(address) == DEPTH - 1) ? '0 : address + 1'b1;
  endfunction

  always_ff @(posedge clk) begin
    if (write) mem[write_at] <= in_data;
    if (read) out_data <= mem[read_at];
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      write_at <= '0;
      read_at <= '0;
      stored <= '0;
      out_valid <= 1'b0;
    end else begin
      if (write) write_at <= next_address(write_at);
      if (read) read_at <= next_address(read_at);
      stored <= stored + (ADDR_BITS + 1)'(write) - (ADDR_BITS + 1)'(read);
      if (read) out_valid <= 1'b1;
      else if (out_take) out_valid <= 1'b0;
    end
  end
endmodule

`default_nettype wire
