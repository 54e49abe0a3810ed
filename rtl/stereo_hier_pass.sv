// stereo_hier_pass: the hierarchical core's 1-D pass along the field of a plane (issue 45;
// docs/hierarchical.md, "The streaming core"), bit-exact with
// stereo::hierarchical::match_along_field(left, right, plane_field(plane, W, H, V_MIN, V_MAX),
// params) and the vertical offsets of Result::vertical:
//
//   s_axis -> stereo_row_warp -> stereo_top (min_disp 0) -> stereo_field_border -> m_axis
//
//   s_axis: tdata = {right RGB, left RGB}, tuser = start of frame, tlast = end of line (as
//           stereo_top).
//   m_axis: tdata = {v[7:0], fx_pkg::out_beat_t}: stage 6's beat of the pass and, for a valid
//           pixel, the vertical offset of its match (0 where invalid): the vertical map as a
//           second field. tuser on the first pixel, tlast at each row end; one beat per pixel.
//
// The plane (plane_a + plane_b x + plane_c y, 1/2^16 pixel, x the right image's column) is what
// the host's PlaneTracker computed from the previous frame's statistics (stereo_plane_stats). The
// whole configuration, plane included, is sampled when the row select takes a frame's first
// beat, and kept in a two-entry queue until the frame leaves: stereo_top takes it when the frame
// reaches it (V_MAX rows later), the border stage when the frame's first result reaches it. So
// the host may write the next frame's setting as soon as a frame has started. A third frame
// waits at the input until the oldest has left. Reset (synchronous, active high) abandons every
// frame in flight.
`default_nettype none
`include "stereo_assert.svh"

