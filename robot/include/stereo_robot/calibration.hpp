// Camera geometry for the safety threshold T = f * B / Z_safe, and stereo sequences on disk.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace stereo::robot {

struct StereoGeometry {
    double focal_px = 0.0;  // rectified focal length, pixels
    double baseline = 0.0;  // metres (or any unit, the same as the safety distance)
    // Principal point of the left camera, full-size pixels; NaN when unknown (--focal/--baseline
    // given by hand): the ground model then assumes the image centre.
    double cx = std::numeric_limits<double>::quiet_NaN();
    double cy = std::numeric_limits<double>::quiet_NaN();
};

// Reads a rectified calibration in KITTI form: lines of 12 numbers (a 3x4 projection matrix,
// row-major), each optionally prefixed by a label ("P0:", "P_rect_00:", ...). With labels P0 and
// P1 those are used, otherwise the first two matrices are left and right. f = P_left[0][0],
// B = (P_left[0][3] - P_right[0][3]) / f. Throws std::runtime_error when unreadable, and
// std::invalid_argument when the content is not such a calibration.
StereoGeometry load_calibration(const std::filesystem::path& path);

// T = f * B / (Z * downscale): the disparity, in pixels of the (downscaled) image, of a point
// at the safety distance. Throws std::invalid_argument for non-positive inputs.
double disparity_threshold(const StereoGeometry& geometry, double safe_distance, int downscale = 1);

// A stereo sequence: pairs of files. From two folders, the image files present in both under
// the same name, sorted by name; from a list file, one "LEFT RIGHT" pair per line (relative
// paths are relative to the list file, blank lines and lines starting with # are skipped).
using FramePair = std::pair<std::filesystem::path, std::filesystem::path>;
std::vector<FramePair> pairs_from_folders(const std::filesystem::path& left,
                                          const std::filesystem::path& right);
std::vector<FramePair> pairs_from_list(const std::filesystem::path& list);

}  // namespace stereo::robot
