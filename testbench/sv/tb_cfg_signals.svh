  // The frame configuration tb_stereo_vectors reads from the vectors and drives (stereo_top's
  // cfg_* ports, or the AXI4-Lite registers of stereo_axil_top).
  fx_pkg::cfg_size_t cfg_width, cfg_height;
  fx_pkg::cfg_ndisp_t cfg_ndisp;
  fx_pkg::cfg_radius_t cfg_radius;
  logic [WINDOW*fx_pkg::TAP_BITS-1:0] cfg_kernel;
  logic cfg_use_ca, cfg_uniqueness_en, cfg_lr_en, cfg_subpixel_en;
  fx_pkg::cfg_min_disp_t cfg_min_disp;
  fx_pkg::cfg_uniqueness_t cfg_uniqueness;
  fx_pkg::cfg_lr_tolerance_t cfg_lr_tolerance;
