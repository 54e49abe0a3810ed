// The census cost (docs/architecture.md, the worked example of adding a cost function): each
// pixel's 5x5 neighbourhood in the luma becomes a 24-bit code, bit set where the neighbour is
// darker than the centre (a neighbour outside the image counts as equal: bit clear); the cost is
// the Hamming distance of two codes times kCensusWeight, so that it spans the AD cost's range
// and the aggregation keeps its resolution.
#pragma once

#include <cstdint>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/image.hpp"

namespace stereo::census {

inline constexpr int kRadius = fx::kCensusRadius;  // 5x5 window
inline constexpr int kBits = fx::kCensusBits;      // 24
inline constexpr int kWeight = fx::kCensusWeight;  // 31

// Row-major 24-bit codes of an image (grey, or RGB through edge_frontend::luma).
std::vector<std::uint32_t> transform(const Image& image);

}  // namespace stereo::census
