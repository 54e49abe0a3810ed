// Comparisons of the RTL's results with the golden model's (expected first), listing the first
// few mismatches: DSI volumes (the stage testbenches), disparity maps (the WTA and top
// testbenches) and stage 6's output. Shared with tests/: stereo_io/test_compare.hpp.
#pragma once

#include "stereo_io/test_compare.hpp"

namespace stereo::tb {

using test::same_map;
using test::same_validated;
using test::same_volume;

}  // namespace stereo::tb
