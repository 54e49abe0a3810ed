// stereo_window_centre: the centre of the window that the incoming pixel (in_x, in_y) completes,
// RADIUS columns behind it on the row RADIUS rows up, (in_x - RADIUS, in_y - RADIUS), wrapping to
// earlier rows in raster order up to max(RADIUS, 1) times (a frame narrower than RADIUS wraps
// more than once: at RADIUS = 2, width 1). 18-bit signed: the 16-bit positions, the no-pixel code
// and the wrap fit. Combinational; the window stages (stereo_window3x3, stereo_census,
// stereo_aggregate) hand it to their stereo_border_flags and register it.
`default_nettype none

module stereo_window_centre #(
    parameter int RADIUS = 1  // of the window (side 2 RADIUS + 1)
) (
    input  wire fx_pkg::coord_t     in_x,
    input  wire fx_pkg::coord_t     in_y,
    input  wire fx_pkg::cfg_size_t  cfg_width,
    output      logic signed [17:0] centre_x,
    output      logic signed [17:0] centre_y
);
  always_comb begin
    centre_x = 18'(in_x) - 18'(RADIUS);
    centre_y = 18'(in_y) - 18'(RADIUS);
    for (int wrap = 0; wrap < ((RADIUS > 0) ? RADIUS : 1); wrap++) begin
      if (centre_x < 18'sd0) begin
        centre_x = centre_x + $signed(18'(cfg_width));
        centre_y = centre_y - 18'sd1;
      end
    end
  end
endmodule

`default_nettype wire
