// stereo_hier_level: one level of the hierarchical 2-D search (model:
// stereo::hierarchical::match_level with the census cost and CaNeighbours::horizontal;
// docs/hierarchical.md "Candidates and the DSI of a level", "The streaming core"). The 1-D
// pipeline's stages on the level's COLS x ROWS candidates per pixel, label k = j * COLS + i:
//   stereo_census -> stereo_level_cost (2-D candidates, any side outside) -> stereo_aggregate
//   (one plane per candidate, the cost as it is) -> CA rule 1 (stereo_ca_plane with runs of COLS
//   labels: the "d +- 1" neighbours of (i, j) are (i -+ 1, j), none past the row's ends) -> CA
//   rule 2 (in-plane, every label) -> stereo_level_wta (the 2-D tie key) -> the displacement and
//   validity.
//
// Time-multiplexed lanes (LANES < COLS * ROWS, docs/rtl.md): a pixel step takes
// G = COLS * ROWS / LANES clocks, `group` 0 .. G-1 from the caller and the step (ce) at group
// G-1, as in stereo_top; every stage then computes LANES labels a clock.
//
// Candidates. REFINE = 0 (the quarter level): every displacement of the level's range for every
// pixel, base (0, V_MIN), COLS x ROWS = (D/f) x (V/f); the base ports are ignored. REFINE = 1
// (half and full): the 3x3 around the pixel's prediction, base (bd, bv) given by the caller,
// once when the pixel's costs are computed (req_x / req_y, in_base_*) and once when its winner
// leaves (out_x / out_y, out_base_*): the prediction is the coarse level's winner, which the
// caller holds anyway, so the base does not travel through the pipeline's row delays.
//
// The WTA's ties go to the smallest key (|v - pv|, |d - pd|, v, d) (stereo::tie_key), pv, pd the
// preferred displacement: (0, 0) at the quarter level, the 3x3 centre at the others. Relative to
// the base that order is the same for every pixel: a rank per label (TIE_RANK, at elaboration),
// which stereo_level_wta compares after the cost.
//
// Validity (stereo::hierarchical::level_valid): reach = WINDOW/2 (+1 with CA) and
//   reach <= x < W - reach, reach <= y < H - reach, x - d >= reach, reach <= y + v < H - reach.
// Input: the level's pixel pairs (RGB, raster order) with their coordinates, one per ce; after a
// frame's last pixel the caller keeps stepping with rows beyond the frame (any data) until the
// last winner has left (stereo_top's flush). Output: out_x / out_y (NO_PIXEL or outside the
// frame: not a pixel) and the winner, combinational from the WTA's register and out_base_*.
`default_nettype none
`include "stereo_assert.svh"

