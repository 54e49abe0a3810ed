// Disparity files that hold what stage 6 outputs: signed, sub-pixel, with an invalid code
// (docs/cli.md "Disparity files"). In memory a disparity map is CV_32FC1 with NaN where invalid.
//   PFM      Middlebury 2014's float format: "Pf", width height, -1 (little endian), rows bottom
//            to top; invalid = +inf (written), inf or NaN-free required on reading.
//   offset16 16-bit PNG: value = 32768 + 16 d (d in 1/16 pixel, signed), 0 = invalid.
//   scaled   8- or 16-bit PNG: value = d * scale, 0 = invalid (the classic format).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
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

// Self-describing disparity PNGs (issue 47): every disparity PNG the tools write carries a tEXt
// chunk with the keyword kDisparityTagKeyword and the text "encoding=scaled scale=K" or
// "encoding=offset16", so that `stereo eval` reads it right without --scale or --encoding. The
// chunk sits just before IEND; the pixels and every other byte are what cv::imencode wrote.
inline constexpr std::string_view kDisparityTagKeyword = "stereo-disparity";

struct DisparityTag {
    DisparityEncoding encoding = DisparityEncoding::scaled;  // scaled or offset16
    double scale = 1.0;                                      // scaled: the file holds d * scale
    bool operator==(const DisparityTag&) const = default;
};

// The CRC-32 of PNG chunks (ISO 3309, the one zlib's crc32 computes).
std::uint32_t png_crc32(std::span<const unsigned char> bytes);

// `png` with a tEXt chunk "keyword\0text" inserted before its IEND chunk. Throws
// std::invalid_argument when `png` is not a PNG ending in IEND, or the keyword is not 1..79
// printable Latin-1 characters.
std::string with_png_text(std::string png, std::string_view keyword, std::string_view text);
// The text of the first tEXt chunk named `keyword`, if any; std::nullopt for other files.
std::optional<std::string> png_text(std::span<const unsigned char> bytes, std::string_view keyword);

// The tag's text ("encoding=scaled scale=4") and back; parse_disparity_tag throws
// std::runtime_error naming `name` for a text it cannot read.
std::string disparity_tag_text(const DisparityTag& tag);
DisparityTag parse_disparity_tag(std::string_view text, const std::string& name);
// The tag of a disparity PNG, std::nullopt when it has none (written by another tool, or not a
// PNG at all).
std::optional<DisparityTag> read_disparity_tag(const std::filesystem::path& path);

// `mat` (a scaled or offset16 disparity image) as PNG bytes with its tag; the scale is written
// for the scaled encoding only. std::runtime_error naming `path` when it cannot be encoded.
std::string encode_disparity_png(const cv::Mat& mat, const DisparityTag& tag,
                                 const std::filesystem::path& path);

// Reads a disparity file in `encoding` into CV_32FC1 with NaN where invalid / unknown; `scale`
// applies to the scaled encoding only.
cv::Mat load_disparity_file(const std::filesystem::path& path, DisparityEncoding encoding,
                            double scale);

}  // namespace stereo::io
