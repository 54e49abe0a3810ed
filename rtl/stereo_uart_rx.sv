// stereo_uart_rx: UART receiver, 8 data bits, no parity, one stop bit (8N1), LSB first.
//
// The line passes a two-flop synchroniser. A falling edge on the idle line starts a frame; the
// start bit is checked again half a bit later (a shorter low pulse is a glitch and ignored), and
// from there every bit is sampled once, in the middle of its bit time (CLKS_PER_BIT clocks per
// bit). At the middle of the stop bit the byte is delivered: `valid` is high for one cycle with
// `data`, and `framing_error` is high with it when the stop bit was 0 (the byte is delivered all
// the same; the receiver then waits for the line to go idle (high) before it looks for the next
// start bit). Reset is synchronous, active high.
`default_nettype none
`include "stereo_assert.svh"

module stereo_uart_rx #(
    parameter int CLKS_PER_BIT = 4  // clock cycles per bit (clock / baud rate), at least 4
) (
    input  wire logic       clk,
    input  wire logic       rst,
    input  wire logic       rx,             // the serial line, idle high (asynchronous)
    output      logic [7:0] data,
    output      logic       valid,          // one cycle per received byte
    output      logic       framing_error   // with valid: the stop bit was 0
);
  localparam int COUNT_BITS = $clog2(CLKS_PER_BIT + 1);
  localparam logic [COUNT_BITS-1:0] FULL_BIT = COUNT_BITS'(CLKS_PER_BIT - 1);
  localparam logic [COUNT_BITS-1:0] HALF_BIT = COUNT_BITS'(CLKS_PER_BIT / 2 - 1);

  `STEREO_ASSERT(clks_per_bit_min, CLKS_PER_BIT >= 4, "CLKS_PER_BIT must be at least 4")

  // Two-flop synchroniser; the line is idle high, so the flops start high.
  logic rx_meta, rx_sync;
  always_ff @(posedge clk) begin
    if (rst) begin
      rx_meta <= 1'b1;
      rx_sync <= 1'b1;
    end else begin
      rx_meta <= rx;
      rx_sync <= rx_meta;
    end
  end

  typedef enum logic [2:0] {
    IDLE,   // waiting for a falling edge
    START,  // half a bit into the start bit
    DATA,   // eight data bits, one per bit time
    STOP,   // the stop bit
    WAIT    // after a framing error: until the line is high again
  } state_t;
  state_t state;
  logic [COUNT_BITS-1:0] count;  // clocks left until the next sample
  logic [2:0] bit_index;
  logic [7:0] shift;
  logic timing;  // START, DATA and STOP sample the line when their bit timer `count` runs out
  assign timing = state == START || state == DATA || state == STOP;

  always_ff @(posedge clk) begin
    valid <= 1'b0;
    framing_error <= 1'b0;
    if (rst) begin
      state <= IDLE;
      count <= '0;
      bit_index <= '0;
      shift <= '0;
      data <= '0;
    end else if (timing && count != 0) begin
      count <= count - 1'b1;  // the bit timer: the states below act when it has run out
    end else begin
      unique case (state)
        IDLE: begin
          if (!rx_sync) begin
            state <= START;
            count <= HALF_BIT;
          end
        end
        START: begin
          if (rx_sync) begin
            state <= IDLE;  // a glitch, not a start bit
          end else begin
            state <= DATA;
            count <= FULL_BIT;
            bit_index <= '0;
          end
        end
        DATA: begin
          shift <= {rx_sync, shift[7:1]};
          count <= FULL_BIT;
          bit_index <= bit_index + 1'b1;
          if (bit_index == 3'd7) state <= STOP;
        end
        STOP: begin
          valid <= 1'b1;
          data <= shift;
          framing_error <= !rx_sync;
          state <= rx_sync ? IDLE : WAIT;
        end
        WAIT: begin
          if (rx_sync) state <= IDLE;
        end
        default: state <= IDLE;
      endcase
    end
  end
endmodule

`default_nettype wire
