// stereo_hier_top: the hierarchical search's streaming core (issue 45; docs/hierarchical.md "The
// streaming core"): one AXI4-Stream of pixel pairs into the 1-D pass along the vertical plane
// (stereo_hier_pass) and into the three levels (stereo_hier_levels), whose full-level winners
// feed the plane's statistics (stereo_plane_stats). The host reads the statistics after a frame
// (out_done), solves the next plane (stereo::hierarchical::PlaneTracker) and writes it with its
// tolerance on plane_* and tolerance, then pulses plane_commit.
//
// Frame t runs its pass along the plane on the ports when its first beat is taken, and its
// statistics are gathered against the same plane. With cfg_wait_plane = 1 the core takes no beat
// of the next frame after a frame's statistics are out until plane_commit (and one clock more,
// so the pass's registered ports hold the new plane): each frame then uses the plane fitted on
// the frame before, as stereo::hierarchical::match_frame. With cfg_wait_plane = 0 the core never
// waits; a plane written late applies to a later frame.
//
// The input beat goes to both consumers in the same clock: s_axis_tready = the pass's ready and
// the levels'; each sees tvalid only when the other is ready too. The levels take pixels from a
// start of frame on (raster coordinates counted here), and none between a frame's last pixel
// and their last winner (about 73 full rows of clocks at the default setting; the pass takes G
// clocks per pixel, so this costs a few per cent of the frame time at 640x480).
// m_axis is the pass's: {vertical offset, stereo_top's beat}, one beat per pixel.
`default_nettype none
`include "stereo_assert.svh"

