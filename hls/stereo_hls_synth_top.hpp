// The synthesisable top of the vendor flow (scripts/hls/run_vitis_hls.tcl): stereo_hls_top in
// one fixed variant, 640x480 frames, 64 disparity lanes, 11x11 window. The runtime
// configuration ports are the RTL's cfg_* ports; the testbench drives cfg_kernel with the
// model's default kernel (stereo::gaussian_kernel(11, fx::kDefaultSigma)).
#pragma once

#include <cstdint>

#include "stereo/hls/stream.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls::synth {
inline constexpr int kWidth = 640;
inline constexpr int kHeight = 480;
inline constexpr int kNdisp = 64;
inline constexpr int kWindow = 11;
inline constexpr int kMaxMinDisp = stereo::table::kDefaultMaxMinDisp;  // |cfg_min_disp|
}  // namespace stereo::hls::synth

// One frame per call; returns the status bits (stereo::hls::kStatus*). The stage state is a
// static object: RAM contents and registers persist from call to call, as in the RTL.
stereo::hls::status_t stereo_hls_synth_top(
    stereo::hls::stream<stereo::hls::InputBeat>& s_axis,
    stereo::hls::stream<stereo::hls::OutputBeat>& m_axis, std::uint16_t cfg_width,
    std::uint16_t cfg_height, std::uint16_t cfg_ndisp, std::uint8_t cfg_radius,
    const stereo::hls::tap_t cfg_kernel[stereo::hls::synth::kWindow], bool cfg_use_ca,
    std::int16_t cfg_min_disp, bool cfg_uniqueness_en, std::uint8_t cfg_uniqueness, bool cfg_lr_en,
    std::uint8_t cfg_lr_tolerance, bool cfg_subpixel_en);
