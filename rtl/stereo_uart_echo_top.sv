// stereo_uart_echo_top: the iCEBreaker's link test (docs/board.md). Same pins and UART as
// stereo_board_top, no core: every byte received is sent back. Flash it first to check the FTDI
// channel, the port name and the baud rate with any serial terminal, before the stereo build
// (which, today, does not fit the UP5K). It also proves the synthesis flow to a .bin
// (synth.py board --top stereo_uart_echo_top: nextpnr with the board's pins, icepack).
// A byte that arrives while the one before still waits for the transmitter is dropped and
// lights the red LED, as does a UART framing error (sticky until the button resets the design);
// with the same baud rate on both sides neither happens. The green LED is lit out of reset.
`default_nettype none

// A top in rtl/files.f beside stereo_board_top, stereo_axil_top and stereo_synth_top.
/* verilator lint_off MULTITOP */
module stereo_uart_echo_top #(
    parameter int CLKS_PER_BIT = 104,  // clock / baud: 104 is 115200 baud at 12 MHz
    parameter int POR_BITS     = 8     // power-on reset: 2^POR_BITS clocks
) (
    input  wire logic clk,          // 12 MHz oscillator
    input  wire logic uart_rx,      // from the FTDI (host to board)
    output      logic uart_tx,      // to the FTDI (board to host)
    input  wire logic button_n,     // user button, active low: reset
    output      logic led_red_n,    // active low: a byte was dropped or a stop bit was 0
    output      logic led_green_n   // active low: running
);
  logic rst;
  logic [7:0] rx_data, held;
  logic rx_valid, rx_framing_error, held_valid, tx_ready, dropped, framing_error;
  stereo_board_link #(
      .CLKS_PER_BIT(CLKS_PER_BIT),
      .POR_BITS(POR_BITS)
  ) link (
      .tx_data(held),
      .tx_valid(held_valid),
      .*
  );

  always_ff @(posedge clk) begin
    if (rst) begin
      held <= '0;
      held_valid <= 1'b0;
      dropped <= 1'b0;
      framing_error <= 1'b0;
    end else begin
      if (held_valid && tx_ready) held_valid <= 1'b0;
      if (rx_valid) begin
        if (rx_framing_error) framing_error <= 1'b1;
        if (held_valid && !tx_ready) begin
          dropped <= 1'b1;
        end else begin
          held <= rx_data;
          held_valid <= 1'b1;
        end
      end
    end
  end

  assign led_red_n = !(dropped || framing_error);
  assign led_green_n = rst;
endmodule
/* verilator lint_on MULTITOP */

`default_nettype wire
