// What a stage-6 output exercises: how often each reason code occurs, and how many valid pixels
// have a fractional or a negative disparity. Shared by the HLS and the quad tests.
#pragma once

#include <array>
#include <cstddef>

#include "stereo/constants.hpp"
#include "stereo/validated.hpp"

namespace stereo::test {

struct Stage6Counts {
    std::array<int, 8> reason{};
    int fractional = 0;
    int negative = 0;
};

inline Stage6Counts stage6_counts(const ValidatedDisparity& map) {
    Stage6Counts counts;
    for (std::size_t i = 0; i < map.fixed.size(); ++i) {
        ++counts.reason[map.reason[i] & 7];
        counts.fractional += map.valid(i) && map.fixed[i] % fx::kSubpixelScale != 0 ? 1 : 0;
        counts.negative += map.valid(i) && map.fixed[i] < 0 ? 1 : 0;
    }
    return counts;
}

}  // namespace stereo::test
