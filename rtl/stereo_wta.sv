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
    input  wire logic                                          clk,
    input  wire logic                                          rst,  // clears coordinates only
    input  wire logic                                          ce,
    input  wire logic signed [15:0]                            in_x,
    input  wire logic signed [15:0]                            in_y,
    input  wire logic        [NDISP*fx_pkg::AGG_BITS-1:0]  in_data,
    input  wire logic        [15:0]                            cfg_width,
    input  wire logic        [15:0]                            cfg_height,
    input  wire logic        [8:0]                             cfg_ndisp,
    input  wire logic        [4:0]                             cfg_radius,
    input  wire logic                                          cfg_use_ca,
    output      logic signed [15:0]                            out_x,
    output      logic signed [15:0]                            out_y,
    output      logic        [fx_pkg::DISP_BITS-1:0]       out_disparity,
    output      logic                                          out_valid
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int LEVELS = (NDISP > 1) ? $clog2(NDISP) : 1;
  localparam int LEAVES = 1 << LEVELS;
  localparam logic signed [15:0] NO_PIXEL = -16'sd32768;

  // Heap-ordered tree: node n has children 2n and 2n+1; leaves LEAVES .. 2*LEAVES-1 hold d.
  logic [2*LEAVES*BITS-1:0] node_value;
  logic [2*LEAVES*DISP_BITS-1:0] node_label;
  logic [DISP_BITS-1:0] winner;
  always_comb begin
    node_value = '0;
    node_label = '0;
    for (int d = 0; d < LEAVES; d++) begin
      // Absent labels carry the largest code, above any aggregated cost: they never win.
      node_value[(LEAVES+d)*BITS +: BITS] = (d < NDISP && d < $signed(32'(cfg_ndisp)))
                                                ? in_data[(d < NDISP ? d : 0)*BITS +: BITS]
                                                : {BITS{1'b1}};
      node_label[(LEAVES+d)*DISP_BITS +: DISP_BITS] = DISP_BITS'(d);
    end
    for (int n = LEAVES - 1; n >= 1; n--) begin
      logic take_left;
      take_left = node_value[(2*n)*BITS +: BITS] <= node_value[(2*n+1)*BITS +: BITS];
      node_value[n*BITS +: BITS] = take_left ? node_value[(2*n)*BITS +: BITS]
                                             : node_value[(2*n+1)*BITS +: BITS];
      node_label[n*DISP_BITS +: DISP_BITS] = take_left ? node_label[(2*n)*DISP_BITS +: DISP_BITS]
                                                       : node_label[(2*n+1)*DISP_BITS +: DISP_BITS];
    end
    winner = node_label[DISP_BITS +: DISP_BITS];
  end

  logic valid_d;
  always_comb begin
    int reach;
    reach = $signed(32'(cfg_radius)) + (cfg_use_ca ? 1 : 0);
    valid_d = 32'(in_x) >= reach && 32'(in_x) < $signed(32'(cfg_width)) - reach &&
              32'(in_y) >= reach && 32'(in_y) < $signed(32'(cfg_height)) - reach &&
              32'(in_x) - $signed(32'(winner)) >= reach;
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_disparity <= valid_d ? winner : '0;
      out_valid <= valid_d;
    end
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      out_x <= '0;
      out_y <= NO_PIXEL;
    end else if (ce) begin
      out_x <= in_x;
      out_y <= in_y;
    end
  end
endmodule

`default_nettype wire
