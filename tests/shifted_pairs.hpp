// Test pairs with a known 2-D displacement and the per-level comparison of the hierarchical
// search, shared by the hierarchical, matcher and LCDM tests.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/image.hpp"
#include "stereo/search.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::test {

// right(x', y') = left(x' + dx, y' - dy) plus noise, random where that leaves the left image:
// true displacement (dx, dy) everywhere (the hierarchical search's d = dx, v = dy).
inline Image shifted_2d(const Image& left, int dx, int dy, int noise, std::mt19937& rng) {
    Image right = random_image(left.width, left.height, left.channels, rng);
    std::uniform_int_distribution<int> jitter(-noise, noise);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            const int sx = x + dx;
            const int sy = y - dy;
            if (sx < 0 || sx >= left.width || sy < 0 || sy >= left.height) {
                continue;
            }
            for (int c = 0; c < left.channels; ++c) {
                right.at(x, y, c) =
                    static_cast<std::uint8_t>(std::clamp(left.at(sx, sy, c) + jitter(rng), 0, 255));
            }
        }
    }
    return right;
}

// The 2-D search's parameters for pairs displaced by a few pixels across and +-3 down or up (the
// LCDM and census tests): the thesis' levels and full-level output, 16 labels, vertical range 16.
inline hierarchical::Params displaced_pair_params(const std::string& cost) {
    hierarchical::Params params = hierarchical::Params::thesis();
    params.ndisp = 16;
    params.vrange = 16;  // -8 .. 7: dy = +-3 lies inside every level's range
    params.cost = cost;
    return params;
}

// Horizontal and vertical disparity and the valid flag of every pixel of a level.
inline ::testing::AssertionResult same_level(const Winners& expected, const Winners& actual) {
    return same_pixels(
        expected, actual,
        [&](std::size_t i) {
            return expected.disparity[i] != actual.disparity[i] ||
                   expected.vertical[i] != actual.vertical[i] ||
                   expected.valid[i] != actual.valid[i];
        },
        [](const Winners& map, std::size_t i) {
            return "(d " + std::to_string(map.disparity[i]) + ", v " +
                   std::to_string(map.vertical[i]) + ", valid " + std::to_string(map.valid[i]) +
                   ")";
        });
}

// Runs the hierarchical search through the model and the naive reference and expects every
// level, the disparities and the vertical offsets equal; returns the model's result.
inline hierarchical::Result match_hierarchical_as_naive(const Image& left, const Image& right,
                                                        const hierarchical::Params& params) {
    const hierarchical::Result model = hierarchical::match(left, right, params);
    const hierarchical::Result reference = hierarchical::naive::match(left, right, params);
    for (std::size_t l = 0; l < static_cast<std::size_t>(hierarchical::kLevels); ++l) {
        EXPECT_TRUE(same_level(reference.levels[l], model.levels[l]))
            << hierarchical::kLevelNames[l];
    }
    EXPECT_EQ(reference.disparity, model.disparity);
    EXPECT_EQ(reference.vertical, model.vertical) << "the vertical offsets differ";
    EXPECT_EQ(reference.cost_evaluations.level, model.cost_evaluations.level);
    EXPECT_EQ(reference.cost_evaluations.field_pass, model.cost_evaluations.field_pass);
    EXPECT_EQ(reference.field, model.field) << "the vertical fields differ";
    EXPECT_EQ(reference.validated, model.validated) << "the validated 1-D passes differ";
    return model;
}

}  // namespace stereo::test
