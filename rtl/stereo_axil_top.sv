// stereo_axil_top: stereo_top for SoC integration. The video streams pass straight through
// (AXI4-Stream, the beat layouts of stereo_top); the configuration lives in registers behind an
// AXI4-Lite slave instead of ports. The register map is defined once, in
// model/include/stereo/stage_table.hpp (kRegisters), and generated into fx_pkg's REG_* constants
// (offsets, field LSBs and widths, used below), the C header drivers/c/stereo_regs.h and the
// table of docs/integration.md (fields, reset values, a driver sequence): ID, VERSION, MAX_SIZE,
// BUILD (read-only: the build), FRAME, MATCH, STAGE6, THRESHOLDS (the frame configuration),
// STATUS (stereo_top's sticky status, cleared by CONTROL.soft_reset), CONTROL (soft reset of the
// core and the counters), FRAMES_IN, FRAMES_OUT, STALLS (counters) and KERNEL[i] (used when
// RUNTIME_KERNEL = 1; reset: the model's default kernel for WINDOW).
// Writes to RO registers and reads of unmapped offsets complete with OKAY and read 0. The core
// samples the configuration with each start-of-frame beat (stereo_top), so register writes take
// effect from the next frame. One outstanding transaction per direction; the write address and
// data may arrive in either order.
`default_nettype none
`include "stereo_assert.svh"

