// Bounds on what an input may make the tools allocate (docs/reliability.md, "Bounded inputs"). An
// image's declared size is read from its header (declared_image) and checked before it is
// decoded, so a small file that declares a huge image fails at once with a clear message instead
// of exhausting memory; the decode itself then refuses any matrix above the limit whatever the
// header said (io::decode_bounded in stereo_io/io.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
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

// What an image file's header declares, read the way the decoder OpenCV picks for it reads it.
struct DeclaredImage {
    std::int64_t width = 0;
    std::int64_t height = 0;
    // The most pixels one buffer of the decode may hold: width x height, or more when the file
    // makes the decoder allocate by another measure (a TIFF's tiles or strips, which OpenCV sizes
    // from TileWidth x TileLength or ImageWidth x RowsPerStrip, not from the image; a later TIFF
    // page). Saturates at INT64_MAX.
    std::int64_t largest_pixels = 0;
    // What largest_pixels measures when it is more than width x height ("12000x12000 tiles",
    // "page 2, 9000x9000"), else empty.
    std::string largest_what;
};

// The header of a PNG, JPEG, PNM (PBM/PGM/PPM), BMP, TIFF (classic or BigTIFF, every page) or
// WebP file; nullopt for other formats, a header too short or malformed to tell, or a file that
// OpenCV would hand to a decoder other than the one whose header was read (a polyglot). The
// format is recognised by OpenCV 4's own signature rules in its own order, and each header is
// walked as its decoder walks it (libjpeg's marker loop, OpenCV's PNM number reader, libtiff's
// directory chain), so that a file cannot show this reader one size and the decoder another.
// The image loaders refuse a file this returns nullopt for, before decoding it.
std::optional<DeclaredImage> declared_image(std::string_view bytes);

// declared_image's width and height.
std::optional<std::pair<std::int64_t, std::int64_t>> declared_size(std::string_view bytes);

}  // namespace stereo::io
