// 3-D point clouds from disparity maps (`stereo cloud`, issue 22) and the PLY files that hold
// them: every valid pixel with d + doffs > 0 becomes one coloured point of a pinhole camera,
//   Z = f * B / (d + doffs),  X = (x - cx) * Z / f,  Y = (y - cy) * Z / f
// (x right, y down, Z forward: the left camera's frame, in the unit of B).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace stereo::io {

struct CloudPoint {
    float x = 0.0F;
    float y = 0.0F;
    float z = 0.0F;
    std::uint8_t red = 0;
    std::uint8_t green = 0;
    std::uint8_t blue = 0;
    bool operator==(const CloudPoint&) const = default;
};

struct CloudGeometry {
    double focal = 0.0;     // pixels
    double baseline = 0.0;  // any unit > 0: the cloud's unit
    double cx = 0.0;        // principal point, pixels
    double cy = 0.0;
    double doffs = 0.0;  // disparity offset (Middlebury 2014's doffs; a light field's focal plane)
};

// Throws std::invalid_argument for a non-positive or non-finite focal length or baseline, or a
// non-finite principal point or offset.
void check_geometry(const CloudGeometry& geometry);

// `disparity`: CV_32FC1, NaN where invalid; `bgr`: CV_8UC3 (or CV_8UC1) of the same size.
// Points in raster order. Throws std::invalid_argument on a size or type mismatch.
std::vector<CloudPoint> disparity_to_points(const cv::Mat& disparity, const cv::Mat& bgr,
                                            const CloudGeometry& geometry);

// PLY 1.0 with vertex properties float x, y, z and uchar red, green, blue: ASCII, or
// binary_little_endian.
std::string encode_ply(const std::vector<CloudPoint>& points, bool binary);

// Reads what encode_ply writes (either format, those six properties in that order). Throws
// std::runtime_error naming `name` for anything else.
std::vector<CloudPoint> decode_ply(std::string_view bytes, const std::string& name);

}  // namespace stereo::io
