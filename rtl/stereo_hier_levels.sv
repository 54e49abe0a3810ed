// stereo_hier_levels: the three levels of the hierarchical search chained (model:
// stereo::hierarchical::match_levels with the census cost; docs/hierarchical.md "The streaming
// core"). The full-size pixel pairs come in once; out come the full level's winners, which
// stereo_plane_stats turns into the next frame's plane.
//
//   in -> stereo_downscale x4 -> FIFO -> quarter level (the whole range) --winners--> ring
//      -> stereo_downscale x2 -> FIFO -> half level (3x3 around the ring's prediction) -> ring
//      -> FIFO -> full level (3x3 around the half ring's prediction) -> out
//
// The FIFOs hold lumas (census needs nothing else; a level sees (g, g, g), whose luma is g), so
// the rows a level waits for its prediction cost 16 bits a pixel for the pair. Each level steps
// on its own (stereo_level_stepper) when its FIFO has a pixel and its prediction is there
// (stereo_prediction_ring: the parent row written) and, for the quarter and the half level,
// when the ring has room for the winner's row (its oldest row no longer needed by the finer
// level's winners). A FIFO must hold the rows its level waits: FIFO_ROWS_* (docs). in_ready falls
// when a FIFO is full, and between a frame's last pixel and the moment all three levels have
// put out their last winner (frames do not overlap).
`default_nettype none
`include "stereo_assert.svh"

