// stereo_top: the enhanced-disparity stereo pipeline (thesis Sec. 3.1) as an AXI4-Stream core.
//
//   s_axis: tdata = {right RGB, left RGB} (R in the high byte of each half), tuser = start of
//           frame, tlast = end of line; one pixel pair per beat, raster order.
//   m_axis: tdata = fx_pkg::out_beat_t {certainty[31:24], 5'b0, reason[18:16], fixed[15:0]}
//           (stage_table.hpp: fixed = signed disparity x 16, 0 where invalid; reason 0 valid,
//           1 border, 2 uniqueness, 3 left-right), tuser on the first pixel, tlast at each row
//           end; exactly one output beat per input pixel, bit-exact with stereo::match_validated.
//           With cfg_min_disp 0 and every stage-6 switch off, fixed = 16 * stereo::match's
//           disparity and reason = 0 exactly where it is valid.
//
// All stages advance together on one clock enable (a "pixel step", docs/rtl.md): a step happens
// when there is something to push (an input pixel, or a flush step after the frame's last
// pixel) and the output skid register is empty. The skid register takes the output register's
// beat when a step would overwrite it while m_axis_tready is low; m_axis shows the skid register
// while it is full. So the clock enable and s_axis_tready depend on a register only, never
// combinationally on m_axis_tready (which would fan out into every stage's enable), and a
// stalled m_axis_tready still stalls everything without losing or duplicating a pixel. Without
// stalls the skid register stays empty: latency and throughput are unchanged. The input side
// has a register slice (below): a step waits on its main register, not on s_axis_tvalid, and
// s_axis_tready is a register. After the last input pixel of a frame the core steps on its own
// (taking no input; the slice holds up to two beats of the next frame) until the frame's last
// output has left the WTA, so a frame never waits for the next one. Cycles per frame without
// stalls:
//   G * S - 2 * (G - 1) + 1, S = W*H + (R + 2)*W + R + 11 + NDISP + K pixel steps
//   (+ 2*W + 4 with COST_CENSUS),
//   R = WINDOW/2, K = max(0, -cfg_min_disp), G = NDISP / LANES clocks per step
// (stage_table.hpp frame_cycles, docs/rtl.md; G = 1: S + 1).
// LANES < NDISP: a step every G clocks (the slice fills and s_axis_tready falls between steps);
// every stage computes LANES labels per clock (group counter below), the per-group state
// of the aggregation and the CA windows in stereo_group_ring.
// Input before the first start of frame is dropped. Status bits (sticky until reset; the
// indices are fx_pkg::STATUS_*):
//   [0] tlast not at the row end, [1] tuser inside a frame, [2] configuration out of range
//   (clamped; |cfg_min_disp| > MAX_MIN_DISP included). Reset is synchronous, active high, and clears control state only.
`default_nettype none
`include "stereo_assert.svh"

