// stereo_cost_select: the matching cost stage of stereo_top, chosen by parameter: COST = 0 the
// AD cost over RGB (stereo_cost), COST = 1 the LCDM cost (stereo_cost_lcdm, thesis Sec. 3.5).
// Both have these ports and a latency of one pixel step, so the rest of the pipeline and the
// stage table are the same for both.
`default_nettype none

module stereo_cost_select #(
    parameter int NDISP = 16,  // disparities evaluated in parallel
    parameter int COST  = 0    // 0: AD, 1: LCDM
) (
    input  wire logic                               clk,
    input  wire logic                               rst,
    input  wire logic                               ce,
    input  wire fx_pkg::coord_t                     in_x,
    input  wire fx_pkg::coord_t                     in_y,
    input  wire logic [23:0]                        in_left,   // {R, G, B}
    input  wire logic [23:0]                        in_right,  // {R, G, B}
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    output      logic [NDISP*fx_pkg::COST_BITS-1:0] out_data
);
  generate
    if (COST == 1) begin : g_lcdm
      stereo_cost_lcdm #(.NDISP(NDISP)) cost (.*);
    end else begin : g_ad
      stereo_cost #(.NDISP(NDISP)) cost (.*);
    end
  endgenerate
endmodule

`default_nettype wire