module stereo_hier_levels #(
    parameter int WIDTH    = 128,  // longest full-size row
    parameter int NDISP    = 16,   // D: horizontal labels at full size (multiple of 4)
    parameter int VRANGE   = 16,   // V: vertical labels at full size (multiple of 4)
    parameter int WINDOW_Q = 9,    // the levels' windows
    parameter int WINDOW_H = 15,
    parameter int WINDOW_F = 15,
    parameter int RING     = 8,    // coarse rows each prediction ring holds
    parameter int FIFO_ROWS_Q = 4,   // level rows each input FIFO holds
    parameter int FIFO_ROWS_H = 24,
    parameter int FIFO_ROWS_F = 80,
    // Labels per clock of each level (divide its labels: (NDISP/4) x (VRANGE/4), 3x3, 3x3); a
    // level's pixel then takes its labels / LANES clocks (docs/hierarchical.md "Resources").
    // By default one candidate row a clock.
    parameter int LANES_Q = NDISP / 4,
    parameter int LANES_H = 3,
    parameter int LANES_F = 3,
    // 1: the levels' kernels from cfg_kernel_*; 0: their constant kernels (fx_pkg::constant_tap).
    parameter bit RUNTIME_KERNEL = 1'b0
) (
    input  wire logic                                  clk,
    input  wire logic                                  rst,
    input  wire logic                                  in_valid,
    output      logic                                  in_ready,
    input  wire fx_pkg::coord_t                        in_x,      // raster order, from (0, 0)
    input  wire fx_pkg::coord_t                        in_y,
    input  wire logic [fx_pkg::RGB_BITS-1:0]           in_left,
    input  wire logic [fx_pkg::RGB_BITS-1:0]           in_right,
    // The frame's setting: registered every clock, held from a frame's first pixel until its last
    // winner (ports set at least a clock before the first pixel).
    input  wire fx_pkg::cfg_size_t                     cfg_width,  // the full-size frame
    input  wire fx_pkg::cfg_size_t                     cfg_height,
    input  wire logic                                  cfg_use_ca,
    /* verilator lint_off UNUSEDSIGNAL */  // RUNTIME_KERNEL = 0
    input  wire logic [WINDOW_Q*fx_pkg::TAP_BITS-1:0]  cfg_kernel_q,
    input  wire logic [WINDOW_H*fx_pkg::TAP_BITS-1:0]  cfg_kernel_h,
    input  wire logic [WINDOW_F*fx_pkg::TAP_BITS-1:0]  cfg_kernel_f,
    /* verilator lint_on UNUSEDSIGNAL */
    output      logic                                  out_valid,  // one clock per winner
    output      fx_pkg::coord_t                        out_x,
    output      fx_pkg::coord_t                        out_y,
    output      logic [fx_pkg::DISP_BITS-1:0]          out_d,
    output      logic signed [fx_pkg::DISP_BITS-1:0]   out_v,
    output      logic                                  out_ok,     // the level's validity
    output      logic                                  busy        // a frame is in the levels
);
  localparam int D = fx_pkg::DISP_BITS;
  // The levels' ranges (stereo::hierarchical::level_range): d = 0 .. D/f - 1, v centred on 0.
  localparam int VQ = VRANGE / 4;
  localparam int VH = VRANGE / 2;
  localparam int V_MIN_Q = -(VQ / 2);
  localparam int V_MIN_H = -(VH / 2);
  localparam int V_MIN_F = -(VRANGE / 2);
  localparam int LABELS_Q = (NDISP / 4) * VQ;
  localparam int GROUPS_Q = LABELS_Q / LANES_Q;
  localparam int GROUPS_H = 9 / LANES_H;
  localparam int GROUPS_F = 9 / LANES_F;
  `STEREO_ASSERT(lanes, LANES_Q >= 1 && LABELS_Q % LANES_Q == 0 && LANES_H >= 1 && 9 % LANES_H == 0 &&
                 LANES_F >= 1 && 9 % LANES_F == 0,
                 "LANES_Q must divide (NDISP/4) x (VRANGE/4), LANES_H and LANES_F must divide 9")
  `STEREO_ASSERT(ranges, NDISP % 4 == 0 && VRANGE % 4 == 0 && NDISP >= 8 && VRANGE >= 12 &&
                 NDISP <= 256 && VRANGE <= 252,
                 "NDISP 8 .. 256 and VRANGE 12 .. 252, multiples of 4")

  // ---- frames -------------------------------------------------------------------------------
  // IDLE: the setting follows the ports; FEED: a frame's pixels come in; DRAIN: its last pixel is
  // in, the levels finish it (no input taken).
  typedef enum logic [1:0] {
    IDLE,
    FEED,
    DRAIN
  } frame_e;
  frame_e frame_state;
  fx_pkg::cfg_size_t width, height, width_q, height_q, width_h, height_h;
  logic use_ca;
  /* verilator lint_off UNUSEDSIGNAL */  // RUNTIME_KERNEL = 0
  logic [WINDOW_Q*fx_pkg::TAP_BITS-1:0] kernel_q;
  logic [WINDOW_H*fx_pkg::TAP_BITS-1:0] kernel_h;
  logic [WINDOW_F*fx_pkg::TAP_BITS-1:0] kernel_f;
  /* verilator lint_on UNUSEDSIGNAL */
  assign width_q = width >> 2;
  assign height_q = height >> 2;
  assign width_h = width >> 1;
  assign height_h = height >> 1;

  logic done_q, done_h, done_f, take, last_input, new_frame;
  logic fifo_ready_q, fifo_ready_h, fifo_ready_f;
  assign busy = frame_state != IDLE;
  assign in_ready = frame_state != DRAIN && fifo_ready_q && fifo_ready_h && fifo_ready_f;
  assign take = in_valid && in_ready;
  assign new_frame = take && frame_state == IDLE;
  assign last_input = in_x == 16'($signed(32'(width)) - 1) && in_y == 16'($signed(32'(height)) - 1);
  always_ff @(posedge clk) begin
    if (rst) begin
      frame_state <= IDLE;
    end else begin
      unique case (frame_state)
        IDLE: if (take) frame_state <= last_input ? DRAIN : FEED;
        FEED: if (take && last_input) frame_state <= DRAIN;
        default: if (done_q && done_h && done_f) frame_state <= IDLE;
      endcase
    end
  end
  // As stereo_top: the ports registered every clock (idle_*), latched when a frame's first pixel
  // is taken (frame_*); the levels see the registered ports while idle, the latched ones after.
  fx_pkg::cfg_size_t idle_width, idle_height, frame_width, frame_height;
  logic idle_use_ca, frame_use_ca;
  logic [WINDOW_Q*fx_pkg::TAP_BITS-1:0] idle_kernel_q, frame_kernel_q;
  logic [WINDOW_H*fx_pkg::TAP_BITS-1:0] idle_kernel_h, frame_kernel_h;
  logic [WINDOW_F*fx_pkg::TAP_BITS-1:0] idle_kernel_f, frame_kernel_f;
  always_ff @(posedge clk) begin
    idle_width <= cfg_width;
    idle_height <= cfg_height;
    idle_use_ca <= cfg_use_ca;
    idle_kernel_q <= cfg_kernel_q;
    idle_kernel_h <= cfg_kernel_h;
    idle_kernel_f <= cfg_kernel_f;
    if (new_frame) begin
      frame_width <= idle_width;
      frame_height <= idle_height;
      frame_use_ca <= idle_use_ca;
      frame_kernel_q <= idle_kernel_q;
      frame_kernel_h <= idle_kernel_h;
      frame_kernel_f <= idle_kernel_f;
    end
  end
  always_comb begin
    width = (frame_state == IDLE) ? idle_width : frame_width;
    height = (frame_state == IDLE) ? idle_height : frame_height;
    use_ca = (frame_state == IDLE) ? idle_use_ca : frame_use_ca;
    kernel_q = (frame_state == IDLE) ? idle_kernel_q : frame_kernel_q;
    kernel_h = (frame_state == IDLE) ? idle_kernel_h : frame_kernel_h;
    kernel_f = (frame_state == IDLE) ? idle_kernel_f : frame_kernel_f;
  end

  function automatic logic [15:0] luma_pair(input logic [23:0] left, input logic [23:0] right);
    luma_pair = {luma(right), luma(left)};
  endfunction
  function automatic logic [7:0] luma(input logic [23:0] rgb);
    /* verilator lint_off UNUSEDSIGNAL */  // the fraction, and the high bits (at most 255)
    logic [17:0] sum;
    /* verilator lint_on UNUSEDSIGNAL */
    sum = 18'(rgb[23:16]) * 18'(fx_pkg::LUMA_R) + 18'(rgb[15:8]) * 18'(fx_pkg::LUMA_G) +
          18'(rgb[7:0]) * 18'(fx_pkg::LUMA_B) + 18'(1 << (fx_pkg::LUMA_SHIFT - 1));
    luma = sum[fx_pkg::LUMA_SHIFT+:8];
  endfunction
  function automatic logic [23:0] grey(input logic [7:0] value);
    grey = {value, value, value};
  endfunction

  // ---- the pyramid and the FIFOs -------------------------------------------------------------
  logic down_valid_q, down_valid_h;
  /* verilator lint_off UNUSEDSIGNAL */  // the FIFOs keep raster order: no coordinates needed
  fx_pkg::coord_t down_x_q, down_y_q, down_x_h, down_y_h;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [47:0] down_q, down_h;
  stereo_downscale #(.WIDTH(WIDTH), .FACTOR(4), .CHANNELS(6)) downscale_q (
      .clk(clk), .rst(rst), .ce(take), .in_x(in_x), .in_y(in_y), .cfg_width(width),
      .cfg_height(height), .in_pixel({in_right, in_left}), .out_valid(down_valid_q),
      .out_x(down_x_q), .out_y(down_y_q), .out_pixel(down_q));
  stereo_downscale #(.WIDTH(WIDTH), .FACTOR(2), .CHANNELS(6)) downscale_h (
      .clk(clk), .rst(rst), .ce(take), .in_x(in_x), .in_y(in_y), .cfg_width(width),
      .cfg_height(height), .in_pixel({in_right, in_left}), .out_valid(down_valid_h),
      .out_x(down_x_h), .out_y(down_y_h), .out_pixel(down_h));

  logic fifo_valid_q, fifo_valid_h, fifo_valid_f, take_q, take_h, take_f;
  logic [15:0] fifo_q, fifo_h, fifo_f;
  stereo_fifo #(.BITS(16), .DEPTH(FIFO_ROWS_Q * (WIDTH / 4))) fifo_quarter (
      .clk(clk), .rst(rst), .in_valid(down_valid_q), .in_data(luma_pair(down_q[23:0], down_q[47:24])),
      .in_ready(fifo_ready_q), .out_valid(fifo_valid_q), .out_data(fifo_q), .out_take(take_q));
  stereo_fifo #(.BITS(16), .DEPTH(FIFO_ROWS_H * (WIDTH / 2))) fifo_half (
      .clk(clk), .rst(rst), .in_valid(down_valid_h), .in_data(luma_pair(down_h[23:0], down_h[47:24])),
      .in_ready(fifo_ready_h), .out_valid(fifo_valid_h), .out_data(fifo_h), .out_take(take_h));
  stereo_fifo #(.BITS(16), .DEPTH(FIFO_ROWS_F * WIDTH)) fifo_full (
      .clk(clk), .rst(rst), .in_valid(take), .in_data(luma_pair(in_left, in_right)),
      .in_ready(fifo_ready_f), .out_valid(fifo_valid_f), .out_data(fifo_f), .out_take(take_f));

  // ---- the levels ----------------------------------------------------------------------------
  // Per level: the stepper's signals, the level's base request and its winner.
  logic [((GROUPS_Q > 1) ? $clog2(GROUPS_Q) : 1)-1:0] group_q;
  logic [((GROUPS_H > 1) ? $clog2(GROUPS_H) : 1)-1:0] group_h;
  logic [((GROUPS_F > 1) ? $clog2(GROUPS_F) : 1)-1:0] group_f;
  logic ce_q, ce_h, ce_f, flush_q, flush_h, flush_f, stepped_q, stepped_h, stepped_f;
  logic clear_q, clear_h, clear_f, allow_q, allow_h, allow_f;
  fx_pkg::coord_t x_q, y_q, x_h, y_h, x_f, y_f;
  /* verilator lint_off UNUSEDSIGNAL */  // the quarter level needs no prediction
  fx_pkg::coord_t req_x_q, req_y_q;
  /* verilator lint_on UNUSEDSIGNAL */
  fx_pkg::coord_t req_x_h, req_y_h, req_x_f, req_y_f;
  fx_pkg::coord_t win_x_q, win_y_q, win_x_h, win_y_h, win_x_f, win_y_f;
  logic [D-1:0] win_d_q, win_d_h, win_d_f, base_d_h, base_d_f, out_base_d_h, out_base_d_f;
  logic signed [D-1:0] win_v_q, win_v_h, win_v_f, base_v_h, base_v_f, out_base_v_h, out_base_v_f;
  /* verilator lint_off UNUSEDSIGNAL */  // a prediction is taken whether valid or not
  logic win_ok_q, win_ok_h;
  /* verilator lint_on UNUSEDSIGNAL */
  logic win_ok_f, ready_h, ready_f;
  fx_pkg::coord_t oldest_q, oldest_h;  // the coarse rows the finer level still needs

  stereo_level_stepper #(.GROUPS(GROUPS_Q)) step_quarter (
      .clk(clk), .rst(rst), .cfg_width(width_q), .cfg_height(height_q), .in_valid(fifo_valid_q),
      .in_take(take_q), .allow(allow_q), .level_out_x(win_x_q), .level_out_y(win_y_q), .ce(ce_q),
      .group(group_q), .x(x_q), .y(y_q), .flushing(flush_q), .stepped(stepped_q), .clear(clear_q), .done(done_q));
  stereo_level_stepper #(.GROUPS(GROUPS_H)) step_half (
      .clk(clk), .rst(rst), .cfg_width(width_h), .cfg_height(height_h), .in_valid(fifo_valid_h),
      .in_take(take_h), .allow(allow_h), .level_out_x(win_x_h), .level_out_y(win_y_h), .ce(ce_h),
      .group(group_h), .x(x_h), .y(y_h), .flushing(flush_h), .stepped(stepped_h), .clear(clear_h), .done(done_h));
  stereo_level_stepper #(.GROUPS(GROUPS_F)) step_full (
      .clk(clk), .rst(rst), .cfg_width(width), .cfg_height(height), .in_valid(fifo_valid_f),
      .in_take(take_f), .allow(allow_f), .level_out_x(win_x_f), .level_out_y(win_y_f), .ce(ce_f),
      .group(group_f), .x(x_f), .y(y_f), .flushing(flush_f), .stepped(stepped_f), .clear(clear_f), .done(done_f));

  // A coarse level steps while the row of its next winner has a free slot in its ring.
  function automatic logic room(input fx_pkg::coord_t winner_y, input fx_pkg::cfg_size_t rows,
                                input fx_pkg::coord_t oldest);
    logic signed [17:0] next_row;
    next_row = (winner_y < 0) ? 18'sd0 : 18'(winner_y) + 18'sd1;
    room = next_row >= $signed(18'(rows)) || next_row < 18'(oldest) + 18'(RING);
  endfunction
  assign allow_q = room(win_y_q, height_q, oldest_q);
  assign allow_h = ready_h && room(win_y_h, height_h, oldest_h);
  assign allow_f = ready_f;

  stereo_hier_level #(.WIDTH(WIDTH / 4), .COLS(NDISP / 4), .ROWS(VQ), .V_MIN(V_MIN_Q),
                      .V_MAX(V_MIN_Q + VQ - 1), .WINDOW(WINDOW_Q), .LANES(LANES_Q),
                      .RUNTIME_KERNEL(RUNTIME_KERNEL), .REFINE(1'b0)) quarter (
      .clk(clk), .rst(rst || clear_q), .ce(ce_q), .group(group_q), .in_x(x_q), .in_y(y_q),
      .in_left(flush_q ? '0 : grey(fifo_q[7:0])), .in_right(flush_q ? '0 : grey(fifo_q[15:8])),
      .cfg_width(width_q), .cfg_height(height_q), .cfg_use_ca(use_ca),
      .cfg_kernel(kernel_q), .req_x(req_x_q), .req_y(req_y_q), .in_base_d('0),
      .in_base_v('0), .out_base_d('0), .out_base_v('0), .out_x(win_x_q), .out_y(win_y_q),
      .out_d(win_d_q), .out_v(win_v_q), .out_valid(win_ok_q));
  stereo_hier_level #(.WIDTH(WIDTH / 2), .COLS(3), .ROWS(3), .V_MIN(V_MIN_H),
                      .V_MAX(V_MIN_H + VH - 1), .WINDOW(WINDOW_H), .LANES(LANES_H),
                      .RUNTIME_KERNEL(RUNTIME_KERNEL), .REFINE(1'b1)) half (
      .clk(clk), .rst(rst || clear_h), .ce(ce_h), .group(group_h), .in_x(x_h), .in_y(y_h),
      .in_left(flush_h ? '0 : grey(fifo_h[7:0])), .in_right(flush_h ? '0 : grey(fifo_h[15:8])),
      .cfg_width(width_h), .cfg_height(height_h), .cfg_use_ca(use_ca),
      .cfg_kernel(kernel_h), .req_x(req_x_h), .req_y(req_y_h), .in_base_d(base_d_h),
      .in_base_v(base_v_h), .out_base_d(out_base_d_h), .out_base_v(out_base_v_h),
      .out_x(win_x_h), .out_y(win_y_h), .out_d(win_d_h), .out_v(win_v_h), .out_valid(win_ok_h));
  stereo_hier_level #(.WIDTH(WIDTH), .COLS(3), .ROWS(3), .V_MIN(V_MIN_F),
                      .V_MAX(V_MIN_F + VRANGE - 1), .WINDOW(WINDOW_F), .LANES(LANES_F),
                      .RUNTIME_KERNEL(RUNTIME_KERNEL), .REFINE(1'b1)) full (
      .clk(clk), .rst(rst || clear_f), .ce(ce_f), .group(group_f), .in_x(x_f), .in_y(y_f),
      .in_left(flush_f ? '0 : grey(fifo_f[7:0])), .in_right(flush_f ? '0 : grey(fifo_f[15:8])),
      .cfg_width(width), .cfg_height(height), .cfg_use_ca(use_ca),
      .cfg_kernel(kernel_f), .req_x(req_x_f), .req_y(req_y_f), .in_base_d(base_d_f),
      .in_base_v(base_v_f), .out_base_d(out_base_d_f), .out_base_v(out_base_v_f),
      .out_x(win_x_f), .out_y(win_y_f), .out_d(win_d_f), .out_v(win_v_f), .out_valid(win_ok_f));

  // ---- the predictions -------------------------------------------------------------------------
  function automatic logic in_frame(input fx_pkg::coord_t x, input fx_pkg::coord_t y,
                                    input fx_pkg::cfg_size_t columns, input fx_pkg::cfg_size_t rows);
    in_frame = x >= 0 && y >= 0 && 32'(x) < 32'(columns) && 32'(y) < 32'(rows);
  endfunction
  logic ready_ring_h, ready_ring_f;
  stereo_prediction_ring #(.WIDTH(WIDTH / 4), .RING(RING), .D_FINE(NDISP / 2),
                           .V_MIN(V_MIN_H), .V_MAX(V_MIN_H + VH - 1)) ring_quarter (
      .clk(clk), .new_frame(new_frame), .cfg_width(width_q), .cfg_height(height_q),
      .write(stepped_q && in_frame(win_x_q, win_y_q, width_q, height_q)), .write_x(win_x_q),
      .write_y(win_y_q), .write_d(win_d_q), .write_v(win_v_q), .a_x(req_x_h), .a_y(req_y_h),
      .a_base_d(base_d_h), .a_base_v(base_v_h), .a_ready(ready_ring_h), .b_x(win_x_h),
      .b_y(win_y_h), .b_base_d(out_base_d_h), .b_base_v(out_base_v_h), .oldest_needed(oldest_q));
  stereo_prediction_ring #(.WIDTH(WIDTH / 2), .RING(RING), .D_FINE(NDISP),
                           .V_MIN(V_MIN_F), .V_MAX(V_MIN_F + VRANGE - 1)) ring_half (
      .clk(clk), .new_frame(new_frame), .cfg_width(width_h), .cfg_height(height_h),
      .write(stepped_h && in_frame(win_x_h, win_y_h, width_h, height_h)), .write_x(win_x_h),
      .write_y(win_y_h), .write_d(win_d_h), .write_v(win_v_h), .a_x(req_x_f), .a_y(req_y_f),
      .a_base_d(base_d_f), .a_base_v(base_v_f), .a_ready(ready_ring_f), .b_x(win_x_f),
      .b_y(win_y_f), .b_base_d(out_base_d_f), .b_base_v(out_base_v_f), .oldest_needed(oldest_h));
  // A request beyond the fine frame (flush) needs no prediction.
  assign ready_h = ready_ring_h || 32'(req_y_h) >= 32'(height_h) && req_y_h >= 0;
  assign ready_f = ready_ring_f || 32'(req_y_f) >= 32'(height) && req_y_f >= 0;

  // ---- out: the full level's winners ------------------------------------------------------------
  assign out_valid = stepped_f && in_frame(win_x_f, win_y_f, width, height);
  assign out_x = win_x_f;
  assign out_y = win_y_f;
  assign out_d = win_d_f;
  assign out_v = win_v_f;
  assign out_ok = win_ok_f;
endmodule

`default_nettype wire
