#include "stereo_hls_synth_top.hpp"

#include "stereo/hls/top.hpp"

using namespace stereo::hls;

status_t stereo_hls_synth_top(stream<InputBeat>& s_axis, stream<OutputBeat>& m_axis,
                              std::uint16_t cfg_width, std::uint16_t cfg_height,
                              std::uint16_t cfg_ndisp, std::uint8_t cfg_radius,
                              const tap_t cfg_kernel[synth::kWindow], bool cfg_use_ca) {
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
#pragma HLS INTERFACE s_axilite port = return bundle = control
    static pipeline<synth::kWidth, synth::kHeight, synth::kNdisp, synth::kWindow> state;
    FrameConfig<synth::kWindow> cfg;
    cfg.width = cfg_width;
    cfg.height = cfg_height;
    cfg.ndisp = cfg_ndisp;
    cfg.radius = cfg_radius;
    cfg.use_ca = cfg_use_ca;
    for (int i = 0; i < synth::kWindow; ++i) {
        cfg.kernel[i] = cfg_kernel[i];
    }
    return stereo_hls_top(s_axis, m_axis, cfg, state);
}
