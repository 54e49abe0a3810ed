// stereo_plane_offset: the vertical field of a plane at one pixel, as
// stereo::hierarchical::plane_field computes it (issue 45; docs/hierarchical.md):
//   offset = clamp(floor((a + b x + c y + 2^15) / 2^16), V_MIN, V_MAX),
// the plane's value rounded half up (for negative values too) and clamped into the offsets the
// core holds. a, b, c in 1/2^16 pixel (stereo::hierarchical::Plane), x the right image's column.
// Combinational; the one definition the row select (stereo_row_warp) and the pass's output
// stage (stereo_field_border) both instantiate.
`default_nettype none

module stereo_plane_offset #(
    parameter int V_MIN = -8,  // smallest offset
    parameter int V_MAX = 7    // largest offset
) (
    input  wire logic signed [31:0] plane_a,
    input  wire logic signed [31:0] plane_b,
    input  wire logic signed [31:0] plane_c,
    input  wire logic signed [16:0] x,  // a coordinate, or a row above the frame
    input  wire logic signed [16:0] y,
    output      logic signed [7:0]  offset
);
  // |b x|, |c y| < 2^31 2^16: each product 49 bits (two DSP48 at most), the sum 51.
  localparam logic signed [50:0] LOWEST = 51'(V_MIN);
  localparam logic signed [50:0] HIGHEST = 51'(V_MAX);
  logic signed [48:0] bx, cy;
  logic signed [50:0] value, rounded;
  always_comb begin
    bx = 49'(plane_b) * 49'(x);
    cy = 49'(plane_c) * 49'(y);
    value = 51'(plane_a) + 51'(bx) + 51'(cy) + 51'sd32768;
    rounded = value >>> 16;  // floor
    if (rounded < LOWEST) rounded = LOWEST;
    if (rounded > HIGHEST) rounded = HIGHEST;
    offset = 8'(rounded);
  end
endmodule

`default_nettype wire
