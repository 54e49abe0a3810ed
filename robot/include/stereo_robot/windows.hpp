// The three decision windows of a disparity map (thesis Fig. 4.3) and their statistics.
#pragma once

#include <array>
#include <vector>

#include "stereo/image.hpp"

namespace stereo::robot {

inline constexpr int kDefaultBorder = 20;  // pixels excluded on every side (thesis Sec. 4.1.1)

struct GroundModel;  // ground.hpp

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
    int above = 0;                // valid, not ignored pixels with disparity > threshold
    int ignored = 0;              // valid pixels the ground model calls ground or overhead
    long long disparity_sum = 0;  // sum of the disparities of valid, not ignored pixels
    std::vector<int> histogram;   // valid, not ignored pixels per disparity (index = disparity)

    // Fraction of valid pixels above the threshold (ignored pixels count as free); a window
    // without any valid pixel counts as fully occupied (1), since nothing shows that it is free.
    double occupancy() const { return valid == 0 ? 1.0 : static_cast<double>(above) / valid; }
    // Mean disparity of the valid, not ignored pixels; `none` when there is no valid pixel, 0
    // when all valid pixels are ground (nothing stands there).
    double mean_disparity(double none) const {
        const int counted = valid - ignored;
        return valid == 0     ? none
               : counted == 0 ? 0.0
                              : static_cast<double>(disparity_sum) / counted;
    }
    // The free distance of the window as a disparity: the smallest D for which fewer than `rate`
    // of its valid pixels are nearer (disparity > D; ignored pixels count as free), i.e. the
    // window is "occupied" (the forward rule's sense) within f B / D and free up to it. Smaller
    // means freer. A window without valid pixels is blocked at once: +infinity.
    double free_disparity(double rate) const;
};

// `ground` (optional): pixels that are not obstacles by the ground model are ignored.
WindowStats window_stats(const DisparityMap& map, const Rect& window, double threshold,
                         const GroundModel* ground = nullptr);

std::array<WindowStats, 3> all_window_stats(const DisparityMap& map, double threshold,
                                            int border = kDefaultBorder,
                                            const GroundModel* ground = nullptr);

}  // namespace stereo::robot
