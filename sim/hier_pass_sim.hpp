// The Verilated stereo_hier_pass (the hierarchical core's 1-D pass along a plane, issue 45;
// docs/hierarchical.md "The streaming core") behind a small interface, and what the model says it
// computes: stereo::hierarchical::match_along_field over plane_field(plane) and the vertical
// offset of each valid pixel (field_at_match). Used by tb_stereo_hier_pass, and the model's side
// and the beats' form by the whole core's driver (hier_top_sim.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "stereo/hierarchical.hpp"
#include "stereo/validated.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::sim {

// The Verilated configuration's parameters (stage_table.hpp: stereo_hier_pass's defaults).
struct HierPassLimits {
    int width = 64;
    int height = 48;
    int ndisp = 16;
    int window = 5;
    int v_min = -8;
    int v_max = 7;
};
inline constexpr HierPassLimits kHierPassLimits{};

// The pass's output: stage 6's map and the vertical offset of each pixel (0 where invalid).
struct HierPassOutput {
    ValidatedDisparity validated;
    std::vector<std::int8_t> vertical;
};

// The model's output for a frame streamed with `plane` (params: the pass's cost, window, CA and
// validation; the field's range is kHierPassLimits').
HierPassOutput hier_pass_expected(const Image& left, const Image& right,
                                  const hierarchical::Plane& plane,
                                  const hierarchical::Params& params);

// The RTL's output beats of one frame (from beat `first` on), in the model's form; throws
// std::runtime_error on missing beats or wrong tuser/tlast framing.
HierPassOutput hier_pass_assemble(const std::vector<OutputBeat>& beats, std::size_t first,
                                  int width, int height);

class HierPassSim {
  public:
    HierPassSim();
    ~HierPassSim();
    HierPassSim(const HierPassSim&) = delete;
    HierPassSim& operator=(const HierPassSim&) = delete;

    void reset();
    // The ports of a frame's setting (held until the core samples them at its start of frame).
    void configure(int width, int height, const hierarchical::Plane& plane,
                   const hierarchical::Params& params);
    // Streams `beats` under `traffic` until `expected_outputs` output beats arrived or
    // `max_cycles` passed. `first_result(n)`, when given, is called when the first result of
    // the n-th frame (from 1) leaves the core (a host would write the next setting then).
    StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                        const Traffic& traffic, std::uint64_t max_cycles,
                        const std::function<void(std::size_t)>& first_result = {});

  private:
    struct Model;
    std::unique_ptr<Model> model_;
};

}  // namespace stereo::sim
