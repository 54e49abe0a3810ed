#include "stereo_robot/ground.hpp"

#include <cmath>

namespace stereo::robot {

bool GroundModel::obstacle(int v, int d) const {
    if (!(d > line.disparity(v) + tolerance)) {
        return false;
    }
    // The ground at this disparity is seen at row (d - b) / a; each row is B / d metres there.
    const double ground_row = (d - line.intercept) / line.slope;
    const double height = baseline * (ground_row - v) / d;
    return height <= max_height;
}

slam::VDisparity v_disparity(const DisparityMap& map, int ndisp) {
    slam::VDisparity out{map.height, ndisp,
                         std::vector<int>(static_cast<std::size_t>(map.height) * ndisp)};
    for (int v = 0; v < map.height; ++v) {
        for (int u = 0; u < map.width; ++u) {
            const std::size_t i = map.index(u, v);
            const int d = map.disparity[i];
            if (map.valid[i] != 0 && d < ndisp) {
                ++out.counts[static_cast<std::size_t>(v) * ndisp + d];
            }
        }
    }
    return out;
}

slam::Camera avoidance_camera(const StereoGeometry& geometry, int downscale, int width,
                              int height) {
    const bool known = std::isfinite(geometry.cx) && std::isfinite(geometry.cy);
    slam::Camera full{geometry.focal_px, known ? geometry.cx : 0.0, known ? geometry.cy : 0.0,
                      geometry.baseline};
    slam::Camera camera = full.downscaled(downscale);
    if (!known) {
        camera.cx = (width - 1) / 2.0;
        camera.cy = (height - 1) / 2.0;
    }
    return camera;
}

std::optional<GroundModel> fit_ground(const DisparityMap& map, int ndisp,
                                      const slam::Camera& camera, const GroundRemoval& params) {
    if (!params.enabled) {
        return std::nullopt;
    }
    const auto line = slam::fit_ground_line(v_disparity(map, ndisp), camera, params.fit);
    if (!line) {
        return std::nullopt;
    }
    return GroundModel{*line, params.fit.tolerance, params.max_height, camera.baseline};
}

}  // namespace stereo::robot
