// stereo_aggregate: Gaussian-weighted window sum of every disparity plane
// (model: stereo::aggregate, docs/fixed-point.md stage 2).
//
// Separable and exact: a vertical pass over WINDOW rows (line buffer of WINDOW-1 rows) gives
// V = sum_j k[j] C, full precision (VSUM_BITS); a horizontal pass over WINDOW consecutive V
// gives T = sum_i k[i] V (WSUM_BITS); one rounding shift gives A = (T + 2^(AGG_SHIFT-1)) >>
// AGG_SHIFT. Taps whose row or column lies outside the frame read 0 (zero padding).
// Output pixel = input pixel moved back R rows and R columns, R = WINDOW/2.
// Latency: R*W + R + 2 pixel steps. Throughput: one pixel per ce.
//
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): a pixel step takes G = NDISP / LANES
// clocks, and the clock of label group g (`group`, 0 .. G-1, from stereo_top; the step, ce, comes
// at group G-1) computes labels [g*LANES +: LANES] only, on LANES copies of the vertical and
// horizontal multiply-adds; in_data carries that group's costs (stereo_cost computes them in the
// same clock). The line buffer has G words per column, one group each; the
// vertical sums and their history (the horizontal window) of the G groups circulate in a ring
// of G slots that advances one slot per group, so the group being computed is always at its
// head; out_data is this clock's group result, unregistered (the next stage, stereo_ca_plane,
// delays it in its input ring), while out_x/out_y step with ce. LANES = NDISP is the
// all-parallel stage (G = 1: the advance is ce, the ring one register, out_data a register).
//
// Census codes (COST = COST_CENSUS, docs/rtl.md): in_data carries each label's census code
// (stereo_cost CENSUS_CODES: the Hamming distance h, or CENSUS_CODE_OUTSIDE where the right pixel
// lies outside), and the line buffer keeps these CENSUS_CODE_BITS-bit codes instead of 10-bit
// costs. The cost is CENSUS_WEIGHT * h, or COST_OUTSIDE in a column whose right pixel is outside,
// which is the same for every row of the column (it depends on x, the label and the frame's
// configuration only). So, exactly as on the costs, V = CENSUS_WEIGHT * sum_j k[j] h, or
// COST_OUTSIDE * (the sum of the taps whose rows lie inside) when the centre row's code says
// outside. A vertical sum whose centre row lies outside the frame is never used.
//
// RECOMPUTE (census or AD; stereo_top RECOMPUTE_COSTS, docs/rtl.md "Lean memory"): in_data
// carries, for each label, the codes (AD: costs) of all WINDOW rows of the column (stereo_cost
// ROWS = WINDOW recomputes them from its line buffer of census codes or RGB), row in_y - 2R + j at
// [(d*WINDOW + j)*COST_BITS +: LINE_BITS]; this stage then has no line buffer. The
// arithmetic after the taps is the same, so is the output.
`default_nettype none
`include "stereo_assert.svh"

