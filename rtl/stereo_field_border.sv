// stereo_field_border: the output stage of the hierarchical core's 1-D pass (issue 45;
// docs/hierarchical.md), bit-exact with the end of stereo::hierarchical::match_along_field and
// Result::vertical. It takes stereo_top's output beats (the pass on the row-warped right image)
// in raster order and, for each valid pixel (x, y) with disparity fixed / 16, reads the plane's
// field at the match, the right image's column
//   xr = clamp(x - round(fixed / 16), 0, W - 1)  (halves up; field_at_match),
//   v  = clamp(round((a + b xr + c y) / 2^16), V_MIN, V_MAX)  (halves up; plane_field).
// A valid pixel whose right row y + v lies within `reach` of the top or bottom edge becomes
// invalid (reason border, fixed 0), as the model's border rule of the pass; reach = the window's
// radius (cfg_radius, at most WINDOW / 2) + 1 with the CA rules (cfg_use_ca).
//
//   s_axis: tdata = fx_pkg::out_beat_t, tuser on a frame's first pixel, tlast at each row end.
//   m_axis: tdata = {v[7:0], out_beat_t}: the vertical offset of a valid pixel (0 where invalid)
//           above the (possibly border-marked) beat; tuser and tlast passed on.
// The frame's configuration (cfg_*, plane_*) is sampled with its tuser beat, clamped as stereo_top
// clamps it (a size of 0 or above WIDTH, HEIGHT is WIDTH, HEIGHT; the radius at most WINDOW / 2);
// the pixels are counted by the sampled width. One output register: s_axis_tready = it is empty or being taken.
`default_nettype none
`include "stereo_assert.svh"

module stereo_field_border #(
    parameter int WIDTH  = 64,  // longest row
    parameter int HEIGHT = 48,  // tallest frame
    parameter int WINDOW = 5,   // largest aggregation window (odd), as stereo_top's
    parameter int V_MIN  = -8,  // smallest vertical offset
    parameter int V_MAX  = 7    // largest vertical offset
) (
    input  wire logic                              clk,
    input  wire logic                              rst,
    input  wire fx_pkg::cfg_size_t                 cfg_width,
    input  wire fx_pkg::cfg_size_t                 cfg_height,
    input  wire fx_pkg::cfg_radius_t               cfg_radius,
    input  wire logic                              cfg_use_ca,
    input  wire logic signed [31:0]                plane_a,
    input  wire logic signed [31:0]                plane_b,
    input  wire logic signed [31:0]                plane_c,
    output      logic                              frame_start,  // configuration sampled now
    input  wire fx_pkg::out_beat_t                 s_axis_tdata,
    input  wire logic                              s_axis_tvalid,
    output      logic                              s_axis_tready,
    input  wire logic                              s_axis_tlast,
    input  wire logic                              s_axis_tuser,
`include "stereo_hier_out_ports.svh"
);
  `STEREO_ASSERT(offset_range, V_MIN >= -128 && V_MAX <= 127 && V_MIN <= V_MAX,
                 "V_MIN .. V_MAX must fit a signed byte")

  localparam int R = WINDOW / 2;

  logic take;
  assign s_axis_tready = !m_axis_tvalid || m_axis_tready;
  assign take = s_axis_tvalid && s_axis_tready;
  assign frame_start = take && s_axis_tuser;

  // The frame's configuration, and the position of the next beat; the tuser beat uses the ports.
  fx_pkg::cfg_size_t width_q, height_q;
  logic signed [31:0] a_q, b_q, c_q;
  logic [5:0] reach_q;
  fx_pkg::coord_t x_q, y_q;

  fx_pkg::cfg_size_t width, height;
  logic signed [31:0] a, b, c;
  logic [5:0] reach;
  logic signed [63:0] x, y, disparity, column, row;
  logic signed [7:0] offset;
  logic border;
  fx_pkg::out_beat_t beat;
  always_comb begin
    width = s_axis_tuser ? ((cfg_width == '0 || 32'(cfg_width) > WIDTH) ?
                            fx_pkg::CFG_SIZE_BITS'(WIDTH) : cfg_width) : width_q;
    height = s_axis_tuser ? ((cfg_height == '0 || 32'(cfg_height) > HEIGHT) ?
                             fx_pkg::CFG_SIZE_BITS'(HEIGHT) : cfg_height) : height_q;
    a = s_axis_tuser ? plane_a : a_q;
    b = s_axis_tuser ? plane_b : b_q;
    c = s_axis_tuser ? plane_c : c_q;
    reach = s_axis_tuser ? 6'((32'(cfg_radius) > R ? R : 32'(cfg_radius)) + 32'(cfg_use_ca))
                         : reach_q;
    x = s_axis_tuser ? 64'sd0 : 64'(x_q);
    y = s_axis_tuser ? 64'sd0 : 64'(y_q);
    // round(fixed / 16), halves up: floor((fixed + 8) / 16).
    disparity = (64'(s_axis_tdata.fixed) + 64'sd8) >>> 4;
    column = x - disparity;
    if (column < 0) column = 0;
    if (column > 64'(width) - 1) column = 64'(width) - 1;
  end

  stereo_plane_offset #(
      .V_MIN(V_MIN),
      .V_MAX(V_MAX)
  ) field (
      .plane_a(a),
      .plane_b(b),
      .plane_c(c),
      .x(17'(column)),
      .y(17'(y)),
      .offset(offset)
  );

  always_comb begin
    row = y + 64'(offset);
    border = s_axis_tdata.reason == fx_pkg::REASON_BITS'(fx_pkg::REASON_VALID) &&
             (row < 64'(reach) || row >= 64'(height) - 64'(reach));
    beat = s_axis_tdata;
    if (border) begin
      beat.reason = fx_pkg::REASON_BITS'(fx_pkg::REASON_BORDER);
      beat.fixed = '0;
    end
  end

  always_ff @(posedge clk) begin
    if (rst) begin
      m_axis_tvalid <= 1'b0;
      x_q <= '0;
      y_q <= '0;
    end else begin
      if (m_axis_tready) m_axis_tvalid <= 1'b0;
      if (take) begin
        m_axis_tvalid <= 1'b1;
        m_axis_tdata <= {beat.reason == fx_pkg::REASON_BITS'(fx_pkg::REASON_VALID) ?
                         8'(offset) : 8'd0, beat};
        m_axis_tuser <= s_axis_tuser;
        m_axis_tlast <= s_axis_tlast;
        width_q <= width;
        height_q <= height;
        a_q <= a;
        b_q <= b;
        c_q <= c;
        reach_q <= reach;
        if (x + 1 == 64'(width)) begin
          x_q <= '0;
          y_q <= 16'(y + 1);
        end else begin
          x_q <= 16'(x + 1);
          y_q <= 16'(y);
        end
      end
    end
  end
endmodule

`default_nettype wire
