// Plain image containers used by the golden model (no OpenCV dependency, so RTL and HLS
// testbenches can link the model alone).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace stereo {

// 8-bit image, 1 (grey) or 3 (RGB) interleaved channels, row-major.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint8_t> pixels;

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(checked_size(w, h, c)) {}

    std::uint8_t& at(int x, int y, int c) {
        return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
    }
    std::uint8_t at(int x, int y, int c) const {
        return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
    }
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
struct DisparityMap {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> disparity;
    std::vector<std::uint8_t> valid;  // 1 = valid, 0 = invalid

    DisparityMap() = default;
    DisparityMap(int w, int h)
        : width(w),
          height(h),
          disparity(static_cast<std::size_t>(w) * h, 0),
          valid(static_cast<std::size_t>(w) * h, 0) {}

    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    bool operator==(const DisparityMap&) const = default;
};

}  // namespace stereo
