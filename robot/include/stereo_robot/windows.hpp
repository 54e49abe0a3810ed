// The three decision windows of a disparity map (thesis Fig. 4.3) and their statistics.
#pragma once

#include <array>

#include "stereo/image.hpp"

namespace stereo::robot {

inline constexpr int kDefaultBorder = 20;  // pixels excluded on every side (thesis Sec. 4.1.1)

enum class Side { left = 0, centre = 1, right = 2 };

// Half-open pixel rectangle [x0, x1) x [y0, y1).
struct Rect {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    int area() const { return (x1 - x0) * (y1 - y0); }
};

// The interior left after removing `border` pixels on every side, cut into three windows of
// equal width (the remainder of the division goes to the right-most ones): window i spans
// x in [border + floor(i * Wi / 3), border + floor((i + 1) * Wi / 3)). Throws
// std::invalid_argument when the interior is narrower than 3 pixels or empty.
std::array<Rect, 3> split_windows(int width, int height, int border = kDefaultBorder);

// What the decisions need from one window. Only valid pixels are counted: an invalid pixel has
// no disparity, and counting it as 0 would call it free.
struct WindowStats {
    int valid = 0;                // valid pixels in the window
    int above = 0;                // valid pixels with disparity > threshold
    long long disparity_sum = 0;  // sum of valid disparities

    // Fraction of valid pixels above the threshold; a window without any valid pixel counts as
    // fully occupied (1), since nothing shows that it is free.
    double occupancy() const { return valid == 0 ? 1.0 : static_cast<double>(above) / valid; }
    // Mean valid disparity; `none` when there is no valid pixel.
    double mean_disparity(double none) const {
        return valid == 0 ? none : static_cast<double>(disparity_sum) / valid;
    }
};

WindowStats window_stats(const DisparityMap& map, const Rect& window, double threshold);

std::array<WindowStats, 3> all_window_stats(const DisparityMap& map, double threshold,
                                            int border = kDefaultBorder);

}  // namespace stereo::robot
