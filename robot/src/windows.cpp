#include "stereo_robot/windows.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "stereo_robot/ground.hpp"

namespace stereo::robot {

double WindowStats::free_disparity(double rate) const {
    if (valid == 0) {
        return std::numeric_limits<double>::infinity();
    }
    // nearer = valid pixels with disparity > D, for D = -1, 0, 1, ...
    long long nearer = valid - ignored;
    if (static_cast<double>(nearer) < rate * valid) {
        return 0.0;  // free as far as the window shows
    }
    for (std::size_t d = 0; d < histogram.size(); ++d) {
        nearer -= histogram[d];
        if (static_cast<double>(nearer) < rate * valid) {
            return static_cast<double>(d);
        }
    }
    return std::numeric_limits<double>::infinity();  // rate 0: never free
}

std::array<Rect, 3> split_windows(int width, int height, int border) {
    if (border < 0) {
        throw std::invalid_argument("window border must be >= 0, got " + std::to_string(border));
    }
    // In 64 bits: 2 * border overflows an int for --border 2147483647 (undefined behaviour).
    const std::int64_t wide_inner_width = std::int64_t{width} - 2 * std::int64_t{border};
    const std::int64_t wide_inner_height = std::int64_t{height} - 2 * std::int64_t{border};
    if (wide_inner_width < 3 || wide_inner_height < 1) {
        throw std::invalid_argument("a " + std::to_string(width) + "x" + std::to_string(height) +
                                    " map leaves no room for three windows inside a " +
                                    std::to_string(border) + "-pixel border");
    }
    const int inner_width = static_cast<int>(wide_inner_width);
    std::array<Rect, 3> windows{};
    for (int i = 0; i < 3; ++i) {
        windows[i] = {border + i * inner_width / 3, border, border + (i + 1) * inner_width / 3,
                      height - border};
    }
    return windows;
}

WindowStats window_stats(const DisparityMap& map, const Rect& window, double threshold,
                         const GroundModel* ground) {
    WindowStats stats;
    for (int y = window.y0; y < window.y1; ++y) {
        for (int x = window.x0; x < window.x1; ++x) {
            const std::size_t i = map.index(x, y);
            if (map.valid[i] == 0) {
                continue;
            }
            const int d = map.disparity[i];
            ++stats.valid;
            if (ground != nullptr && !ground->obstacle(y, d)) {
                ++stats.ignored;
                continue;
            }
            stats.above += d > threshold ? 1 : 0;
            stats.disparity_sum += d;
            if (d >= 0) {
                if (static_cast<std::size_t>(d) >= stats.histogram.size()) {
                    stats.histogram.resize(static_cast<std::size_t>(d) + 1, 0);
                }
                ++stats.histogram[static_cast<std::size_t>(d)];
            }
        }
    }
    return stats;
}

std::array<WindowStats, 3> all_window_stats(const DisparityMap& map, double threshold, int border,
                                            const GroundModel* ground) {
    const auto windows = split_windows(map.width, map.height, border);
    return {window_stats(map, windows[0], threshold, ground),
            window_stats(map, windows[1], threshold, ground),
            window_stats(map, windows[2], threshold, ground)};
}

}  // namespace stereo::robot
