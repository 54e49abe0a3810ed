// Disparity files that hold what stage 6 outputs: signed, sub-pixel, with an invalid code
// (docs/cli.md "Disparity files"). In memory a disparity map is CV_32FC1 with NaN where invalid.
//   PFM      Middlebury 2014's float format: "Pf", width height, -1 (little endian), rows bottom
//            to top; invalid = +inf (written), inf or NaN-free required on reading.
//   offset16 16-bit PNG: value = 32768 + 16 d (d in 1/16 pixel, signed), 0 = invalid.
//   scaled   8- or 16-bit PNG: value = d * scale, 0 = invalid (the classic format).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <opencv2/core/mat.hpp>

#include "stereo/validated.hpp"

namespace stereo::io {

inline constexpr int kOffset16Zero = 32768;  // the code of disparity 0 in an offset16 PNG

enum class DisparityEncoding { scaled, offset16, pfm };

// CV_32FC1: fixed / 16 where valid, NaN elsewhere.
cv::Mat to_float_disparity(const ValidatedDisparity& validated);
// CV_16UC1: 32768 + fixed where valid, 0 elsewhere.
cv::Mat to_offset16(const ValidatedDisparity& validated);

// PFM bytes of a CV_32FC1 map; NaN and inf are written as +inf.
std::string encode_pfm(const cv::Mat& disparity);
// A PFM file's map with +inf / -inf as NaN. Throws std::runtime_error naming `name` for a
// colour PFM, a malformed header, a size above the image limit, a wrong length or a NaN value.
cv::Mat decode_pfm(std::string_view bytes, const std::string& name);

// The encoding a path implies: .pfm -> pfm; otherwise `png_encoding`.
DisparityEncoding encoding_of(const std::filesystem::path& path, DisparityEncoding png_encoding);

// The encoding an output path asks for: .pfm -> pfm, .png or no extension -> `png_encoding`.
// Throws std::invalid_argument naming `option` for any other extension (.tiff, .ply, ...), so
// that no tool writes PNG bytes under another format's name.
DisparityEncoding output_encoding(const std::filesystem::path& path, DisparityEncoding png_encoding,
                                  const std::string& option = "-o");

// The file bytes of stage 6's output in `encoding`: PFM (pixels, +inf invalid), offset16 PNG, or
// the scaled 8-bit PNG of its label map (labels x scale, `ndisp` labels).
std::string encode_disparity(const ValidatedDisparity& validated, DisparityEncoding encoding,
                             int ndisp, int scale, const std::filesystem::path& path);

// Reads a disparity file in `encoding` into CV_32FC1 with NaN where invalid / unknown; `scale`
// applies to the scaled encoding only.
cv::Mat load_disparity_file(const std::filesystem::path& path, DisparityEncoding encoding,
                            double scale);

}  // namespace stereo::io
