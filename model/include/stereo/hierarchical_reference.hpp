// Independent implementation of the hierarchical search, used only to check the golden model.
#pragma once

#include "stereo/hierarchical.hpp"

namespace stereo::hierarchical::naive {

// Obviously-correct versions, straight from docs/hierarchical.md: direct 2-D window sums per
// pixel and candidate, integer division for the CA roundings, no streaming.
Image downscale_area(const Image& image, int factor);
LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                     std::string_view cost = "ad");
Result match(const Image& left, const Image& right, const Params& params);

}  // namespace stereo::hierarchical::naive
