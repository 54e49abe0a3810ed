// stereo_board_top: stereo_top on an iCEBreaker (iCE40 UP5K), driven over the UART of the
// board's FTDI chip (docs/board.md has the protocol, the pins and the build).
//
// Byte protocol, 8N1 at clock / CLKS_PER_BIT baud. Every command is HEADER (0xA5) and an opcode:
//   'I' (0x49) identify  reply: 0x5A, REGMAP_ID (4 bytes), REGMAP_VERSION (4), WIDTH (2),
//                        HEIGHT (2), NDISP (2), WINDOW (1), MAX_MIN_DISP (1), status (1): 18 bytes
//   'C' (0x43) configure + 12 bytes: width (2), height (2), ndisp (2, bits 8:0), radius (1),
//                        flags (1: [0] use_ca, [1] uniqueness enable, [2] left-right enable,
//                        [3] sub-pixel enable), min_disp (2, 12-bit two's complement in bits 11:0),
//                        uniqueness ratio (1), left-right tolerance (1)
//                        reply: 0x5A, status
//   'F' (0x46) frame     + width * height pixel pairs of 6 bytes (left R, G, B, right R, G, B) in
//                        raster order, width and height as configured (clamped like stereo_top's
//                        cfg ports: 0 or more than WIDTH / HEIGHT is WIDTH / HEIGHT)
//                        reply: one output beat per pixel, 4 bytes each, least significant first
//                        (fx_pkg::out_beat_t: fixed[7:0], fixed[15:8], reason, certainty)
//   'R' (0x52) clear     resets the core and every sticky status bit, dropping the beats
//                        still in the core (the way out of an abandoned frame)
//                        reply: 0x5A, status before the clear
// Multi-byte fields are little-endian. Replies to 'I', 'C' and 'R' wait until every output beat
// of the frames before has been sent, so they never interleave with a frame's beats; a new
// command should wait for the reply of the one before, and a frame for the last beat of the
// frame before (the core takes no pixels while it flushes a frame). A command or frame whose next
// byte does not come within 2^TIMEOUT_BITS bit times is abandoned (protocol error; the parser
// waits for HEADER again, and 'R' clears a core left inside a frame). Status (sticky, cleared by 'R'):
//   [0] tlast misplaced, [1] tuser misplaced (stereo_top; cannot happen with this framing),
//   [2] configuration out of range (stereo_top clamps it; here also a radius other than
//       WINDOW / 2, the core's constant kernel), [3] protocol error (a byte that is not HEADER
//   where a command should start, an unknown opcode, or a timeout), [4] UART framing error (a stop bit was
//   0), [5] input overrun (a pixel arrived while the one before still waited for the core: it
//   was dropped), [7:6] zero.
// Flow control: the UART has none, so the core must keep up with the line. It takes a pixel
// per clock unless its output stalls; output beats wait in a beat register and a byte FIFO for
// the transmitter, and the core stalls (never drops) while they are full. A pixel takes 60 bit
// times to arrive and its beat 40 to leave, so in a frame the output keeps pace and the input
// never overruns. The configuration uses stereo_top's constant default kernel (RUNTIME_KERNEL
// 0, like stereo_synth_top): the radius is always WINDOW / 2.
//
// Reset: a power-on counter holds the design in reset for 2^POR_BITS clocks after configuration
// (iCE40 flip-flops start at their init values); the user button (active low) restarts it.
// LEDs (active low): green lit while idle (out of reset, no frame streaming), red lit while any
// status bit is set.
`default_nettype none
`include "stereo_assert.svh"

