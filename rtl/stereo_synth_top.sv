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
    parameter int RING_BLOCK_MIN_FILL = 50,  // stereo_group_ring BLOCK_MIN_FILL
    parameter fx_pkg::cost_e COST = fx_pkg::COST_AD,  // COST_AD, COST_LCDM or COST_CENSUS
    // Tap products from shifts and adds (stereo_top SHIFT_ADD): none, census vertical, all
    parameter fx_pkg::shift_add_e SHIFT_ADD = fx_pkg::SHIFT_ADD_NONE,
    // The lean memory architecture (stereo_top RECOMPUTE_COSTS; census or AD)
    parameter bit RECOMPUTE_COSTS = 1'b0,
    // Adaptive support weights of diameter WINDOW (stereo_top ASW; census or AD)
    parameter bit ASW = 1'b0
) (
    input  wire logic                            clk,
    input  wire logic                            rst,
`include "stereo_core_ports.svh"
);
  stereo_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW), .RUNTIME_KERNEL(1'b0),
      .MAX_MIN_DISP(MAX_MIN_DISP), .LANES(LANES), .RING_BLOCK_RAM(RING_BLOCK_RAM),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL), .COST(COST),
      .SHIFT_ADD(SHIFT_ADD), .RECOMPUTE_COSTS(RECOMPUTE_COSTS), .ASW(ASW)
  ) core (
      .cfg_radius(fx_pkg::CFG_RADIUS_BITS'(WINDOW / 2)),
      .cfg_kernel('0),  // unused: the kernel is constant
      .*  // every other port: the signal of the same name
  );
endmodule
/* verilator lint_on MULTITOP */

`default_nettype wire
