#include "stereo_hls_synth_top.hpp"

#include "stereo/hls/top.hpp"

using namespace stereo::hls;

status_t stereo_hls_synth_top(stream<InputBeat>& s_axis, stream<OutputBeat>& m_axis,
                              std::uint16_t cfg_width, std::uint16_t cfg_height,
                              std::uint16_t cfg_ndisp, std::uint8_t cfg_radius,
                              const tap_t cfg_kernel[synth::kWindow], bool cfg_use_ca,
                              std::int16_t cfg_min_disp, bool cfg_uniqueness_en,
                              std::uint8_t cfg_uniqueness, bool cfg_lr_en,
                              std::uint8_t cfg_lr_tolerance, bool cfg_subpixel_en) {
// Pixel streams as AXI4-Stream (the beat structs are packed into TDATA, sof/eol in-band); the
// configuration and the status as registers of one AXI4-Lite slave.
#pragma HLS INTERFACE axis port = s_axis
#pragma HLS INTERFACE axis port = m_axis
#pragma HLS INTERFACE s_axilite port = cfg_width bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_height bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_ndisp bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_radius bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_kernel bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_use_ca bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_min_disp bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_uniqueness_en bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_uniqueness bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_lr_en bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_lr_tolerance bundle = control
#pragma HLS INTERFACE s_axilite port = cfg_subpixel_en bundle = control
#pragma HLS INTERFACE s_axilite port = return bundle = control
    static pipeline<synth::kWidth, synth::kHeight, synth::kNdisp, synth::kWindow,
                    synth::kMaxMinDisp>
        state;
    FrameConfig<synth::kWindow> cfg;
    cfg.width = cfg_width;
    cfg.height = cfg_height;
    cfg.ndisp = cfg_ndisp;
    cfg.radius = cfg_radius;
    cfg.use_ca = cfg_use_ca;
    cfg.min_disp = cfg_min_disp;
    cfg.uniqueness = cfg_uniqueness_en;
    cfg.uniqueness_ratio = cfg_uniqueness;
    cfg.left_right = cfg_lr_en;
    cfg.lr_tolerance = cfg_lr_tolerance;
    cfg.subpixel = cfg_subpixel_en;
    for (int i = 0; i < synth::kWindow; ++i) {
        cfg.kernel[i] = cfg_kernel[i];
    }
    return stereo_hls_top(s_axis, m_axis, cfg, state);
}