module stereo_hier_top #(
    parameter int WIDTH  = 64,  // largest frame
    parameter int HEIGHT = 48,
    parameter int NDISP  = 16,  // D: the pass's labels and the levels' horizontal range
    parameter int WINDOW = 5,   // the pass's largest window
    parameter int LANES  = NDISP,
    parameter bit RECOMPUTE_COSTS = 1'b0,
    parameter int VRANGE = 16,  // V: the levels' vertical range, the field's -V/2 .. V/2 - 1
    parameter int WINDOW_Q = 9,  // the levels' windows
    parameter int WINDOW_H = 15,
    parameter int WINDOW_F = 15,
    // The levels' labels per clock and kernels (stereo_hier_levels)
    parameter int LANES_Q = NDISP / 4,
    parameter int LANES_H = 3,
    parameter int LANES_F = 3,
    parameter bit LEVEL_RUNTIME_KERNEL = 1'b0
) (
    input  wire logic                                 clk,
    input  wire logic                                 rst,
    // The pass (stereo_top's configuration ports) and the levels' kernels and CA.
`include "stereo_pass_cfg_ports.svh"
    input  wire logic [WINDOW_Q*fx_pkg::TAP_BITS-1:0] cfg_kernel_q,
    input  wire logic [WINDOW_H*fx_pkg::TAP_BITS-1:0] cfg_kernel_h,
    input  wire logic [WINDOW_F*fx_pkg::TAP_BITS-1:0] cfg_kernel_f,
    input  wire logic                                 cfg_wait_plane,
    // The plane and its inlier tolerance (1/2^16 pixel), and the host's commit.
    input  wire logic signed [31:0]                   plane_a,
    input  wire logic signed [31:0]                   plane_b,
    input  wire logic signed [31:0]                   plane_c,
    input  wire logic [31:0]                          tolerance,
    input  wire logic                                 plane_commit,
    output      logic [fx_pkg::STATUS_BITS-1:0]       status,  // the pass's sticky bits
    input  wire logic [fx_pkg::IN_BEAT_BITS-1:0]      s_axis_tdata,
    input  wire logic                                 s_axis_tvalid,
    output      logic                                 s_axis_tready,
    input  wire logic                                 s_axis_tlast,
    input  wire logic                                 s_axis_tuser,
`include "stereo_hier_out_ports.svh"
    ,  // the last frame's statistics (stereo_plane_stats)
`include "stereo_plane_stats_ports.svh"
);
  localparam int V_MIN = -(VRANGE / 2);
  localparam int V_MAX = VRANGE / 2 - 1;
  `STEREO_ASSERT(field_range, VRANGE >= 12 && VRANGE % 4 == 0 && VRANGE <= 252,
                 "VRANGE must be a multiple of 4, 12 .. 252")

  // ---- waiting for the host's plane ------------------------------------------------------------
  logic waiting, commit_q;  // statistics out, no commit yet; the commit a clock ago
  always_ff @(posedge clk) begin
    if (rst) begin
      waiting <= 1'b0;
      commit_q <= 1'b0;
    end else begin
      commit_q <= plane_commit;
      if (out_done && cfg_wait_plane) waiting <= 1'b1;
      else if (commit_q) waiting <= 1'b0;
    end
  end

  // ---- the fork --------------------------------------------------------------------------------
  logic pass_ready, levels_ready, levels_valid, take, in_frame, start;
  fx_pkg::coord_t x, y, level_x, level_y;
  assign s_axis_tready = pass_ready && levels_ready && !waiting && !plane_commit && !commit_q;
  assign take = s_axis_tvalid && s_axis_tready;
  // A start of frame inside a frame is a pixel of that frame, as in stereo_top (which flags it in
  // status): the pass and the levels keep the same raster.
  assign start = s_axis_tuser && !in_frame;
  assign level_x = start ? 16'sd0 : x;
  assign level_y = start ? 16'sd0 : y;
  // A beat is a level pixel from a start of frame to the frame's last pixel.
  assign levels_valid = s_axis_tvalid && pass_ready && !waiting && !plane_commit && !commit_q &&
                        (in_frame || start);
  always_ff @(posedge clk) begin
    if (rst) begin
      in_frame <= 1'b0;
      x <= '0;
      y <= '0;
    end else if (take && (in_frame || start)) begin
      if (next_x(level_x) == 16'($signed(32'(cfg_width)))) begin
        x <= '0;
        y <= level_y + 16'sd1;
        in_frame <= level_y + 16'sd1 < 16'($signed(32'(cfg_height)));
      end else begin
        x <= next_x(level_x);
        y <= level_y;
        in_frame <= 1'b1;
      end
    end
  end
  function automatic fx_pkg::coord_t next_x(input fx_pkg::coord_t value);
    next_x = value + 16'sd1;
  endfunction

  stereo_hier_pass #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW), .LANES(LANES),
      .RECOMPUTE_COSTS(RECOMPUTE_COSTS), .V_MIN(V_MIN), .V_MAX(V_MAX)
  ) pass (
      .clk(clk), .rst(rst), .cfg_radius(cfg_radius), .cfg_kernel(cfg_kernel),
      .cfg_width(cfg_width), .cfg_height(cfg_height), .cfg_ndisp(cfg_ndisp),
      .cfg_use_ca(cfg_use_ca), .cfg_uniqueness_en(cfg_uniqueness_en),
      .cfg_uniqueness(cfg_uniqueness), .cfg_lr_en(cfg_lr_en), .cfg_lr_tolerance(cfg_lr_tolerance),
      .cfg_subpixel_en(cfg_subpixel_en), .plane_a(plane_a), .plane_b(plane_b), .plane_c(plane_c),
      .status(status), .s_axis_tdata(s_axis_tdata),
      .s_axis_tvalid(s_axis_tvalid && levels_ready && !waiting && !plane_commit && !commit_q),
      .s_axis_tready(pass_ready), .s_axis_tlast(s_axis_tlast), .s_axis_tuser(s_axis_tuser),
      .m_axis_tdata(m_axis_tdata), .m_axis_tvalid(m_axis_tvalid), .m_axis_tready(m_axis_tready),
      .m_axis_tlast(m_axis_tlast), .m_axis_tuser(m_axis_tuser));

  logic win_valid, win_ok;
  fx_pkg::coord_t win_x, win_y;
  logic [fx_pkg::DISP_BITS-1:0] win_d;
  logic signed [fx_pkg::DISP_BITS-1:0] win_v;
  /* verilator lint_off UNUSEDSIGNAL */
  logic levels_busy;
  /* verilator lint_on UNUSEDSIGNAL */
  stereo_hier_levels #(
      .WIDTH(WIDTH), .NDISP(NDISP), .VRANGE(VRANGE), .WINDOW_Q(WINDOW_Q), .WINDOW_H(WINDOW_H),
      .WINDOW_F(WINDOW_F), .LANES_Q(LANES_Q), .LANES_H(LANES_H), .LANES_F(LANES_F),
      .RUNTIME_KERNEL(LEVEL_RUNTIME_KERNEL)
  ) levels (
      .clk(clk), .rst(rst), .in_valid(levels_valid), .in_ready(levels_ready),
      .in_x(level_x), .in_y(level_y),
      .in_left(s_axis_tdata[fx_pkg::IN_LEFT_LSB +: fx_pkg::RGB_BITS]),
      .in_right(s_axis_tdata[fx_pkg::IN_RIGHT_LSB +: fx_pkg::RGB_BITS]), .cfg_width(cfg_width),
      .cfg_height(cfg_height), .cfg_use_ca(cfg_use_ca), .cfg_kernel_q(cfg_kernel_q),
      .cfg_kernel_h(cfg_kernel_h), .cfg_kernel_f(cfg_kernel_f), .out_valid(win_valid),
      .out_x(win_x), .out_y(win_y), .out_d(win_d), .out_v(win_v), .out_ok(win_ok),
      .busy(levels_busy));

  stereo_plane_stats #(
      .VRANGE(VRANGE), .V_MIN(V_MIN)
  ) stats (
      .clk(clk), .rst(rst), .ce(win_valid), .in_x(win_x), .in_y(win_y), .in_valid(win_ok),
      .in_d(16'(win_d)), .in_v(win_v), .cfg_width(cfg_width), .cfg_height(cfg_height),
      .plane_a(plane_a), .plane_b(plane_b), .plane_c(plane_c), .tolerance(tolerance),
      .hist_index(hist_index), .hist_count(hist_count), .out_done(out_done),
      .out_count(out_count), .out_sum_x(out_sum_x), .out_sum_y(out_sum_y),
      .out_sum_xx(out_sum_xx), .out_sum_xy(out_sum_xy), .out_sum_yy(out_sum_yy),
      .out_sum_v(out_sum_v), .out_sum_xv(out_sum_xv), .out_sum_yv(out_sum_yv));
endmodule

`default_nettype wire