module stereo_top #(
    parameter int WIDTH  = 64,  // largest frame width
    parameter int HEIGHT = 48,  // largest frame height
    parameter int NDISP  = 16,  // disparities evaluated in parallel (largest cfg_ndisp)
    parameter int WINDOW = 5,   // largest aggregation window (odd)
    // 1: cfg_kernel and cfg_radius set the window at run time. 0: the model's default kernel
    // for WINDOW as constants (cheaper multipliers); cfg_kernel is ignored and cfg_radius must
    // be WINDOW/2 (a smaller radius with the full-size constant kernel would not be the model).
    parameter bit RUNTIME_KERNEL = 1'b1,
    // Largest |cfg_min_disp|: sizes the cost stage's delay lines.
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,
    // Matching cost: fx_pkg::COST_AD (0) over RGB, COST_LCDM (1, thesis Sec. 3.5; colour input;
    // same latency) or COST_CENSUS (2, 5x5 census of the luma: stereo_census in front of the
    // cost stage, 2 * W + 4 more pixel steps of latency, 4 rows of lumas more memory).
    parameter fx_pkg::cost_e COST = fx_pkg::COST_AD,
    // Labels computed per clock (divides NDISP). A pixel step takes G = NDISP / LANES clocks;
    // the converted stages compute LANES labels per clock on shared arithmetic (docs/rtl.md,
    // "Time-multiplexed lanes"). LANES = NDISP: one pixel per clock, every label in parallel.
    parameter int LANES = NDISP,
    // 1: the per-group state rings of the converted stages (stereo_group_ring) in block RAM at
    // any group count; for the iCE40, whose flip-flops are logic cells (it has no LUT RAM).
    // 0: block or LUT RAM from 8 groups on, registers below, as synthesis sees fit.
    parameter bit RING_BLOCK_RAM = 1'b0,
    parameter int RING_BLOCK_MIN_FILL = 50,  // stereo_group_ring BLOCK_MIN_FILL
    // RUNTIME_KERNEL = 0: which constant tap products of the aggregation are built from shifts
    // and adds (canonical signed digits) instead of being left to the tools (DSP blocks where the
    // target has them): SHIFT_ADD_NONE (0), SHIFT_ADD_NARROW (1, the census codes' narrow vertical
    // products) or SHIFT_ADD_ALL (2).
    parameter fx_pkg::shift_add_e SHIFT_ADD = fx_pkg::SHIFT_ADD_NONE,
    // COST_CENSUS or COST_AD. 1: the lean memory architecture (docs/rtl.md "Lean memory"): the
    // cost stage keeps WINDOW - 1 rows of both images' census codes (RGB) and recomputes every
    // label's codes (costs) for the aggregation's vertical window, which then has no per-label
    // line buffer (memory grows with WIDTH * WINDOW, not with NDISP). 0: the aggregation keeps
    // each label's code (5 bits; AD: cost, 10 bits) for WINDOW - 1 rows, cheaper below about 10
    // labels (5 with AD).
    parameter bit RECOMPUTE_COSTS = 1'b0,
    // 1: adaptive support weights (thesis Sec. 3.4; docs/asw.md) instead of the Gaussian
    // aggregation and the CA rules: the separable two-pass ASW of diameter WINDOW
    // (stereo_asw_column, stereo_asw_aggregate; COST_CENSUS or COST_AD, RECOMPUTE_COSTS = 0),
    // its outside matches no candidates, the border rule at reach 0 (cfg_radius and cfg_use_ca
    // are not read). Bit-exact with stereo::asw::match (Params::separable, the default responses).
    parameter bit ASW = 1'b0
) (
    input  wire logic                               clk,
    input  wire logic                               rst,
    // The window, sampled with the rest of the configuration (stereo_core_ports.svh).
    input  wire fx_pkg::cfg_radius_t                cfg_radius,
    /* verilator lint_off UNUSEDSIGNAL */  // ignored with RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0] cfg_kernel,
    /* verilator lint_on UNUSEDSIGNAL */
`include "stereo_core_ports.svh"
);
  localparam int R = WINDOW / 2;
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int AGG_BITS = fx_pkg::AGG_BITS;
  localparam int DISP_BITS = fx_pkg::DISP_BITS;
  localparam int FIXED_BITS = fx_pkg::FIXED_BITS;
  localparam int GROUPS = NDISP / LANES;  // clocks per pixel step
  localparam int GROUP_BITS = (GROUPS > 1) ? $clog2(GROUPS) : 1;

  `STEREO_ASSERT(window_odd, WINDOW % 2 == 1 && WINDOW <= fx_pkg::MAX_WINDOW,
                 "WINDOW must be odd, at most MAX_WINDOW")
  `STEREO_ASSERT(ndisp_range, NDISP >= 1 && NDISP <= 256, "NDISP must be 1 .. 256")
  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && LANES <= NDISP && NDISP % LANES == 0,
                 "LANES must be 1 .. NDISP and divide NDISP")
  `STEREO_ASSERT(max_min_disp_range,
                 MAX_MIN_DISP >= 0 && MAX_MIN_DISP <= fx_pkg::MAX_MIN_DISPARITY,
                 "MAX_MIN_DISP must be 0 .. MAX_MIN_DISPARITY")
  `STEREO_ASSERT(frame_size_range,
                 WIDTH >= 1 && WIDTH <= fx_pkg::MAX_FRAME_SIDE && HEIGHT >= 1 &&
                     HEIGHT <= fx_pkg::MAX_FRAME_SIDE,
                 "WIDTH and HEIGHT must be 1 .. MAX_FRAME_SIDE")
  `STEREO_ASSERT(recompute_costs_cost,
                 !RECOMPUTE_COSTS || COST == fx_pkg::COST_CENSUS || COST == fx_pkg::COST_AD,
                 "COST must be COST_CENSUS or COST_AD when RECOMPUTE_COSTS = 1")
  `STEREO_ASSERT(asw_configuration,
                 !ASW || ((COST == fx_pkg::COST_CENSUS || COST == fx_pkg::COST_AD) &&
                          !RECOMPUTE_COSTS && WINDOW >= fx_pkg::ASW_MIN_DIAMETER &&
                          WINDOW <= fx_pkg::ASW_MAX_DIAMETER),
                 "ASW = 1 needs COST_CENSUS or COST_AD, RECOMPUTE_COSTS = 0 and WINDOW (the diameter) in ASW_MIN_DIAMETER .. ASW_MAX_DIAMETER")
  // Rows of codes per label between the cost stage and the aggregation.
  localparam int COST_ROWS = RECOMPUTE_COSTS ? WINDOW : 1;

  // ---- configuration: sanitised ports, latched at the start of a frame ----------------------
  typedef enum logic [1:0] {
    IDLE,  // waiting for a start of frame
    RUN,   // taking the frame's pixels
    FLUSH  // stepping until the frame's last output has left the WTA
  } state_t;
  state_t state;

  // The run-time configuration as the stages see it: the ports, each clamped to what the
  // parameters support (port_cfg), latched when the frame starts (frame_cfg).
  // The kernel beside it (its width depends on WINDOW): cfg_kernel and frame_kernel.
  fx_pkg::config_t port_cfg, frame_cfg;
  /* verilator lint_off UNUSEDSIGNAL */  // ASW = 1: no kernel
  logic [WINDOW*fx_pkg::TAP_BITS-1:0] frame_kernel, use_kernel;
  /* verilator lint_on UNUSEDSIGNAL */
  logic port_cfg_error;
  always_comb begin
    port_cfg.width = cfg_width;
    port_cfg.height = cfg_height;
    port_cfg.ndisp = cfg_ndisp;
    port_cfg.radius = cfg_radius;
    port_cfg.use_ca = cfg_use_ca;
    port_cfg.min_disp = cfg_min_disp;
    port_cfg.uniqueness_en = cfg_uniqueness_en;
    port_cfg.uniqueness = cfg_uniqueness;
    port_cfg.lr_en = cfg_lr_en;
    port_cfg.lr_tolerance = cfg_lr_tolerance;
    port_cfg.subpixel_en = cfg_subpixel_en;
    port_cfg_error = 1'b0;
    if (cfg_width == 0 || $signed(32'(cfg_width)) > WIDTH) begin
      port_cfg.width = fx_pkg::CFG_SIZE_BITS'(WIDTH);
      port_cfg_error = 1'b1;
    end
    if (cfg_height == 0 || $signed(32'(cfg_height)) > HEIGHT) begin
      port_cfg.height = fx_pkg::CFG_SIZE_BITS'(HEIGHT);
      port_cfg_error = 1'b1;
    end
    if (cfg_ndisp == 0 || $signed(32'(cfg_ndisp)) > NDISP) begin
      port_cfg.ndisp = fx_pkg::CFG_NDISP_BITS'(NDISP);
      port_cfg_error = 1'b1;
    end
    if ($signed(32'(cfg_radius)) > R) begin
      port_cfg.radius = fx_pkg::CFG_RADIUS_BITS'(R);
      port_cfg_error = 1'b1;
    end
    if (32'(cfg_min_disp) > MAX_MIN_DISP) begin
      port_cfg.min_disp = fx_pkg::CFG_MIN_DISP_BITS'(MAX_MIN_DISP);
      port_cfg_error = 1'b1;
    end
    if (32'(cfg_min_disp) < -MAX_MIN_DISP) begin
      port_cfg.min_disp = fx_pkg::CFG_MIN_DISP_BITS'(-MAX_MIN_DISP);
      port_cfg_error = 1'b1;
    end
  end

  // The clamped ports and the kernel registered every clock (idle_cfg): nothing of the datapath
  // depends on a port combinationally, so the configuration registers in front of the core
  // (stereo_axil_top) have no timing path into the stages, and a simulator evaluates the
  // datapath once per clock instead of on every change of an input. The ports must therefore
  // hold their values from the clock before a frame's first beat is stepped (one clock after the
  // input slice takes it, so ports set with or before that beat are in time).
  fx_pkg::config_t idle_cfg;
  logic idle_cfg_error;
  logic [WINDOW*fx_pkg::TAP_BITS-1:0] idle_kernel;
  always_ff @(posedge clk) begin
    idle_cfg <= port_cfg;
    idle_cfg_error <= port_cfg_error;
  end

  // What the stages see: the registered ports while idle (the start-of-frame step uses them), the
  // latched values during the frame and its flush. A setting whose clamped range is one value is that
  // constant for the stages (the one-label core: cfg_ndisp is 1; MAX_MIN_DISP = 0: cfg_min_disp
  // is 0), so no multiplexer from the frame state runs in front of their logic (the one-label
  // iCE40 core's critical path). The clamps and the status bit see the registered ports. Every
  // stage takes use_cfg whole on its `cfg` port and reads the fields it needs.
  fx_pkg::config_t use_cfg;
  always_comb begin
    use_cfg = (state == IDLE) ? idle_cfg : frame_cfg;
    use_kernel = (state == IDLE) ? idle_kernel : frame_kernel;
    if (NDISP == 1) use_cfg.ndisp = fx_pkg::CFG_NDISP_BITS'(1);
    if (MAX_MIN_DISP == 0) use_cfg.min_disp = '0;
  end

  // ---- stepping ----------------------------------------------------------------------------
  logic output_pending;  // m_axis holds a beat not yet taken
  logic can_step, step, start_of_frame;
  fx_pkg::coord_t x_in, y_in;  // raster position of the next step
  fx_pkg::coord_t final_x, final_y;  // the pixel entering the output register at a step
  logic last_output_entering;  // this step moves pixel (W-1, H-1) into the output register

  logic skid_full;  // the skid register holds the oldest beat not yet taken

  // ---- label groups: G = NDISP / LANES clocks per pixel step ----------------------------------
  // After a step, `group` counts 0, 1, ..., G-1, one per clock, and stays at G-1 until the next
  // step: at clock `group` the converted stages compute labels [group*LANES +: LANES] of the
  // pixel their input register holds (stable from one step to the next), and the step itself
  // can only happen at group G-1 (round_done), where they compute the last group and update
  // their output registers. Reset leaves group at G-1, so a step may follow at once. G = 1:
  // group is always 0 = G-1, and a step may happen at every clock.
  logic [GROUP_BITS-1:0] group;
  logic round_done;
  assign round_done = group == GROUP_BITS'(GROUPS - 1);
  generate
    if (GROUPS > 1) begin : g_group_counter
      always_ff @(posedge clk) begin
        if (rst) group <= GROUP_BITS'(GROUPS - 1);
        else if (step) group <= '0;
        else if (!round_done) group <= group + 1'b1;
      end
    end else begin : g_one_group
      assign group = '0;
    end
  endgenerate

  // ---- input register slice ------------------------------------------------------------------
  // The step waits on a register (the main beat), not on s_axis_tvalid, and s_axis_tready is a
  // register (the spare is empty): the input port reaches no stage's clock enable. Two beats of
  // storage: the core takes the main beat, the spare catches the beat that arrives in a clock
  // where the main one could not be taken. Without stalls the spare stays empty and a beat
  // waits one clock in the main register (frame_cycles counts it); during a flush the slice
  // takes the next frame's first beats, so frames back to back are not slowed.
  typedef struct packed {
    logic [fx_pkg::IN_BEAT_BITS-1:0] data;
    logic last;
    logic user;
  } in_beat_t;
  in_beat_t in_main, in_spare, in_port;
  logic in_main_full, in_spare_full;
  logic in_take;  // the core takes (steps on, or drops) the main beat at this clock
  assign in_port = {s_axis_tdata, s_axis_tlast, s_axis_tuser};
  assign s_axis_tready = !in_spare_full;
  always_ff @(posedge clk) begin
    if (rst) begin
      in_main_full <= 1'b0;
      in_spare_full <= 1'b0;
    end else if (!in_main_full || in_take) begin
      if (in_spare_full) begin
        in_main <= in_spare;
        in_main_full <= 1'b1;
        in_spare_full <= 1'b0;
      end else begin
        in_main <= in_port;
        in_main_full <= s_axis_tvalid;
      end
    end else if (s_axis_tvalid && !in_spare_full) begin
      in_spare <= in_port;
      in_spare_full <= 1'b1;
    end
  end

  always_comb begin
    can_step = !skid_full && round_done;
    start_of_frame = state == IDLE && in_main_full && in_main.user;
    unique case (state)
      IDLE: begin
        in_take = can_step && in_main_full;  // beats before a start of frame are dropped (at a step's pace)
        step = can_step && start_of_frame;
      end
      RUN: begin
        in_take = can_step && in_main_full;
        step = in_take;
      end
      default: begin  // FLUSH
        in_take = 1'b0;
        step = can_step;
      end
    endcase
    last_output_entering = step &&
                           final_x == fx_pkg::COORD_BITS'($signed(32'(use_cfg.width)) - 1) &&
                           final_y == fx_pkg::COORD_BITS'($signed(32'(use_cfg.height)) - 1);
  end

  logic last_input;
  assign last_input = x_in == fx_pkg::COORD_BITS'($signed(32'(use_cfg.width)) - 1) &&
                      y_in == fx_pkg::COORD_BITS'($signed(32'(use_cfg.height)) - 1);

  always_ff @(posedge clk) begin
    if (rst) begin
      state <= IDLE;
      x_in <= '0;
      y_in <= '0;
      status <= '0;
    end else begin
      if (step) begin
        if (state == IDLE) begin
          frame_cfg <= idle_cfg;
          if (idle_cfg_error) status[fx_pkg::STATUS_CONFIG_CLAMPED] <= 1'b1;
        end
        if (state != FLUSH) begin
          if (in_main.last != (x_in == fx_pkg::COORD_BITS'($signed(32'(use_cfg.width)) - 1)))
            status[fx_pkg::STATUS_EOL_MISPLACED] <= 1'b1;
          if (state == RUN && in_main.user) status[fx_pkg::STATUS_SOF_MISPLACED] <= 1'b1;
        end
        if (x_in == fx_pkg::COORD_BITS'($signed(32'(use_cfg.width)) - 1)) begin
          x_in <= '0;
          y_in <= y_in + 16'sd1;
        end else begin
          x_in <= x_in + 16'sd1;
        end
        unique case (state)
          IDLE: state <= last_input ? FLUSH : RUN;
          RUN: if (last_input) state <= FLUSH;
          default: ;
        endcase
      end
      if (state == FLUSH && last_output_entering) begin
        state <= IDLE;
        x_in <= '0;
        y_in <= '0;
      end
    end
  end

  // The kernel's registers exist with the runtime kernel only: with RUNTIME_KERNEL = 0 the stages
  // use their constant kernel and never read use_kernel.
  generate
    if (RUNTIME_KERNEL) begin : g_kernel_registers
      always_ff @(posedge clk) begin
        idle_kernel <= cfg_kernel;
        if (!rst && step && state == IDLE) frame_kernel <= idle_kernel;
      end
    end else begin : g_constant_kernel
      assign idle_kernel = '0;
      assign frame_kernel = '0;
    end
  endgenerate

  // ---- the pipeline ------------------------------------------------------------------------
  // When a frame's last output enters the output register, everything still in the stages is flush filler
  // whose coordinates (y >= H) would read as real pixels if a taller frame came next: the stage
  // coordinate registers are cleared to "no pixel" then, as by a reset. The output register
  // (stereo_lr_check's) keeps its coordinates: it holds the frame's last output beat.
  logic clear_coordinates;
  assign clear_coordinates = rst || (state == FLUSH && last_output_entering);

  logic [fx_pkg::RGB_BITS-1:0] left_pixel, right_pixel;
  assign left_pixel = (state == FLUSH) ? '0 : in_main.data[fx_pkg::IN_LEFT_LSB +: fx_pkg::RGB_BITS];
  assign right_pixel = (state == FLUSH) ? '0 : in_main.data[fx_pkg::IN_RIGHT_LSB +: fx_pkg::RGB_BITS];

  // The cost stage's input: the pixels, or (COST_CENSUS) their census codes.
  fx_pkg::coord_t match_x, match_y;
  logic [fx_pkg::RGB_BITS-1:0] match_left, match_right;
  // ASW: the RGB pixels of (match_x, match_y) beside the census codes (COST_AD: the same).
  /* verilator lint_off UNUSEDSIGNAL */  // ASW = 0
  logic [fx_pkg::RGB_BITS-1:0] match_left_rgb, match_right_rgb;
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    if (COST == fx_pkg::COST_CENSUS) begin : g_census
      stereo_census #(
          .WIDTH(WIDTH),
          .RGB_THROUGH(ASW)
      ) census (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .in_x(x_in),
          .in_y(y_in),
          .in_left(left_pixel),
          .in_right(right_pixel),
          .cfg(use_cfg),
          .out_x(match_x),
          .out_y(match_y),
          .out_left(match_left),
          .out_right(match_right),
          .out_left_rgb(match_left_rgb),
          .out_right_rgb(match_right_rgb)
      );
    end else begin : g_pixels
      assign match_x = x_in;
      assign match_y = y_in;
      assign match_left = left_pixel;
      assign match_right = right_pixel;
      assign match_left_rgb = left_pixel;
      assign match_right_rgb = right_pixel;
    end
  endgenerate

  fx_pkg::coord_t wta_in_x, wta_in_y;  // the WTA's input pixel
  logic [LANES*AGG_BITS-1:0] rule2_data;  // ... and its costs (this clock's group when G > 1)
  generate
    if (ASW) begin : g_asw
      // ---- adaptive support weights: column words, their delay lines, the three passes ----------
      localparam int WORD_BITS = 48 * WINDOW;
      fx_pkg::coord_t column_x, column_y, cost_x, cost_y;
      logic [WORD_BITS-1:0] column_left, column_right, cost_left;
      logic [LANES*WORD_BITS-1:0] cost_right;
      /* verilator lint_off UNUSEDSIGNAL */  // the cost stage's outputs not used with RAW_BITS
      fx_pkg::coord_t cost_next_y;
      logic [LANES*COST_BITS-1:0] cost_data;
      /* verilator lint_on UNUSEDSIGNAL */
      stereo_asw_column #(
          .WIDTH(WIDTH),
          .DIAMETER(WINDOW),
          .CODES(COST == fx_pkg::COST_CENSUS)
      ) asw_column (
          .clk(clk),
          .ce(step),
          .in_x(match_x),
          .in_y(match_y),
          .in_left_code(match_left),
          .in_right_code(match_right),
          .in_left_rgb(match_left_rgb),
          .in_right_rgb(match_right_rgb),
          .cfg_width(use_cfg.width),
          .out_x(column_x),
          .out_y(column_y),
          .out_left(column_left),
          .out_right(column_right)
      );
      stereo_cost #(
          .NDISP(NDISP),
          .MAX_MIN_DISP(MAX_MIN_DISP),
          .COST(COST),
          .LANES(LANES),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL),
          .RAW_BITS(WORD_BITS)
      ) cost (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(column_x),
          .in_y(column_y),
          .in_left(24'(0)),
          .in_right(24'(0)),
          .cfg(use_cfg),
          .out_x(cost_x),
          .out_y(cost_y),
          .out_next_y(cost_next_y),
          .out_data(cost_data),
          .in_left_raw(column_left),
          .in_right_raw(column_right),
          .out_left_raw(cost_left),
          .out_right_raw(cost_right)
      );
      stereo_asw_aggregate #(
          .NDISP(NDISP),
          .LANES(LANES),
          .DIAMETER(WINDOW),
          .CODES(COST == fx_pkg::COST_CENSUS),
          .TRUNCATION((COST == fx_pkg::COST_CENSUS) ? fx_pkg::ASW_TRUNCATION_CENSUS
                                                   : fx_pkg::ASW_TRUNCATION_AD),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL),
          .SHIFT_ADD(SHIFT_ADD)
      ) asw (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(cost_x),
          .in_y(cost_y),
          .in_left(cost_left),
          .in_right(cost_right),
          .cfg(use_cfg),
          .out_x(wta_in_x),
          .out_y(wta_in_y),
          .out_data(rule2_data)
      );
    end else begin : g_gaussian_ca
      fx_pkg::coord_t cost_x, cost_y, agg_x, agg_y, rule1_x, rule1_y;
      fx_pkg::coord_t cost_next_y;  // the row cost_y takes at this step
      // LANES < NDISP: this clock's group of labels; COST_ROWS fields per label.
      logic [LANES*COST_ROWS*COST_BITS-1:0] cost_data;
      // G = 1: all labels of a pixel, registered; G > 1: the group each stage computes in this clock.
      logic [LANES*AGG_BITS-1:0] agg_data, rule1_data;
      /* verilator lint_off UNUSEDSIGNAL */  // RAW_BITS = 0: zeros
      logic unused_left_raw;
      logic [LANES-1:0] unused_right_raw;
      /* verilator lint_on UNUSEDSIGNAL */

      stereo_cost #(
          .NDISP(NDISP),
          .MAX_MIN_DISP(MAX_MIN_DISP),
          .COST(COST),
          .LANES(LANES),
          .CENSUS_CODES(COST == fx_pkg::COST_CENSUS),  // the aggregation keeps census codes
          .ROWS(COST_ROWS),
          .WIDTH(WIDTH),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) cost (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(match_x),
          .in_y(match_y),
          .in_left(match_left),
          .in_right(match_right),
          .cfg(use_cfg),
          .out_x(cost_x),
          .out_y(cost_y),
          .out_next_y(cost_next_y),
          .out_data(cost_data),
          .in_left_raw(1'b0),
          .in_right_raw(1'b0),
          .out_left_raw(unused_left_raw),
          .out_right_raw(unused_right_raw)
      );

      stereo_aggregate #(
          .WIDTH(WIDTH),
          .NDISP(NDISP),
          .WINDOW(WINDOW),
          .RUNTIME_KERNEL(RUNTIME_KERNEL),
          .LANES(LANES),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL),
          .COST(COST),
          .SHIFT_ADD(SHIFT_ADD),
          .RECOMPUTE(RECOMPUTE_COSTS)
      ) aggregate (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(cost_x),
          .in_y(cost_y),
          .in_next_y(cost_next_y),
          .in_data(cost_data),
          .cfg(use_cfg),
          .cfg_kernel(use_kernel),
          .out_x(agg_x),
          .out_y(agg_y),
          .out_data(agg_data)
      );

      // The two CA rules: the skeleton stereo_ca_plane with RULE CA_RULE1 and CA_RULE2 (rule 2 ignores
      // cfg.ndisp).
      stereo_ca_plane #(
          .WIDTH(WIDTH),
          .NDISP(NDISP),
          .RULE(fx_pkg::CA_RULE1),
          .LANES(LANES),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) ca_rule1 (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(agg_x),
          .in_y(agg_y),
          .in_data(agg_data),
          .cfg(use_cfg),
          .out_x(rule1_x),
          .out_y(rule1_y),
          .out_data(rule1_data)
      );

      stereo_ca_plane #(
          .WIDTH(WIDTH),
          .NDISP(NDISP),
          .RULE(fx_pkg::CA_RULE2),
          .LANES(LANES),
          .RING_BLOCK_RAM(RING_BLOCK_RAM),
          .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
      ) ca_rule2 (
          .clk(clk),
          .rst(clear_coordinates),
          .ce(step),
          .group(group),
          .in_x(rule1_x),
          .in_y(rule1_y),
          .in_data(rule1_data),
          .cfg(use_cfg),
          .out_x(wta_in_x),
          .out_y(wta_in_y),
          .out_data(rule2_data)
      );
    end
  endgenerate

  // ---- winner, stage 6 and the output register ------------------------------------------------
  // ASW: the border rule at reach 0 (the support region is clipped at the frame's edges, and the
  // outside matches are no candidates: a pixel is invalid only where its winner's match lies
  // outside, i.e. none lies inside).
  fx_pkg::config_t wta_cfg;
  always_comb begin
    wta_cfg = use_cfg;
    if (ASW) begin
      wta_cfg.radius = '0;
      wta_cfg.use_ca = 1'b0;
    end
  end
  fx_pkg::coord_t wta_x, wta_y, validate_x, validate_y, out_x, out_y;
  logic [DISP_BITS-1:0] wta_label, validate_label;
  logic wta_border, validate_border;
  logic [AGG_BITS-1:0] wta_cost, wta_before, wta_after, wta_second, validate_cost,
      validate_second;
  logic [NDISP*AGG_BITS-1:0] wta_data;
  logic [LANES*AGG_BITS-1:0] wta_group;
  logic signed [FIXED_BITS-1:0] validate_fixed;
  stereo_wta #(
      .NDISP(NDISP),
      .LANES(LANES),
      .RING_BLOCK_RAM(RING_BLOCK_RAM),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) wta (
      .clk(clk),
      .rst(clear_coordinates),
      .ce(step),
      .group(group),
      .in_x(wta_in_x),
      .in_y(wta_in_y),
      .in_data(rule2_data),
      .cfg(wta_cfg),
      .out_x(wta_x),
      .out_y(wta_y),
      .out_label(wta_label),
      .out_border(wta_border),
      .out_cost(wta_cost),
      .out_before(wta_before),
      .out_after(wta_after),
      .out_data(wta_data),
      .out_second(wta_second),
      .out_group(wta_group)
  );

  stereo_validate #(
      .NDISP(NDISP),
      .LANES(LANES)
  ) validate (
      .clk(clk),
      .rst(clear_coordinates),
      .ce(step),
      .in_x(wta_x),
      .in_y(wta_y),
      .in_label(wta_label),
      .in_border(wta_border),
      .in_cost(wta_cost),
      .in_before(wta_before),
      .in_after(wta_after),
      .in_data(wta_data),
      .in_second(wta_second),
      .cfg(use_cfg),
      .out_x(validate_x),
      .out_y(validate_y),
      .out_label(validate_label),
      .out_border(validate_border),
      .out_cost(validate_cost),
      .out_second(validate_second),
      .out_fixed(validate_fixed)
  );

  fx_pkg::out_beat_t out_beat;
  stereo_lr_check #(
      .NDISP(NDISP),
      .LANES(LANES),
      .RING_BLOCK_RAM(RING_BLOCK_RAM),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) lr_check (
      .clk(clk),
      .rst(clear_coordinates),
      .rst_output(rst),
      .ce(step),
      .group(group),
      // LANES < NDISP: the WTA's input pixel and its group of this clock (one step ahead).
      .acc_x(GROUPS > 1 ? wta_in_x : wta_x),
      .acc_y(GROUPS > 1 ? wta_in_y : wta_y),
      .acc_data(wta_data),
      .acc_group(wta_group),
      .in_x(validate_x),
      .in_y(validate_y),
      .in_label(validate_label),
      .in_border(validate_border),
      .in_cost(validate_cost),
      .in_second(validate_second),
      .in_fixed(validate_fixed),
      .cfg(use_cfg),
      .next_x(final_x),
      .next_y(final_y),
      .out_x(out_x),
      .out_y(out_y),
      .out_beat(out_beat)
  );

  // ---- output: stereo_lr_check's register is the output register ------------------------------
  logic entering_in_frame;
  assign entering_in_frame = final_x >= 0 && 32'(final_x) < $signed(32'(use_cfg.width)) &&
                             final_y >= 0 && 32'(final_y) < $signed(32'(use_cfg.height));
  always_ff @(posedge clk) begin
    if (rst) begin
      output_pending <= 1'b0;
    end else if (step) begin
      output_pending <= entering_in_frame;
    end else if (m_axis_tready && !skid_full) begin
      output_pending <= 1'b0;
    end
  end

  // The output register's beat with its framing.
  logic out_user, out_last;
  assign out_user = out_x == 0 && out_y == 0;
  assign out_last = 32'(out_x) == $signed(32'(frame_cfg.width)) - 1;

  // The skid register: filled when a step moves a new beat into the output register while its
  // beat is on m_axis and not taken (a step needs it empty, so it never overflows); emptied when
  // m_axis takes its beat.
  fx_pkg::out_beat_t skid_beat;
  logic skid_user, skid_last;
  always_ff @(posedge clk) begin
    if (rst) begin
      skid_full <= 1'b0;
    end else if (skid_full) begin
      if (m_axis_tready) skid_full <= 1'b0;
    end else if (step && output_pending && !m_axis_tready) begin
      skid_full <= 1'b1;
    end
  end
  always_ff @(posedge clk) begin
    if (!skid_full) begin
      skid_beat <= out_beat;
      skid_user <= out_user;
      skid_last <= out_last;
    end
  end

  assign m_axis_tvalid = skid_full || output_pending;
  assign m_axis_tdata = skid_full ? skid_beat : out_beat;
  assign m_axis_tuser = skid_full ? skid_user : out_user;
  assign m_axis_tlast = skid_full ? skid_last : out_last;
endmodule

`default_nettype wire
