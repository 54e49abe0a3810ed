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
// labels exist), the border flag and the whole cost vector.
// Latency: 1 pixel step.
//
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): the clock of label group g (`group`; the
// step, ce, at group G-1, G = NDISP / LANES) runs the tree over labels [g*LANES +: LANES] only
// and merges its winner into a running (cost, label) register, which groups 0 .. G-2 update and
// group 0 restarts; at the step the last group's winner merges with it. Groups come in label
// order and on equal costs the running one (smaller labels) wins, so ties still go to the
// smallest label. The neighbours' costs, the border rule and the registered outputs are as with
// LANES = NDISP (the all-parallel stage, G = 1: no running register).
`default_nettype none

module stereo_wta #(
    parameter int NDISP = 16,  // disparities
    parameter int LANES = NDISP  // labels compared per clock (divides NDISP)
) (
    input  wire logic                              clk,
    input  wire logic                              rst,  // clears coordinates only
    input  wire logic                              ce,   // the pixel step (at group G-1)
    /* verilator lint_off UNUSEDSIGNAL */  // LANES = NDISP: always 0
    input  wire logic [((NDISP / LANES > 1) ? $clog2(NDISP / LANES) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::coord_t                    in_x,
    input  wire fx_pkg::coord_t                    in_y,
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0] in_data,
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
    output      logic [NDISP*fx_pkg::AGG_BITS-1:0] out_data     // the cost vector, as it came
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int GROUPS = NDISP / LANES;
  localparam int LEVELS = (LANES > 1) ? $clog2(LANES) : 1;
  localparam int LEAVES = 1 << LEVELS;

  initial begin
    assert (LANES >= 1 && NDISP % LANES == 0);
  end

  // The group of this clock; G = 1: 0 whatever the port carries (stage testbenches leave it open).
  /* verilator lint_off UNUSEDSIGNAL */  // G = 1: not needed
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  /* verilator lint_on UNUSEDSIGNAL */
  assign group_now = (GROUPS > 1) ? group : '0;

  // This clock's group of the costs, and its first label.
  logic [LANES*BITS-1:0] group_costs;
  logic [31:0] first_label;
  generate
    if (GROUPS > 1) begin : g_select_group
      assign group_costs = in_data[32'(group_now)*LANES*BITS +: LANES*BITS];
      assign first_label = 32'(group_now) * LANES;
    end else begin : g_all_labels
      assign group_costs = in_data;
      assign first_label = '0;
    end
  endgenerate

  // Heap-ordered tree: node n has children 2n+1 and 2n+2; leaf LEAVES-1+d holds label
  // first_label + d.
  // split_var lets Verilator schedule the nodes one by one (the vector is a tree, not a loop).
  localparam int NODES = 2 * LEAVES - 1;
  // The leaves' values feed the nodes only.
  logic [NODES*BITS-1:0] node_value  /*verilator split_var*/;
  logic [NODES*DISP_BITS-1:0] node_label  /*verilator split_var*/;
  logic [DISP_BITS-1:0] winner;
  generate
    for (genvar d = 0; d < LEAVES; d++) begin : g_leaf
      // Absent labels carry the largest code, above any aggregated cost: they never win.
      if (d < LANES) begin : g_label
        assign node_value[(LEAVES-1+d)*BITS +: BITS] =
            ($signed(first_label + d) < $signed(32'(cfg_ndisp))) ? group_costs[d*BITS +: BITS]
                                                                 : {BITS{1'b1}};
      end else begin : g_padding
        assign node_value[(LEAVES-1+d)*BITS +: BITS] = {BITS{1'b1}};
      end
      assign node_label[(LEAVES-1+d)*DISP_BITS +: DISP_BITS] = DISP_BITS'(first_label + d);
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
  endgenerate
  // The winner so far: the tree's, merged with the running one of the earlier groups.
  logic [BITS-1:0] winner_cost;
  generate
    if (GROUPS > 1) begin : g_running
      logic [BITS-1:0] running_cost;
      logic [DISP_BITS-1:0] running_label;
      logic keep_running;  // on equal costs the running winner, which has the smaller label
      assign keep_running = group_now != '0 && running_cost <= node_value[0 +: BITS];
      assign winner = keep_running ? running_label : node_label[0 +: DISP_BITS];
      assign winner_cost = keep_running ? running_cost : node_value[0 +: BITS];
      always_ff @(posedge clk) begin
        if (32'(group_now) != GROUPS - 1) begin
          running_cost <= winner_cost;
          running_label <= winner;
        end
      end
    end else begin : g_one_group
      assign winner = node_label[0 +: DISP_BITS];
      assign winner_cost = node_value[0 +: BITS];
    end
  endgenerate

  // The winner's neighbours (a don't-care where the label does not exist).
  logic [BITS-1:0] cost_before, cost_after;
  always_comb begin
    cost_before = '0;
    cost_after = '0;
    for (int k = 0; k < NDISP; k++) begin
      if (32'(winner) == k + 1) cost_before = in_data[k*BITS +: BITS];
      if (32'(winner) + 1 == k) cost_after = in_data[k*BITS +: BITS];
    end
  end

  logic border_ok;
  always_comb begin
    logic signed [17:0] reach;  // 18-bit signed coordinate arithmetic
    logic signed [17:0] right_x;  // x - d, d = m + k1
    reach = $signed(18'(cfg_radius)) + (cfg_use_ca ? 18'sd1 : 18'sd0);
    right_x = 18'(in_x) - 18'(cfg_min_disp) - $signed(18'(winner));
    border_ok = 18'(in_x) >= reach && 18'(in_x) < $signed(18'(cfg_width)) - reach &&
                18'(in_y) >= reach && 18'(in_y) < $signed(18'(cfg_height)) - reach &&
                right_x >= reach && right_x < $signed(18'(cfg_width)) - reach;
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_label <= winner;
      out_border <= border_ok;
      out_cost <= winner_cost;
      out_before <= cost_before;
      out_after <= cost_after;
      out_data <= in_data;
    end
  end
  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