module stereo_aggregate #(
    parameter int WIDTH  = 64,  // longest row
    parameter int NDISP  = 16,  // disparities in parallel
    parameter int WINDOW = 5,   // odd window side (largest runtime window)
    // 1: the taps come from cfg_kernel at run time (generic multipliers). 0: the taps are the
    // model's default kernel for WINDOW (fx_pkg::default_tap), constants that synthesis turns
    // into shifts and adds; cfg_kernel is then ignored.
    parameter bit RUNTIME_KERNEL = 1'b1,
    // RUNTIME_KERNEL = 0: 1 takes the hierarchical levels' kernel for WINDOW (fx_pkg::constant_tap,
    // sigma 3 WINDOW / 11) instead of the default one.
    parameter bit LEVEL_KERNEL = 1'b0,
    parameter int LANES = NDISP,  // labels computed per clock (divides NDISP)
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM (stereo_top)
    parameter int RING_BLOCK_MIN_FILL = 50,  // stereo_group_ring BLOCK_MIN_FILL
    // COST_CENSUS: in_data carries census codes, kept narrow in the line buffer (above); any
    // other cost: in_data carries the costs.
    parameter fx_pkg::cost_e COST = fx_pkg::COST_AD,
    // RUNTIME_KERNEL = 0, which constant tap products are built from shifts and adds
    // (stereo_weighted_sum SHIFT_ADD) rather than left to the tools (DSP blocks where the target
    // has them): SHIFT_ADD_NONE; SHIFT_ADD_NARROW the census codes' vertical products (6-bit
    // operands, not worth a DSP block); SHIFT_ADD_ALL every product.
    parameter fx_pkg::shift_add_e SHIFT_ADD = fx_pkg::SHIFT_ADD_NONE,
    // 1 (COST_CENSUS or COST_AD): every row's code (cost) arrives with the column (above), no line
    // buffer.
    parameter bit RECOMPUTE = 1'b0
) (
`include "stereo_stage_ports.svh"
    // The in_y of the next step (stereo_top: stereo_cost's out_next_y, what its coordinate
    // register takes at this ce): the row flags are computed from it and registered.
    input  wire fx_pkg::coord_t                     in_next_y,
    // labels [group*LANES +: LANES]; census codes are zero-extended to COST_BITS
    /* verilator lint_off UNUSEDSIGNAL */  // the upper bits of census codes
    input  wire logic [LANES*(RECOMPUTE ? WINDOW : 1)*fx_pkg::COST_BITS-1:0] in_data,
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_off UNUSEDSIGNAL */  // reads width and height only
    input  wire fx_pkg::config_t                    cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_off UNUSEDSIGNAL */  // ignored with RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0] cfg_kernel,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                     out_x,
    output      fx_pkg::coord_t                     out_y,
    // G = 1: all labels, registered at ce; G > 1: this clock's group, combinational.
    output      logic [LANES*fx_pkg::AGG_BITS-1:0]  out_data
);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int TAP_BITS = fx_pkg::TAP_BITS;
  localparam int VSUM_BITS = fx_pkg::VSUM_BITS;
  localparam int WSUM_BITS = fx_pkg::WSUM_BITS;
  localparam int AGG_BITS = fx_pkg::AGG_BITS;
  localparam int AGG_SHIFT = fx_pkg::AGG_SHIFT;
  localparam int R = WINDOW / 2;
  localparam int GROUPS = NDISP / LANES;           // clocks per pixel step
  localparam bit CODES = COST == fx_pkg::COST_CENSUS;  // census codes in the line buffer
  localparam int LINE_BITS = CODES ? fx_pkg::CENSUS_CODE_BITS : COST_BITS;  // one label's entry
  // sum_j k[j] h of census codes: the taps sum to 2^KERNEL_BITS.
  localparam int CODE_SUM_BITS = fx_pkg::CENSUS_CODE_BITS + fx_pkg::KERNEL_BITS;
  localparam int COLUMN_BITS = LANES * LINE_BITS;  // one group's line buffer entries
  localparam int V_BITS = LANES * VSUM_BITS;       // one group's vertical sums
  localparam int OUT_BITS = LANES * AGG_BITS;      // one group's results

  localparam int IN_ROWS = RECOMPUTE ? WINDOW : 1;  // rows of codes per label in in_data

  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")
  `STEREO_ASSERT(recompute_cost, !RECOMPUTE || CODES || COST == fx_pkg::COST_AD,
                 "COST must be COST_CENSUS or COST_AD when RECOMPUTE = 1")

  // The group of this clock; G = 1: 0 whatever the port carries (stage testbenches leave it open).
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  assign group_now = (GROUPS > 1) ? group : '0;
  // A clock that processes a group: every group below the last, and the last at the step.
  logic advance;
  assign advance = ce || 32'(group_now) != GROUPS - 1;
  // This clock's group of the input costs (codes): stereo_cost computes it for this clock's group.
  // (RECOMPUTE: the incoming row's, j = 2R.)
  logic [COLUMN_BITS-1:0] group_costs;
  always_comb begin
    for (int d = 0; d < LANES; d++)
      group_costs[d*LINE_BITS +: LINE_BITS] =
          in_data[(d*IN_ROWS + IN_ROWS - 1)*COST_BITS +: LINE_BITS];
  end

  // Tap i of the constant kernel (RUNTIME_KERNEL = 0).
  function automatic int constant_tap(input int i);
    constant_tap = fx_pkg::constant_tap(LEVEL_KERNEL, WINDOW, i);
  endfunction
  logic [WINDOW*TAP_BITS-1:0] kernel;
  generate
    if (RUNTIME_KERNEL) begin : g_runtime_kernel
      assign kernel = cfg_kernel;
    end else begin : g_constant_kernel
      for (genvar i = 0; i < WINDOW; i++) begin : g_tap
        assign kernel[i*TAP_BITS+:TAP_BITS] = TAP_BITS'(constant_tap(i));
        // stereo_weighted_sum pairs mirrored taps: stop elaboration if the kernel is not symmetric.
        `STEREO_ASSERT(default_kernel_symmetric, constant_tap(i) == constant_tap(WINDOW - 1 - i),
                       "the constant kernel must be symmetric (RUNTIME_KERNEL = 0)")
      end
    end
  endgenerate

  // ---- vertical pass -------------------------------------------------------------------
  logic [((R > 0) ? 2 * R : 1)*COLUMN_BITS-1:0] rows_above;  // row in_y-1-k at slot k
  generate
    if (R > 0 && RECOMPUTE) begin : g_rows_with_column
      // Row in_y-1-k of label d is in_data's row 2R-1-k.
      always_comb begin
        for (int k = 0; k < 2 * R; k++)
          for (int d = 0; d < LANES; d++)
            rows_above[k*COLUMN_BITS + d*LINE_BITS +: LINE_BITS] =
                in_data[(d*IN_ROWS + 2*R - 1 - k)*COST_BITS +: LINE_BITS];
      end
    end else if (R > 0) begin : g_line_buffer
      stereo_line_buffer #(
          .WIDTH(WIDTH),
          .DATA_BITS(COLUMN_BITS),
          .ROWS(2 * R),
          .GROUPS(GROUPS)
      ) line_buffer (
          .clk(clk),
          .ce(advance),
          .in_x(in_x),
          .group(group_now),
          .cfg_width(cfg.width),
          .in_data(group_costs),
          .rows_above(rows_above)
      );
    end else begin : g_no_line_buffer
      assign rows_above = '0;
    end
  endgenerate

  // Which of the WINDOW rows of the incoming column lie inside the frame (shared by all d): row
  // in_y - 2R + j at j (stereo_border_flags: one subtraction, not two comparisons per row). They
  // are computed a step ahead, from in_next_y, and registered, so the subtraction and the tests
  // do not run in front of the masks and the vertical sums (the one-label iCE40 core's critical
  // path, docs/synthesis.md "Border flags"). A reset clears them: the first step's in_y is then
  // "no pixel" (stereo_top), whose rows all lie outside. Where in_y does not continue as
  // in_next_y said (a new frame; a stage testbench's first step), the flags are those of another
  // row for one step, which only concerns the output row in_y - R, not a frame row there.
  logic [WINDOW-1:0] next_row_inside, row_inside;
  stereo_border_flags #(
      .OFFSET_LO(-2 * R),
      .OFFSET_HI(0)
  ) row_flags (
      .position(18'(in_next_y)),
      .limit(cfg.height),
      .in_frame(next_row_inside)
  );
  always_ff @(posedge clk) begin
    if (rst) row_inside <= '0;
    else if (ce) row_inside <= next_row_inside;
  end

  // Census codes: COST_OUTSIDE times the taps of the rows inside, the vertical sum of every
  // label whose column is outside (shared by the lanes).
  /* verilator lint_off UNUSEDSIGNAL */  // a constant 0 without census codes
  logic [VSUM_BITS-1:0] outside_sum;
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    if (CODES) begin : g_outside_sum
      always_comb begin
        logic [VSUM_BITS-1:0] inside_taps;
        inside_taps = '0;
        for (int j = 0; j < WINDOW; j++) begin
          if (row_inside[j]) inside_taps = inside_taps + VSUM_BITS'(kernel[j*TAP_BITS +: TAP_BITS]);
        end
        outside_sum = inside_taps * VSUM_BITS'(fx_pkg::COST_OUTSIDE);
      end
    end else begin : g_no_outside_sum
      assign outside_sum = '0;
    end
  endgenerate

  // The column's WINDOW rows: slot k the row k above the incoming one (slot 0: group_costs).
  logic [WINDOW*COLUMN_BITS-1:0] column_rows;
  assign column_rows = (WINDOW * COLUMN_BITS)'({rows_above, group_costs});  // R = 0: no row above
  logic [V_BITS-1:0] vertical_d;
  generate
    for (genvar d = 0; d < LANES; d++) begin : g_vertical
      // Tap j covers row in_y - 2R + j, i.e. the row 2R - j above the incoming one.
      logic [WINDOW*LINE_BITS-1:0] tap_cost;  // cost (code) of tap j, 0 when its row is outside
      for (genvar j = 0; j < WINDOW; j++) begin : g_tap
        assign tap_cost[j*LINE_BITS +: LINE_BITS] =
            row_inside[j] ? column_rows[(2*R-j)*COLUMN_BITS + d*LINE_BITS +: LINE_BITS] : '0;
      end
      // One weighted sum of the taps: of census codes (narrow, CODE_SUM_BITS) or of costs.
      logic [(CODES ? CODE_SUM_BITS : VSUM_BITS)-1:0] column_sum;
      stereo_weighted_sum #(
          .WINDOW(WINDOW), .IN_BITS(LINE_BITS), .SUM_BITS(CODES ? CODE_SUM_BITS : VSUM_BITS),
          .RUNTIME_KERNEL(RUNTIME_KERNEL), .LEVEL_KERNEL(LEVEL_KERNEL),
          .SHIFT_ADD(SHIFT_ADD >= (CODES ? fx_pkg::SHIFT_ADD_NARROW : fx_pkg::SHIFT_ADD_ALL))
      ) vertical_sum (
          .taps(tap_cost), .kernel(kernel), .sum(column_sum));
      if (CODES) begin : g_codes
        // The centre row's code tells whether the column is outside (it lies inside the frame
        // wherever the sum is used); sum_j k[j] h times CENSUS_WEIGHT otherwise, as a shift and
        // a subtraction (31 = 32 - 1) like stereo_cost's.
        localparam int SHIFT = $clog2(fx_pkg::CENSUS_WEIGHT + 1);
        logic [LINE_BITS-1:0] centre_code;
        if (R > 0) begin : g_centre_above  // tap R: the row R above the incoming one
          assign centre_code = rows_above[(R-1)*COLUMN_BITS + d*LINE_BITS +: LINE_BITS];
        end else begin : g_centre_incoming
          assign centre_code = group_costs[d*LINE_BITS +: LINE_BITS];
        end
        assign vertical_d[d*VSUM_BITS +: VSUM_BITS] =
            (centre_code == LINE_BITS'(fx_pkg::CENSUS_CODE_OUTSIDE))
                ? outside_sum
                : (VSUM_BITS'(column_sum) << SHIFT) -
                      VSUM_BITS'(column_sum) * VSUM_BITS'((1 << SHIFT) - fx_pkg::CENSUS_WEIGHT);
      end else begin : g_costs
        assign vertical_d[d*VSUM_BITS +: VSUM_BITS] = VSUM_BITS'(column_sum);
      end
    end
  endgenerate

  // ---- horizontal pass -----------------------------------------------------------------
  // The state of one group: WINDOW slots of V_BITS, slot k the vertical sums of the k-th column
  // before the newest (same row, or masked), k = 0 .. 2R; slot 0 holds the incoming column's (for
  // centre row in_y - R). ring[0] is the state of the group being computed; each advance moves
  // ring[k+1] to ring[k] and puts the head's next state (vertical_d in at slot 0, the oldest
  // column out) into ring[G-1], so after G advances (one step) every group is back at its place,
  // one column further. The ring is a RAM (stereo_group_ring).
  localparam int STATE_BITS = WINDOW * V_BITS;
  logic [STATE_BITS-1:0] head_state;  // ring[0], the head of stereo_group_ring
  logic [STATE_BITS-1:0] next_state;
  generate
    if (R > 0) begin : g_history
      assign next_state = {head_state[0+:2*R*V_BITS], vertical_d};
    end else begin : g_no_history
      assign next_state = vertical_d;
    end
  endgenerate
  stereo_group_ring #(
      .BITS     (STATE_BITS),
      .GROUPS   (GROUPS),
      .BLOCK_RAM(RING_BLOCK_RAM),
      .BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) group_ring (
      .clk(clk),
      .advance(advance),
      .next_state(next_state),
      .head(head_state)
  );

  // Geometry of the horizontal window whose newest column enters slot 0 of the state at this
  // step: its centre is R pixels behind (in_x, in_y - R) in raster order, wrapping to earlier
  // rows (more than one when the frame is narrower than R), and column_inside says which of its
  // WINDOW columns lie inside the frame. It is computed from this step's coordinates and
  // registered beside the state, so that the coordinate arithmetic runs beside the vertical sums
  // instead of in front of the horizontal ones (the critical path before, docs/synthesis.md).
  logic signed [17:0] next_centre_x;  // 18 bits: positions, no-pixel code, wrap
  /* verilator lint_off UNUSEDSIGNAL */  // its low 16 bits are the registered centre_y
  logic signed [17:0] next_centre_y;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [WINDOW-1:0] next_column_inside;
  stereo_window_centre #(.RADIUS(R)) window_centre (
      .in_x(in_x), .in_y(in_y), .cfg_width(cfg.width), .centre_x(next_centre_x),
      .centre_y(next_centre_y));
  stereo_border_flags #(
      .OFFSET_LO(-R),
      .OFFSET_HI(R)
  ) column_flags (
      .position(next_centre_x),
      .limit(cfg.width),
      .in_frame(next_column_inside)
  );

  fx_pkg::coord_t centre_x, centre_y;
  logic [WINDOW-1:0] column_inside;
  always_ff @(posedge clk) begin
    if (rst) begin
      centre_x <= '0;
      centre_y <= fx_pkg::NO_PIXEL;
      column_inside <= '0;
    end else if (ce) begin
      centre_x <= 16'(next_centre_x);
      centre_y <= 16'(next_centre_y);
      column_inside <= next_column_inside;
    end
  end

  logic [OUT_BITS-1:0] aggregate_d;  // this clock's group
  generate
    for (genvar d = 0; d < LANES; d++) begin : g_horizontal
      // Tap i covers column centre_x - R + i, i.e. 2R - i columns behind the newest (slot 2R - i).
      logic [WINDOW*VSUM_BITS-1:0] tap_sum;  // vertical sum of tap i, 0 when outside
      for (genvar i = 0; i < WINDOW; i++) begin : g_tap
        assign tap_sum[i*VSUM_BITS +: VSUM_BITS] =
            column_inside[i] ? head_state[(2*R-i)*V_BITS + d*VSUM_BITS +: VSUM_BITS] : '0;
      end
      logic [WSUM_BITS-1:0] sum;
      stereo_weighted_sum #(
          .WINDOW(WINDOW), .IN_BITS(VSUM_BITS), .SUM_BITS(WSUM_BITS),
          .RUNTIME_KERNEL(RUNTIME_KERNEL), .LEVEL_KERNEL(LEVEL_KERNEL),
          .SHIFT_ADD(SHIFT_ADD >= fx_pkg::SHIFT_ADD_ALL)
      ) horizontal_sum (
          .taps(tap_sum), .kernel(kernel), .sum(sum));
      // Rounded to the nearest (half up) by the kernel's scale.
      assign aggregate_d[d*AGG_BITS +: AGG_BITS] =
          AGG_BITS'((sum + WSUM_BITS'(1 << (AGG_SHIFT - 1))) >> AGG_SHIFT);
    end
  endgenerate

  // G > 1: the group goes on as computed (the consumer's input ring registers it); G = 1: the
  // output register.
  stereo_stage_output #(.BITS(LANES * AGG_BITS), .REGISTERED(GROUPS == 1)) outputs (
      .in_x(centre_x), .in_y(centre_y), .in_data(aggregate_d), .*);
endmodule

`default_nettype wire
