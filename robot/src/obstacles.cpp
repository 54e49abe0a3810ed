#include "stereo_robot/obstacles.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace stereo::robot {

void paste_obstacle(Image& left, Image& right, const PastedObstacle& obstacle) {
    const Rect& b = obstacle.box;
    if (left.width != right.width || left.height != right.height ||
        left.channels != right.channels) {
        throw std::invalid_argument("obstacle: the two images differ in size");
    }
    if (b.x0 >= b.x1 || b.y0 >= b.y1 || b.x0 < 0 || b.y0 < 0 || b.x1 > left.width ||
        b.y1 > left.height) {
        throw std::invalid_argument("obstacle: the box must be non-empty and inside the image");
    }
    if (obstacle.disparity < 0 || b.x1 - obstacle.disparity <= 0) {
        throw std::invalid_argument("obstacle: disparity " + std::to_string(obstacle.disparity) +
                                    " must be >= 0 and leave part of the box in the right image");
    }
    if (obstacle.block < 1) {
        throw std::invalid_argument("obstacle: texture block must be >= 1 pixel");
    }
    const int bw = (b.x1 - b.x0 + obstacle.block - 1) / obstacle.block;
    const int bh = (b.y1 - b.y0 + obstacle.block - 1) / obstacle.block;
    std::mt19937 rng(obstacle.seed);
    std::uniform_int_distribution<int> grey(20, 235);
    std::vector<std::uint8_t> texture(static_cast<std::size_t>(bw) * bh);
    for (auto& t : texture) {
        t = static_cast<std::uint8_t>(grey(rng));
    }
    for (int y = b.y0; y < b.y1; ++y) {
        for (int x = b.x0; x < b.x1; ++x) {
            const std::uint8_t value =
                texture[static_cast<std::size_t>((y - b.y0) / obstacle.block) * bw +
                        (x - b.x0) / obstacle.block];
            const int xr = x - obstacle.disparity;  // left of 0: not seen by the right camera
            for (int c = 0; c < left.channels; ++c) {
                left.at(x, y, c) = value;
                if (xr >= 0) {
                    right.at(xr, y, c) = value;
                }
            }
        }
    }
}

PastedObstacle obstacle_in_window(int width, int height, int border, const std::string& position,
                                  double coverage, double distance, const StereoGeometry& geometry,
                                  int downscale, std::uint32_t seed) {
    if (!(coverage > 0.0 && coverage <= 1.0)) {
        throw std::invalid_argument("obstacle coverage must be in (0, 1]");
    }
    if (!(distance >= 0.1 && distance <= 1000.0)) {
        throw std::invalid_argument("obstacle distance must be in [0.1, 1000] m");
    }
    const auto windows = split_windows(width, height, border);
    Rect area;
    if (position == "left") {
        area = windows[0];
    } else if (position == "centre" || position == "center") {
        area = windows[1];
    } else if (position == "right") {
        area = windows[2];
    } else if (position == "wall") {
        area = {windows[0].x0, windows[0].y0, windows[2].x1, windows[2].y1};
    } else {
        throw std::invalid_argument("obstacle position must be left, centre, right or wall, got " +
                                    position);
    }
    const double scale = std::sqrt(coverage);
    const int w = std::max(1, static_cast<int>(std::lround((area.x1 - area.x0) * scale)));
    const int h = std::max(1, static_cast<int>(std::lround((area.y1 - area.y0) * scale)));
    const int x0 = area.x0 + (area.x1 - area.x0 - w) / 2;
    const int y0 = area.y0 + (area.y1 - area.y0 - h) / 2;
    const double d = disparity_threshold(geometry, distance, downscale);  // f B / (Z F)
    PastedObstacle obstacle{{x0, y0, x0 + w, y0 + h}, static_cast<int>(std::lround(d)), seed};
    if (obstacle.box.x1 - obstacle.disparity <= 0) {
        throw std::invalid_argument("obstacle at " + std::to_string(distance) +
                                    " m has a disparity too large for its position");
    }
    return obstacle;
}

}  // namespace stereo::robot
