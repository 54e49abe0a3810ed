// Ground removal for the avoidance windows: the road or floor in front of the robot is not an
// obstacle, even when it is nearer than the safety distance. The ground is the line of the
// v-disparity image that a flat floor seen by this camera can make (the SLAM layer's robust fit,
// slam::fit_ground_line); pixels on or below it, and pixels higher above it than the robot can
// hit, are "ignored" by the window statistics. Rules and defaults: docs/avoidance.md.
#pragma once

#include <optional>

#include "stereo/image.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/slam/maps.hpp"

namespace stereo::robot {

struct GroundRemoval {
    bool enabled = true;
    slam::GroundParams fit;   // camera height 0.1-3 m, pitch within 15 degrees, tolerance 1 px
    double max_height = 3.0;  // metres above the ground: higher pixels (sky, canopies, signs)
                              // cannot block the robot
};

// The plane model of one disparity map: pixel (u, v, d) is ground when
// d <= line(v) + tolerance, and "overhead" when its height above the ground,
// B ((d - b) / a - v) / d, exceeds max_height.
struct GroundModel {
    slam::GroundLine line;
    double tolerance = 1.0;
    double max_height = 3.0;
    double baseline = 0.0;

    // True when the pixel can be an obstacle: above the ground band and not overhead.
    bool obstacle(int v, int d) const;
};

// v-disparity of the valid pixels of an integer disparity map (labels 0 .. ndisp - 1).
slam::VDisparity v_disparity(const DisparityMap& map, int ndisp);

// The camera of a map matched at 1/downscale of the calibration's size: principal point from
// the calibration, or the map's centre when unknown.
slam::Camera avoidance_camera(const StereoGeometry& geometry, int downscale, int width, int height);

// Fits the ground line to the map; nothing when disabled or when no plausible line exists
// (then every valid pixel counts, as in the thesis).
std::optional<GroundModel> fit_ground(const DisparityMap& map, int ndisp,
                                      const slam::Camera& camera, const GroundRemoval& params);

}  // namespace stereo::robot
