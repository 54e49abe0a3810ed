// stereo_ca_rule1: CA rule 1 (model: stereo::ca_rule1, docs/fixed-point.md stage 3), the
// stage module of stereo_top: stereo_ca_plane with RULE = 1 (the rule, the latency W + 3 and
// the border handling are described there).
`default_nettype none

module stereo_ca_rule1 #(
    parameter int WIDTH = 64,  // longest row
    parameter int NDISP = 16   // disparities in parallel
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
    input  wire logic                              cfg_use_ca,
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    output      logic [NDISP*fx_pkg::AGG_BITS-1:0] out_data
);
  stereo_ca_plane #(
      .WIDTH(WIDTH),
      .NDISP(NDISP),
      .RULE (1)
  ) plane (
      .*
  );
endmodule

`default_nettype wire
