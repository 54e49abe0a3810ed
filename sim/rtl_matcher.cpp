// The Verilated RTL as an engine of the matcher registry: `stereo match --engine rtl` streams the
// pair through the smallest built stereo_top configuration that covers it (no stalls) and
// returns what the core wrote; `--method hierarchical --engine rtl` streams it through the built
// stereo_hier_top as a steady rig until the host's plane settles. `stereo cosim` adds traffic
// shaping, traces and the comparison.
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "hier_top_sim.hpp"
#include "stereo/asw.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical_plane.hpp"
#include "stereo/stages/lcdm.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::sim {
namespace {

// One frame through a reset and configured core, without stalls.
ValidatedDisparity stream_frame(TopSim& top, const Image& left, const Image& right) {
    const auto beats = frame_beats(left, right);
    const StreamResult result = top.stream(beats, beats.size(), {}, 100 * beats.size() + 100000);
    if (!result.completed || !result.protocol_error.empty()) {
        throw std::runtime_error(
            "the RTL did not complete the frame: " +
            (result.protocol_error.empty() ? std::string("it stalled") : result.protocol_error));
    }
    return assemble_validated(result.outputs, 0, left.width, left.height);
}

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
    return stream_frame(*top, left, right);
}

ValidatedDisparity run_asw_rtl(const Image& left, const Image& right, const MatchParams& params,
                               const asw::Params& weights) {
    check_pair(left, right);
    const TopConfig& config = asw_top_config(left.width, left.height, params, weights);
    const auto top = make_top_sim(config);
    top->reset();
    MatchParams ports = params;
    ports.window = config.window;  // cfg_radius: the core's (the diameter is its WINDOW)
    top->set_params({left.width, left.height, ports});
    return stream_frame(*top, left, right);
}

// The frames of a steady rig until the plane settles, at most: the start frame, the mode's and
// vertical_plane's 16 fits (its max_iterations), the last of which runs along the 16th fit.
constexpr int kHierarchicalMaxFrames = 2 + 16;

MatchResult run_hier_rtl(const Image& left, const Image& right,
                         const hierarchical::Params& params) {
    check_pair(left, right);
    check_hier_top(params, left.width, left.height);
    // After frame t >= 1 (a fit frame) frame t ran along vertical_plane's plane when the host's
    // fit repeats the frame's setting (its inliers no longer change) or fails (vertical_plane
    // keeps the last plane; the tracker would start again from the mode).
    int frame = 0;
    const auto settled = [&frame](const HierTopFrame& done) {
        const bool fit_frame = frame++ >= 1;
        return fit_frame && (done.next == done.setting ||
                             done.next.tolerance == hierarchical::kFirstFitTolerance);
    };
    HierTopRunOptions options;
    options.frames = kHierarchicalMaxFrames;
    options.stop_after = settled;
    HierTopRun run = run_hier_top(left, right, params, options);
    HierPassOutput last = std::move(run.frames.back().output);
    MatchResult result;
    result.disparity = to_label_map(last.validated);
    result.vertical = std::move(last.vertical);
    result.validated = std::move(last.validated);
    result.counts.emplace_back("rtl_frames", static_cast<std::int64_t>(run.frames.size()));
    result.counts.emplace_back("rtl_clocks", static_cast<std::int64_t>(run.total_clocks));
    return result;
}

// The hierarchical search's whole core: its plane field only (the hardware form of
// FieldModel::plane), within the built configuration.
std::unique_ptr<Matcher> make_hier_rtl(const MatchConfig& config) {
    const hierarchical::Params params = hierarchical_params(config);
    if (params.output != hierarchical::Output::vertical_field ||
        params.field_model != hierarchical::FieldModel::plane) {
        throw std::invalid_argument(
            "the hierarchical core (engine rtl) computes the plane field only: use --field " +
            std::string(hierarchical::field_model_name(hierarchical::FieldModel::plane)));
    }
    check_hier_top(params);
    return std::make_unique<FunctionMatcher>(
        [params](int width, int height) { check_hier_top(params, width, height); },
        [params](const Image& left, const Image& right) {
            return run_hier_rtl(left, right, params);
        });
}

}  // namespace

void register_matchers(MatcherRegistry& registry) {
    registry.add({"pipeline", "rtl", "Sec. 3.1 pipeline, the Verilated RTL (built configurations)",
                  pipeline_factory(&run_rtl)});
    registry.add({"asw", "rtl",
                  "Sec. 3.4 separable adaptive support weights, the Verilated stereo_top ASW = 1 "
                  "(64x48, 16 labels; census at diameter 5, AD at 31)",
                  asw_factory(&run_asw_rtl)});
    registry.add({"hierarchical", "rtl",
                  "Sec. 3.3 search with the plane field, the Verilated stereo_hier_top (64x48, "
                  "16 labels, pass window 5) as a steady rig until the host's plane settles",
                  &make_hier_rtl});
}

}  // namespace stereo::sim
