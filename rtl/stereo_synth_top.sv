// stereo_synth_top: stereo_top as it is built for an FPGA (docs/synthesis.md).
//
// The aggregation kernel is the model's default for WINDOW (fx_pkg::default_tap, sigma 3) and is
// a constant here (stereo_top RUNTIME_KERNEL = 0), so every tap multiplier reduces to shifts and
// adds; the radius is WINDOW/2.
// Frame size, label count, the CA switch and stage 6's configuration stay run-time inputs. Everything else, including
// the AXI4-Stream ports and the latency, is stereo_top's.
`default_nettype none

// Two tops in rtl/files.f (this FPGA build and stereo_axil_top): linting every file at once is fine.
/* verilator lint_off MULTITOP */
module stereo_synth_top #(
    parameter int WIDTH  = 64,  // largest frame width
    parameter int HEIGHT = 48,  // largest frame height
    parameter int NDISP  = 16,  // disparities evaluated in parallel (largest cfg_ndisp)
    parameter int WINDOW = 5,   // aggregation window (odd), fixed by the constant kernel
    parameter int LANES  = NDISP,  // labels computed per clock: NDISP / LANES clocks per pixel
    // Largest |cfg_min_disp| (stereo_top's cost delay lines); 0: the range 0 .. ndisp-1 only.
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,
    // stereo_top RING_BLOCK_RAM: 1 for the iCE40 (synth.py sets it there).
    parameter bit RING_BLOCK_RAM = 1'b0,
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
    input  wire logic                            clk,
    input  wire logic                            rst,
    input  wire fx_pkg::cfg_size_t               cfg_width,
    input  wire fx_pkg::cfg_size_t               cfg_height,
    input  wire fx_pkg::cfg_ndisp_t              cfg_ndisp,
    input  wire logic                            cfg_use_ca,
    input  wire fx_pkg::cfg_min_disp_t           cfg_min_disp,
    input  wire logic                            cfg_uniqueness_en,
    input  wire fx_pkg::cfg_uniqueness_t         cfg_uniqueness,
    input  wire logic                            cfg_lr_en,
    input  wire fx_pkg::cfg_lr_tolerance_t       cfg_lr_tolerance,
    input  wire logic                            cfg_subpixel_en,
    input  wire logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata,
    input  wire logic                            s_axis_tvalid,
    output      logic                            s_axis_tready,
    input  wire logic                            s_axis_tlast,
    input  wire logic                            s_axis_tuser,
    output      fx_pkg::out_beat_t               m_axis_tdata,
    output      logic                            m_axis_tvalid,
    input  wire logic                            m_axis_tready,
    output      logic                            m_axis_tlast,
    output      logic                            m_axis_tuser,
    output      logic [fx_pkg::STATUS_BITS-1:0]  status
);
  stereo_top #(
      .WIDTH(WIDTH),
      .HEIGHT(HEIGHT),
      .NDISP(NDISP),
      .WINDOW(WINDOW),
      .RUNTIME_KERNEL(1'b0),
      .MAX_MIN_DISP(MAX_MIN_DISP),
      .LANES(LANES),
      .RING_BLOCK_RAM(RING_BLOCK_RAM),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) core (
      .clk(clk),
      .rst(rst),
      .cfg_width(cfg_width),
      .cfg_height(cfg_height),
      .cfg_ndisp(cfg_ndisp),
      .cfg_radius(fx_pkg::CFG_RADIUS_BITS'(WINDOW / 2)),
      .cfg_kernel('0),  // unused: the kernel is constant
      .cfg_use_ca(cfg_use_ca),
      .cfg_min_disp(cfg_min_disp),
      .cfg_uniqueness_en(cfg_uniqueness_en),
      .cfg_uniqueness(cfg_uniqueness),
      .cfg_lr_en(cfg_lr_en),
      .cfg_lr_tolerance(cfg_lr_tolerance),
      .cfg_subpixel_en(cfg_subpixel_en),
      .s_axis_tdata(s_axis_tdata),
      .s_axis_tvalid(s_axis_tvalid),
      .s_axis_tready(s_axis_tready),
      .s_axis_tlast(s_axis_tlast),
      .s_axis_tuser(s_axis_tuser),
      .m_axis_tdata(m_axis_tdata),
      .m_axis_tvalid(m_axis_tvalid),
      .m_axis_tready(m_axis_tready),
      .m_axis_tlast(m_axis_tlast),
      .m_axis_tuser(m_axis_tuser),
      .status(status)
  );
endmodule
/* verilator lint_on MULTITOP */

`default_nettype wire
