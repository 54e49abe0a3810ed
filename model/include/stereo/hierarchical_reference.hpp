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
// The vertical field by direct counting in every window; the plane's field by exact long division.
std::vector<std::int8_t> vertical_field(const LevelMap& level, int radius,
                                        const std::vector<std::int8_t>& prior, int prior_factor);
std::vector<std::int8_t> plane_field(const Plane& plane, int width, int height, int v_min,
                                     int v_max);
// The 1-D pass along a field: the right image warped row by row, then the naive 1-D pipeline
// (stereo::naive::match_validated) and the border rule of the right row.
ValidatedDisparity match_along_field(const Image& left, const Image& right,
                                     const std::vector<std::int8_t>& field, const Params& params);
// Output::vertical_field included (the plane's coefficients from hierarchical::vertical_plane,
// whose least-squares property tests/test_hierarchical.cpp checks on its own).
Result match(const Image& left, const Image& right, const Params& params);

}  // namespace stereo::hierarchical::naive
