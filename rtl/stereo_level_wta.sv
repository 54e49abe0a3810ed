// stereo_level_wta: the winner of a hierarchical level's candidates (model:
// stereo::hierarchical::match_level's winner, stereo::tie_key; docs/hierarchical.md "The levels
// in hardware"). The smallest cost wins; among equal costs the label of the smallest RANK (the
// tie key's order, the same for every pixel relative to the base) wins. As the ranks are distinct,
// that is the smallest of the keys {cost, rank}, one comparison per pair of labels. Out comes the
// winner's label k (not its rank) with the pixel's coordinates. Latency: 1 pixel step.
//
// LANES = LABELS (G = 1): one tree over all labels of the registered input. Time-multiplexed lanes
// (LANES < LABELS, the stage contract of docs/rtl.md): the clock of group g (`group`; the step,
// ce, at group G-1) takes labels [g*LANES +: LANES] of the previous stage's result for this group,
// held G group clocks in a ring (stereo_group_ring) as in stereo_wta, reduces them in a tree and
// merges the group's best key with the running one, which groups 0 .. G-2 register and group 0
// restarts; at the step the merge of the last group is registered.
`default_nettype none
`include "stereo_assert.svh"

module stereo_level_wta #(
    parameter int NDISP = 9,      // candidate labels (the stage ports' name for the label count)
    parameter int LANES = NDISP,  // labels compared per clock (divides NDISP)
    // RANK[k*9 +: 9]: the tie rank of label k (0 wins all ties); distinct, below NDISP.
    parameter logic [NDISP*9-1:0] RANK = '0
) (
`include "stereo_stage_ports.svh"
    input  wire logic [LANES*fx_pkg::AGG_BITS-1:0] in_data,
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    output      logic [8:0]                        out_label
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int GROUPS = NDISP / LANES;
  localparam int RANK_BITS = (NDISP > 1) ? $clog2(NDISP) : 1;
  localparam int KEY_BITS = BITS + RANK_BITS + 9;  // {cost, rank, label}: the label rides along
  localparam int LEVELS = (LANES > 1) ? $clog2(LANES) : 1;
  localparam int LEAVES = 1 << LEVELS;

  `STEREO_ASSERT(lanes_divide_labels, LANES >= 1 && NDISP % LANES == 0 && NDISP <= 256,
                 "LANES must divide NDISP, NDISP at most 256")

  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  assign group_now = (GROUPS > 1) ? group : '0;

  // This clock's group of the costs: the input itself (G = 1: the producer's register), or what
  // the producer computed for this group G advances ago.
  logic [LANES*BITS-1:0] group_costs;
  generate
    if (GROUPS > 1) begin : g_ring
      stereo_group_ring #(
          .BITS  (LANES * BITS),
          .GROUPS(GROUPS)
      ) input_ring (
          .clk(clk),
          .advance(ce || 32'(group_now) != GROUPS - 1),
          .next_state(in_data),
          .head(group_costs)
      );
    end else begin : g_direct
      assign group_costs = in_data;
    end
  endgenerate

  // The keys of the group's lanes: label k = group * LANES + lane, its rank from RANK.
  function automatic logic [KEY_BITS-1:0] key_of(input logic [BITS-1:0] cost, input int label);
    key_of = {cost, RANK_BITS'(RANK[label*9 +: 9]), 9'(label)};
  endfunction
  logic [LEAVES*KEY_BITS-1:0] leaf;
  always_comb begin
    leaf = '1;  // padding leaves: the largest key, never the smallest
    for (int lane = 0; lane < LANES; lane++) begin
      for (int g = 0; g < GROUPS; g++) begin
        if (32'(group_now) == g)
          leaf[lane*KEY_BITS +: KEY_BITS] =
              key_of(group_costs[lane*BITS +: BITS], g * LANES + lane);
      end
    end
  end
  // Heap-ordered minimum tree: node n has children 2n+1 and 2n+2, leaf LEAVES-1+l is lane l.
  logic [(2*LEAVES-1)*KEY_BITS-1:0] node  /*verilator split_var*/;
  for (genvar l = 0; l < LEAVES; l++) begin : g_leaf
    assign node[(LEAVES-1+l)*KEY_BITS +: KEY_BITS] = leaf[l*KEY_BITS +: KEY_BITS];
  end
  for (genvar n = 0; n < LEAVES - 1; n++) begin : g_node
    logic [KEY_BITS-1:0] left_key, right_key;
    assign left_key = node[(2*n+1)*KEY_BITS +: KEY_BITS];
    assign right_key = node[(2*n+2)*KEY_BITS +: KEY_BITS];
    assign node[n*KEY_BITS +: KEY_BITS] = (right_key < left_key) ? right_key : left_key;
  end

  /* verilator lint_off UNUSEDSIGNAL */  // G = 1: only the label leaves
  logic [KEY_BITS-1:0] best;  // over the labels of this pixel's groups so far
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    if (GROUPS > 1) begin : g_running
      logic [KEY_BITS-1:0] running;
      assign best = (group_now == '0 || node[0 +: KEY_BITS] < running) ? node[0 +: KEY_BITS]
                                                                      : running;
      always_ff @(posedge clk) begin
        if (32'(group_now) != GROUPS - 1) running <= best;
      end
    end else begin : g_single
      assign best = node[0 +: KEY_BITS];
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) out_label <= best[8:0];
  end
  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
