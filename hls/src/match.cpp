#include "stereo/hls/match.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "stereo/catalogue.hpp"
#include "stereo/hls/asw_match.hpp"
#include "stereo/hls/hierarchical.hpp"
#include "stereo/hls/host.hpp"
#include "stereo/hls/stream.hpp"
#include "stereo/hls/top.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::hls {
namespace {

template <int NDISP, int WINDOW, class MEASURE>
ValidatedDisparity run_variant(const Image& left, const Image& right, const MatchParams& params) {
    using Pipeline =
        pipeline<kHostMaxWidth, kHostMaxHeight, NDISP, WINDOW, kHostMaxMinDisp, MEASURE>;
    // Megabytes of line buffers: on the heap, never on the stack.
    const auto state = std::make_unique<Pipeline>();
    const FrameConfig<WINDOW> cfg = frame_config<WINDOW>(params, left.width, left.height);
    stream<InputBeat> in("match.in");
    stream<OutputBeat> out("match.out");
    push_frame(left, right, in);
    const status_t status =
        stereo_hls_top<kHostMaxWidth, kHostMaxHeight, NDISP, WINDOW, kHostMaxMinDisp, MEASURE>(
            in, out, cfg, *state);
    return finish_frame("HLS top", status, in, out, left.width, left.height);
}

template <int NDISP, class MEASURE>
ValidatedDisparity run_cost(const Image& left, const Image& right, const MatchParams& params,
                            const Variant& variant) {
    return variant.window == 11 ? run_variant<NDISP, 11, MEASURE>(left, right, params)
                                : run_variant<NDISP, 31, MEASURE>(left, right, params);
}

template <int NDISP>
ValidatedDisparity run_window(const Image& left, const Image& right, const MatchParams& params,
                              const Variant& variant) {
    switch (catalogue::cost(params.cost).id) {
        case catalogue::Cost::lcdm:
            return run_cost<NDISP, lcdm_measure>(left, right, params, variant);
        case catalogue::Cost::census:
            return run_cost<NDISP, census_measure>(left, right, params, variant);
        case catalogue::Cost::ad:
            return run_cost<NDISP, ad_measure>(left, right, params, variant);
        case catalogue::Cost::zncc:  // refused by require_cost
            break;
    }
    throw std::invalid_argument("the HLS kernels have no " + params.cost + " cost");
}

}  // namespace

Variant variant_for(const MatchParams& params) {
    if (params.ndisp < 1 || params.ndisp > 256 || params.window < 1 || params.window > 31) {
        throw std::invalid_argument("no HLS variant for ndisp " + std::to_string(params.ndisp) +
                                    " and window " + std::to_string(params.window));
    }
    const int ndisp = params.ndisp <= 16 ? 16 : params.ndisp <= 64 ? 64 : 256;
    const int window = params.window <= 11 ? 11 : 31;
    return {kHostMaxWidth, kHostMaxHeight, ndisp, window};
}

ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params) {
    check_pair(left, right);
    stereo::validate(params, left.width, left.height);
    if (params.min_disp > kHostMaxMinDisp || params.min_disp < -kHostMaxMinDisp) {
        throw std::invalid_argument("min_disp " + std::to_string(params.min_disp) +
                                    " is outside the HLS variants' +-" +
                                    std::to_string(kHostMaxMinDisp));
    }
    if (left.width > kHostMaxWidth || left.height > kHostMaxHeight) {
        throw std::invalid_argument(
            "image " + std::to_string(left.width) + "x" + std::to_string(left.height) +
            " is larger than the HLS variants' " + std::to_string(kHostMaxWidth) + "x" +
            std::to_string(kHostMaxHeight));
    }
    catalogue::require_cost(params.cost, catalogue::CostUse::hardware, "the HLS kernels");
    if (catalogue::cost(params.cost).id == catalogue::Cost::lcdm) {
        lcdm::require_colour(left);
    }
    const Variant variant = variant_for(params);
    switch (variant.ndisp) {
        case 16:
            return run_window<16>(left, right, params, variant);
        case 64:
            return run_window<64>(left, right, params, variant);
        default:
            return run_window<256>(left, right, params, variant);
    }
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    return to_label_map(hls::match_validated(left, right, params));
}

void register_matchers(MatcherRegistry& registry) {
    registry.add({"pipeline", "hls",
                  "Sec. 3.1 pipeline with stage 6, the HLS kernels in C simulation",
                  pipeline_factory(&match_validated)});
    registry.add({"asw", "hls",
                  "Sec. 3.4 separable adaptive support weights, the HLS ASW core in C simulation "
                  "(census or AD, diameters 3 .. 31)",
                  asw_factory(&asw_match_validated)});
    hierarchical::register_matchers(registry);
}

}  // namespace stereo::hls
