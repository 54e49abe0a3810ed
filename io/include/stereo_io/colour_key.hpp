// Images people look at carry their key (issue 47): the colour view of a disparity map with a
// colour bar in pixels and invalid pixels in a colour the colour map never uses, and the error
// map with a legend. In OpenCV's BGR order, ready for encode_png / write_png.
#pragma once

#include <opencv2/core/mat.hpp>

#include "stereo/image.hpp"

namespace stereo::io {

// Invalid pixels of the keyed colour view: white, which TURBO never reaches (its ends are dark
// purple and dark red, and every entry is far from white; tested), so that far (purple) and
// invalid read apart.
inline const cv::Vec3b kInvalidColour{255, 255, 255};

// Height in pixels of the strip colour_view and with_error_legend append below the image.
inline constexpr int kKeyHeight = 30;

// The TURBO view of `map` (labels 0..ndisp-1 spread over the colour map, as
// disparity_to_colour), invalid pixels in kInvalidColour, and with `bar` a strip of kKeyHeight
// rows below it: the colour map from label 0 to ndisp-1 across the width, tick values in pixels
// (min_disp + label) and, where the image is wide enough, an "invalid" swatch.
cv::Mat colour_view(const DisparityMap& map, int ndisp, int min_disp, bool bar);

// The error map (metrics.hpp error_map) with a strip below naming its colours: correct (grey),
// bad (red), invalid (blue), not scored (black).
cv::Mat with_error_legend(const cv::Mat& error_map);

}  // namespace stereo::io