// One of several top-level modules (a top per integration: AXI4-Lite here, the boards', the
// synthesis wrapper): Verilator linting every file of rtl/ as one design names the first top it
// meets, this one, as MULTITOP; scripts/lint_rtl.sh lints each top on its own.
// verilator lint_off MULTITOP
module stereo_axil_top #(
    parameter int WIDTH          = 64,
    parameter int HEIGHT         = 48,
    parameter int NDISP          = 16,
    parameter int WINDOW         = 5,
    parameter bit RUNTIME_KERNEL = 1'b1,
    parameter int MAX_MIN_DISP   = fx_pkg::DEFAULT_MAX_MIN_DISP,
    parameter fx_pkg::cost_e COST = fx_pkg::COST_AD,
    parameter int LANES          = NDISP,  // labels per clock: NDISP / LANES clocks per pixel
    // RUNTIME_KERNEL = 0: tap products from shifts and adds (stereo_top)
    parameter fx_pkg::shift_add_e SHIFT_ADD = fx_pkg::SHIFT_ADD_NONE,
    parameter bit RECOMPUTE_COSTS = 1'b0,  // census, AD: the lean memory architecture (stereo_top)
    parameter int ADDR_BITS      = 8  // AXI4-Lite address width
) (
    input  wire logic                            clk,
    input  wire logic                            rst,
    // AXI4-Lite slave (32-bit data).
    input  wire logic [ADDR_BITS-1:0]            s_axil_awaddr,
    input  wire logic                            s_axil_awvalid,
    output      logic                            s_axil_awready,
    input  wire logic [31:0]                     s_axil_wdata,
    input  wire logic [3:0]                      s_axil_wstrb,
    input  wire logic                            s_axil_wvalid,
    output      logic                            s_axil_wready,
    output      logic [1:0]                      s_axil_bresp,
    output      logic                            s_axil_bvalid,
    input  wire logic                            s_axil_bready,
    input  wire logic [ADDR_BITS-1:0]            s_axil_araddr,
    input  wire logic                            s_axil_arvalid,
    output      logic                            s_axil_arready,
    output      logic [31:0]                     s_axil_rdata,
    output      logic [1:0]                      s_axil_rresp,
    output      logic                            s_axil_rvalid,
    input  wire logic                            s_axil_rready,
    // Video in and out: stereo_top's streams.
`include "stereo_stream_ports.svh"
);
  localparam int R = WINDOW / 2;
  localparam int TAP_BITS = fx_pkg::TAP_BITS;
  localparam logic [31:0] ID = 32'(fx_pkg::REGMAP_ID);
  localparam logic [31:0] REGMAP_VERSION = 32'(fx_pkg::REGMAP_VERSION);
  localparam int KERNEL_BASE = fx_pkg::REG_KERNEL;

  `STEREO_ASSERT(addr_bits_range, ADDR_BITS >= 8 && ADDR_BITS <= 32, "ADDR_BITS must be 8 .. 32")
  `STEREO_ASSERT(kernel_registers_fit, KERNEL_BASE + 4 * WINDOW <= (1 << ADDR_BITS),
                 "the KERNEL registers of WINDOW taps must fit in the ADDR_BITS address space")

  // ---- registers ------------------------------------------------------------------------------
  fx_pkg::cfg_size_t cfg_width, cfg_height;
  fx_pkg::cfg_ndisp_t cfg_ndisp;
  fx_pkg::cfg_radius_t cfg_radius;
  logic cfg_use_ca;
  fx_pkg::cfg_min_disp_t cfg_min_disp;
  logic cfg_uniqueness_en, cfg_lr_en, cfg_subpixel_en;
  fx_pkg::cfg_uniqueness_t cfg_uniqueness;
  fx_pkg::cfg_lr_tolerance_t cfg_lr_tolerance;
  logic [WINDOW*TAP_BITS-1:0] cfg_kernel;
  logic [31:0] frames_in, frames_out, stalls;
  logic soft_reset;
  logic [fx_pkg::STATUS_BITS-1:0] core_status;

  function automatic logic [WINDOW*TAP_BITS-1:0] default_kernel();
    for (int i = 0; i < WINDOW; i++) begin
      default_kernel[i*TAP_BITS+:TAP_BITS] = TAP_BITS'(fx_pkg::default_tap(WINDOW, i));
    end
  endfunction

  // A 32-bit register word with the write strobes applied.
  function automatic logic [31:0] merge(input logic [31:0] old, input logic [31:0] data,
                                        input logic [3:0] strobe);
    for (int b = 0; b < 4; b++) begin
      merge[b*8+:8] = strobe[b] ? data[b*8+:8] : old[b*8+:8];
    end
  endfunction

  // ---- AXI4-Lite write: address and data in either order, one response at a time -------------
  logic [ADDR_BITS-1:0] write_addr;
  logic write_addr_held, write_data_held;
  logic [31:0] write_data;
  logic [3:0] write_strobe;
  assign s_axil_awready = !write_addr_held && !s_axil_bvalid;
  assign s_axil_wready = !write_data_held && !s_axil_bvalid;
  assign s_axil_bresp = 2'b00;  // OKAY

  logic write_now;  // both halves present this cycle
  logic [ADDR_BITS-1:0] write_addr_now;
  logic [31:0] write_data_now;
  logic [3:0] write_strobe_now;
  always_comb begin
    write_addr_now = write_addr_held ? write_addr : s_axil_awaddr;
    write_data_now = write_data_held ? write_data : s_axil_wdata;
    write_strobe_now = write_data_held ? write_strobe : s_axil_wstrb;
    write_now = (write_addr_held || (s_axil_awvalid && s_axil_awready)) &&
                (write_data_held || (s_axil_wvalid && s_axil_wready));
  end

  // The register word at a word offset, for reads and for merging partial writes.
  function automatic logic [31:0] register_word(input logic [ADDR_BITS-1:0] addr);
    logic [ADDR_BITS-1:0] word;
    word = addr & ~(ADDR_BITS'(3));
    register_word = '0;
    case (32'(word))
      fx_pkg::REG_ID: register_word = ID;
      fx_pkg::REG_VERSION: register_word = REGMAP_VERSION;
      fx_pkg::REG_MAX_SIZE: begin
        register_word[fx_pkg::REG_MAX_SIZE_WIDTH_LSB+:fx_pkg::REG_MAX_SIZE_WIDTH_BITS] =
            fx_pkg::REG_MAX_SIZE_WIDTH_BITS'(WIDTH);
        register_word[fx_pkg::REG_MAX_SIZE_HEIGHT_LSB+:fx_pkg::REG_MAX_SIZE_HEIGHT_BITS] =
            fx_pkg::REG_MAX_SIZE_HEIGHT_BITS'(HEIGHT);
      end
      fx_pkg::REG_BUILD: begin
        register_word[fx_pkg::REG_BUILD_NDISP_LSB+:fx_pkg::REG_BUILD_NDISP_BITS] =
            fx_pkg::REG_BUILD_NDISP_BITS'(NDISP);
        register_word[fx_pkg::REG_BUILD_RADIUS_LSB+:fx_pkg::REG_BUILD_RADIUS_BITS] =
            fx_pkg::REG_BUILD_RADIUS_BITS'(R);
        register_word[fx_pkg::REG_BUILD_MAX_MIN_DISP_LSB+:fx_pkg::REG_BUILD_MAX_MIN_DISP_BITS] =
            fx_pkg::REG_BUILD_MAX_MIN_DISP_BITS'(MAX_MIN_DISP);
        register_word[fx_pkg::REG_BUILD_RUNTIME_KERNEL_LSB] = RUNTIME_KERNEL;
        register_word[fx_pkg::REG_BUILD_COST_LSB+:fx_pkg::REG_BUILD_COST_BITS] =
            fx_pkg::REG_BUILD_COST_BITS'(COST);
      end
      fx_pkg::REG_FRAME: begin
        register_word[fx_pkg::REG_FRAME_WIDTH_LSB+:fx_pkg::REG_FRAME_WIDTH_BITS] = cfg_width;
        register_word[fx_pkg::REG_FRAME_HEIGHT_LSB+:fx_pkg::REG_FRAME_HEIGHT_BITS] = cfg_height;
      end
      fx_pkg::REG_MATCH: begin
        register_word[fx_pkg::REG_MATCH_NDISP_LSB+:fx_pkg::REG_MATCH_NDISP_BITS] = cfg_ndisp;
        register_word[fx_pkg::REG_MATCH_RADIUS_LSB+:fx_pkg::REG_MATCH_RADIUS_BITS] = cfg_radius;
        register_word[fx_pkg::REG_MATCH_USE_CA_LSB] = cfg_use_ca;
      end
      fx_pkg::REG_STAGE6: begin
        register_word[fx_pkg::REG_STAGE6_MIN_DISP_LSB+:fx_pkg::REG_STAGE6_MIN_DISP_BITS] =
            cfg_min_disp;
        register_word[fx_pkg::REG_STAGE6_UNIQUENESS_EN_LSB] = cfg_uniqueness_en;
        register_word[fx_pkg::REG_STAGE6_LR_EN_LSB] = cfg_lr_en;
        register_word[fx_pkg::REG_STAGE6_SUBPIXEL_EN_LSB] = cfg_subpixel_en;
      end
      fx_pkg::REG_THRESHOLDS: begin
        register_word[fx_pkg::REG_THRESHOLDS_UNIQUENESS_LSB+:fx_pkg::REG_THRESHOLDS_UNIQUENESS_BITS] =
            cfg_uniqueness;
        register_word[fx_pkg::REG_THRESHOLDS_LR_TOLERANCE_LSB+:fx_pkg::REG_THRESHOLDS_LR_TOLERANCE_BITS] =
            cfg_lr_tolerance;
      end
      fx_pkg::REG_STATUS: register_word = 32'(core_status);
      fx_pkg::REG_FRAMES_IN: register_word = frames_in;
      fx_pkg::REG_FRAMES_OUT: register_word = frames_out;
      fx_pkg::REG_STALLS: register_word = stalls;
      default: begin
        for (int i = 0; i < WINDOW; i++) begin
          if (32'(word) == KERNEL_BASE + 4 * i) begin
            register_word = 32'(cfg_kernel[i*TAP_BITS+:TAP_BITS]);
          end
        end
      end
    endcase
  endfunction

  // The word written this cycle: its offset and its value with the strobes applied.
  logic [ADDR_BITS-1:0] write_word;
  logic [31:0] write_value;
  always_comb begin
    write_word = write_addr_now & ~(ADDR_BITS'(3));
    write_value = merge(register_word(write_addr_now), write_data_now, write_strobe_now);
  end

  always_ff @(posedge clk) begin
    soft_reset <= 1'b0;
    if (rst) begin
      write_addr_held <= 1'b0;
      write_data_held <= 1'b0;
      s_axil_bvalid <= 1'b0;
      write_addr <= '0;
      write_data <= '0;
      write_strobe <= '0;
      cfg_width <= fx_pkg::CFG_SIZE_BITS'(WIDTH);
      cfg_height <= fx_pkg::CFG_SIZE_BITS'(HEIGHT);
      cfg_ndisp <= fx_pkg::CFG_NDISP_BITS'(NDISP);
      cfg_radius <= fx_pkg::CFG_RADIUS_BITS'(R);
      cfg_use_ca <= 1'b1;
      cfg_min_disp <= '0;
      cfg_uniqueness_en <= 1'b0;
      cfg_lr_en <= 1'b0;
      cfg_subpixel_en <= 1'b0;
      cfg_uniqueness <= fx_pkg::CFG_UNIQUENESS_BITS'(fx_pkg::REG_THRESHOLDS_RESET);
      cfg_lr_tolerance <= '0;
      cfg_kernel <= default_kernel();
    end else begin
      if (s_axil_bvalid && s_axil_bready) s_axil_bvalid <= 1'b0;
      if (write_now) begin
        write_addr_held <= 1'b0;
        write_data_held <= 1'b0;
        s_axil_bvalid <= 1'b1;
        begin
          case (32'(write_word))
            fx_pkg::REG_FRAME: begin
              cfg_width <= write_value[fx_pkg::REG_FRAME_WIDTH_LSB+:fx_pkg::REG_FRAME_WIDTH_BITS];
              cfg_height <= write_value[fx_pkg::REG_FRAME_HEIGHT_LSB+:fx_pkg::REG_FRAME_HEIGHT_BITS];
            end
            fx_pkg::REG_MATCH: begin
              cfg_ndisp <= write_value[fx_pkg::REG_MATCH_NDISP_LSB+:fx_pkg::REG_MATCH_NDISP_BITS];
              cfg_radius <= write_value[fx_pkg::REG_MATCH_RADIUS_LSB+:fx_pkg::REG_MATCH_RADIUS_BITS];
              cfg_use_ca <= write_value[fx_pkg::REG_MATCH_USE_CA_LSB];
            end
            fx_pkg::REG_STAGE6: begin
              cfg_min_disp <=
                  write_value[fx_pkg::REG_STAGE6_MIN_DISP_LSB+:fx_pkg::REG_STAGE6_MIN_DISP_BITS];
              cfg_uniqueness_en <= write_value[fx_pkg::REG_STAGE6_UNIQUENESS_EN_LSB];
              cfg_lr_en <= write_value[fx_pkg::REG_STAGE6_LR_EN_LSB];
              cfg_subpixel_en <= write_value[fx_pkg::REG_STAGE6_SUBPIXEL_EN_LSB];
            end
            fx_pkg::REG_THRESHOLDS: begin
              cfg_uniqueness <= write_value[fx_pkg::REG_THRESHOLDS_UNIQUENESS_LSB+:
                                            fx_pkg::REG_THRESHOLDS_UNIQUENESS_BITS];
              cfg_lr_tolerance <= write_value[fx_pkg::REG_THRESHOLDS_LR_TOLERANCE_LSB+:
                                              fx_pkg::REG_THRESHOLDS_LR_TOLERANCE_BITS];
            end
            fx_pkg::REG_CONTROL:
            soft_reset <= write_strobe_now[0] && write_data_now[fx_pkg::REG_CONTROL_SOFT_RESET_LSB];
            default: begin
              for (int i = 0; i < WINDOW; i++) begin
                if (32'(write_word) == KERNEL_BASE + 4 * i) begin
                  cfg_kernel[i*TAP_BITS+:TAP_BITS] <= write_value[TAP_BITS-1:0];
                end
              end
            end
          endcase
        end
      end else begin
        if (s_axil_awvalid && s_axil_awready) begin
          write_addr_held <= 1'b1;
          write_addr <= s_axil_awaddr;
        end
        if (s_axil_wvalid && s_axil_wready) begin
          write_data_held <= 1'b1;
          write_data <= s_axil_wdata;
          write_strobe <= s_axil_wstrb;
        end
      end
    end
  end

  // ---- AXI4-Lite read -------------------------------------------------------------------------
  assign s_axil_arready = !s_axil_rvalid;
  assign s_axil_rresp = 2'b00;  // OKAY
  always_ff @(posedge clk) begin
    if (rst) begin
      s_axil_rvalid <= 1'b0;
      s_axil_rdata <= '0;
    end else if (s_axil_arvalid && s_axil_arready) begin
      s_axil_rvalid <= 1'b1;
      s_axil_rdata <= register_word(s_axil_araddr);
    end else if (s_axil_rready) begin
      s_axil_rvalid <= 1'b0;
    end
  end

  // ---- counters -------------------------------------------------------------------------------
  always_ff @(posedge clk) begin
    if (rst || soft_reset) begin
      frames_in <= '0;
      frames_out <= '0;
      stalls <= '0;
    end else begin
      if (s_axis_tvalid && s_axis_tready && s_axis_tuser) frames_in <= frames_in + 1;
      if (m_axis_tvalid && m_axis_tready && m_axis_tuser) frames_out <= frames_out + 1;
      if (m_axis_tvalid && !m_axis_tready) stalls <= stalls + 1;
    end
  end

  // ---- the core -------------------------------------------------------------------------------
  stereo_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL), .MAX_MIN_DISP(MAX_MIN_DISP), .COST(COST), .LANES(LANES),
      .SHIFT_ADD(SHIFT_ADD), .RECOMPUTE_COSTS(RECOMPUTE_COSTS)
  ) core (
      .rst(rst || soft_reset),
      .status(core_status),
      .*  // every other port: the signal of the same name
  );
endmodule

`default_nettype wire
