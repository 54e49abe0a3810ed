#include "stereo/hls/asw_match.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "stereo/catalogue.hpp"
#include "stereo/hls/stream.hpp"

namespace stereo::hls {
namespace {

template <int NDISP, int DIAMETER, class MEASURE>
ValidatedDisparity run_asw_variant(const Image& left, const Image& right, const AswConfig& cfg) {
    using Core = asw_pipeline<kAswHostMaxWidth, kAswHostMaxHeight, NDISP, DIAMETER,
                              kAswHostMaxMinDisp, MEASURE>;
    const auto state = std::make_unique<Core>();  // megabytes of column stack: on the heap
    stream<InputBeat> in("asw.in");
    stream<OutputBeat> out("asw.out");
    push_frame(left, right, in);
    const status_t status = stereo_hls_asw_top<kAswHostMaxWidth, kAswHostMaxHeight, NDISP, DIAMETER,
                                               kAswHostMaxMinDisp, MEASURE>(in, out, cfg, *state);
    return finish_frame("HLS ASW top", status, in, out, left.width, left.height);
}

// The variant of `diameter` among the odd diameters kAswMinDiameter + 2 i, i in DIAMETERS.
template <int NDISP, class MEASURE, int... I>
ValidatedDisparity run_diameter(const Image& left, const Image& right, const AswConfig& cfg,
                                int diameter, std::integer_sequence<int, I...>) {
    ValidatedDisparity result;
    const bool found =
        ((diameter == table::kAswMinDiameter + 2 * I
              ? (result = run_asw_variant<NDISP, table::kAswMinDiameter + 2 * I, MEASURE>(
                     left, right, cfg),
                 true)
              : false) ||
         ...);
    if (!found) {
        throw std::invalid_argument("no HLS ASW variant of diameter " + std::to_string(diameter));
    }
    return result;
}

template <int NDISP, class MEASURE>
ValidatedDisparity run_measure(const Image& left, const Image& right, const AswConfig& cfg,
                               int diameter) {
    constexpr int kDiameters = (table::kAswMaxDiameter - table::kAswMinDiameter) / 2 + 1;
    return run_diameter<NDISP, MEASURE>(left, right, cfg, diameter,
                                        std::make_integer_sequence<int, kDiameters>{});
}

template <int NDISP>
ValidatedDisparity run_lanes(const Image& left, const Image& right, const AswConfig& cfg,
                             int diameter, bool census) {
    return census ? run_measure<NDISP, census_measure>(left, right, cfg, diameter)
                  : run_measure<NDISP, ad_measure>(left, right, cfg, diameter);
}

}  // namespace

void check_asw_core(const MatchParams& params, const asw::Params& weights, int width, int height) {
    asw::validate(weights, width, height);
    MatchParams checked = params;
    checked.window = 1;  // not read by ASW; its checks must not reject
    checked.use_ca = false;
    stereo::validate(checked, width, height);
    asw::check_hardware_variant(weights, "the HLS ASW core (engine hls)", true);
    const catalogue::Cost cost = catalogue::cost(params.cost).id;
    if (cost != catalogue::Cost::census && cost != catalogue::Cost::ad) {
        throw std::invalid_argument("the HLS ASW core compares census or AD codes, not " +
                                    params.cost);
    }
    if (weights.diameter < table::kAswMinDiameter || weights.diameter > table::kAswMaxDiameter) {
        throw std::invalid_argument("the HLS ASW core is compiled for diameters " +
                                    std::to_string(table::kAswMinDiameter) + " .. " +
                                    std::to_string(table::kAswMaxDiameter) + ", got " +
                                    std::to_string(weights.diameter));
    }
    if (params.ndisp > 256) {
        throw std::invalid_argument("the HLS ASW core has at most 256 labels, got " +
                                    std::to_string(params.ndisp));
    }
    if (params.min_disp > kAswHostMaxMinDisp || params.min_disp < -kAswHostMaxMinDisp) {
        throw std::invalid_argument("min_disp " + std::to_string(params.min_disp) +
                                    " is outside the HLS ASW variants' +-" +
                                    std::to_string(kAswHostMaxMinDisp));
    }
    if (width > kAswHostMaxWidth || height > kAswHostMaxHeight) {
        throw std::invalid_argument(
            "image " + std::to_string(width) + "x" + std::to_string(height) +
            " is larger than the HLS ASW "
            "variants' " +
            std::to_string(kAswHostMaxWidth) + "x" + std::to_string(kAswHostMaxHeight));
    }
}

ValidatedDisparity asw_match_validated(const Image& left, const Image& right,
                                       const MatchParams& params, const asw::Params& weights) {
    check_pair(left, right);
    check_asw_core(params, weights, left.width, left.height);
    const AswConfig cfg = asw_frame_config(params, weights, left.width, left.height);
    const bool census = catalogue::cost(params.cost).id == catalogue::Cost::census;
    if (params.ndisp <= 16) {
        return run_lanes<16>(left, right, cfg, weights.diameter, census);
    }
    if (params.ndisp <= 64) {
        return run_lanes<64>(left, right, cfg, weights.diameter, census);
    }
    return run_lanes<256>(left, right, cfg, weights.diameter, census);
}

}  // namespace stereo::hls