module stereo_hier_level #(
    parameter int WIDTH  = 32,  // longest row of the level
    parameter int COLS   = 3,   // candidate columns
    parameter int ROWS   = 3,   // candidate rows
    parameter int V_MIN  = -2,  // the level's vertical offsets V_MIN .. V_MAX
    parameter int V_MAX  = 1,
    parameter int WINDOW = 5,   // the level's aggregation window
    parameter bit REFINE = 1'b1,  // 1: 3x3 around a prediction; 0: the whole range (COLS x ROWS)
    parameter int LANES = COLS * ROWS,  // labels per clock (divides COLS * ROWS)
    // 1: the kernel from cfg_kernel; 0: the levels' constant kernel for WINDOW (fx_pkg::constant_tap,
    // hierarchical::default_level), built from shifts and adds, cfg_kernel ignored.
    parameter bit RUNTIME_KERNEL = 1'b1
) (
    input  wire logic                                clk,
    input  wire logic                                rst,  // clears coordinates only
    input  wire logic                                ce,   // the pixel step (at group G-1)
    /* verilator lint_off UNUSEDSIGNAL */  // G = 1: always 0
    input  wire logic [(((COLS * ROWS) / LANES > 1) ? $clog2((COLS * ROWS) / LANES) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::coord_t                      in_x,
    input  wire fx_pkg::coord_t                      in_y,
    input  wire logic [fx_pkg::RGB_BITS-1:0]         in_left,
    input  wire logic [fx_pkg::RGB_BITS-1:0]         in_right,
    input  wire fx_pkg::cfg_size_t                   cfg_width,
    input  wire fx_pkg::cfg_size_t                   cfg_height,
    input  wire logic                                cfg_use_ca,
    /* verilator lint_off UNUSEDSIGNAL */  // RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0]  cfg_kernel,
    /* verilator lint_on UNUSEDSIGNAL */
    // REFINE = 1: the base of the pixel whose costs the next step computes.
    output      fx_pkg::coord_t                      req_x,
    output      fx_pkg::coord_t                      req_y,
    /* verilator lint_off UNUSEDSIGNAL */  // REFINE = 0: the base is (0, V_MIN)
    input  wire logic [fx_pkg::DISP_BITS-1:0]        in_base_d,
    input  wire logic signed [fx_pkg::DISP_BITS-1:0] in_base_v,
    input  wire logic [fx_pkg::DISP_BITS-1:0]        out_base_d,  // of (out_x, out_y)
    input  wire logic signed [fx_pkg::DISP_BITS-1:0] out_base_v,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                      out_x,
    output      fx_pkg::coord_t                      out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]        out_d,
    output      logic signed [fx_pkg::DISP_BITS-1:0] out_v,
    output      logic                                out_valid
);
  localparam int LABELS = COLS * ROWS;
  localparam int AGG_BITS = fx_pkg::AGG_BITS;
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int R = WINDOW / 2;

  `STEREO_ASSERT(grid_shape, REFINE ? (COLS == 3 && ROWS == 3) : (ROWS == V_MAX - V_MIN + 1),
                 "REFINE = 1 needs a 3x3 grid; REFINE = 0 one candidate row per offset V_MIN .. V_MAX")
  `STEREO_ASSERT(label_count, LABELS >= 2 && LABELS <= 256, "COLS * ROWS must be 2 .. 256")
  `STEREO_ASSERT(window_odd, WINDOW >= 1 && WINDOW % 2 == 1 && WINDOW <= 31,
                 "WINDOW must be odd, 1 .. 31")

  // ---- the tie order --------------------------------------------------------------------------
  // stereo::tie_key relative to the base, compared field by field: d = i, v = j (REFINE:
  // preferred (1, 1)) or v = V_MIN + j (preferred (0, 0)).
  function automatic int abs_of(input int value);
    abs_of = (value < 0) ? -value : value;
  endfunction
  function automatic bit key_less(input int a, input int b);
    int da, va, db, vb, pv, pd;
    pd = REFINE ? 1 : 0;
    pv = REFINE ? 1 : 0;
    da = a % COLS;
    va = (REFINE ? 0 : V_MIN) + a / COLS;
    db = b % COLS;
    vb = (REFINE ? 0 : V_MIN) + b / COLS;
    if (abs_of(va - pv) != abs_of(vb - pv)) key_less = abs_of(va - pv) < abs_of(vb - pv);
    else if (abs_of(da - pd) != abs_of(db - pd)) key_less = abs_of(da - pd) < abs_of(db - pd);
    else if (va != vb) key_less = va < vb;
    else key_less = da < db;
  endfunction
  // TIE_RANK: the rank of label k at [k*9 +: 9] (how many keys are smaller).
  function automatic logic [LABELS*9-1:0] tie_rank();
    int smaller;
    tie_rank = '0;
    for (int k = 0; k < LABELS; k++) begin
      smaller = 0;
      for (int m = 0; m < LABELS; m++) if (key_less(m, k)) smaller++;
      tie_rank[k*9 +: 9] = 9'(smaller);
    end
  endfunction
  localparam logic [LABELS*9-1:0] TIE_RANK = tie_rank();

  // ---- configuration of the reused stages -------------------------------------------------------
  fx_pkg::config_t all_cfg;
  always_comb begin
    all_cfg = '0;
    all_cfg.width = cfg_width;
    all_cfg.height = cfg_height;
    all_cfg.ndisp = fx_pkg::CFG_NDISP_BITS'(LABELS);
    all_cfg.radius = fx_pkg::CFG_RADIUS_BITS'(R);
    all_cfg.use_ca = cfg_use_ca;
  end

  // ---- census and cost ------------------------------------------------------------------------
  fx_pkg::coord_t census_x, census_y, cost_x, cost_y, cost_next_y;
  logic [23:0] census_left, census_right;
  /* verilator lint_off UNUSEDSIGNAL */  // RGB_THROUGH = 0: zeros
  logic [23:0] census_left_rgb, census_right_rgb;
  /* verilator lint_on UNUSEDSIGNAL */
  stereo_census #(
      .WIDTH(WIDTH)
  ) census (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .in_x(in_x),
      .in_y(in_y),
      .in_left(in_left),
      .in_right(in_right),
      .cfg(all_cfg),
      .out_x(census_x),
      .out_y(census_y),
      .out_left(census_left),
      .out_right(census_right),
      .out_left_rgb(census_left_rgb),
      .out_right_rgb(census_right_rgb)
  );

  logic [fx_pkg::DISP_BITS-1:0] cost_base_d;
  logic signed [fx_pkg::DISP_BITS-1:0] cost_base_v;
  assign cost_base_d = REFINE ? in_base_d : '0;
  assign cost_base_v = REFINE ? in_base_v : fx_pkg::DISP_BITS'(V_MIN);
  logic [LANES*COST_BITS-1:0] cost_data;
  stereo_level_cost #(
      .WIDTH(WIDTH),
      .COLS(COLS),
      .ROWS(ROWS),
      .V_MIN(V_MIN),
      .V_MAX(V_MAX),
      .LANES(LANES)
  ) cost (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group),
      .in_x(census_x),
      .in_y(census_y),
      .in_left(census_left),
      .in_right(census_right),
      .cfg(all_cfg),
      .req_x(req_x),
      .req_y(req_y),
      .in_base_d(cost_base_d),
      .in_base_v(cost_base_v),
      .out_x(cost_x),
      .out_y(cost_y),
      .out_next_y(cost_next_y),
      .out_data(cost_data)
  );

  // ---- aggregation and the CA rules -------------------------------------------------------------
  fx_pkg::coord_t agg_x, agg_y, rule1_x, rule1_y, wta_in_x, wta_in_y;
  logic [LANES*AGG_BITS-1:0] agg_data, rule1_data, rule2_data;
  stereo_aggregate #(
      .WIDTH(WIDTH),
      .NDISP(LABELS),
      .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL),
      .LEVEL_KERNEL(1'b1),
      .LANES(LANES),
      .COST(fx_pkg::COST_AD)  // the costs as they are: a 2-D candidate's outside varies by row
  ) aggregate (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group),
      .in_x(cost_x),
      .in_y(cost_y),
      .in_next_y(cost_next_y),
      .in_data(cost_data),
      .cfg(all_cfg),
      .cfg_kernel(cfg_kernel),
      .out_x(agg_x),
      .out_y(agg_y),
      .out_data(agg_data)
  );

  stereo_ca_plane #(
      .WIDTH(WIDTH),
      .NDISP(LABELS),
      .RULE(fx_pkg::CA_RULE1),
      .LANES(LANES),
      .SEGMENT(COLS)  // one run per candidate row
  ) rule1 (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group),
      .in_x(agg_x),
      .in_y(agg_y),
      .in_data(agg_data),
      .cfg(all_cfg),
      .out_x(rule1_x),
      .out_y(rule1_y),
      .out_data(rule1_data)
  );

  stereo_ca_plane #(
      .WIDTH(WIDTH),
      .NDISP(LABELS),
      .RULE(fx_pkg::CA_RULE2),
      .LANES(LANES)
  ) rule2 (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group),
      .in_x(rule1_x),
      .in_y(rule1_y),
      .in_data(rule1_data),
      .cfg(all_cfg),
      .out_x(wta_in_x),
      .out_y(wta_in_y),
      .out_data(rule2_data)
  );

  // ---- WTA with the tie key -----------------------------------------------------------------------
  logic [8:0] winner;  // label k of the winner
  stereo_level_wta #(
      .NDISP(LABELS),
      .LANES(LANES),
      .RANK (TIE_RANK)
  ) wta (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group),
      .in_x(wta_in_x),
      .in_y(wta_in_y),
      .in_data(rule2_data),
      .out_x(out_x),
      .out_y(out_y),
      .out_label(winner)
  );

  // ---- the winner's displacement and validity ---------------------------------------------------
  logic signed [17:0] winner_d, winner_v, reach, x, y;
  logic [8:0] winner_i, winner_j;  // the candidate's column and row in the grid
  always_comb begin
    // 9-bit operands: a small constant division where COLS is not a power of two.
    winner_i = winner % 9'(COLS);
    winner_j = winner / 9'(COLS);
    winner_d = 18'(REFINE ? 18'(out_base_d) : 18'(0)) + 18'(winner_i);
    winner_v = 18'(REFINE ? 18'(out_base_v) : 18'(V_MIN)) + 18'(winner_j);
    reach = 18'(R) + 18'(cfg_use_ca);
    x = 18'(out_x);
    y = 18'(out_y);
    out_d = fx_pkg::DISP_BITS'(winner_d);
    out_v = fx_pkg::DISP_BITS'(winner_v);
    out_valid = x >= reach && x < $signed(18'(cfg_width)) - reach && y >= reach &&
                y < $signed(18'(cfg_height)) - reach && x - winner_d >= reach && y + winner_v >= reach &&
                y + winner_v < $signed(18'(cfg_height)) - reach;
  end
endmodule

`default_nettype wire
