// stereo_power_on_reset: the reset of a board design without a reset pin. iCE40 flip-flops start
// at their init values after configuration, so a counter that starts at 0 holds `rst` high for
// 2^POR_BITS clocks; a button (active low, asynchronous: two synchroniser flops) restarts it.
`default_nettype none
`include "stereo_assert.svh"

module stereo_power_on_reset #(
    parameter int POR_BITS = 8  // reset length: 2^POR_BITS clocks
) (
    input  wire logic clk,
    input  wire logic button_n,  // active low: held in reset while pressed
    output      logic rst        // active high, synchronous to clk
);
  `STEREO_ASSERT(por_bits_positive, POR_BITS >= 1, "POR_BITS must be at least 1")

  logic [POR_BITS:0] count = '0;
  logic button_meta = 1'b1;
  logic button_sync = 1'b1;
  always_ff @(posedge clk) begin
    button_meta <= button_n;
    button_sync <= button_meta;
    if (!button_sync) begin
      count <= '0;
    end else if (!count[POR_BITS]) begin
      count <= count + 1'b1;
    end
  end
  assign rst = !count[POR_BITS];
endmodule

`default_nettype wire
