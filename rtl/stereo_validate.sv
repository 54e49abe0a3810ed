// stereo_validate: the second cost and the sub-pixel disparity of a pixel (model:
// stereo::ValidatingSelector and stereo::validation::subpixel_offset, docs/fixed-point.md
// stage 6), from stereo_wta's registered winner and cost vector.
//
//   C2 = min { E(k) : |k - k1| > 1, k < cfg_ndisp }: a second comparator tree whose leaves are
//        masked by the winner; a masked leaf holds all ones = NO_SECOND_COST, which is what
//        the tree yields when no label lies away from the winner.
//   fixed = 16 (m + k1) + offset, offset = sign(a - b) floor((16 |a - b| + den) / (2 den)),
//        a = E(k1 - 1), b = E(k1 + 1), den = a + b - 2 C1 > 0, when cfg_subpixel_en and
//        0 < k1 < cfg_ndisp - 1; else 0. Since |offset| <= 8, it is the number of t = 1 .. 8
//        with 16 |a - b| >= (2t - 1) den: a ladder of constant multiples, no divider.
// Latency: 1 pixel step.
`default_nettype none

module stereo_validate #(
    parameter int NDISP = 16  // labels in parallel
) (
    input  wire logic                               clk,
    input  wire logic                               rst,  // clears coordinates only
    input  wire logic                               ce,
    input  wire fx_pkg::coord_t                     in_x,
    input  wire fx_pkg::coord_t                     in_y,
    input  wire logic [fx_pkg::DISP_BITS-1:0]       in_label,   // k1
    input  wire logic                               in_border,  // the border rule holds
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_cost,    // C1
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_before,  // E(k1 - 1)
    input  wire logic [fx_pkg::AGG_BITS-1:0]        in_after,   // E(k1 + 1)
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0]  in_data,    // E(0 .. NDISP-1)
    input  wire fx_pkg::cfg_ndisp_t                 cfg_ndisp,
    input  wire fx_pkg::cfg_min_disp_t              cfg_min_disp,
    input  wire logic                               cfg_subpixel_en,
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]       out_label,
    output      logic                               out_border,
    output      logic [fx_pkg::AGG_BITS-1:0]        out_cost,    // C1
    output      logic [fx_pkg::AGG_BITS-1:0]        out_second,  // C2
    output      logic signed [fx_pkg::FIXED_BITS-1:0] out_fixed  // 16 d + offset
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int LEVELS = (NDISP > 1) ? $clog2(NDISP) : 1;
  localparam int LEAVES = 1 << LEVELS;
  localparam int NODES = 2 * LEAVES - 1;
  localparam int STEPS = 1 << (fx_pkg::SUBPIXEL_BITS - 1);  // largest |offset|: 8

  initial begin
    assert (fx_pkg::NO_SECOND_COST == (1 << BITS) - 1);  // a masked leaf is "no second cost"
  end

  // ---- C2: the minimum over labels away from the winner --------------------------------------
  logic [NODES*BITS-1:0] node  /*verilator split_var*/;
  generate
    for (genvar k = 0; k < LEAVES; k++) begin : g_leaf
      if (k < NDISP) begin : g_label
        logic away;  // |k - k1| > 1
        assign away = (k + 1 < $signed(32'(in_label))) || (k > $signed(32'(in_label)) + 1);
        assign node[(LEAVES-1+k)*BITS +: BITS] =
            // A shift, not a part-select: Verilator's lint of several tops at once (different
            // NDISP) checks this select against another instance's width.
            (away && k < $signed(32'(cfg_ndisp))) ? BITS'(in_data >> (k * BITS))
                                                   : BITS'(fx_pkg::NO_SECOND_COST);
      end else begin : g_padding
        assign node[(LEAVES-1+k)*BITS +: BITS] = BITS'(fx_pkg::NO_SECOND_COST);
      end
    end
    for (genvar n = 0; n < LEAVES - 1; n++) begin : g_node
      assign node[n*BITS +: BITS] =
          (node[(2*n+1)*BITS +: BITS] <= node[(2*n+2)*BITS +: BITS]) ? node[(2*n+1)*BITS +: BITS]
                                                                     : node[(2*n+2)*BITS +: BITS];
    end
  endgenerate

  // ---- sub-pixel offset: the comparator ladder -------------------------------------------------
  logic signed [fx_pkg::FIXED_BITS-1:0] fixed;
  always_comb begin
    logic [BITS:0] difference;          // |a - b|
    logic [BITS+1:0] denominator;       // a + b - 2 C1 >= 0
    logic [BITS+fx_pkg::SUBPIXEL_BITS:0] scaled;  // 16 |a - b|
    logic [BITS+fx_pkg::SUBPIXEL_BITS+1:0] threshold;
    logic [fx_pkg::SUBPIXEL_BITS:0] steps;
    logic refine;
    difference = (in_before >= in_after) ? (BITS + 1)'(in_before - in_after)
                                         : (BITS + 1)'(in_after - in_before);
    denominator = (BITS + 2)'(in_before) + (BITS + 2)'(in_after) - {1'b0, in_cost, 1'b0};
    scaled = (BITS + fx_pkg::SUBPIXEL_BITS + 1)'(difference) << fx_pkg::SUBPIXEL_BITS;
    steps = '0;
    for (int t = 1; t <= STEPS; t++) begin
      threshold = (BITS + fx_pkg::SUBPIXEL_BITS + 2)'(denominator) *
                  (BITS + fx_pkg::SUBPIXEL_BITS + 2)'(2 * t - 1);
      if ((BITS + fx_pkg::SUBPIXEL_BITS + 2)'(scaled) >= threshold) steps = steps + 1'b1;
    end
    refine = cfg_subpixel_en && in_label != '0 && 32'(in_label) + 1 < 32'(cfg_ndisp) &&
             denominator != '0;
    fixed = (fx_pkg::FIXED_BITS'(cfg_min_disp) + fx_pkg::FIXED_BITS'(in_label))
            <<< fx_pkg::SUBPIXEL_BITS;
    if (refine) begin
      if (in_before >= in_after) fixed = fixed + fx_pkg::FIXED_BITS'(steps);
      else fixed = fixed - fx_pkg::FIXED_BITS'(steps);
    end
  end

  always_ff @(posedge clk) begin
    if (ce) begin
      out_label <= in_label;
      out_border <= in_border;
      out_cost <= in_cost;
      out_second <= node[0 +: BITS];
      out_fixed <= fixed;
    end
  end
  stereo_coord_reg coordinates (.*);
endmodule

`default_nettype wire
