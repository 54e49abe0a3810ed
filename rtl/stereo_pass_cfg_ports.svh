// The hierarchical pass's run-time configuration (stereo_top's, without the minimum disparity:
// the pass searches 0 .. cfg_ndisp - 1), sampled with the frame's plane when its first beat is
// taken. Included in the port lists of stereo_hier_pass and stereo_hier_top, which declare the
// parameter WINDOW.
    input  wire fx_pkg::cfg_radius_t                cfg_radius,
    /* verilator lint_off UNUSEDSIGNAL */  // ignored with RUNTIME_KERNEL = 0
    input  wire logic [WINDOW*fx_pkg::TAP_BITS-1:0] cfg_kernel,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::cfg_size_t                  cfg_width,
    input  wire fx_pkg::cfg_size_t                  cfg_height,
    input  wire fx_pkg::cfg_ndisp_t                 cfg_ndisp,
    input  wire logic                               cfg_use_ca,
    input  wire logic                               cfg_uniqueness_en,
    input  wire fx_pkg::cfg_uniqueness_t            cfg_uniqueness,
    input  wire logic                               cfg_lr_en,
    input  wire fx_pkg::cfg_lr_tolerance_t          cfg_lr_tolerance,
    input  wire logic                               cfg_subpixel_en,
