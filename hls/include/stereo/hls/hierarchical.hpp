// The hierarchical 2-D search with the HLS kernels in C simulation (issue 45), bit-exact with
// stereo::hierarchical with the census cost and CaNeighbours::horizontal. Each level is one
// hier_level (hier_level.hpp) streamed over the level's image pair; what lies between the levels
// is host C++, as the 1-D host wrapper streams whole frames:
//   * the pyramid: stereo::hierarchical::downscale_area (the RTL's stereo_downscale);
//   * the candidates: full_grid for the quarter level, refine_grid from the coarser level's
//     winners for the half and full levels, read by the host at the pixel each level asks for
//     (the RTL's stereo_prediction_ring);
//   * for Output::vertical_field, the field between the levels and the 1-D pass (the host's in
//     the hardware core too) and the pass itself through stereo::hls::match_validated.
// The host wrapper behind `stereo match --method hierarchical --engine hls`.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "stereo/hierarchical.hpp"
#include "stereo/image.hpp"
#include "stereo/matcher.hpp"

namespace stereo::hls::hierarchical {

using stereo::hierarchical::CostCount;
using stereo::hierarchical::LevelMap;
using stereo::hierarchical::LevelParams;
using stereo::hierarchical::Params;
using stereo::hierarchical::SearchRange;

// The synthesised aggregation window of every compiled level (the levels' largest window, 31):
// a smaller level window is centred in its taps.
inline constexpr int kHostLevelWindow = stereo::hierarchical::kMaxLevelWindow;

// A compiled level: its candidate grid, its vertical range (the row slots and when a pixel is
// complete) and whether it refines a prediction (REFINE = 1) or searches the whole range.
struct LevelShape {
    int cols = 0;
    int rows = 0;
    int v_min = 0;
    int v_max = 0;
    bool refine = false;
    bool operator==(const LevelShape&) const = default;
};
std::vector<LevelShape> compiled_levels();
// "D 8 V 8, D 16 V 16, ...": the (ndisp, vrange) pairs whose three levels are compiled.
std::string compiled_ranges();

// One level on its image pair: the quarter level's grid (uniform, base (0, v_min) of `range`,
// preferring (0, 0)) or a refinement level's (3x3 per pixel, preferring the centre, inside
// `range`), as stereo::hierarchical::match_level with the census cost and horizontal CA
// neighbours. Adds the DSI cells to `count`. Throws std::invalid_argument for a grid or shape
// that no compiled level computes.
LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const SearchRange& range, const LevelParams& level, bool use_ca,
                     std::int64_t& count);

// What the HLS levels take beyond stereo::hierarchical::validate: the census cost, horizontal CA
// neighbours, a compiled (ndisp, vrange) and frames up to the host's 4096 x 4096. Throws
// std::invalid_argument.
void check(const Params& params, int width, int height);

// The three levels, as stereo::hierarchical::match_levels (a LevelsFunction).
std::array<LevelMap, stereo::hierarchical::kLevels> match_levels(const Image& left,
                                                                 const Image& right,
                                                                 const Params& params,
                                                                 CostCount& count);

// The search: these levels, the model's field, the pass through the HLS 1-D kernels.
stereo::hierarchical::Result match(const Image& left, const Image& right, const Params& params);

// Registers method "hierarchical", engine "hls" (called by stereo::hls::register_matchers).
void register_matchers(MatcherRegistry& registry);

}  // namespace stereo::hls::hierarchical
