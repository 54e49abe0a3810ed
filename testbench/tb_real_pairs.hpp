// Crops of real pairs, at the size of the small stereo_top configuration, for the testbenches
// that compare them with the model; a pair whose files are missing gives nothing (the test skips).
#pragma once

#include <filesystem>
#include <optional>

#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"

namespace stereo::tb {

inline constexpr int kCropWidth = 64;
inline constexpr int kCropHeight = 48;

// The kCropWidth x kCropHeight window at (x0, y0) of the pair, loaded downscaled by `downscale`.
inline std::optional<io::ImagePair> real_crop(const std::filesystem::path& left,
                                              const std::filesystem::path& right, int downscale,
                                              int x0, int y0) {
    if (!std::filesystem::exists(left) || !std::filesystem::exists(right)) {
        return std::nullopt;
    }
    return io::crop(io::load_pair(left, right, downscale), x0, y0, kCropWidth, kCropHeight);
}

// A Middlebury 2003 file (left.png, right.png) of `scene`.
inline std::filesystem::path middlebury(const char* scene, const char* file) {
    return io::data_dir() / "middlebury2003" / scene / file;
}

// The Tsukuba window at (150, 100) that several testbenches compare.
inline std::optional<io::ImagePair> tsukuba_crop() {
    return real_crop(middlebury("tsukuba", "left.png"), middlebury("tsukuba", "right.png"), 1, 150,
                     100);
}

// `image` at three quarters of its brightness: the relit right image of the cost testbenches.
inline Image darkened(Image image) {
    for (auto& p : image.pixels) {
        p = static_cast<std::uint8_t>(p * 3 / 4);
    }
    return image;
}

}  // namespace stereo::tb
