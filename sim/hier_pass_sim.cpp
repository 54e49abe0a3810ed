// The Verilated stereo_hier_pass behind HierPassSim (hier_pass_sim.hpp).
#include "hier_pass_sim.hpp"

#include <stdexcept>
#include <string>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_hier_pass.h"
#include "axis_driver.hpp"
#include "port_bits.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "verilated_harness.hpp"

namespace stereo::sim {

HierPassOutput hier_pass_expected(const Image& left, const Image& right,
                                  const hierarchical::Plane& plane,
                                  const hierarchical::Params& params) {
    const int width = left.width;
    const auto field = hierarchical::plane_field(plane, width, left.height, kHierPassLimits.v_min,
                                                 kHierPassLimits.v_max);
    std::int64_t count = 0;
    HierPassOutput out{hierarchical::match_along_field(left, right, field, params, count), {}};
    out.vertical.assign(field.size(), 0);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = out.validated.index(x, y);
            if (out.validated.valid(p)) {
                out.vertical[p] = static_cast<std::int8_t>(
                    hierarchical::field_at_match(field, width, x, y, out.validated.fixed[p]));
            }
        }
    }
    return out;
}

HierPassOutput hier_pass_assemble(const std::vector<OutputBeat>& beats, std::size_t first,
                                  int width, int height) {
    // The low 32 bits are stereo_top's beat (assemble_validated checks its framing and padding).
    HierPassOutput out{assemble_validated(beats, first, width, height), {}};
    out.vertical.resize(static_cast<std::size_t>(width) * height);
    for (std::size_t p = 0; p < out.vertical.size(); ++p) {
        out.vertical[p] = static_cast<std::int8_t>((beats[first + p].data >> 32) & 0xffU);
    }
    return out;
}

struct HierPassSim::Model {
    VerilatedHarness<Vstereo_hier_pass> harness{"hier_pass"};
};

HierPassSim::HierPassSim() : model_(std::make_unique<Model>()) {
    reset();
}
HierPassSim::~HierPassSim() = default;

void HierPassSim::reset() {
    Vstereo_hier_pass& m = model_->harness.model();
    m.s_axis_tvalid = 0;
    m.m_axis_tready = 0;
    m.rst = 1;
    model_->harness.tick();
    model_->harness.tick();
    m.rst = 0;
}

void HierPassSim::configure(int width, int height, const hierarchical::Plane& plane,
                            const hierarchical::Params& params) {
    Vstereo_hier_pass& m = model_->harness.model();
    const int window = params.field_level.window;
    if (width < 1 || width > kHierPassLimits.width || height < 1 ||
        height > kHierPassLimits.height || params.ndisp < 1 ||
        params.ndisp > kHierPassLimits.ndisp || window > kHierPassLimits.window) {
        throw std::invalid_argument(
            "stereo_hier_pass holds " + std::to_string(kHierPassLimits.width) + "x" +
            std::to_string(kHierPassLimits.height) + ", " + std::to_string(kHierPassLimits.ndisp) +
            " labels, window " + std::to_string(kHierPassLimits.window));
    }
    m.cfg_width = static_cast<std::uint16_t>(width);
    m.cfg_height = static_cast<std::uint16_t>(height);
    m.cfg_ndisp = static_cast<std::uint16_t>(params.ndisp);
    m.cfg_radius = static_cast<std::uint8_t>(window / 2);
    // The window's kernel centred in the core's WINDOW taps, zero beside it.
    MatchParams match;
    match.window = window;
    match.sigma = params.field_level.sigma;
    const auto kernel = centred_kernel(match, kHierPassLimits.window);
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
    m.plane_a = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.a));
    m.plane_b = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.b));
    m.plane_c = static_cast<std::uint32_t>(static_cast<std::int32_t>(plane.c));
}

StreamResult HierPassSim::stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                                 const Traffic& traffic, std::uint64_t max_cycles,
                                 const std::function<void(std::size_t)>& first_result) {
    std::size_t results_started = 0;
    bool first_beat_seen = false;
    auto after_edge = [&](const Vstereo_hier_pass& m) {
        const bool first_beat = m.m_axis_tvalid != 0 && m.m_axis_tuser != 0;
        if (first_beat && !first_beat_seen && first_result) {
            first_result(++results_started);
        }
        first_beat_seen = first_beat;
    };
    return stream_axis(model_->harness, beats, expected_outputs, traffic, max_cycles, after_edge);
}

}  // namespace stereo::sim
