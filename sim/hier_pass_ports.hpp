// The hierarchical pass's configuration ports (rtl/stereo_pass_cfg_ports.svh), shared by
// stereo_hier_pass and stereo_hier_top: the frame's size, the pass's labels, window, CA and
// stage 6. Include the Verilated model's header before this one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "port_bits.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::sim {

// The pass's window (up to `core_window`, the module's WINDOW) centred in the core's taps.
template <typename Model>
void put_pass_config(Model& m, int width, int height, const hierarchical::Params& params,
                     int core_window) {
    m.cfg_width = static_cast<std::uint16_t>(width);
    m.cfg_height = static_cast<std::uint16_t>(height);
    m.cfg_ndisp = static_cast<std::uint16_t>(params.ndisp);
    m.cfg_radius = static_cast<std::uint8_t>(params.field_level.window / 2);
    MatchParams match;
    match.window = params.field_level.window;
    match.sigma = params.field_level.sigma;
    const auto kernel = centred_kernel(match, core_window);
    for (std::size_t i = 0; i < kernel.size(); ++i) {
        put_bits(m.cfg_kernel, static_cast<int>(i) * table::kTapBits, table::kTapBits,
                 static_cast<std::uint64_t>(kernel[i]));
    }
    m.cfg_use_ca = params.use_ca ? 1 : 0;
    m.cfg_uniqueness_en = params.validation.uniqueness ? 1 : 0;
    m.cfg_uniqueness = static_cast<std::uint8_t>(params.validation.uniqueness_ratio);
    m.cfg_lr_en = params.validation.left_right ? 1 : 0;
    m.cfg_lr_tolerance = static_cast<std::uint8_t>(params.validation.lr_tolerance);
    m.cfg_subpixel_en = params.validation.subpixel ? 1 : 0;
}

// The plane's coefficients as the 32-bit signed ports take them.
template <typename Model>
void put_plane(Model& m, const hierarchical::Plane& plane) {
    m.plane_a = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.a));
    m.plane_b = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.b));
    m.plane_c = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.c));
}

}  // namespace stereo::sim
