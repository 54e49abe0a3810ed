// stereo_level_stepper: the pixel steps of one hierarchical level (stereo_hier_levels). A frame of
// cfg_width x cfg_height level pixels: one step per pixel taken from the level's input FIFO, in
// raster order, then flush steps (rows beyond the frame, data 0) until the level's last winner,
// (W-1, H-1), has come out; a step also waits for `allow` (the level's prediction, or room for
// its winners). Then one step with `clear` (the level's rst: stale flush coordinates would read as
// pixels of the next frame; some stages clear at a step only) and `done` until the next frame's
// first pixel. `stepped` is high in
// the clock after a step: the level's outputs then show a new winner.
// GROUPS > 1 (a time-multiplexed level, LANES < its labels): after a step `group` counts
// 0 .. GROUPS-1, one per clock, and stays at GROUPS-1 until the next step, which can only come
// there (stereo_top's group counter); reset leaves it at GROUPS-1.
`default_nettype none
`include "stereo_assert.svh"

module stereo_level_stepper #(
    parameter int GROUPS = 1  // clocks per pixel step
) (
    input  wire logic              clk,
    input  wire logic              rst,
    input  wire fx_pkg::cfg_size_t cfg_width,   // the level's frame
    input  wire fx_pkg::cfg_size_t cfg_height,
    input  wire logic              in_valid,    // the FIFO holds the next pixel
    output      logic              in_take,     // ... taken at this step
    input  wire logic              allow,
    input  wire fx_pkg::coord_t    level_out_x,  // the level's winner
    input  wire fx_pkg::coord_t    level_out_y,
    output      logic              ce,           // the level's pixel step
    output      logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group,  // the level's group
    output      fx_pkg::coord_t    x,            // the step's coordinates
    output      fx_pkg::coord_t    y,
    output      logic              flushing,     // the step carries no pixel
    output      logic              stepped,
    output      logic              clear,
    output      logic              done          // the frame's last winner has come out
);
  typedef enum logic [1:0] {
    RUN,
    FLUSH,
    CLEAR,
    DONE
  } state_e;
  state_e state;

  logic last_pixel, last_winner;
  assign last_pixel = x == 16'($signed(32'(cfg_width)) - 1) && y == 16'($signed(32'(cfg_height)) - 1);
  assign last_winner = stepped && level_out_x == 16'($signed(32'(cfg_width)) - 1) &&
                       level_out_y == 16'($signed(32'(cfg_height)) - 1);
  assign flushing = state == FLUSH;
  assign clear = state == CLEAR;
  assign done = state == DONE;
  localparam int GROUP_BITS = (GROUPS > 1) ? $clog2(GROUPS) : 1;
  logic round_done;  // the last group: a step may come
  generate
    if (GROUPS > 1) begin : g_group_counter
      assign round_done = 32'(group) == GROUPS - 1;
      always_ff @(posedge clk) begin
        if (rst) group <= GROUP_BITS'(GROUPS - 1);
        else if (ce) group <= '0;
        else if (!round_done) group <= group + 1'b1;
      end
    end else begin : g_one_group
      assign round_done = 1'b1;
      assign group = '0;
    end
  endgenerate
  always_comb begin
    unique case (state)
      RUN: ce = round_done && in_valid && allow;
      FLUSH: ce = round_done && allow && !last_winner;
      CLEAR: ce = round_done;  // the clear is a step, as stereo_top clears its stages at a step
      default: ce = 1'b0;
    endcase
    in_take = state == RUN && ce;
  end

  always_ff @(posedge clk) begin
    if (rst) begin
      state <= DONE;
      x <= '0;
      y <= '0;
      stepped <= 1'b0;
    end else begin
      stepped <= ce;
      if (ce) begin
        if (x == 16'($signed(32'(cfg_width)) - 1)) begin
          x <= '0;
          y <= y + 16'sd1;
        end else begin
          x <= x + 16'sd1;
        end
      end
      unique case (state)
        RUN: if (ce && last_pixel) state <= FLUSH;
        FLUSH: if (last_winner) state <= CLEAR;
        CLEAR: state <= DONE;
        default: if (in_valid) begin  // DONE: the next frame's first pixel
          state <= RUN;
          x <= '0;
          y <= '0;
        end
      endcase
    end
  end
endmodule

`default_nettype wire
