// The Verilated RTL as an engine of the matcher registry: `stereo match --engine rtl` streams the
// pair through the smallest built stereo_top configuration that covers it (no stalls) and
// returns what the core wrote. `stereo cosim` adds traffic shaping, traces and the comparison.
#include <stdexcept>
#include <string>

#include "stereo/catalogue.hpp"
#include "stereo/stages/lcdm.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::sim {
namespace {

ValidatedDisparity run_rtl(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    catalogue::require_cost(params.cost, catalogue::CostUse::hardware, "the RTL");
    const bool lcdm = catalogue::cost(params.cost).id == catalogue::Cost::lcdm;
    if (lcdm) {
        lcdm::require_colour(left);
    }
    const TopConfig* config = covering_config(left.width, left.height, params.ndisp, params.window,
                                              params.min_disp, params.cost);
    if (config == nullptr) {
        const TopConfig& largest = largest_config(params.cost);
        throw std::invalid_argument(
            "no Verilated configuration covers " + std::to_string(left.width) + "x" +
            std::to_string(left.height) + " ndisp " + std::to_string(params.ndisp) + " window " +
            std::to_string(params.window) + " min_disp " + std::to_string(params.min_disp) +
            "; the largest built is " + std::to_string(largest.width) + "x" +
            std::to_string(largest.height) + " ndisp " + std::to_string(largest.ndisp) +
            " window " + std::to_string(largest.window) +
            " |min_disp| <= " + std::to_string(largest.max_min_disp) +
            " (stereo cosim --crop, or -DSTEREO_COSIM_FULL=ON)");
    }
    const auto top = make_top_sim(*config);
    top->reset();
    top->set_params({left.width, left.height, params});
    const auto beats = frame_beats(left, right);
    const StreamResult result = top->stream(beats, beats.size(), {}, 100 * beats.size() + 100000);
    if (!result.completed || !result.protocol_error.empty()) {
        throw std::runtime_error(
            "the RTL did not complete the frame: " +
            (result.protocol_error.empty() ? std::string("it stalled") : result.protocol_error));
    }
    return assemble_validated(result.outputs, 0, left.width, left.height);
}

}  // namespace

void register_matchers(MatcherRegistry& registry) {
    registry.add({"pipeline", "rtl", "Sec. 3.1 pipeline, the Verilated RTL (built configurations)",
                  pipeline_factory(&run_rtl)});
}

}  // namespace stereo::sim
