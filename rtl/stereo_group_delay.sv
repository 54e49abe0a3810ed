// stereo_group_delay: a group's value, STEPS pixel steps later, for the time-multiplexed stages
// (stereo_asw_aggregate): STEPS stereo_group_ring in a row, each handing group g's value of one
// step to group g's clock of the next (a plain register would hand it to group g + 1's clock).
// STEPS = 0 is a wire.
`default_nettype none
`include "stereo_assert.svh"

module stereo_group_delay #(
    parameter int BITS   = 8,  // one group's value
    parameter int GROUPS = 2,  // label groups per pixel step
    parameter int STEPS  = 1,  // steps of delay, 0 or more
    parameter bit BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM
    parameter int BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
    input  wire logic            clk,
    input  wire logic            advance,  // a group clock (or the step at the last group)
    input  wire logic [BITS-1:0] in_data,  // this clock's group, now
    output      logic [BITS-1:0] out_data  // this clock's group, STEPS steps ago
);
  `STEREO_ASSERT(steps_range, STEPS >= 0, "STEPS must be 0 or more")

  logic [BITS-1:0] stage[STEPS+1];  // stage[s]: s steps late
  assign stage[0] = in_data;
  for (genvar s = 1; s <= STEPS; s++) begin : g_step
    stereo_group_ring #(
        .BITS(BITS),
        .GROUPS(GROUPS),
        .BLOCK_RAM(BLOCK_RAM),
        .BLOCK_MIN_FILL(BLOCK_MIN_FILL)
    ) ring (
        .clk(clk),
        .advance(advance),
        .next_state(stage[s-1]),
        .head(stage[s])
    );
  end
  assign out_data = stage[STEPS];
endmodule

`default_nettype wire
