#include "stereo_io/data_dir.hpp"

#include <cstdlib>

// Defined by io/CMakeLists.txt for this library only; the fallbacks keep a stray build working.
#ifndef STEREO_DATA_DIR
#define STEREO_DATA_DIR "../shared/data"
#endif
#ifndef STEREO_ALOE_DIR
#define STEREO_ALOE_DIR "/usr/share/doc/opencv-doc/examples/data"
#endif

namespace stereo::io {

namespace {

// The run-time override wins so that one binary can be pointed at another copy of the data.
std::filesystem::path from_env_or(const char* variable, const char* built_in) {
    const char* value = std::getenv(variable);
    return value != nullptr && *value != '\0' ? std::filesystem::path(value)
                                              : std::filesystem::path(built_in);
}

}  // namespace

std::filesystem::path data_dir() {
    return from_env_or("STEREO_DATA_DIR", STEREO_DATA_DIR);
}

std::filesystem::path aloe_dir() {
    return from_env_or("STEREO_ALOE_DIR", STEREO_ALOE_DIR);
}

}  // namespace stereo::io
