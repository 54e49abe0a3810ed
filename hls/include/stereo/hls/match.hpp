// stereo::hls::match_validated: the HLS kernels in C simulation on a whole image pair, bit-exact
// with stereo::match_validated (stage 6 included). The host wrapper behind
// `stereo match --engine hls`.
#pragma once

#include "stereo/image.hpp"
#include "stereo/matcher.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::hls {

// Largest frame the compiled variants take (the line buffers are this many columns wide).
inline constexpr int kHostMaxWidth = 4096;
inline constexpr int kHostMaxHeight = 4096;
// Largest |min_disp| the compiled variants take (MAX_MIN_DISP: the cost stage's delay lines).
inline constexpr int kHostMaxMinDisp = 64;

// Template parameters of a compiled stereo_hls_top variant.
struct Variant {
    int width = 0;   // WIDTH: largest frame width
    int height = 0;  // HEIGHT: largest frame height
    int ndisp = 0;   // NDISP: disparity lanes
    int window = 0;  // WINDOW: synthesised window side
};

// The variant match() runs for these parameters: the fewest lanes and the smallest window
// that cover them (ndisp 16 / 64 / 256, window 11 / 31). Throws std::invalid_argument for
// parameters no variant covers.
Variant variant_for(const MatchParams& params);

// Validates like stereo::match (same exceptions, and |min_disp| <= kHostMaxMinDisp), then streams
// the pair through the variant's stereo_hls_top and returns its output. The stage objects live
// on the heap for the call.
ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params);
// Its 8-bit view, stereo::to_label_map(match_validated(...)).
DisparityMap match(const Image& left, const Image& right, const MatchParams& params);

// Registers method "pipeline", engine "hls", and the hierarchical levels' (hierarchical.hpp).
void register_matchers(MatcherRegistry& registry);

}  // namespace stereo::hls
