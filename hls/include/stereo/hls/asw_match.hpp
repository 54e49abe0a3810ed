// stereo::hls::asw_match_validated: the HLS ASW core (asw.hpp) in C simulation on a whole image
// pair, bit-exact with stereo::asw::match with Params::separable (stage 6 included): the engine
// behind `stereo match --aggregation asw --separable --engine hls`.
#pragma once

#include "stereo/asw.hpp"
#include "stereo/hls/asw.hpp"
#include "stereo/hls/host.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::hls {

// The cfg_* values of a frame: size, labels, the cost's truncation (asw::truncation_for) and
// stage 6.
inline AswConfig asw_frame_config(const MatchParams& params, const asw::Params& weights, int width,
                                  int height) {
    AswConfig cfg;
    cfg.width = width;
    cfg.height = height;
    cfg.ndisp = params.ndisp;
    cfg.min_disp = params.min_disp;
    cfg.truncation = asw::truncation_for(weights.truncation, params.cost);
    cfg.uniqueness = params.validation.uniqueness;
    cfg.uniqueness_ratio = params.validation.uniqueness_ratio;
    cfg.left_right = params.validation.left_right;
    cfg.lr_tolerance = params.validation.lr_tolerance;
    cfg.subpixel = params.validation.subpixel;
    return cfg;
}

// Largest frame, |min_disp| and label count of the compiled variants; the diameters are every odd
// one of table::kAswMinDiameter .. kAswMaxDiameter (3 .. 31), the label lanes 16, 64 or 256.
inline constexpr int kAswHostMaxWidth = 4096;
inline constexpr int kAswHostMaxHeight = 4096;
inline constexpr int kAswHostMaxMinDisp = 64;

// Throws std::invalid_argument (one line) for what the compiled core does not compute: not the
// separable variant with the default responses (response, shape, continuity, right weights,
// normalisers), a cost other than census or AD, a diameter outside 3 .. 31, more than 256 labels,
// |min_disp| above kAswHostMaxMinDisp or a frame above 4096 x 4096; and for what asw::match
// refuses.
void check_asw_core(const MatchParams& params, const asw::Params& weights, int width, int height);

// Checks (check_asw_core), then streams the pair through the smallest compiled variant's
// stereo_hls_asw_top and returns its output.
ValidatedDisparity asw_match_validated(const Image& left, const Image& right,
                                       const MatchParams& params, const asw::Params& weights);

}  // namespace stereo::hls
