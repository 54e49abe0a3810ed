// stereo_wta: winner takes all and the border rule (model: stereo::wta and the winner of
// stereo::ValidatingSelector, docs/fixed-point.md stages 5 and 6).
//
// A comparator tree over the NDISP values of a pixel finds the smallest; on equal values the
// left (smaller k) input wins, so ties go to the smallest label. Labels k >= cfg.ndisp take no
// part. Label k stands for disparity d = cfg.min_disp + k. The pixel passes the border rule when
// its window stays inside the frame and its winner's right-image samples do too:
//   reach <= x < W - reach,  reach <= y < H - reach,  reach <= x - d < W - reach,
// reach = cfg.radius + (cfg.use_ca ? 1 : 0).
// Registered outputs for stage 6 (stereo_validate, stereo_lr_check): the winner k1 (whatever
// the border rule says), its cost C1, the costs at k1 - 1 and k1 + 1 (meaningful where those
// labels exist), the border flag and, with LANES = NDISP, the whole cost vector (out_data); with
// LANES < NDISP instead the second cost C2 = min { E(k) : |k - k1| > 1, k < cfg.ndisp }
// (NO_SECOND_COST when there is none), and out_group, this clock's group of the input pixel's
// costs (combinational), from which stereo_lr_check's accumulators take the costs one step ahead.
// Latency: 1 pixel step.
//
// LANES = NDISP (G = 1): one comparator tree over all labels; the neighbours' costs by
// multiplexers on k1; out_second is not computed (0; stereo_validate computes C2 from out_data).
// out_group is in_data.
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): the clock of label group g (`group`; the
// step, ce, at group G-1, G = NDISP / LANES; in_data is the previous stage's result of the
// clock's group, held G group clocks in a RAM ring) combines labels [g*LANES +: LANES] with a
// running state that groups 0 .. G-2 register and group 0 restarts, with the result a scan in
// label order would give: the winner (cost, label; a label replaces it only with a strictly
// smaller cost, so ties go to the smallest label), its neighbours' costs E(k1 - 1), E(k1 + 1) and
// C2 = min { E(k) : |k - k1| > 1 }. The group is reduced in trees (its minimum and first lane of
// it, the minima before and after each lane) and merged with the running state once, so the
// logic depth grows with log2 LANES, not LANES (docs/synthesis.md "Logic depth"). At the step
// the last group's merge is registered.
// Absent labels (>= cfg.ndisp) count as the largest code, which never wins and is NO_SECOND_COST.
`default_nettype none
`include "stereo_assert.svh"

module stereo_wta #(
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP,  // labels compared per clock (divides NDISP)
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM (stereo_top)
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
`include "stereo_stage_ports.svh"
    // G = 1: the pixel's NDISP costs; G > 1: the producer's result of this clock's group.
    input  wire logic [LANES*fx_pkg::AGG_BITS-1:0] in_data,
    /* verilator lint_off UNUSEDSIGNAL */  // reads all but uniqueness, lr and subpixel fields
    input  wire fx_pkg::config_t                   cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]      out_label,   // k1
    output      logic                              out_border,  // the border rule holds
    output      logic [fx_pkg::AGG_BITS-1:0]       out_cost,    // C1 = E(k1)
    output      logic [fx_pkg::AGG_BITS-1:0]       out_before,  // E(k1 - 1)
    output      logic [fx_pkg::AGG_BITS-1:0]       out_after,   // E(k1 + 1)
    // LANES = NDISP: the cost vector, as it came (LANES < NDISP: 0).
    output      logic [NDISP*fx_pkg::AGG_BITS-1:0] out_data,
    output      logic [fx_pkg::AGG_BITS-1:0]       out_second,  // C2 (LANES < NDISP only)
    // LANES < NDISP: labels [group*LANES +: LANES] of the input pixel (LANES = NDISP: in_data).
    output      logic [LANES*fx_pkg::AGG_BITS-1:0] out_group
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int GROUPS = NDISP / LANES;

  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")

  // The group of this clock; G = 1: 0 whatever the port carries (stage testbenches leave it open).
  /* verilator lint_off UNUSEDSIGNAL */  // G = 1: not needed
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  /* verilator lint_on UNUSEDSIGNAL */
  assign group_now = (GROUPS > 1) ? group : '0;

  logic [DISP_BITS-1:0] winner;
  logic [BITS-1:0] winner_cost, cost_before, cost_after;
  generate
    if (GROUPS > 1) begin : g_scan
      // This clock's group of the costs, and its first label: what the previous stage computed
      // for this group G advances ago (where the all-parallel stage has that stage's output
      // register), from a RAM ring of G words.
      logic [LANES*BITS-1:0] group_costs;
      logic [31:0] first_label;
      logic advance;  // a clock that processes a group
      assign advance = ce || 32'(group_now) != GROUPS - 1;
      stereo_group_ring #(
          .BITS     (LANES * BITS),
          .GROUPS   (GROUPS),
          .BLOCK_RAM(RING_BLOCK_RAM),
          .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) input_ring (
          .clk(clk),
          .advance(advance),
          .next_state(in_data),
          .head(group_costs)
      );
      assign first_label = 32'(group_now) * LANES;
      assign out_group = group_costs;
      // The running state (registered after groups 0 .. G-2; group 0 does not read it).
      logic [BITS-1:0] running_cost, running_before, running_after, running_second;
      logic [BITS-1:0] running_rest;  // the minimum over the labels before the last one
      logic [BITS-1:0] running_last;  // the last label's cost
      logic [DISP_BITS-1:0] running_label;
      logic running_pending;  // the winner is the last label: E(k1 + 1) comes next
      logic [BITS-1:0] second_cost, scan_rest, scan_last;
      logic scan_pending;
      // The group's labels are combined in trees, not one after the other (a chain of LANES
      // comparisons was the core's longest path, docs/synthesis.md "Logic depth"): the group's
      // minimum m and its first lane j (a comparator tree, ties to the left), the minima of the
      // lanes before and after each lane (parallel prefix, log2 LANES levels), and then one merge
      // with the running state that gives exactly what the scan in label order gave: the winner
      // changes to label first_label + j where m is strictly below the running winner's cost (or
      // at group 0, which restarts), and C2 is then the minimum over the labels <= k1 - 2 and,
      // within the group, >= k1 + 2; otherwise the group's labels lower C2, except a first lane
      // that is the pending E(k1 + 1).
      localparam int LEVELS = (LANES > 1) ? $clog2(LANES) : 1;
      localparam int LEAVES = 1 << LEVELS;
      localparam logic [BITS-1:0] NONE = BITS'(fx_pkg::NO_SECOND_COST);
      logic [LANES*BITS-1:0] cost;  // absent labels carry the largest code: they never win
      for (genvar l = 0; l < LANES; l++) begin : g_lane_cost
        assign cost[l*BITS +: BITS] = ($signed(first_label + l) < $signed(32'(cfg.ndisp)))
                                          ? group_costs[l*BITS +: BITS] : {BITS{1'b1}};
      end
      // Heap-ordered argmin tree: node n has children 2n+1 and 2n+2; leaf LEAVES-1+l is lane l.
      logic [(2*LEAVES-1)*BITS-1:0] node_value  /*verilator split_var*/;
      logic [(2*LEAVES-1)*LEVELS-1:0] node_lane  /*verilator split_var*/;
      for (genvar l = 0; l < LEAVES; l++) begin : g_leaf
        assign node_value[(LEAVES-1+l)*BITS +: BITS] =
            (l < LANES) ? cost[((l < LANES) ? l : 0)*BITS +: BITS] : {BITS{1'b1}};
        assign node_lane[(LEAVES-1+l)*LEVELS +: LEVELS] = LEVELS'(l);
      end
      for (genvar n = 0; n < LEAVES - 1; n++) begin : g_node
        logic take_left;
        assign take_left = node_value[(2*n+1)*BITS +: BITS] <= node_value[(2*n+2)*BITS +: BITS];
        assign node_value[n*BITS +: BITS] = take_left ? node_value[(2*n+1)*BITS +: BITS]
                                                      : node_value[(2*n+2)*BITS +: BITS];
        assign node_lane[n*LEVELS +: LEVELS] = take_left ? node_lane[(2*n+1)*LEVELS +: LEVELS]
                                                         : node_lane[(2*n+2)*LEVELS +: LEVELS];
      end
      logic [BITS-1:0] group_min;
      logic [LEVELS-1:0] group_lane;
      assign group_min = node_value[0 +: BITS];
      assign group_lane = (LANES > 1) ? node_lane[0 +: LEVELS] : '0;
      // from_start[l] = min(cost[0 .. l]), to_end[l] = min(cost[l .. LANES-1]) (Kogge-Stone), at
      // [l*BITS +: BITS].
      logic [LANES*BITS-1:0] from_start, to_end;
      always_comb begin
        logic [LANES*BITS-1:0] up, down;
        from_start = cost;
        to_end = cost;
        for (int span = 1; span < LANES; span = span * 2) begin
          up = from_start;
          down = to_end;
          for (int l = 0; l < LANES; l++) begin
            // The lanes span before and after (clamped: the test in front excludes them).
            int earlier, later;
            earlier = (l >= span) ? l - span : l;
            later = (l + span < LANES) ? l + span : l;
            if (l >= span && up[earlier*BITS +: BITS] < up[l*BITS +: BITS])
              from_start[l*BITS +: BITS] = up[earlier*BITS +: BITS];
            if (l + span < LANES && down[later*BITS +: BITS] < down[l*BITS +: BITS])
              to_end[l*BITS +: BITS] = down[later*BITS +: BITS];
          end
        end
      end
      // What the merge needs of lane j = group_lane: the lanes around it, the minima before
      // j - 1 and after j + 1 (NONE where there are none).
      logic [BITS-1:0] lane_before, lane_after, below_before, above_after, all_but_first;
      always_comb begin
        lane_before = '0;
        lane_after = running_after;
        below_before = NONE;
        above_after = NONE;
        for (int l = 0; l < LANES; l++) begin
          if (32'(group_lane) == l) begin
            if (l >= 1) lane_before = cost[(l-1)*BITS +: BITS];
            if (l + 1 < LANES) lane_after = cost[(l+1)*BITS +: BITS];
            if (l >= 2) below_before = from_start[(l-2)*BITS +: BITS];
            if (l + 2 < LANES) above_after = to_end[(l+2)*BITS +: BITS];
          end
        end
        all_but_first = (LANES > 1) ? to_end[((LANES > 1) ? 1 : 0)*BITS +: BITS] : NONE;
      end
      function automatic logic [BITS-1:0] smaller(input logic [BITS-1:0] a,
                                                  input logic [BITS-1:0] b);
        smaller = (b < a) ? b : a;
      endfunction
      logic restart, new_winner;
      logic [BITS-1:0] prior_all;  // the minimum over the labels of the groups before
      assign restart = group_now == '0;
      assign new_winner = restart || group_min < running_cost;
      assign prior_all = restart ? NONE : smaller(running_rest, running_last);
      always_comb begin
        winner = running_label;
        winner_cost = running_cost;
        cost_before = running_before;
        cost_after = running_after;
        second_cost = running_second;
        scan_pending = running_pending;
        if (new_winner) begin
          winner = DISP_BITS'(first_label + 32'(group_lane));
          winner_cost = group_min;
          // E(k1 - 1): the lane before, or the previous group's last label (0 before label 0)
          cost_before = (group_lane != '0) ? lane_before : (restart ? '0 : running_last);
          cost_after = lane_after;  // the last lane's comes with the next group (pending)
          scan_pending = 32'(group_lane) == LANES - 1;
          // C2: the labels <= k1 - 2 (before the group: all but its last when j = 0) and the
          // group's labels >= k1 + 2.
          second_cost = smaller(smaller((group_lane != '0) ? prior_all
                                                           : (restart ? NONE : running_rest),
                                        below_before), above_after);
        end else if (running_pending) begin  // the first lane is E(k1 + 1)
          cost_after = cost[0 +: BITS];
          scan_pending = 1'b0;
          second_cost = smaller(running_second, all_but_first);
        end else begin
          second_cost = smaller(running_second, group_min);
        end
        // The minimum over every label but the group's last, and the last one's cost.
        scan_rest = (LANES > 1)
            ? smaller(prior_all, from_start[((LANES > 1) ? LANES - 2 : 0)*BITS +: BITS])
            : prior_all;
        scan_last = cost[(LANES-1)*BITS +: BITS];
      end
      always_ff @(posedge clk) begin
        if (ce) out_second <= second_cost;
      end
      assign out_data = '0;  // stereo_lr_check takes out_group, stereo_validate out_second
      always_ff @(posedge clk) begin
        if (32'(group_now) != GROUPS - 1) begin
          running_cost <= winner_cost;
          running_label <= winner;
          running_before <= cost_before;
          running_after <= cost_after;
          running_second <= second_cost;
          running_rest <= scan_rest;
          running_last <= scan_last;
          running_pending <= scan_pending;
        end
      end
    end else if (NDISP == 1) begin : g_single_label
      // One label: it wins (a cost of all ones when cfg.ndisp is 0), no comparator, so the
      // border rule below does not wait for one (it did on the one-label iCE40 core).
      assign winner = '0;
      assign winner_cost = (cfg.ndisp != '0) ? in_data[0 +: BITS] : {BITS{1'b1}};
      assign cost_before = '0;
      assign cost_after = '0;
      assign out_second = '0;
      assign out_group = in_data;
      always_ff @(posedge clk) begin
        if (ce) out_data <= in_data;
      end
    end else begin : g_tree
      // Heap-ordered tree: node n has children 2n+1 and 2n+2; leaf LEAVES-1+d holds label d.
      // split_var lets Verilator schedule the nodes one by one (the vector is a tree, not a loop).
      localparam int LEVELS = (NDISP > 1) ? $clog2(NDISP) : 1;
      localparam int LEAVES = 1 << LEVELS;
      localparam int NODES = 2 * LEAVES - 1;
      // The leaves' values feed the nodes only.
      logic [NODES*BITS-1:0] node_value  /*verilator split_var*/;
      logic [NODES*DISP_BITS-1:0] node_label  /*verilator split_var*/;
      for (genvar d = 0; d < LEAVES; d++) begin : g_leaf
        // Absent labels carry the largest code, above any aggregated cost: they never win.
        if (d < NDISP) begin : g_label
          assign node_value[(LEAVES-1+d)*BITS +: BITS] =
              (d < $signed(32'(cfg.ndisp))) ? in_data[d*BITS +: BITS] : {BITS{1'b1}};
        end else begin : g_padding
          assign node_value[(LEAVES-1+d)*BITS +: BITS] = {BITS{1'b1}};
        end
        assign node_label[(LEAVES-1+d)*DISP_BITS +: DISP_BITS] = DISP_BITS'(d);
      end
      for (genvar n = 0; n < LEAVES - 1; n++) begin : g_node
        logic take_left;  // on equal values the left child, which holds the smaller labels
        assign take_left = node_value[(2*n+1)*BITS +: BITS] <= node_value[(2*n+2)*BITS +: BITS];
        assign node_value[n*BITS +: BITS] = take_left ? node_value[(2*n+1)*BITS +: BITS]
                                                      : node_value[(2*n+2)*BITS +: BITS];
        assign node_label[n*DISP_BITS +: DISP_BITS] =
            take_left ? node_label[(2*n+1)*DISP_BITS +: DISP_BITS]
                      : node_label[(2*n+2)*DISP_BITS +: DISP_BITS];
      end
      assign winner = node_label[0 +: DISP_BITS];
      assign winner_cost = node_value[0 +: BITS];
      // The winner's neighbours (a don't-care where the label does not exist).
      always_comb begin
        cost_before = '0;
        cost_after = '0;
        for (int k = 0; k < NDISP; k++) begin
          if (32'(winner) == k + 1) cost_before = in_data[k*BITS +: BITS];
          if (32'(winner) + 1 == k) cost_after = in_data[k*BITS +: BITS];
        end
      end
      assign out_second = '0;  // stereo_validate's tree computes C2
      assign out_group = in_data;
      always_ff @(posedge clk) begin
        if (ce) out_data <= in_data;
      end
    end
  endgenerate

  // reach <= x - m - k1 < W - reach as k1 <= x - m - reach and k1 > x - m - (W - reach): the
  // winner, last to settle, meets two comparators and no subtractor.
  logic border_ok;
  always_comb begin
    logic signed [17:0] reach;  // 18-bit signed coordinate arithmetic
    logic signed [17:0] inner_width;  // W - reach
    logic signed [17:0] shifted_x;  // x - m
    reach = $signed(18'(cfg.radius)) + (cfg.use_ca ? 18'sd1 : 18'sd0);
    inner_width = $signed(18'(cfg.width)) - reach;
    shifted_x = 18'(in_x) - 18'(cfg.min_disp);
    border_ok = 18'(in_x) >= reach && 18'(in_x) < inner_width &&
                18'(in_y) >= reach && 18'(in_y) < $signed(18'(cfg.height)) - reach &&
                $signed(18'(winner)) <= shifted_x - reach &&
                $signed(18'(winner)) > shifted_x - inner_width;
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_label <= winner;
      out_border <= border_ok;
      out_cost <= winner_cost;
      out_before <= cost_before;
      out_after <= cost_after;
    end
  end
  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
