// stereo_plane_stats: the statistics of the hierarchical core's vertical plane over one frame
// (issue 45; docs/hierarchical.md "Hardware form of the field"), bit-exact with
// stereo::hierarchical::plane_statistics. It sees the full level's winners in raster order, one
// per step (ce): the pixel (in_x, in_y), whether it is valid, and its displacement (in_d, in_v).
// A valid winner votes at the right image's column xr = in_x - in_d (none when xr is outside
// 0 .. cfg_width - 1: the field lives in the right image's columns). Over the frame it counts the
// votes per offset (the histogram of V_MIN .. V_MIN + VRANGE - 1), and sums the normal equations
// of v = a + b xr + c y over the votes that are inliers of the plane it was given,
//   |v 2^16 - (a + b xr + c y)| <= tolerance,
// all in exact integers (the plane's coefficients and the tolerance in 1/2^16 pixel, as
// stereo::hierarchical::Plane). The pixel (0, 0) starts a frame and clears the sums; the pixel
// (cfg_width - 1, cfg_height - 1) ends it: the frame's totals are copied to the out_* registers
// (held until the next frame ends, for the host to read) and out_done is high for one clock.
// The histogram is read one bin at a time (hist_index, hist_count: combinational), as a
// register map reads it. Reset clears out_done and the frame state; an abandoned frame (reset,
// or a new start of frame) never reaches the out_* registers.
`default_nettype none
`include "stereo_assert.svh"

module stereo_plane_stats #(
    parameter int VRANGE = 16,  // histogram bins, offsets V_MIN .. V_MIN + VRANGE - 1
    parameter int V_MIN  = -8
) (
    input  wire logic                      clk,
    input  wire logic                      rst,
    input  wire logic                      ce,          // one winner
    input  wire fx_pkg::coord_t            in_x,
    input  wire fx_pkg::coord_t            in_y,
    input  wire logic                      in_valid,    // the winner is valid
    input  wire fx_pkg::coord_t            in_d,        // its horizontal displacement
    input  wire logic signed [7:0]         in_v,        // its vertical offset
    input  wire fx_pkg::cfg_size_t         cfg_width,
    input  wire fx_pkg::cfg_size_t         cfg_height,
    input  wire logic signed [31:0]        plane_a,     // 1/2^16 pixel
    input  wire logic signed [31:0]        plane_b,     // 1/2^16 pixel per column
    input  wire logic signed [31:0]        plane_c,     // 1/2^16 pixel per row
    input  wire logic        [31:0]        tolerance,   // 1/2^16 pixel
`include "stereo_plane_stats_ports.svh"
);
  `STEREO_ASSERT(vrange_positive, VRANGE >= 1 && VRANGE <= 256, "VRANGE must be 1 .. 256")
  `STEREO_ASSERT(offsets_fit_a_byte, V_MIN >= -128 && V_MIN + VRANGE - 1 <= 127,
                 "V_MIN .. V_MIN + VRANGE - 1 must fit a signed byte")

  localparam int SUMS = 9;  // count, x, y, xx, xy, yy, v, xv, yv

  // The residual v 2^16 - (a + b xr + c y) in 64 bits: |b xr| and |c y| < 2^31 * 2^16.
  logic signed [63:0] x, y, v, residual, magnitude;
  logic vote, inlier, in_range, first, last;
  logic [7:0] bin;
  assign x = 64'(in_x) - 64'(in_d);  // xr
  assign vote = in_valid && x >= 0 && x < 64'(cfg_width);
  assign y = 64'(in_y);
  assign v = 64'(in_v);
  assign residual = (v <<< 16) - (64'(plane_a) + 64'(plane_b) * x + 64'(plane_c) * y);
  assign magnitude = residual < 0 ? -residual : residual;
  assign inlier = vote && magnitude <= 64'(tolerance);
  assign in_range = 32'(in_v) >= V_MIN && 32'(in_v) < V_MIN + VRANGE;
  assign bin = 8'(32'(in_v) - V_MIN);
  assign first = in_x == '0 && in_y == '0;
  assign last = 32'(in_x) + 1 == 32'(cfg_width) && 32'(in_y) + 1 == 32'(cfg_height);

  // This vote's terms (x is xr), and the frame's running sums (cleared by the frame's first pixel).
  logic signed [63:0] terms[SUMS];
  logic signed [63:0] sums_q[SUMS];
  logic signed [63:0] sums[SUMS];  // with this pixel
  always_comb begin
    terms[0] = 64'sd1;
    terms[1] = x;
    terms[2] = y;
    terms[3] = x * x;
    terms[4] = x * y;
    terms[5] = y * y;
    terms[6] = v;
    terms[7] = x * v;
    terms[8] = y * v;
    for (int i = 0; i < SUMS; i++) begin
      sums[i] = (first ? 64'sd0 : sums_q[i]) + (inlier ? terms[i] : 64'sd0);
    end
  end

  logic [31:0] hist_q[VRANGE];
  logic [31:0] hist_out[VRANGE];
  logic [31:0] hist_next[VRANGE];
  always_comb begin
    for (int b = 0; b < VRANGE; b++) begin
      hist_next[b] = (first ? 32'd0 : hist_q[b]) + 32'(vote && in_range && bin == 8'(b));
    end
  end

  always_ff @(posedge clk) begin
    out_done <= 1'b0;
    if (rst) begin
      for (int i = 0; i < SUMS; i++) sums_q[i] <= '0;
      for (int b = 0; b < VRANGE; b++) hist_q[b] <= '0;
    end else if (ce) begin
      for (int i = 0; i < SUMS; i++) sums_q[i] <= sums[i];
      for (int b = 0; b < VRANGE; b++) hist_q[b] <= hist_next[b];
      if (last) begin
        out_done <= 1'b1;
        out_count <= sums[0];
        out_sum_x <= sums[1];
        out_sum_y <= sums[2];
        out_sum_xx <= sums[3];
        out_sum_xy <= sums[4];
        out_sum_yy <= sums[5];
        out_sum_v <= sums[6];
        out_sum_xv <= sums[7];
        out_sum_yv <= sums[8];
        for (int b = 0; b < VRANGE; b++) hist_out[b] <= hist_next[b];
      end
    end
  end
  assign hist_count = hist_out[hist_index];
endmodule

`default_nettype wire
