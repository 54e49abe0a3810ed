// The figure strip of one scene with ground truth (`stereo middlebury --figures`,
// `stereo_experiments asw-eval --figures`): five half-size panels, left image, ground truth,
// our disparity, signed error (io::signed_error_image, mid-grey = 0) and bad > 1 map
// (io::error_map inside the `all` mask when the scene has one), a title above each and, below,
// a key: the disparity colour bar, the signed-error scale and the legend of the bad-pixel map.
#pragma once

#include <string>

#include <opencv2/core/mat.hpp>

#include "stereo_io/middlebury.hpp"

namespace stereo::io {

// `ours`: CV_32FC1, 0 = invalid (to_float_disparity). `ours_title` names the third panel.
// Returned in OpenCV's BGR order, ready for encode_png / write_png.
cv::Mat scene_strip(const SceneData& data, const cv::Mat& ours, const std::string& ours_title);

}  // namespace stereo::io
