// Comparisons of the RTL's results with the golden model's (expected first), listing the first
// few mismatches: DSI volumes (the stage testbenches), disparity maps (the WTA and top
// testbenches) and stage 6's output. Shared with tests/: stereo_io/test_compare.hpp. And a top's
// report of its build against its Verilated configuration.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>

#include "stereo/stage_table.hpp"
#include "stereo_io/test_compare.hpp"

namespace stereo::tb {

using test::same_map;
using test::same_validated;
using test::same_volume;

// The build a top reports (the C driver's stereo_probe, the board's identify command): the
// register map's version, the largest frame, the labels and window of `config`, and stereo_top's
// default largest |min_disp|.
inline void expect_reported_build(const table::Params& config, std::uint32_t version, int width,
                                  int height, int ndisp, int window, int max_min_disp) {
    EXPECT_EQ(version, table::kRegmapVersion);
    EXPECT_EQ(width, config.width);
    EXPECT_EQ(height, config.height);
    EXPECT_EQ(ndisp, config.ndisp);
    EXPECT_EQ(window, config.window);
    EXPECT_EQ(max_min_disp, table::kDefaultMaxMinDisp);
}

}  // namespace stereo::tb
