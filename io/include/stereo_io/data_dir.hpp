// The one rule for where the shared stereo data lives (Middlebury, KITTI, ... and the Aloe
// pair). Every program and test asks here instead of reading its own variable or define.
#pragma once

#include <filesystem>

namespace stereo::io {

// The environment variable STEREO_DATA_DIR when set and non-empty, else the folder given to
// CMake as STEREO_DATA_DIR (made absolute at configure time). Not checked for existence:
// callers that need the data skip or report when it is absent.
std::filesystem::path data_dir();

// The same for the Aloe pair (aloeL.jpg, aloeR.jpg, aloeGT.png): env STEREO_ALOE_DIR, else
// the CMake variable STEREO_ALOE_DIR.
std::filesystem::path aloe_dir();

}  // namespace stereo::io