module stereo_hier_pass #(
    parameter int WIDTH  = 64,  // largest frame width
    parameter int HEIGHT = 48,  // largest frame height
    parameter int NDISP  = 16,  // labels of the pass
    parameter int WINDOW = 5,   // largest aggregation window (odd)
    parameter bit RUNTIME_KERNEL = 1'b1,
    parameter fx_pkg::cost_e COST = fx_pkg::COST_CENSUS,  // the core's cost (docs: census only)
    parameter int LANES = NDISP,
    parameter bit RECOMPUTE_COSTS = 1'b0,
    parameter int V_MIN = -8,  // the field's range, as the model's level_range at full size
    parameter int V_MAX = 7
) (
    input  wire logic                               clk,
    input  wire logic                               rst,
`include "stereo_pass_cfg_ports.svh"
    input  wire logic signed [31:0]                 plane_a,
    input  wire logic signed [31:0]                 plane_b,
    input  wire logic signed [31:0]                 plane_c,
    output      logic [fx_pkg::STATUS_BITS-1:0]     status,  // stereo_top's sticky bits
    input  wire logic [fx_pkg::IN_BEAT_BITS-1:0]    s_axis_tdata,
    input  wire logic                               s_axis_tvalid,
    output      logic                               s_axis_tready,
    input  wire logic                               s_axis_tlast,
    input  wire logic                               s_axis_tuser,
`include "stereo_hier_out_ports.svh"
);
  // (Member widths spelled out: Yosys does not resolve a package's types inside a struct.)
  typedef struct packed {
    logic [fx_pkg::CFG_SIZE_BITS-1:0] width;
    logic [fx_pkg::CFG_SIZE_BITS-1:0] height;
    logic [fx_pkg::CFG_NDISP_BITS-1:0] ndisp;
    logic [fx_pkg::CFG_RADIUS_BITS-1:0] radius;
    logic [WINDOW*fx_pkg::TAP_BITS-1:0] kernel;
    logic use_ca;
    logic uniqueness_en;
    logic [fx_pkg::CFG_UNIQUENESS_BITS-1:0] uniqueness;
    logic lr_en;
    logic [fx_pkg::CFG_LR_TOLERANCE_BITS-1:0] lr_tolerance;
    logic subpixel_en;
    logic signed [31:0] a;
    logic signed [31:0] b;
    logic signed [31:0] c;
  } setting_t;

  // The queue of the frames' settings: pushed when the row select starts a frame, popped when
  // the frame's first result enters the border stage; its head is the oldest frame in flight.
  setting_t queue[2];
  setting_t head, incoming, current;
  logic [1:0] count;
  logic write_slot, read_slot;
  logic push, pop;
  assign head = queue[read_slot];
  // With no frame in flight stereo_top sees the ports, as it would on its own (its idle checks).
  assign current = count != 2'd0 ? head : incoming;
  always_comb begin
    incoming.width = cfg_width;
    incoming.height = cfg_height;
    incoming.ndisp = cfg_ndisp;
    incoming.radius = cfg_radius;
    incoming.kernel = cfg_kernel;
    incoming.use_ca = cfg_use_ca;
    incoming.uniqueness_en = cfg_uniqueness_en;
    incoming.uniqueness = cfg_uniqueness;
    incoming.lr_en = cfg_lr_en;
    incoming.lr_tolerance = cfg_lr_tolerance;
    incoming.subpixel_en = cfg_subpixel_en;
    incoming.a = plane_a;
    incoming.b = plane_b;
    incoming.c = plane_c;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      count <= '0;
      write_slot <= 1'b0;
      read_slot <= 1'b0;
    end else begin
      if (push) begin
        queue[write_slot] <= incoming;
        write_slot <= !write_slot;
      end
      if (pop) read_slot <= !read_slot;
      count <= count + 2'(push) - 2'(pop);
    end
  end

  logic [fx_pkg::IN_BEAT_BITS-1:0] warped_tdata;
  logic warped_tvalid, warped_tready, warped_tlast, warped_tuser;
  stereo_row_warp #(
      .WIDTH(WIDTH),
      .HEIGHT(HEIGHT),
      .V_MIN(V_MIN),
      .V_MAX(V_MAX)
  ) row_select (
      .clk(clk),
      .rst(rst),
      .cfg_width(cfg_width),
      .cfg_height(cfg_height),
      .plane_a(plane_a),
      .plane_b(plane_b),
      .plane_c(plane_c),
      .start_allowed(count != 2'd2),
      .frame_start(push),
      .s_axis_tdata(s_axis_tdata),
      .s_axis_tvalid(s_axis_tvalid),
      .s_axis_tready(s_axis_tready),
      .s_axis_tlast(s_axis_tlast),
      .s_axis_tuser(s_axis_tuser),
      .m_axis_tdata(warped_tdata),
      .m_axis_tvalid(warped_tvalid),
      .m_axis_tready(warped_tready),
      .m_axis_tlast(warped_tlast),
      .m_axis_tuser(warped_tuser)
  );

  fx_pkg::out_beat_t pass_tdata;
  logic pass_tvalid, pass_tready, pass_tlast, pass_tuser;
  stereo_top #(
      .WIDTH(WIDTH),
      .HEIGHT(HEIGHT),
      .NDISP(NDISP),
      .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL),
      .MAX_MIN_DISP(0),
      .COST(COST),
      .LANES(LANES),
      .RECOMPUTE_COSTS(RECOMPUTE_COSTS)
  ) pass (
      .clk(clk),
      .rst(rst),
      .cfg_radius(current.radius),
      .cfg_kernel(current.kernel),
      .cfg_width(current.width),
      .cfg_height(current.height),
      .cfg_ndisp(current.ndisp),
      .cfg_use_ca(current.use_ca),
      .cfg_min_disp('0),
      .cfg_uniqueness_en(current.uniqueness_en),
      .cfg_uniqueness(current.uniqueness),
      .cfg_lr_en(current.lr_en),
      .cfg_lr_tolerance(current.lr_tolerance),
      .cfg_subpixel_en(current.subpixel_en),
      .status(status),
      .s_axis_tdata(warped_tdata),
      .s_axis_tvalid(warped_tvalid),
      .s_axis_tready(warped_tready),
      .s_axis_tlast(warped_tlast),
      .s_axis_tuser(warped_tuser),
      .m_axis_tdata(pass_tdata),
      .m_axis_tvalid(pass_tvalid),
      .m_axis_tready(pass_tready),
      .m_axis_tlast(pass_tlast),
      .m_axis_tuser(pass_tuser)
  );

  stereo_field_border #(
      .WIDTH(WIDTH),
      .HEIGHT(HEIGHT),
      .WINDOW(WINDOW),
      .V_MIN(V_MIN),
      .V_MAX(V_MAX)
  ) field_border (
      .clk(clk),
      .rst(rst),
      .cfg_width(current.width),
      .cfg_height(current.height),
      .cfg_radius(current.radius),
      .cfg_use_ca(current.use_ca),
      .plane_a(current.a),
      .plane_b(current.b),
      .plane_c(current.c),
      .frame_start(pop),
      .s_axis_tdata(pass_tdata),
      .s_axis_tvalid(pass_tvalid),
      .s_axis_tready(pass_tready),
      .s_axis_tlast(pass_tlast),
      .s_axis_tuser(pass_tuser),
      .m_axis_tdata(m_axis_tdata),
      .m_axis_tvalid(m_axis_tvalid),
      .m_axis_tready(m_axis_tready),
      .m_axis_tlast(m_axis_tlast),
      .m_axis_tuser(m_axis_tuser)
  );
endmodule

`default_nettype wire
