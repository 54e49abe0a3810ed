// An obstacle benchmark we control: a textured, fronto-parallel rectangle pasted into both
// images of a real (or synthetic) rectified pair at the disparity of a chosen distance, so that
// the true answer of the avoidance decision is known. Docs: docs/results-avoidance.md.
#pragma once

#include <cstdint>
#include <string>

#include "stereo/image.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/windows.hpp"

namespace stereo::robot {

struct PastedObstacle {
    Rect box;           // in the left image, [x0, x1) x [y0, y1)
    int disparity = 0;  // pixels: the right image gets the same texture at x - disparity
    std::uint32_t seed = 1;
    int block = 3;  // texture: random grey blocks of block x block pixels
};

// Paints the obstacle into both images (every channel, the same grey); columns whose
// x - disparity < 0 are outside the right camera's view and only painted into the left image.
// Throws std::invalid_argument when the box is empty or leaves the left image, when the
// disparity is negative or moves the whole box out of the right image, when the images differ in
// size, or when block < 1.
void paste_obstacle(Image& left, Image& right, const PastedObstacle& obstacle);

// Where: one window ("left", "centre", "right") or "wall" (the whole interior, all three).
// The box is centred in the window(s) and covers `coverage` of their area (each side scaled by
// sqrt(coverage)); its disparity is round(f B / (distance * downscale)). Throws
// std::invalid_argument for coverage outside (0, 1], a distance outside [0.1, 1000] m, an
// unknown position, or a disparity that does not fit the image.
PastedObstacle obstacle_in_window(int width, int height, int border, const std::string& position,
                                  double coverage, double distance, const StereoGeometry& geometry,
                                  int downscale = 1, std::uint32_t seed = 1);

}  // namespace stereo::robot
