// The plane statistics' read-out ports (docs/hierarchical.md, "Hardware form of the field"): one
// histogram bin at a time and the frame's inlier sums, held until the next frame ends; out_done is
// high for one clock when they change. Included at the end of the port lists of
// stereo_plane_stats and stereo_hier_top, which declare the parameter VRANGE.
    input  wire logic [((VRANGE > 1) ? $clog2(VRANGE) : 1)-1:0] hist_index,
    output      logic [31:0]               hist_count,  // the last frame's bin hist_index
    output      logic                      out_done,    // one clock: a frame's totals are out
    output      logic signed [63:0]        out_count,
    output      logic signed [63:0]        out_sum_x,
    output      logic signed [63:0]        out_sum_y,
    output      logic signed [63:0]        out_sum_xx,
    output      logic signed [63:0]        out_sum_xy,
    output      logic signed [63:0]        out_sum_yy,
    output      logic signed [63:0]        out_sum_v,
    output      logic signed [63:0]        out_sum_xv,
    output      logic signed [63:0]        out_sum_yv
