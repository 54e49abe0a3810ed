// Pairs with a known vertical displacement and the level-map comparison that the hierarchical
// core's testbenches (tb_stereo_hier_*) share.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/image.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::tb {

// The hierarchical search with the census cost (the hardware's), D labels, V offsets, CA as
// given; the rest the API's defaults (windows 9 / 15 / 15, the pass without stage 6).
inline hierarchical::Params census_search(int ndisp, int vrange, bool use_ca = true) {
    hierarchical::Params params;
    params.ndisp = ndisp;
    params.vrange = vrange;
    params.use_ca = use_ca;
    params.cost = std::string(catalogue::cost(catalogue::Cost::census).name);
    return params;
}

// The image moved right by dx and down by dy columns and rows (the edges repeated).
inline Image moved(const Image& image, int dx, int dy) {
    Image out(image.width, image.height, image.channels);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                out.at(x, y, c) = image.at(std::clamp(x - dx, 0, image.width - 1),
                                           std::clamp(y - dy, 0, image.height - 1), c);
            }
        }
    }
    return out;
}

// The right image of `left` seen through a plane (offsets clamped into [v_min, v_max]):
// right(x - shift, y + v(x - shift, y)) = left(x, y) plus noise of +-6, random elsewhere; so
// matching along the plane has a true answer.
inline Image moved_by_plane(const Image& left, const hierarchical::Plane& plane, int shift,
                            std::mt19937& rng, int v_min, int v_max) {
    const auto field = hierarchical::plane_field(plane, left.width, left.height, v_min, v_max);
    Image right = test::random_image(left.width, left.height, left.channels, rng);
    std::uniform_int_distribution<int> noise(-6, 6);
    for (int y = 0; y < left.height; ++y) {
        for (int xr = 0; xr < left.width; ++xr) {
            const int row = y + field[static_cast<std::size_t>(y) * left.width + xr];
            const int x = xr + shift;
            if (row < 0 || row >= left.height || x >= left.width) {
                continue;
            }
            for (int c = 0; c < left.channels; ++c) {
                right.at(xr, row, c) =
                    static_cast<std::uint8_t>(std::clamp(left.at(x, y, c) + noise(rng), 0, 255));
            }
        }
    }
    return right;
}

// Every pixel's winner (d, v) and validity equal; the first few differences reported.
inline void expect_levels_equal(const hierarchical::LevelMap& rtl,
                                const hierarchical::LevelMap& model, const std::string& what) {
    int mismatches = 0;
    for (int y = 0; y < model.height; ++y) {
        for (int x = 0; x < model.width; ++x) {
            const std::size_t p = model.index(x, y);
            if (rtl.disparity[p] != model.disparity[p] || rtl.vertical[p] != model.vertical[p] ||
                rtl.valid[p] != model.valid[p]) {
                if (++mismatches <= 5) {
                    ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") RTL (d "
                                  << rtl.disparity[p] << ", v " << rtl.vertical[p] << ", valid "
                                  << int{rtl.valid[p]} << ") model (d " << model.disparity[p]
                                  << ", v " << model.vertical[p] << ", valid "
                                  << int{model.valid[p]} << ")";
                }
            }
        }
    }
    EXPECT_EQ(mismatches, 0) << what;
}

}  // namespace stereo::tb
