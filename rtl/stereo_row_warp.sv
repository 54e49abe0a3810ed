// stereo_row_warp: the hierarchical core's row select (issue 45; docs/hierarchical.md, "The pass on
// a row-warped right image"), bit-exact with stereo::hierarchical::warp_rows over the field of a
// plane (plane_field). It turns the stream of pixel pairs {right, left} into the stream
// {warp_rows(right, field)(x, y), left(x, y)}: the right pixel of column x is taken from row
//   y + v(x, y),  v(x, y) = clamp(round((a + b x + c y) / 2^16), V_MIN, V_MAX)  (halves up),
// that row clamped into the frame; stereo_top's stages then run the 1-D pass on it unchanged.
//
// Both streams are AXI4-Stream, tdata = {right RGB, left RGB} as stereo_top's input: tuser marks
// a frame's first pixel, tlast a row's last. The core holds the last V_MAX - V_MIN right rows and
// the last V_MAX left rows (two stereo_line_buffer, one RAM word per column each), so it outputs
// row y while row y + V_MAX comes in; the first V_MAX rows give no output, and after the frame's
// last pixel it steps V_MAX rows on its own (flush, taking no input) to put out the last ones.
// Exactly one output beat per input pixel of the frame, raster order.
//
// Configuration (cfg_width, cfg_height, plane_*) is sampled when a start-of-frame beat arrives and
// start_allowed is high (frame_start marks that clock)
// (a size of 0 or above WIDTH, HEIGHT is taken as WIDTH, HEIGHT, as in stereo_top);
// a beat before the first start of frame is dropped. The start-of-frame beat waits one clock
// while the configuration is taken. A step (one input pixel, or one flush step) happens when the
// output register is empty or being taken (m_axis_tready), so a stalled output stalls the input
// and nothing is lost. tuser or tlast misplaced inside a frame are not checked here: the beats are
// counted by the sampled size, and stereo_top, behind, sees correct framing. Reset (synchronous,
// active high) abandons the frame; rows buffered before it are never read (row y of a frame is
// only read once the frame has written it).
`default_nettype none
`include "stereo_assert.svh"

