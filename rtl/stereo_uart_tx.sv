// stereo_uart_tx: UART transmitter, 8 data bits, no parity, one stop bit (8N1), LSB first.
//
// A valid/ready byte input: `ready` is high while the transmitter is idle; a byte taken with
// valid && ready goes out as a start bit (0), eight data bits and a stop bit (1), each
// CLKS_PER_BIT clocks long, so back-to-back bytes take exactly 10 * CLKS_PER_BIT clocks each (`ready` is high
// in the last clock of a stop bit). The line
// is high while idle and in reset. Reset is synchronous, active high.
`default_nettype none
`include "stereo_assert.svh"

module stereo_uart_tx #(
    parameter int CLKS_PER_BIT = 4  // clock cycles per bit (clock / baud rate), at least 1
) (
    input  wire logic       clk,
    input  wire logic       rst,
    input  wire logic [7:0] data,
    input  wire logic       valid,
    output      logic       ready,
    output      logic       tx      // the serial line, idle high
);
  localparam int COUNT_BITS = $clog2(CLKS_PER_BIT + 1);
  localparam logic [COUNT_BITS-1:0] FULL_BIT = COUNT_BITS'(CLKS_PER_BIT - 1);

  `STEREO_ASSERT(clks_per_bit_min, CLKS_PER_BIT >= 1, "CLKS_PER_BIT must be at least 1")

  logic busy;
  logic [COUNT_BITS-1:0] count;  // clocks left in the current bit
  logic [3:0] bits_left;  // bits after the current one
  logic [8:0] shift;  // {stop bit, data bits not yet sent}
  logic stop_done;  // the last clock of the stop bit: the next byte may start now

  assign stop_done = busy && count == 0 && bits_left == 0;
  assign ready = !busy || stop_done;

  always_ff @(posedge clk) begin
    if (rst) begin
      busy <= 1'b0;
      count <= '0;
      bits_left <= '0;
      shift <= '1;
      tx <= 1'b1;
    end else if (ready) begin
      if (valid) begin
        busy <= 1'b1;
        tx <= 1'b0;  // start bit
        shift <= {1'b1, data};
        count <= FULL_BIT;
        bits_left <= 4'd9;
      end else begin
        busy <= 1'b0;
        tx <= 1'b1;
      end
    end else if (count != 0) begin
      count <= count - 1'b1;
    end else begin
      tx <= shift[0];
      shift <= {1'b1, shift[8:1]};
      count <= FULL_BIT;
      bits_left <= bits_left - 1'b1;
    end
  end
endmodule

`default_nettype wire
