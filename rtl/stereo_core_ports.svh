// The ports stereo_top shares with stereo_synth_top, which ties its window configuration
// (cfg_radius, cfg_kernel) to constants: the rest of the run-time configuration, sampled when the
// core takes the start-of-frame beat from its input slice, the sticky status bits and the
// AXI4-Stream ports (stereo_stream_ports.svh). Included at the end of both port lists.
    input  wire fx_pkg::cfg_size_t               cfg_width,
    input  wire fx_pkg::cfg_size_t               cfg_height,
    input  wire fx_pkg::cfg_ndisp_t              cfg_ndisp,
    input  wire logic                            cfg_use_ca,
    // Stage 6 (docs/fixed-point.md): signed minimum disparity, uniqueness ratio U (percent),
    // left-right tolerance T (labels), sub-pixel refinement; each check has an enable.
    input  wire fx_pkg::cfg_min_disp_t           cfg_min_disp,
    input  wire logic                            cfg_uniqueness_en,
    input  wire fx_pkg::cfg_uniqueness_t         cfg_uniqueness,
    input  wire logic                            cfg_lr_en,
    input  wire fx_pkg::cfg_lr_tolerance_t       cfg_lr_tolerance,
    input  wire logic                            cfg_subpixel_en,
    output      logic [fx_pkg::STATUS_BITS-1:0]  status,  // sticky, STATUS_* bits
`include "stereo_stream_ports.svh"
