// tb_stereo_vectors: the part of the SystemVerilog testbenches that knows the test vectors
// (README.md): it reads config.hex, input.hex and expected.hex from the folder +vectors=DIR,
// checks that the core's parameters can run them, offers the frame configuration to the top
// testbench (ports for stereo_top, register words for stereo_axil_top), drives the input stream
// with random gaps on s_axis_tvalid once `go` is high, holds m_axis_tready low at random, and
// compares every output beat ({tuser, tlast, tdata}) with the expected one. Plain SystemVerilog:
// no classes, no vendor or UVM libraries, the random numbers from its own xorshift generators,
// so every simulator sees the same stalls for the same +seed.
//
// Plusargs: +vectors=DIR (required), +seed=N (1), +gap=PERCENT (30: s_axis_tvalid withheld),
// +stall=PERCENT (30: m_axis_tready low), +max_errors=N (10 mismatches printed).
// `done` rises once every expected beat has arrived and the quiet time after it (no extra beat)
// has passed; `errors` counts mismatches and protocol faults.
`default_nettype none

module tb_stereo_vectors #(
    `include "tb_core_params.svh"
    parameter int MAX_FRAMES = 4  // sizes the beat memories: WIDTH * HEIGHT * MAX_FRAMES
) (
    input wire logic clk,
    input wire logic rst,
    input wire logic go,  // start streaming (after the configuration is in place)
    // The frame configuration (valid from time 0, after the files are read).
    output fx_pkg::cfg_size_t cfg_width,
    output fx_pkg::cfg_size_t cfg_height,
    output fx_pkg::cfg_ndisp_t cfg_ndisp,
    output fx_pkg::cfg_radius_t cfg_radius,
    output logic [WINDOW*fx_pkg::TAP_BITS-1:0] cfg_kernel,  // the frame's taps, centred
    output logic cfg_use_ca,
    output fx_pkg::cfg_min_disp_t cfg_min_disp,
    output logic cfg_uniqueness_en,
    output fx_pkg::cfg_uniqueness_t cfg_uniqueness,
    output logic cfg_lr_en,
    output fx_pkg::cfg_lr_tolerance_t cfg_lr_tolerance,
    output logic cfg_subpixel_en,
    output int frames,  // frames in the vectors
    // The streams, from the testbench's side.
    output logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata,
    output logic s_axis_tvalid,
    input wire logic s_axis_tready,
    output logic s_axis_tlast,
    output logic s_axis_tuser,
    input wire logic [fx_pkg::OUT_BEAT_BITS-1:0] m_axis_tdata,
    input wire logic m_axis_tvalid,
    output logic m_axis_tready,
    input wire logic m_axis_tlast,
    input wire logic m_axis_tuser,
    output logic done,
    output int errors,
    output int stall_cycles  // cycles with m_axis_tvalid high and m_axis_tready low
);
  localparam int IN_BITS = fx_pkg::IN_BEAT_BITS + 2;  // {tuser, tlast, tdata}
  localparam int OUT_BITS = fx_pkg::OUT_BEAT_BITS + 2;
  localparam int MAX_BEATS = WIDTH * HEIGHT * MAX_FRAMES;
  localparam int TAP_BITS = fx_pkg::TAP_BITS;
  localparam int GROUPS = NDISP / LANES;  // clocks per pixel step
  // config.hex word indices (stereo_io/test_vectors.hpp VectorWord).
  localparam int W_MAGIC = 0, W_COST = 1, W_WIDTH = 2, W_HEIGHT = 3, W_FRAMES = 4, W_NDISP = 5;
  localparam int W_WINDOW = 6, W_USE_CA = 7, W_MIN_DISP = 8, W_UNIQUENESS_EN = 9;
  localparam int W_UNIQUENESS = 10, W_LR_EN = 11, W_LR_TOLERANCE = 12, W_SUBPIXEL_EN = 13;
  localparam int W_KERNEL = 14;
  localparam int CONFIG_WORDS = W_KERNEL + fx_pkg::MAX_WINDOW;
  localparam logic [31:0] MAGIC = 32'h53545631;  // "STV1"
  // After the last expected beat: this many cycles with m_axis_tready high and no beat.
  localparam int QUIET_CYCLES = 4 * WIDTH + 64;

  logic [31:0] config_words[CONFIG_WORDS];
  logic [IN_BITS-1:0] input_beats[MAX_BEATS];
  logic [OUT_BITS-1:0] expected_beats[MAX_BEATS];
  int beats;  // width * height * frames
  int window, min_disp;
  int gap_percent, stall_percent, max_errors;
  longint timeout;
  string folder;