// A third top in rtl/files.f beside stereo_axil_top and stereo_synth_top.
/* verilator lint_off MULTITOP */
module stereo_board_top #(
    parameter int WIDTH        = 32,   // largest frame width
    parameter int HEIGHT       = 24,   // largest frame height
    parameter int NDISP        = 1,    // disparities evaluated in parallel
    parameter int WINDOW       = 3,    // aggregation window (odd), constant kernel
    parameter int CLKS_PER_BIT = 104,  // clock / baud: 104 is 115200 baud at 12 MHz
    parameter int TX_FIFO_DEPTH = 16,  // bytes waiting for the transmitter (a power of 2)
    parameter int POR_BITS     = 8,    // power-on reset: 2^POR_BITS clocks
    parameter int TIMEOUT_BITS = 14,   // idle timeout inside a command: 2^TIMEOUT_BITS bit times
    // Largest |min_disp| (stereo_top's delay lines for shifted ranges). 0 keeps only the
    // classic range 0 .. ndisp-1 and saves about 760 LUT4 and 1,280 flip-flops of the cost stage
    // at one label, which is what lets the core place on the UP5K (docs/board.md).
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,
    // Labels computed per clock (stereo_top LANES, divides NDISP): NDISP / LANES clocks a pixel.
    parameter int LANES = NDISP,
    // stereo_top RING_BLOCK_MIN_FILL: which group rings go to block RAM (stereo_group_ring).
    parameter int RING_BLOCK_MIN_FILL = 50
) (
    input  wire logic clk,          // 12 MHz oscillator
    input  wire logic uart_rx,      // from the FTDI (host to board)
    output      logic uart_tx,      // to the FTDI (board to host)
    input  wire logic button_n,     // user button, active low: reset
    output      logic led_red_n,    // active low: a status bit is set
    output      logic led_green_n   // active low: idle
);
  localparam int R = WINDOW / 2;
  localparam logic [7:0] HEADER = 8'hA5;
  localparam logic [7:0] REPLY = 8'h5A;
  localparam logic [7:0] OP_IDENTIFY = 8'h49;  // 'I'
  localparam logic [7:0] OP_CONFIGURE = 8'h43;  // 'C'
  localparam logic [7:0] OP_FRAME = 8'h46;  // 'F'
  localparam logic [7:0] OP_CLEAR = 8'h52;  // 'R'
  localparam int CONFIG_BYTES = 12;
  localparam int ID_REPLY_BYTES = 18;
  localparam int ACK_REPLY_BYTES = 2;
  localparam int FIFO_BITS = $clog2(TX_FIFO_DEPTH);
  localparam int PIXEL_BITS = $clog2(WIDTH * HEIGHT + 1);
  localparam int TIMEOUT_COUNT_BITS = $clog2(CLKS_PER_BIT) + TIMEOUT_BITS + 1;
  localparam logic [TIMEOUT_COUNT_BITS-1:0] TIMEOUT_CLOCKS =
      TIMEOUT_COUNT_BITS'(CLKS_PER_BIT) << TIMEOUT_BITS;
  localparam logic [31:0] ID = 32'(fx_pkg::REGMAP_ID);
  localparam logic [31:0] VERSION = 32'(fx_pkg::REGMAP_VERSION);

  `STEREO_ASSERT(tx_fifo_depth, TX_FIFO_DEPTH >= 2 && (1 << FIFO_BITS) == TX_FIFO_DEPTH,
                 "TX_FIFO_DEPTH must be a power of 2, at least 2")
  `STEREO_ASSERT(identify_fields,
                 WIDTH < 65536 && HEIGHT < 65536 && NDISP < 65536 && WINDOW < 256,
                 "WIDTH, HEIGHT and NDISP must fit the identify reply's 2 bytes, WINDOW its byte")
  `STEREO_ASSERT(max_min_disp_byte, MAX_MIN_DISP >= 0 && MAX_MIN_DISP < 256,
                 "MAX_MIN_DISP must be 0 .. 255 (one byte of the identify reply)")

  // ---- reset (power-on counter, restarted by the button) and the UART ---------------------------
  logic rst;
  logic [7:0] rx_data;
  logic rx_valid, rx_framing_error;
  logic [7:0] tx_data;
  logic tx_valid, tx_ready;
  stereo_board_link #(
      .CLKS_PER_BIT(CLKS_PER_BIT),
      .POR_BITS(POR_BITS)
  ) link (
      .*
  );

  // ---- configuration registers (reset: the largest frame, all labels, CA on, stage 6 off) -----
  fx_pkg::cfg_size_t cfg_width, cfg_height;
  fx_pkg::cfg_ndisp_t cfg_ndisp;
  fx_pkg::cfg_radius_t cfg_radius;
  logic cfg_use_ca, cfg_uniqueness_en, cfg_lr_en, cfg_subpixel_en;
  fx_pkg::cfg_min_disp_t cfg_min_disp;
  fx_pkg::cfg_uniqueness_t cfg_uniqueness;
  fx_pkg::cfg_lr_tolerance_t cfg_lr_tolerance;

  // The frame size the core will use: stereo_top's clamping of cfg_width / cfg_height.
  fx_pkg::cfg_size_t clamped_width, clamped_height;
  always_comb begin
    clamped_width = cfg_width;
    clamped_height = cfg_height;
    if (cfg_width == 0 || 32'(cfg_width) > WIDTH) clamped_width = fx_pkg::CFG_SIZE_BITS'(WIDTH);
    if (cfg_height == 0 || 32'(cfg_height) > HEIGHT) begin
      clamped_height = fx_pkg::CFG_SIZE_BITS'(HEIGHT);
    end
  end

  // ---- command parser --------------------------------------------------------------------------
  typedef enum logic [1:0] {
    CMD_HEADER,  // waiting for HEADER
    CMD_OPCODE,  // waiting for the opcode
    CMD_CONFIG,  // the configuration bytes
    CMD_FRAME    // the frame's pixel bytes
  } parse_t;
  parse_t parse;

  typedef enum logic [1:0] {
    REPLY_NONE,
    REPLY_ID,
    REPLY_ACK,
    REPLY_CLEAR  // an acknowledgement that first clears the core and the status
  } reply_t;
  reply_t reply_kind;  // the reply waiting or being sent
  logic [4:0] reply_index;  // its next byte

  logic [3:0] config_index;
  logic [2:0] byte_in_pixel;  // 0 .. 5
  logic [39:0] pixel_bytes;  // the pixel's first five bytes, the latest in the low byte
  fx_pkg::cfg_size_t frame_width, frame_height;  // latched at 'F'
  fx_pkg::cfg_size_t pixel_x, pixel_y;  // raster position of the next pixel
  logic radius_clamped;  // sticky: a frame started with a radius other than R
  logic protocol_error, framing_error, overrun;  // sticky

  // The input beat register: one pixel pair waiting for the core.
  logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata;
  logic s_axis_tvalid, s_axis_tlast, s_axis_tuser, s_axis_tready;
  logic soft_reset;
  logic drained, reply_taken, reply_last;

  // Idle timeout: a command or frame whose next byte does not come within 2^TIMEOUT_BITS bit
  // times is abandoned (protocol error) and the parser waits for HEADER again.
  logic [TIMEOUT_COUNT_BITS-1:0] idle_clocks;
  logic timed_out;
  assign timed_out = parse != CMD_HEADER && idle_clocks == TIMEOUT_CLOCKS;
  always_ff @(posedge clk) begin
    if (rst || rx_valid || parse == CMD_HEADER) begin
      idle_clocks <= '0;
    end else if (!timed_out) begin
      idle_clocks <= idle_clocks + 1'b1;
    end
  end

  always_ff @(posedge clk) begin
    if (rst) begin
      parse <= CMD_HEADER;
      reply_kind <= REPLY_NONE;
      config_index <= '0;
      byte_in_pixel <= '0;
      pixel_bytes <= '0;
      frame_width <= '0;
      frame_height <= '0;
      pixel_x <= '0;
      pixel_y <= '0;
      radius_clamped <= 1'b0;
      protocol_error <= 1'b0;
      framing_error <= 1'b0;
      overrun <= 1'b0;
      s_axis_tvalid <= 1'b0;
      s_axis_tdata <= '0;
      s_axis_tlast <= 1'b0;
      s_axis_tuser <= 1'b0;
      cfg_width <= fx_pkg::CFG_SIZE_BITS'(WIDTH);
      cfg_height <= fx_pkg::CFG_SIZE_BITS'(HEIGHT);
      cfg_ndisp <= fx_pkg::CFG_NDISP_BITS'(NDISP);
      cfg_radius <= fx_pkg::CFG_RADIUS_BITS'(R);
      cfg_use_ca <= 1'b1;
      cfg_uniqueness_en <= 1'b0;
      cfg_lr_en <= 1'b0;
      cfg_subpixel_en <= 1'b0;
      cfg_min_disp <= '0;
      cfg_uniqueness <= fx_pkg::CFG_UNIQUENESS_BITS'(20);
      cfg_lr_tolerance <= '0;
    end else begin
      if (s_axis_tvalid && s_axis_tready) s_axis_tvalid <= 1'b0;
      if (timed_out) begin
        parse <= CMD_HEADER;
        protocol_error <= 1'b1;
      end
      if (soft_reset) begin
        s_axis_tvalid <= 1'b0;
        radius_clamped <= 1'b0;
        protocol_error <= 1'b0;
        framing_error <= 1'b0;
        overrun <= 1'b0;
      end
      // The reply's last byte is queued in the cycle the sender takes it (below).
      if (reply_taken && reply_last) reply_kind <= REPLY_NONE;
      if (rx_valid) begin
        if (rx_framing_error) framing_error <= 1'b1;
        unique case (parse)
          CMD_HEADER: begin
            if (rx_data == HEADER) begin
              parse <= CMD_OPCODE;
            end else begin
              protocol_error <= 1'b1;
            end
          end
          CMD_OPCODE: begin
            parse <= CMD_HEADER;
            unique case (rx_data)
              OP_IDENTIFY: reply_kind <= REPLY_ID;
              OP_CLEAR: reply_kind <= REPLY_CLEAR;
              OP_CONFIGURE: begin
                parse <= CMD_CONFIG;
                config_index <= '0;
              end
              OP_FRAME: begin
                parse <= CMD_FRAME;
                frame_width <= clamped_width;
                frame_height <= clamped_height;
                pixel_x <= '0;
                pixel_y <= '0;
                byte_in_pixel <= '0;
                if (32'(cfg_radius) != R) radius_clamped <= 1'b1;
              end
              default: protocol_error <= 1'b1;
            endcase
          end
          CMD_CONFIG: begin
            config_index <= config_index + 1'b1;
            unique case (config_index)
              4'd0: cfg_width[7:0] <= rx_data;
              4'd1: cfg_width[15:8] <= rx_data;
              4'd2: cfg_height[7:0] <= rx_data;
              4'd3: cfg_height[15:8] <= rx_data;
              4'd4: cfg_ndisp[7:0] <= rx_data;
              4'd5: cfg_ndisp[8] <= rx_data[0];
              4'd6: cfg_radius <= rx_data[4:0];
              4'd7: begin
                cfg_use_ca <= rx_data[0];
                cfg_uniqueness_en <= rx_data[1];
                cfg_lr_en <= rx_data[2];
                cfg_subpixel_en <= rx_data[3];
              end
              4'd8: cfg_min_disp[7:0] <= rx_data;
              4'd9: cfg_min_disp[11:8] <= rx_data[3:0];
              4'd10: cfg_uniqueness <= rx_data;
              default: cfg_lr_tolerance <= rx_data;
            endcase
            if (32'(config_index) == CONFIG_BYTES - 1) begin
              parse <= CMD_HEADER;
              reply_kind <= REPLY_ACK;
            end
          end
          CMD_FRAME: begin
            if (byte_in_pixel != 3'd5) begin
              byte_in_pixel <= byte_in_pixel + 1'b1;
              pixel_bytes <= {pixel_bytes[31:0], rx_data};
            end else begin
              byte_in_pixel <= '0;
              // {right RGB, left RGB}: bytes 3, 4, 5 over bytes 0, 1, 2.
              if (s_axis_tvalid && !s_axis_tready) begin
                overrun <= 1'b1;  // the core did not take the pixel before: drop this one
              end else begin
                s_axis_tvalid <= 1'b1;
                s_axis_tdata <= {pixel_bytes[15:0], rx_data, pixel_bytes[39:16]};
                s_axis_tuser <= pixel_x == 0 && pixel_y == 0;
                s_axis_tlast <= pixel_x == frame_width - 1'b1;
              end
              if (pixel_x == frame_width - 1'b1) begin
                pixel_x <= '0;
                pixel_y <= pixel_y + 1'b1;
                if (pixel_y == frame_height - 1'b1) parse <= CMD_HEADER;
              end else begin
                pixel_x <= pixel_x + 1'b1;
              end
            end
          end
          default: parse <= CMD_HEADER;
        endcase
      end
    end
  end

  // ---- output beats to bytes -------------------------------------------------------------------
  fx_pkg::out_beat_t m_axis_tdata;
  logic m_axis_tvalid, m_axis_tready;
  // Every beat has 4 bytes in raster order; the framing flags are not sent.
  /* verilator lint_off UNUSEDSIGNAL */
  logic m_axis_tlast, m_axis_tuser;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [31:0] beat;
  logic beat_held;
  logic [1:0] beat_byte;  // next byte of the held beat
  logic [PIXEL_BITS-1:0] outstanding;  // pixels taken by the core whose beat is not held yet

  // Byte FIFO in front of the transmitter.
  logic [7:0] fifo[TX_FIFO_DEPTH];
  logic [FIFO_BITS:0] fifo_write, fifo_read;
  logic fifo_full, fifo_empty, fifo_push;
  logic [7:0] fifo_in;
  assign fifo_full = (fifo_write ^ fifo_read) == {1'b1, {FIFO_BITS{1'b0}}};
  assign fifo_empty = fifo_write == fifo_read;
  assign tx_valid = !fifo_empty;
  assign tx_data = fifo[fifo_read[FIFO_BITS-1:0]];

  // Replies: queued once every beat before them is in the FIFO ('R' does not wait: it clears the
  // core and drops the beats still in it).
  logic [7:0] reply_byte;
  logic [7:0] status_byte;
  logic [fx_pkg::STATUS_BITS-1:0] core_status;
  assign drained = !beat_held && outstanding == 0 && !s_axis_tvalid;
  assign reply_taken = reply_kind != REPLY_NONE && !fifo_full && !beat_held &&
                       (drained || reply_kind == REPLY_CLEAR);
  assign reply_last = reply_index == 5'(reply_kind == REPLY_ID ? ID_REPLY_BYTES - 1 :
                                                                  ACK_REPLY_BYTES - 1);
  // The clear happens with the reply's last byte, so the reply shows the status before it.
  assign soft_reset = reply_taken && reply_kind == REPLY_CLEAR && reply_last;
  assign status_byte = {
    2'b00, overrun, framing_error, protocol_error, core_status[2] | radius_clamped, core_status[1:0]
  };

  always_comb begin
    reply_byte = REPLY;
    if (reply_kind == REPLY_ID) begin
      unique case (reply_index)
        5'd0: reply_byte = REPLY;
        5'd1: reply_byte = ID[7:0];
        5'd2: reply_byte = ID[15:8];
        5'd3: reply_byte = ID[23:16];
        5'd4: reply_byte = ID[31:24];
        5'd5: reply_byte = VERSION[7:0];
        5'd6: reply_byte = VERSION[15:8];
        5'd7: reply_byte = VERSION[23:16];
        5'd8: reply_byte = VERSION[31:24];
        5'd9: reply_byte = 8'(WIDTH);
        5'd10: reply_byte = 8'(WIDTH >> 8);
        5'd11: reply_byte = 8'(HEIGHT);
        5'd12: reply_byte = 8'(HEIGHT >> 8);
        5'd13: reply_byte = 8'(NDISP);
        5'd14: reply_byte = 8'(NDISP >> 8);
        5'd15: reply_byte = 8'(WINDOW);
        5'd16: reply_byte = 8'(MAX_MIN_DISP);
        default: reply_byte = status_byte;
      endcase
    end else if (reply_index != 0) begin
      reply_byte = status_byte;
    end
  end

  always_comb begin
    fifo_push = 1'b0;
    fifo_in = reply_byte;
    if (beat_held && !fifo_full) begin
      fifo_push = 1'b1;
      fifo_in = beat[8*beat_byte+:8];
    end else if (reply_taken) begin
      fifo_push = 1'b1;
    end
  end

  // The core's beats wait while a clear is answered (it then drops them with the core's reset).
  assign m_axis_tready = !beat_held && reply_kind != REPLY_CLEAR;

  always_ff @(posedge clk) begin
    if (fifo_push) fifo[fifo_write[FIFO_BITS-1:0]] <= fifo_in;
    if (rst) begin
      fifo_write <= '0;
      fifo_read <= '0;
      beat_held <= 1'b0;
      beat <= '0;
      beat_byte <= '0;
      outstanding <= '0;
      reply_index <= '0;
    end else begin
      if (fifo_push) fifo_write <= fifo_write + 1'b1;
      if (tx_valid && tx_ready) fifo_read <= fifo_read + 1'b1;
      if (beat_held && !fifo_full) begin
        beat_byte <= beat_byte + 1'b1;
        if (beat_byte == 2'd3) beat_held <= 1'b0;
      end
      if (m_axis_tvalid && m_axis_tready) begin
        beat_held <= 1'b1;
        beat <= m_axis_tdata;
        beat_byte <= '0;
      end
      // The core answers every pixel it takes with exactly one beat.
      unique case ({
        s_axis_tvalid && s_axis_tready, m_axis_tvalid && m_axis_tready
      })
        2'b10: outstanding <= outstanding + 1'b1;
        2'b01: outstanding <= outstanding - 1'b1;
        default: ;
      endcase
      if (reply_taken) reply_index <= reply_last ? '0 : reply_index + 1'b1;
      if (soft_reset) outstanding <= '0;  // the core forgets the pixels it holds
    end
  end

  // ---- the core --------------------------------------------------------------------------------
  // The constant kernel; RING_BLOCK_RAM = 1: on the iCE40 flip-flops are logic cells.
  stereo_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW), .RUNTIME_KERNEL(1'b0),
      .MAX_MIN_DISP(MAX_MIN_DISP), .LANES(LANES), .RING_BLOCK_RAM(1'b1),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) core (
      .rst(rst || soft_reset),
      .cfg_radius(fx_pkg::CFG_RADIUS_BITS'(R)),
      .cfg_kernel('0),  // unused: the kernel is constant
      .status(core_status),
      .*  // every other port: the signal of the same name
  );

  assign led_red_n = status_byte == 0;
  assign led_green_n = rst || parse == CMD_FRAME || !drained;
endmodule
/* verilator lint_on MULTITOP */

`default_nettype wire
