// stereo_wta: winner takes all and the validity flag (model: stereo::wta, docs/fixed-point.md
// stage 5).
//
// A comparator tree over the NDISP values of a pixel finds the smallest; on equal values the
// left (smaller d) input wins, so ties go to the smallest d. Labels d >= cfg_ndisp take no part.
// The pixel is valid when its window stays inside the frame and its winner's right-image samples
// do too: reach <= x < W - reach, reach <= y < H - reach, x - d >= reach, with
// reach = cfg_radius + (cfg_use_ca ? 1 : 0). Invalid pixels output disparity 0.
// Latency: 1 pixel step.
`default_nettype none

module stereo_wta #(
    parameter int NDISP = 16  // disparities in parallel
) (
    input  wire logic                              clk,
    input  wire logic                              rst,  // clears coordinates only
    input  wire logic                              ce,
    input  wire fx_pkg::coord_t                    in_x,
    input  wire fx_pkg::coord_t                    in_y,
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0] in_data,
    input  wire fx_pkg::cfg_size_t                 cfg_width,
    input  wire fx_pkg::cfg_size_t                 cfg_height,
    input  wire fx_pkg::cfg_ndisp_t                cfg_ndisp,
    input  wire fx_pkg::cfg_radius_t               cfg_radius,
    input  wire logic                              cfg_use_ca,
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]      out_disparity,
    output      logic                              out_valid
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int LEVELS = (NDISP > 1) ? $clog2(NDISP) : 1;
  localparam int LEAVES = 1 << LEVELS;

  // Heap-ordered tree: node n has children 2n+1 and 2n+2; leaf LEAVES-1+d holds label d.
  // split_var lets Verilator schedule the nodes one by one (the vector is a tree, not a loop).
  localparam int NODES = 2 * LEAVES - 1;
  // The root's value (the minimum cost itself) is not needed, only its label.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [NODES*BITS-1:0] node_value  /*verilator split_var*/;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [NODES*DISP_BITS-1:0] node_label  /*verilator split_var*/;
  logic [DISP_BITS-1:0] winner;
  generate
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
  endgenerate
  assign winner = node_label[0 +: DISP_BITS];

  logic valid_d;
  always_comb begin
    logic signed [17:0] reach;  // 18-bit signed coordinate arithmetic
    reach = $signed(18'(cfg_radius)) + (cfg_use_ca ? 18'sd1 : 18'sd0);
    valid_d = 18'(in_x) >= reach && 18'(in_x) < $signed(18'(cfg_width)) - reach &&
              18'(in_y) >= reach && 18'(in_y) < $signed(18'(cfg_height)) - reach &&
              18'(in_x) - $signed(18'(winner)) >= reach;
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_disparity <= valid_d ? winner : '0;
      out_valid <= valid_d;
    end
  end
  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