module stereo_row_warp #(
    parameter int WIDTH  = 64,  // longest row
    parameter int HEIGHT = 48,  // tallest frame
    parameter int V_MIN  = -8,  // smallest vertical offset (<= 0)
    parameter int V_MAX  = 7    // largest vertical offset (>= 1)
) (
    input  wire logic                            clk,
    input  wire logic                            rst,
    input  wire fx_pkg::cfg_size_t               cfg_width,
    input  wire fx_pkg::cfg_size_t               cfg_height,
    input  wire logic signed [31:0]              plane_a,  // 1/2^16 pixel
    input  wire logic signed [31:0]              plane_b,  // 1/2^16 pixel per column
    input  wire logic signed [31:0]              plane_c,  // 1/2^16 pixel per row
    input  wire logic                            start_allowed,  // 0: a start of frame waits
    output      logic                            frame_start,    // configuration sampled now
    input  wire logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata,
    input  wire logic                            s_axis_tvalid,
    output      logic                            s_axis_tready,
    /* verilator lint_off UNUSEDSIGNAL */  // framing is counted, not checked (above)
    input  wire logic                            s_axis_tlast,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic                            s_axis_tuser,
    output      logic [fx_pkg::IN_BEAT_BITS-1:0] m_axis_tdata,
    output      logic                            m_axis_tvalid,
    input  wire logic                            m_axis_tready,
    output      logic                            m_axis_tlast,
    output      logic                            m_axis_tuser
);
  `STEREO_ASSERT(offset_range, V_MIN <= 0 && V_MAX >= 1 && V_MAX - V_MIN <= 127,
                 "V_MIN must be <= 0, V_MAX >= 1, and V_MAX - V_MIN at most 127")
  `STEREO_ASSERT(size_range, WIDTH >= 1 && HEIGHT >= 1 && HEIGHT + V_MAX <= 32767,
                 "WIDTH and HEIGHT must be at least 1, HEIGHT + V_MAX at most 32767")

  localparam int RGB = fx_pkg::RGB_BITS;
  localparam int RIGHT_ROWS = V_MAX - V_MIN;  // rows y_in - 1 .. y_in - RIGHT_ROWS
  localparam int LEFT_ROWS = V_MAX;  // the left pixel is V_MAX rows old
  localparam logic signed [63:0] HIGHEST = 64'(V_MAX);

  typedef enum logic [1:0] {
    IDLE,
    RUN,
    FLUSH
  } state_e;
  state_e state;

  // Sampled configuration, and the position of the next step: (x, y_in) of the input raster,
  // which continues past the frame's last row during the flush.
  fx_pkg::cfg_size_t width_q, height_q;
  logic signed [31:0] a_q, b_q, c_q;
  fx_pkg::coord_t x, y_in;

  logic out_free, step, last_column, last_input, last_step, produces;
  assign out_free = !m_axis_tvalid || m_axis_tready;
  assign step = out_free && ((state == RUN && s_axis_tvalid) || state == FLUSH);
  assign s_axis_tready = (state == IDLE && !s_axis_tuser) || (state == RUN && out_free);
  assign frame_start = state == IDLE && s_axis_tvalid && s_axis_tuser && start_allowed;
  assign last_column = 32'(x) + 1 == 32'(width_q);
  assign last_input = last_column && 32'(y_in) + 1 == 32'(height_q);
  assign last_step = last_column && 32'(y_in) + 1 == 32'(height_q) + V_MAX;
  assign produces = 32'(y_in) >= V_MAX;

  // The rows above the step's column (row y_in - 1 - k at [k*RGB +: RGB]).
  logic [RIGHT_ROWS*RGB-1:0] right_rows;
  /* verilator lint_off UNUSEDSIGNAL */  // only the oldest left row is read
  logic [LEFT_ROWS*RGB-1:0] left_rows;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [RGB-1:0] in_left, in_right;
  assign in_left = s_axis_tdata[fx_pkg::IN_LEFT_LSB+:RGB];
  assign in_right = s_axis_tdata[fx_pkg::IN_RIGHT_LSB+:RGB];

  stereo_line_buffer #(
      .WIDTH(WIDTH),
      .DATA_BITS(RGB),
      .ROWS(RIGHT_ROWS)
  ) right_buffer (
      .clk(clk),
      .ce(step),
      .in_x(x),
      .group(1'b0),
      .cfg_width(width_q),
      .in_data(in_right),
      .rows_above(right_rows)
  );
  stereo_line_buffer #(
      .WIDTH(WIDTH),
      .DATA_BITS(RGB),
      .ROWS(LEFT_ROWS)
  ) left_buffer (
      .clk(clk),
      .ce(step),
      .in_x(x),
      .group(1'b0),
      .cfg_width(width_q),
      .in_data(in_left),
      .rows_above(left_rows)
  );

  // The output row y = y_in - V_MAX, its offset at column x, and the right row it reads, clamped
  // into the frame; distance = y_in - row is 0 .. RIGHT_ROWS (0: the pixel coming in now).
  logic signed [63:0] y_out, row, distance;
  logic signed [7:0] offset;
  logic [RGB-1:0] right_pixel;
  stereo_plane_offset #(
      .V_MIN(V_MIN),
      .V_MAX(V_MAX)
  ) field (
      .plane_a(a_q),
      .plane_b(b_q),
      .plane_c(c_q),
      .x(17'(x)),
      .y(17'(y_out)),
      .offset(offset)
  );
  assign y_out = 64'(y_in) - HIGHEST;
  always_comb begin
    row = y_out + 64'(offset);
    if (row < 0) row = 0;
    if (row > 64'(height_q) - 1) row = 64'(height_q) - 1;
    distance = 64'(y_in) - row;
    right_pixel = in_right;
    for (int k = 1; k <= RIGHT_ROWS; k++) begin
      if (distance == 64'(k)) right_pixel = right_rows[(k-1)*RGB+:RGB];
    end
  end

  always_ff @(posedge clk) begin
    if (rst) begin
      state <= IDLE;
      x <= '0;
      y_in <= '0;
      m_axis_tvalid <= 1'b0;
    end else begin
      if (m_axis_tready) m_axis_tvalid <= 1'b0;
      if (frame_start) begin
        state <= RUN;
        // 0 or above WIDTH (HEIGHT) is WIDTH (HEIGHT), as stereo_top clamps its copy.
        width_q <= (cfg_width == '0 || 32'(cfg_width) > WIDTH) ? fx_pkg::CFG_SIZE_BITS'(WIDTH)
                                                                : cfg_width;
        height_q <= (cfg_height == '0 || 32'(cfg_height) > HEIGHT) ? fx_pkg::CFG_SIZE_BITS'(HEIGHT)
                                                                   : cfg_height;
        a_q <= plane_a;
        b_q <= plane_b;
        c_q <= plane_c;
        x <= '0;
        y_in <= '0;
      end
      if (step) begin
        if (produces) begin
          m_axis_tvalid <= 1'b1;
          m_axis_tdata <= {right_pixel, left_rows[(LEFT_ROWS-1)*RGB+:RGB]};
          m_axis_tuser <= x == '0 && y_out == 0;
          m_axis_tlast <= last_column;
        end
        x <= last_column ? '0 : x + 1'b1;
        if (last_column) y_in <= y_in + 1'b1;
        if (state == RUN && last_input) state <= FLUSH;
        if (last_step) begin
          state <= IDLE;
          y_in <= '0;
        end
      end
    end
  end
endmodule

`default_nettype wire
