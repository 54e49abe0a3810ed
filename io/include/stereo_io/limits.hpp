// Bounds on what an input may make the tools allocate (docs/reliability.md). An image's declared
// size is read from its header and checked before it is decoded, so a small file that declares a
// huge image fails at once with a clear message instead of exhausting memory.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>

namespace stereo::io {

// 64 Mpixel (e.g. 8192 x 8192): four times a 4K frame, far above the data sets used here.
inline constexpr std::int64_t kDefaultMaxImagePixels = std::int64_t{1} << 26;
// The largest image file read into memory.
inline constexpr std::int64_t kMaxImageFileBytes = std::int64_t{1} << 30;

// The current limit: set_max_image_pixels, else the environment variable
// STEREO_MAX_IMAGE_PIXELS, else kDefaultMaxImagePixels.
std::int64_t max_image_pixels();
// Throws std::invalid_argument unless 1 <= pixels <= 2^34.
void set_max_image_pixels(std::int64_t pixels);

// Width and height a PNG, JPEG, PNM (PBM/PGM/PPM), BMP, TIFF or WebP file declares in its
// header; nullopt for other formats or a header too short or malformed to tell. The image
// loaders refuse such files before decoding them: a format whose size is not known up front
// could make the decoder allocate without bound.
std::optional<std::pair<std::int64_t, std::int64_t>> declared_size(std::string_view bytes);

}  // namespace stereo::io
