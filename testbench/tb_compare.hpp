// Comparisons of the RTL's results with the golden model's, listing the first few mismatches:
// DSI volumes (the stage testbenches) and disparity maps (the WTA and top testbenches).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "stereo/dsi.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_compare.hpp"

namespace stereo::tb {

// Compares planes [0, planes) of two volumes value by value; lists the first few mismatches in
// stream order (y, x, d).
inline ::testing::AssertionResult same_volume(const Dsi& model, const Dsi& rtl, int planes) {
    if (model.width() != rtl.width() || model.height() != rtl.height() || model.ndisp() < planes ||
        rtl.ndisp() < planes) {
        return ::testing::AssertionFailure() << "volume shapes differ";
    }
    std::size_t mismatches = 0;
    std::string first;
    for (int y = 0; y < model.height(); ++y) {
        for (int x = 0; x < model.width(); ++x) {
            for (int d = 0; d < planes; ++d) {
                const int expected = model.at(x, y, d);
                const int actual = rtl.at(x, y, d);
                if (expected != actual && mismatches++ < 5) {
                    first += " (x=" + std::to_string(x) + ", y=" + std::to_string(y) +
                             ", d=" + std::to_string(d) + "): model " + std::to_string(expected) +
                             ", rtl " + std::to_string(actual) + ";";
                }
            }
        }
    }
    if (mismatches == 0) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
           << mismatches << " of " << model.plane_size() * static_cast<std::size_t>(planes)
           << " values differ, first:" << first;
}

// Disparity and valid flag of every pixel; lists the first few mismatches in raster order.
inline ::testing::AssertionResult same_map(const DisparityMap& model, const DisparityMap& rtl) {
    std::size_t mismatches = 0;
    std::string first;
    for (int y = 0; y < model.height; ++y) {
        for (int x = 0; x < model.width; ++x) {
            const auto i = model.index(x, y);
            if ((model.disparity[i] != rtl.disparity[i] || model.valid[i] != rtl.valid[i]) &&
                mismatches++ < 5) {
                first += " (x=" + std::to_string(x) + ", y=" + std::to_string(y) +
                         "): model d=" + std::to_string(model.disparity[i]) +
                         " valid=" + std::to_string(model.valid[i]) +
                         ", rtl d=" + std::to_string(rtl.disparity[i]) +
                         " valid=" + std::to_string(rtl.valid[i]) + ";";
            }
        }
    }
    if (mismatches == 0) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
           << mismatches << " of " << model.disparity.size() << " pixels differ, first:" << first;
}

// Stage 6's output of every pixel: fixed disparity, reason and certainty.
using test::same_validated;

}  // namespace stereo::tb
