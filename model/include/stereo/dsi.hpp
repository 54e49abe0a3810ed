// The disparity-space image (DSI): one unsigned value per pixel and disparity label.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stereo/constants.hpp"

namespace stereo {

// Layout is plane-major, [d][y][x], so every stage that works inside a constant-disparity
// plane (aggregation, the 3x3 CA neighbourhoods) walks contiguous memory.
class Dsi {
  public:
    using Value = std::uint16_t;  // wide enough for every stage (checked below)

    Dsi() = default;
    Dsi(int width, int height, int ndisp)
        : width_(width),
          height_(height),
          ndisp_(ndisp),
          cells_(static_cast<std::size_t>(width) * height * ndisp, 0) {}

    int width() const { return width_; }
    int height() const { return height_; }
    int ndisp() const { return ndisp_; }

    Value& at(int x, int y, int d) { return cells_[index(x, y, d)]; }
    Value at(int x, int y, int d) const { return cells_[index(x, y, d)]; }

    std::span<Value> plane(int d) {
        return {cells_.data() + static_cast<std::size_t>(d) * plane_size(), plane_size()};
    }
    std::span<const Value> plane(int d) const {
        return {cells_.data() + static_cast<std::size_t>(d) * plane_size(), plane_size()};
    }
    std::size_t plane_size() const { return static_cast<std::size_t>(width_) * height_; }
    const std::vector<Value>& cells() const { return cells_; }

    bool operator==(const Dsi&) const = default;

  private:
    std::size_t index(int x, int y, int d) const {
        return (static_cast<std::size_t>(d) * height_ + y) * width_ + x;
    }

    int width_ = 0;
    int height_ = 0;
    int ndisp_ = 0;
    std::vector<Value> cells_;
};

static_assert(fx::kAggBits <= 16 && fx::kCostBits <= 16, "DSI cells are 16 bits");

}  // namespace stereo
