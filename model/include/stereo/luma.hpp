// The integer luma every grey-image stage reads (the census and ZNCC costs, the edge front end):
// a small shared helper, so that the stages do not depend on the methods that also use it.
#pragma once

#include "stereo/image.hpp"

namespace stereo {

// ITU-R BT.601 integer luma, (77 R + 150 G + 29 B + 128) >> 8 (fx::kLumaR, kLumaG, kLumaB,
// kLumaShift); a grey image is returned as is.
Image luma(const Image& image);

}  // namespace stereo
