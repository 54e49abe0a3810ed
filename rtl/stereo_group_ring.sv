// stereo_group_ring: the per-group state of a time-multiplexed stage (docs/rtl.md,
// "Time-multiplexed lanes") as a circular buffer in RAM instead of a ring of registers.
//
// A stage with G = GROUPS label groups per pixel step keeps one state word per group (the
// aggregation's horizontal window, the CA window's two column registers). It reads the state of
// the group it computes (`head`) and, at each advance (one per group clock), replaces it with
// that group's next state (`next_state`), so after G advances every group is back at the head,
// one step further. As a ring of registers (slot k moves to slot k-1, the next state enters slot
// G-1) that costs G words of flip-flops and, on an iCE40, a logic cell per bit; here slot k of
// that ring is word (pointer + k) mod G of a RAM, the advance writes the next state over the head
// and moves the pointer. The RAM is read one advance ahead (word pointer + 1, which is not the
// word being written as G >= 2), into its registered output, which is `head` and keeps its value
// while no advance comes; there is no logic between the RAM and that register, so synthesis maps
// it to block RAM (iCE40 SB_RAM40_4K) or LUT RAM. Equivalent to the register ring for any
// initial contents, which the stages never read before writing (they mask them by coordinates).
// GROUPS = 1 (the all-parallel stage): a single register, stepped with advance.
// Where the RAM goes: Yosys maps a ring of 8 or more words to block RAM on the iCE40 (no LUT RAM
// there) and to LUT RAM on the 7-series and ECP5, but implements a shallower one in flip-flops
// plus a read multiplexer, more than the register ring, which is kept below 8 groups.
// BLOCK_RAM = 1 asks for block RAM (`ram_style`): right for the iCE40, where flip-flops are
// logic cells, wasteful on parts with LUT RAM (a block per 36 bits of width). Even on the iCE40
// a block (4 Kib, at most 16 bits wide) is only worth it when it saves enough flip-flops: with
// BLOCK_RAM = 1 the ring goes to block RAM when its GROUPS x BITS bits fill each of the
// ceil(BITS / 16) block columns it needs with at least BLOCK_MIN_FILL bits (docs/rtl.md; 50 by
// default: a ring of four words of 84 bits or eight of 14 goes to block RAM, four words of 14
// bits or three of 52 stay in flip-flops, at any depth).
`default_nettype none
`include "stereo_assert.svh"

module stereo_group_ring #(
    parameter int BITS   = 8,  // one group's state
    parameter int GROUPS = 2,  // label groups per pixel step
    parameter bit BLOCK_RAM = 1'b0,  // 1: block RAM when it is filled enough (see above)
    parameter int BLOCK_MIN_FILL = 50  // bits per 16-bit block column (see above)
) (
    input  wire logic            clk,
    input  wire logic            advance,     // a group clock (or the step at the last group)
    input  wire logic [BITS-1:0] next_state,  // the head group's state after this advance
    output      logic [BITS-1:0] head         // the state of the group computed at this clock
);
  `STEREO_ASSERT(groups_positive, GROUPS >= 1, "GROUPS must be at least 1")

  localparam int POINTER_BITS = (GROUPS > 1) ? $clog2(GROUPS) : 1;
  localparam int FILL = GROUPS * BITS / ((BITS + 15) / 16);  // bits per block column
  localparam bit USE_BLOCK = BLOCK_RAM && FILL >= BLOCK_MIN_FILL;
  generate
    if (GROUPS > 1 && (BLOCK_RAM ? USE_BLOCK : GROUPS >= 8)) begin : g_ram
      logic [POINTER_BITS-1:0] pointer, after;  // the head's word, the next head's
      assign after = (32'(pointer) == GROUPS - 1) ? '0 : pointer + 1'b1;
      // "auto" leaves the choice to synthesis (block RAM on the iCE40, LUT RAM elsewhere).
      (* ram_style = (USE_BLOCK ? "block" : "auto") *) logic [BITS-1:0] memory[GROUPS];
      always_ff @(posedge clk) begin
        if (advance) begin
          memory[pointer] <= next_state;
          head <= memory[after];
          pointer <= after;
        end
      end
    end else if (GROUPS > 1) begin : g_registers
      // slots[k + 1] moves to slots[k]; the head's next state enters slots[G - 1].
      logic [BITS-1:0] slots[GROUPS];
      always_ff @(posedge clk) begin
        if (advance) begin
          for (int k = 0; k + 1 < GROUPS; k++) slots[k] <= slots[k+1];
          slots[GROUPS-1] <= next_state;
        end
      end
      assign head = slots[0];
    end else begin : g_register
      always_ff @(posedge clk) begin
        if (advance) head <= next_state;
      end
    end
  endgenerate
endmodule

`default_nettype wire
