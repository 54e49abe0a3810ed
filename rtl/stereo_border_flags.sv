// stereo_border_flags: which of the positions p + o, o = OFFSET_LO .. OFFSET_HI, lie inside the
// frame [0, limit): in_frame[o - OFFSET_LO] = 0 <= p + o < limit.
//
// The window stages ask this of every row and column of their windows, and written as two
// comparisons per position it cost two carry chains each (about half of the one-label core's
// carry logic on an iCE40, docs/synthesis.md "Border flags"). Here the same integers come from
// one subtraction, room = limit - p, and equality tests against small constants:
//   p + o >= 0     <=>  p >= -o  <=>  p >= 0 and p not in {0 .. -o-1}   (o < 0)
//                                      p >= 0 or  p in {-o .. -1}       (o >= 0)
//   p + o < limit  <=>  room > o  <=>  room > 0 and room not in {1 .. o} (o > 0)
//                                      room > 0 or  room in {o+1 .. 0}  (o <= 0)
// Exact for every POS_BITS-bit p and 16-bit limit (room is computed one bit wider than p).
// Purely combinational.
`default_nettype none
`include "stereo_assert.svh"

module stereo_border_flags #(
    parameter int OFFSET_LO = -2,  // first offset
    parameter int OFFSET_HI = 2,   // last offset (>= OFFSET_LO)
    parameter int POS_BITS  = 18   // signed position width (> 17: limit - p never overflows)
) (
    input  wire logic signed [POS_BITS-1:0]    position,
    input  wire fx_pkg::cfg_size_t             limit,
    output      logic [OFFSET_HI-OFFSET_LO:0]  in_frame
);
  localparam int ROOM_BITS = POS_BITS + 1;

  `STEREO_ASSERT(offsets_ordered, OFFSET_HI >= OFFSET_LO, "OFFSET_HI must not be below OFFSET_LO")
  `STEREO_ASSERT(position_bits, POS_BITS > fx_pkg::CFG_SIZE_BITS,
                 "POS_BITS must exceed CFG_SIZE_BITS (limit - position must not overflow)")

  logic signed [ROOM_BITS-1:0] room;  // limit - position
  assign room = $signed(ROOM_BITS'(limit)) - ROOM_BITS'(position);

  logic position_ge_zero, room_gt_zero;
  assign position_ge_zero = !position[POS_BITS-1];
  assign room_gt_zero = !room[ROOM_BITS-1] && room != '0;

  generate
    for (genvar k = 0; k <= OFFSET_HI - OFFSET_LO; k++) begin : g_offset
      localparam int O = OFFSET_LO + k;
      logic above_zero, below_limit;
      always_comb begin
        // p + O >= 0
        above_zero = position_ge_zero;
        for (int v = 0; v < -O; v++) begin
          if (position == POS_BITS'(v)) above_zero = 1'b0;
        end
        // -(POS_BITS'(v)), not -POS_BITS'(v): Yosys 0.23 drops a unary operator before a sized
        // cast (the synthesized comparison was with +v; Verilator parsed it right).
        for (int v = 1; v <= O; v++) begin
          if (position == -(POS_BITS'(v))) above_zero = 1'b1;
        end
        // p + O < limit
        below_limit = room_gt_zero;
        for (int v = 1; v <= O; v++) begin
          if (room == ROOM_BITS'(v)) below_limit = 1'b0;
        end
        for (int v = O + 1; v <= 0; v++) begin
          if (room == ROOM_BITS'(v)) below_limit = 1'b1;
        end
      end
      assign in_frame[k] = above_zero && below_limit;
    end
  endgenerate
endmodule

`default_nettype wire
