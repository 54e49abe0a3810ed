// stereo_board_link: what every iCEBreaker top (stereo_board_top, stereo_uart_echo_top; docs/
// board.md) puts between the board's pins and its logic: the power-on reset, restarted by the
// user button (stereo_power_on_reset), and the UART receiver and transmitter of the FTDI channel
// (stereo_uart_rx, stereo_uart_tx, 8N1 at clock / CLKS_PER_BIT baud).
`default_nettype none

module stereo_board_link #(
    parameter int CLKS_PER_BIT = 104,  // clock / baud: 104 is 115200 baud at 12 MHz
    parameter int POR_BITS     = 8     // power-on reset: 2^POR_BITS clocks
) (
    input  wire logic       clk,
    input  wire logic       button_n,          // user button, active low: restarts the reset
    input  wire logic       uart_rx,           // from the FTDI
    output      logic       uart_tx,           // to the FTDI
    output      logic       rst,               // synchronous, active high
    output      logic [7:0] rx_data,
    output      logic       rx_valid,          // one clock per received byte
    output      logic       rx_framing_error,  // with rx_valid: the stop bit was 0
    input  wire logic [7:0] tx_data,
    input  wire logic       tx_valid,
    output      logic       tx_ready           // tx_data is taken when tx_valid && tx_ready
);
  stereo_power_on_reset #(
      .POR_BITS(POR_BITS)
  ) power_on_reset (
      .clk(clk),
      .button_n(button_n),
      .rst(rst)
  );

  stereo_uart_rx #(
      .CLKS_PER_BIT(CLKS_PER_BIT)
  ) receiver (
      .clk(clk),
      .rst(rst),
      .rx(uart_rx),
      .data(rx_data),
      .valid(rx_valid),
      .framing_error(rx_framing_error)
  );

  stereo_uart_tx #(
      .CLKS_PER_BIT(CLKS_PER_BIT)
  ) transmitter (
      .clk(clk),
      .rst(rst),
      .data(tx_data),
      .valid(tx_valid),
      .ready(tx_ready),
      .tx(uart_tx)
  );
endmodule

`default_nettype wire