`include "tb_xorshift.svh"

  // Stops with a message naming the problem (a vectors file or a parameter does not fit).
  task automatic refuse(input string message);
    $display("tb_stereo_vectors: FAIL: %s", message);
    $fatal(1, "tb_stereo_vectors: %s", message);
  endtask

  task automatic require_file(input string path);
    int fd;
    fd = $fopen(path, "r");
    if (fd == 0) refuse({"cannot open ", path});
    $fclose(fd);
  endtask

  initial begin : load
    int seed, steps;
    if (!$value$plusargs("vectors=%s", folder)) refuse("give +vectors=DIR (stereo vectors -o DIR)");
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("gap=%d", gap_percent)) gap_percent = 30;
    if (!$value$plusargs("stall=%d", stall_percent)) stall_percent = 30;
    if (!$value$plusargs("max_errors=%d", max_errors)) max_errors = 10;
    if (gap_percent < 0 || gap_percent > 90 || stall_percent < 0 || stall_percent > 90)
      refuse("+gap and +stall must be 0 .. 90 (percent)");
    for (int i = 0; i < CONFIG_WORDS; i++) config_words[i] = '1;
    for (int i = 0; i < MAX_BEATS; i++) begin
      input_beats[i] = '1;
      expected_beats[i] = '1;  // pad bits set: never an expected beat
    end
    require_file({folder, "/config.hex"});
    require_file({folder, "/input.hex"});
    require_file({folder, "/expected.hex"});
    $readmemh({folder, "/config.hex"}, config_words);
    if (config_words[W_MAGIC] != MAGIC) refuse({folder, "/config.hex is not stereo vectors"});
    if (int'(config_words[W_COST]) != COST)
      refuse($sformatf("the vectors are for COST = %0d, the core has COST = %0d",
                       config_words[W_COST], COST));
    if (config_words[W_WIDTH] == 0 || int'(config_words[W_WIDTH]) > WIDTH ||
        config_words[W_HEIGHT] == 0 || int'(config_words[W_HEIGHT]) > HEIGHT)
      refuse($sformatf("the vectors' %0dx%0d frame exceeds the core's %0dx%0d",
                       config_words[W_WIDTH], config_words[W_HEIGHT], WIDTH, HEIGHT));
    if (config_words[W_NDISP] == 0 || int'(config_words[W_NDISP]) > NDISP)
      refuse($sformatf("the vectors search %0d labels, the core NDISP = %0d",
                       config_words[W_NDISP], NDISP));
    window = int'(config_words[W_WINDOW]);
    if (window < 1 || window % 2 == 0 || window > WINDOW)
      refuse($sformatf("the vectors' window %0d does not fit the core's WINDOW = %0d", window,
                       WINDOW));
    min_disp = int'({{20{config_words[W_MIN_DISP][fx_pkg::CFG_MIN_DISP_BITS-1]}},
                     config_words[W_MIN_DISP][fx_pkg::CFG_MIN_DISP_BITS-1:0]});
    if (min_disp < -MAX_MIN_DISP || min_disp > MAX_MIN_DISP)
      refuse($sformatf("the vectors' minimum disparity %0d exceeds MAX_MIN_DISP = %0d", min_disp,
                       MAX_MIN_DISP));
    frames = int'(config_words[W_FRAMES]);
    if (frames < 1 || frames > MAX_FRAMES)
      refuse($sformatf("the vectors hold %0d frames, the testbench at most MAX_FRAMES = %0d",
                       frames, MAX_FRAMES));
    beats = int'(config_words[W_WIDTH]) * int'(config_words[W_HEIGHT]) * frames;
    // The kernel: the frame's taps centred in WINDOW; a constant-kernel core must have them.
    cfg_kernel = '0;
    for (int i = 0; i < window; i++) begin
      cfg_kernel[((WINDOW-window)/2+i)*TAP_BITS+:TAP_BITS] = config_words[W_KERNEL+i][TAP_BITS-1:0];
    end
    if (!RUNTIME_KERNEL) begin
      if (window != WINDOW) refuse("a RUNTIME_KERNEL = 0 core runs its own WINDOW only");
      for (int i = 0; i < WINDOW; i++) begin
        if (int'(cfg_kernel[i*TAP_BITS+:TAP_BITS]) != fx_pkg::default_tap(WINDOW, i))
          refuse("a RUNTIME_KERNEL = 0 core has the default kernel; the vectors' differs");
      end
    end
    cfg_width = fx_pkg::CFG_SIZE_BITS'(config_words[W_WIDTH]);
    cfg_height = fx_pkg::CFG_SIZE_BITS'(config_words[W_HEIGHT]);
    cfg_ndisp = fx_pkg::CFG_NDISP_BITS'(config_words[W_NDISP]);
    cfg_radius = fx_pkg::CFG_RADIUS_BITS'(window / 2);
    cfg_use_ca = config_words[W_USE_CA][0];
    cfg_min_disp = fx_pkg::CFG_MIN_DISP_BITS'(config_words[W_MIN_DISP]);
    cfg_uniqueness_en = config_words[W_UNIQUENESS_EN][0];
    cfg_uniqueness = fx_pkg::CFG_UNIQUENESS_BITS'(config_words[W_UNIQUENESS]);
    cfg_lr_en = config_words[W_LR_EN][0];
    cfg_lr_tolerance = fx_pkg::CFG_LR_TOLERANCE_BITS'(config_words[W_LR_TOLERANCE]);
    cfg_subpixel_en = config_words[W_SUBPIXEL_EN][0];
    $readmemh({folder, "/input.hex"}, input_beats);
    $readmemh({folder, "/expected.hex"}, expected_beats);
    // Exactly `beats` entries in each file: the last one read, the one after it not.
    if (input_beats[beats-1] == '1 || expected_beats[beats-1] == '1)
      refuse($sformatf("input.hex and expected.hex must hold %0d beats each", beats));
    if (beats < MAX_BEATS && (input_beats[beats] != '1 || expected_beats[beats] != '1))
      refuse($sformatf("input.hex or expected.hex holds more than %0d beats", beats));
    // Generous: every pixel step G = NDISP / LANES clocks, stalls and gaps of up to 90 %.
    steps = beats + (WINDOW + 6) * WIDTH * frames + 4096;
    timeout = longint'(steps) * longint'(GROUPS) * 40;
    seed_word = 32'(seed);
    $display("tb_stereo_vectors: %s: %0dx%0d, %0d frame(s), %0d beats, ndisp %0d, window %0d, min_disp %0d; seed %0d, gap %0d %%, stall %0d %%",
             folder, cfg_width, cfg_height, frames, beats, cfg_ndisp, window, min_disp, seed,
             gap_percent, stall_percent);
  end

  // ---- input: beat `sent` next, s_axis_tvalid withheld gap_percent of the cycles ---------------
  // Two generators from the seed (xorshift never leaves 0, hence the constants).
  logic [31:0] seed_word, in_rng, out_rng;
  int sent, received;
  longint cycles;
  always @(posedge clk) begin
    if (rst || !go) begin
      s_axis_tvalid <= 1'b0;
      s_axis_tdata <= '0;
      s_axis_tlast <= 1'b0;
      s_axis_tuser <= 1'b0;
      sent <= 0;
      in_rng <= xorshift(seed_word ^ 32'h9E3779B9);
    end else begin
      // A beat on offer stays until it is taken (AXI4-Stream); the next is offered or withheld.
      if (!s_axis_tvalid || s_axis_tready) begin
        int next;
        next = sent + ((s_axis_tvalid && s_axis_tready) ? 1 : 0);
        in_rng <= xorshift(in_rng);
        if (next < beats && int'(in_rng % 100) >= gap_percent) begin
          s_axis_tvalid <= 1'b1;
          {s_axis_tuser, s_axis_tlast, s_axis_tdata} <= input_beats[next];
        end else begin
          s_axis_tvalid <= 1'b0;
        end
        sent <= next;
      end
    end
  end

  // ---- output: m_axis_tready low stall_percent of the cycles, every beat compared -------------
  logic held;  // m_axis_tvalid was high and not taken at the last edge
  logic [OUT_BITS-1:0] held_beat;
  int quiet;
  always @(posedge clk) begin
    if (rst || !go) begin
      m_axis_tready <= 1'b0;
      out_rng <= xorshift(seed_word ^ 32'h7F4A7C15);
      received <= 0;
      errors <= 0;
      stall_cycles <= 0;
      cycles <= 0;
      held <= 1'b0;
      quiet <= 0;
      done <= 1'b0;
    end else if (!done) begin
      cycles <= cycles + 1;
      if (cycles > timeout) begin
        $display("tb_stereo_vectors: FAIL: timeout after %0d cycles: %0d of %0d beats sent, %0d received",
                 cycles, sent, beats, received);
        errors <= errors + 1;
        done <= 1'b1;
      end
      // AXI4-Stream: a beat on offer stays, unchanged, until it is taken.
      if (held && (!m_axis_tvalid || {m_axis_tuser, m_axis_tlast, m_axis_tdata} != held_beat)) begin
        $display("tb_stereo_vectors: FAIL: output beat %0d changed or withdrawn before it was taken",
                 received);
        errors <= errors + 1;
      end
      held <= m_axis_tvalid && !m_axis_tready;
      held_beat <= {m_axis_tuser, m_axis_tlast, m_axis_tdata};
      if (m_axis_tvalid && !m_axis_tready) stall_cycles <= stall_cycles + 1;
      if (m_axis_tvalid && m_axis_tready) begin
        if (received >= beats) begin
          $display("tb_stereo_vectors: FAIL: an output beat after the %0d expected", beats);
          errors <= errors + 1;
        end else if ({m_axis_tuser, m_axis_tlast, m_axis_tdata} != expected_beats[received]) begin
          if (errors < max_errors) begin
            $display("tb_stereo_vectors: FAIL: beat %0d (frame %0d, x %0d, y %0d): got %09h, expected %09h",
                     received, received / (int'(cfg_width) * int'(cfg_height)),
                     received % int'(cfg_width),
                     (received / int'(cfg_width)) % int'(cfg_height),
                     {m_axis_tuser, m_axis_tlast, m_axis_tdata}, expected_beats[received]);
          end
          errors <= errors + 1;
        end
        received <= received + 1;
      end
      // Random backpressure until the last beat; then ready, watching for extra beats.
      out_rng <= xorshift(out_rng);
      m_axis_tready <= received >= beats || int'(out_rng % 100) >= stall_percent;
      if (received >= beats) begin
        quiet <= quiet + 1;
        if (quiet >= QUIET_CYCLES) done <= 1'b1;
      end
    end
  end
endmodule

`default_nettype wire
