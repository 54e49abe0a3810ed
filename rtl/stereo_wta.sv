// stereo_wta: winner takes all and the border rule (model: stereo::wta and the winner of
// stereo::ValidatingSelector, docs/fixed-point.md stages 5 and 6).
//
// A comparator tree over the NDISP values of a pixel finds the smallest; on equal values the
// left (smaller k) input wins, so ties go to the smallest label. Labels k >= cfg_ndisp take no
// part. Label k stands for disparity d = cfg_min_disp + k. The pixel passes the border rule when
// its window stays inside the frame and its winner's right-image samples do too:
//   reach <= x < W - reach,  reach <= y < H - reach,  reach <= x - d < W - reach,
// reach = cfg_radius + (cfg_use_ca ? 1 : 0).
// Registered outputs for stage 6 (stereo_validate, stereo_lr_check): the winner k1 (whatever
// the border rule says), its cost C1, the costs at k1 - 1 and k1 + 1 (meaningful where those
// labels exist), the border flag and, with LANES = NDISP, the whole cost vector (out_data); with
// LANES < NDISP instead the second cost C2 = min { E(k) : |k - k1| > 1, k < cfg_ndisp }
// (NO_SECOND_COST when there is none), and out_group, this clock's group of the input pixel's
// costs (combinational), from which stereo_lr_check's accumulators take the costs one step ahead.
// Latency: 1 pixel step.
//
// LANES = NDISP (G = 1): one comparator tree over all labels; the neighbours' costs by
// multiplexers on k1; out_second is not computed (0; stereo_validate computes C2 from out_data).
// out_group is in_data.
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): the clock of label group g (`group`; the
// step, ce, at group G-1, G = NDISP / LANES; in_data is the previous stage's result of the
// clock's group, held G group clocks in a RAM ring) scans labels [g*LANES +: LANES] in label order, one
// lane after the other, updating a running state that groups 0 .. G-2 register and group 0
// restarts: the winner (cost, label; a label replaces it only with a strictly smaller cost, so
// ties go to the smallest label), its neighbours' costs (E(k1 - 1) is the last label's cost when
// the winner changes; E(k1 + 1) is the next label's), C2 over the labels so far (when the winner
// changes to k, C2 restarts from the minimum over labels <= k - 2, kept beside the last label's
// cost; later labels above k1 + 1 lower it). At the step the last group's scan is registered.
// Absent labels (>= cfg_ndisp) count as the largest code, which never wins and is NO_SECOND_COST.
`default_nettype none

module stereo_wta #(
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP,  // labels compared per clock (divides NDISP)
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM (stereo_top)
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
`include "stereo_stage_ports.svh"
    // G = 1: the pixel's NDISP costs; G > 1: the producer's result of this clock's group.
    input  wire logic [LANES*fx_pkg::AGG_BITS-1:0] in_data,
    input  wire fx_pkg::cfg_size_t                 cfg_width,
    input  wire fx_pkg::cfg_size_t                 cfg_height,
    input  wire fx_pkg::cfg_ndisp_t                cfg_ndisp,
    input  wire fx_pkg::cfg_radius_t               cfg_radius,
    input  wire logic                              cfg_use_ca,
    input  wire fx_pkg::cfg_min_disp_t             cfg_min_disp,
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

  initial begin
    assert (LANES >= 1 && NDISP % LANES == 0);
  end

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
      always_comb begin
        winner = running_label;
        winner_cost = running_cost;
        cost_before = running_before;
        cost_after = running_after;
        second_cost = running_second;
        scan_rest = running_rest;
        scan_last = running_last;
        scan_pending = running_pending;
        for (int l = 0; l < LANES; l++) begin
          logic [BITS-1:0] cost;
          // Absent labels carry the largest code, above any aggregated cost: they never win.
          cost = ($signed(first_label + l) < $signed(32'(cfg_ndisp))) ? group_costs[l*BITS +: BITS]
                                                                        : {BITS{1'b1}};
          if (l == 0 && group_now == '0) begin  // label 0 restarts the scan
            winner = '0;
            winner_cost = cost;
            cost_before = '0;
            second_cost = BITS'(fx_pkg::NO_SECOND_COST);
            scan_rest = BITS'(fx_pkg::NO_SECOND_COST);
            scan_pending = 1'b1;
          end else begin
            if (cost < winner_cost) begin  // a new winner k: C2 over the labels <= k - 2
              winner = DISP_BITS'(first_label + l);
              winner_cost = cost;
              cost_before = scan_last;
              second_cost = scan_rest;
              scan_pending = 1'b1;
            end else if (scan_pending) begin  // k1 + 1
              cost_after = cost;
              scan_pending = 1'b0;
            end else if (cost < second_cost) begin  // above k1 + 1
              second_cost = cost;
            end
            if (scan_last < scan_rest) scan_rest = scan_last;
          end
          scan_last = cost;
        end
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
      // One label: it wins (a cost of all ones when cfg_ndisp is 0), no comparator, so the
      // border rule below does not wait for one (it did on the one-label iCE40 core).
      assign winner = '0;
      assign winner_cost = (cfg_ndisp != '0) ? in_data[0 +: BITS] : {BITS{1'b1}};
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
              (d < $signed(32'(cfg_ndisp))) ? in_data[d*BITS +: BITS] : {BITS{1'b1}};
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
    reach = $signed(18'(cfg_radius)) + (cfg_use_ca ? 18'sd1 : 18'sd0);
    inner_width = $signed(18'(cfg_width)) - reach;
    shifted_x = 18'(in_x) - 18'(cfg_min_disp);
    border_ok = 18'(in_x) >= reach && 18'(in_x) < inner_width &&
                18'(in_y) >= reach && 18'(in_y) < $signed(18'(cfg_height)) - reach &&
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
