// The Verilated stereo_hier_pass behind HierPassSim (hier_pass_sim.hpp).
#include "hier_pass_sim.hpp"

#include <stdexcept>
#include <string>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_hier_pass.h"
#include "axis_driver.hpp"
#include "hier_pass_ports.hpp"
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
    reset_axis_core(model_->harness);
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
    put_pass_config(m, width, height, params, kHierPassLimits.window);
    put_plane(m, plane);
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
