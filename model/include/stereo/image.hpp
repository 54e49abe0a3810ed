// Plain image containers used by the golden model (no OpenCV dependency, so RTL and HLS
// testbenches can link the model alone).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace stereo {

// The size of a row-major grid of pixels and the index of pixel (x, y) in it: what an image and
// the per-pixel maps (DisparityMap, ValidatedDisparity) share.
struct PixelGrid {
    int width = 0;
    int height = 0;

    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    bool operator==(const PixelGrid&) const = default;
};

// 8-bit image, 1 (grey) or 3 (RGB) interleaved channels, row-major.
struct Image : PixelGrid {
    int channels = 0;
    std::vector<std::uint8_t> pixels;

    Image() = default;
    Image(int w, int h, int c) : PixelGrid{w, h}, channels(c), pixels(checked_size(w, h, c)) {}

    std::uint8_t& at(int x, int y, int c) { return pixels[index(x, y) * channels + c]; }
    std::uint8_t at(int x, int y, int c) const { return pixels[index(x, y) * channels + c]; }
    bool empty() const { return pixels.empty(); }

  private:
    static std::size_t checked_size(int w, int h, int c) {
        if (w <= 0 || h <= 0 || (c != 1 && c != 3)) {
            throw std::invalid_argument("image must be non-empty with 1 or 3 channels, got " +
                                        std::to_string(w) + "x" + std::to_string(h) + "x" +
                                        std::to_string(c));
        }
        return static_cast<std::size_t>(w) * h * c;
    }
};

// Output of the pipeline: an 8-bit disparity and a valid flag per pixel. Invalid pixels hold
// fx::kInvalidDisparity (0).
struct DisparityMap : PixelGrid {
    std::vector<std::uint8_t> disparity;
    std::vector<std::uint8_t> valid;  // 1 = valid, 0 = invalid

    DisparityMap() = default;
    DisparityMap(int w, int h)
        : PixelGrid{w, h},
          disparity(static_cast<std::size_t>(w) * h, 0),
          valid(static_cast<std::size_t>(w) * h, 0) {}

    bool operator==(const DisparityMap&) const = default;
};

}  // namespace stereo
