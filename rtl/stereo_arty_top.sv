// stereo_arty_top: the board protocol of the iCEBreaker build (stereo_board_top, docs/board.md)
// on a Digilent Arty A7-35T or A7-100T: the 100 MHz oscillator, the UART of the board's FTDI
// chip (the same USB cable as JTAG) at 100 MHz / CLKS_PER_BIT baud (868: 115,200), the red RESET
// button and four green LEDs. `stereo board` talks to it as to the iCEBreaker
// (`--port /dev/ttyUSB1`). Pins and clock: scripts/synth/boards/arty_a7.xdc, which constrains
// every port of this module (the ctest board.arty_xdc_constrains_every_port checks it).
// The core is stereo_board_top's: constant default kernel (RUNTIME_KERNEL 0), AD cost.
`default_nettype none

// A top in rtl/files.f beside the other board and SoC tops.
/* verilator lint_off MULTITOP */
module stereo_arty_top #(
    parameter int WIDTH = 64,           // largest frame width
    parameter int HEIGHT = 48,          // largest frame height
    parameter int NDISP = 16,           // disparities evaluated in parallel
    parameter int WINDOW = 5,           // aggregation window (odd), constant kernel
    parameter int CLKS_PER_BIT = 868,   // 100 MHz / 115,200 baud
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,
    parameter int LANES = NDISP         // labels per clock (divides NDISP)
) (
    input  wire logic       clk,        // CLK100MHZ, pin E3
    input  wire logic       uart_rx,    // uart_txd_in, pin A9: host to board
    output      logic       uart_tx,    // uart_rxd_out, pin D10: board to host
    input  wire logic       button_n,   // ck_rst (RESET button), pin C2, active low
    output      logic [3:0] led         // LD4 .. LD7, active high: [0] idle, [1] status set
);
  logic led_red_n, led_green_n;
  stereo_board_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .CLKS_PER_BIT(CLKS_PER_BIT), .MAX_MIN_DISP(MAX_MIN_DISP), .LANES(LANES)
  ) board (
      .*
  );
  assign led = {2'b00, !led_red_n, !led_green_n};
endmodule
/* verilator lint_on MULTITOP */

`default_nettype wire
