// A window of a Middlebury 2003 pair for the tests that compare the model with its naive
// reference on real images; nothing where the pair's files are missing (the test skips).
#pragma once

#include <filesystem>
#include <optional>

#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"

namespace stereo::test {

// The width x height window at (x0, y0) of `scene` (left.png, right.png under data_dir()).
inline std::optional<io::ImagePair> middlebury_crop(const char* scene, int x0, int y0, int width,
                                                    int height) {
    const auto dir = io::data_dir() / "middlebury2003" / scene;
    if (!std::filesystem::exists(dir / "left.png") || !std::filesystem::exists(dir / "right.png")) {
        return std::nullopt;
    }
    return io::crop(io::load_pair(dir / "left.png", dir / "right.png"), x0, y0, width, height);
}

}  // namespace stereo::test
