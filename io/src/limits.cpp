#include "stereo_io/limits.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

namespace stereo::io {
namespace {

constexpr std::int64_t kLargestLimit = std::int64_t{1} << 34;

std::int64_t& configured_limit() {
    static std::int64_t limit = [] {
        const char* text = std::getenv("STEREO_MAX_IMAGE_PIXELS");
        if (text == nullptr || *text == '\0') {
            return kDefaultMaxImagePixels;
        }
        char* end = nullptr;
        const long long value = std::strtoll(text, &end, 10);
        if (*end != '\0' || value < 1 || value > kLargestLimit) {
            throw std::invalid_argument(
                "STEREO_MAX_IMAGE_PIXELS must be a whole number in [1, 2^34], got \"" +
                std::string(text) + "\"");
        }
        return static_cast<std::int64_t>(value);
    }();
    return limit;
}

constexpr std::int64_t kHuge = std::numeric_limits<std::int64_t>::max();

// Unsigned integers of up to 8 bytes. An 8-byte value with its top bit set comes back negative
// (two's complement, C++20); callers that read 8 bytes cast the result to std::uint64_t. The sum
// is formed unsigned: a signed one overflowed on such values (fuzz.image_loaders, BigTIFF).
std::int64_t big_endian(std::string_view bytes, std::size_t at, int count) {
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i) {
        value = value * 256 + static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    }
    return static_cast<std::int64_t>(value);
}

std::int64_t little_endian(std::string_view bytes, std::size_t at, int count) {
    std::uint64_t value = 0;
    for (int i = count - 1; i >= 0; --i) {
        value = value * 256 + static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    }
    return static_cast<std::int64_t>(value);
}

// a x b for sizes >= 0, saturated at kHuge.
std::int64_t product(std::int64_t a, std::int64_t b) {
    if (a <= 0 || b <= 0) {
        return 0;
    }
    return a > kHuge / b ? kHuge : a * b;
}

std::string size_text(std::int64_t width, std::int64_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

DeclaredImage image_of(std::int64_t width, std::int64_t height) {
    return {width, height, product(width, height), {}};
}

bool starts_with(std::string_view bytes, std::string_view prefix) {
    return bytes.substr(0, prefix.size()) == prefix;
}

bool has_at(std::string_view bytes, std::size_t at, std::string_view text) {
    return bytes.size() >= at + text.size() && bytes.substr(at, text.size()) == text;
}

// JPEG, as libjpeg's read_markers() walks it up to the frame header (jdmarker.c): after SOI,
// next_marker() skips every byte that is not 0xFF (garbage, "extraneous bytes before marker"),
// then any number of 0xFF fill bytes; 0xFF 0x00 is a stuffed zero and skipped too. RSTn and TEM
// have no length; a second SOI, SOS or EOI before a frame header, and reserved markers, end
// libjpeg with an error, so the walk gives up there as well. Every other marker has a 16-bit
// length, counted from the length itself. The first SOFn (any of the 13, decodable or not) holds
// the size: a walk that read a length after RSTn or TEM jumped over the real frame header and
// could find a small decoy later in the file (issue 51).
std::optional<DeclaredImage> jpeg_image(std::string_view bytes) {
    const auto byte = [&](std::size_t at) { return static_cast<unsigned char>(bytes[at]); };
    std::size_t at = 2;  // after SOI
    while (true) {
        while (at < bytes.size() && byte(at) != 0xFF) {
            ++at;
        }
        while (at < bytes.size() && byte(at) == 0xFF) {
            ++at;
        }
        if (at >= bytes.size()) {
            return std::nullopt;
        }
        const unsigned marker = byte(at++);
        if (marker == 0x00 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
            continue;  // stuffed zero, RST0..RST7, TEM: no length
        }
        const bool frame =
            marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {  // length, precision, height, width
            if (at + 7 > bytes.size()) {
                return std::nullopt;
            }
            return image_of(big_endian(bytes, at + 5, 2), big_endian(bytes, at + 3, 2));
        }
        const bool has_length = marker == 0xC4 || marker == 0xCC || marker == 0xDB ||
                                marker == 0xDC || marker == 0xDD || marker == 0xFE ||
                                (marker >= 0xE0 && marker <= 0xEF);
        if (!has_length || at + 2 > bytes.size()) {
            return std::nullopt;  // SOI, SOS, EOI, a reserved marker, or the end of the file
        }
        const std::int64_t length = big_endian(bytes, at, 2);
        if (length < 2) {
            return std::nullopt;
        }
        at += static_cast<std::size_t>(length);
    }
}

// PNM (P1..P6), as OpenCV's PxMDecoder reads it (grfmt_pxm.cpp, ReadNumber): before each number,
// white space (isspace) and '#' comments, a comment running to '\n' or '\r'; then decimal digits,
// leading zeros allowed; then ONE character, whatever it is, is consumed as the terminator. So in
// "P5 64#1000\n..." the '#' ends the width and the height is 1000, not a comment: a reader that
// took it for a comment saw another height than the decoder (issue 51). OpenCV refuses a number
// above INT_MAX; such a number is reported here as it is (saturated), so that the message names it.
std::optional<DeclaredImage> pnm_image(std::string_view bytes) {
    std::size_t at = 2;
    std::int64_t numbers[2] = {0, 0};
    for (std::int64_t& number : numbers) {
        while (true) {
            if (at >= bytes.size()) {
                return std::nullopt;
            }
            const char c = bytes[at];
            if (c >= '0' && c <= '9') {
                break;
            }
            if (c == '#') {
                ++at;
                while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') {
                    ++at;
                }
                ++at;  // the end of the comment
            } else if (std::isspace(static_cast<unsigned char>(c)) != 0) {
                ++at;
            } else {
                return std::nullopt;  // OpenCV: "Unexpected code in ReadNumber()"
            }
        }
        while (at < bytes.size() && bytes[at] >= '0' && bytes[at] <= '9') {
            const int digit = bytes[at] - '0';
            number = number > (kHuge - digit) / 10 ? kHuge : number * 10 + digit;
            ++at;
        }
        ++at;  // the terminator
    }
    return image_of(numbers[0], numbers[1]);
}

// TIFF and BigTIFF, as libtiff reads a directory for OpenCV's TiffDecoder (grfmt_tiff.cpp).
// OpenCV decodes the first page; its strip or tile buffer is TileWidth x TileLength when the page
// is tiled and ImageWidth x RowsPerStrip when it is striped (0, absent or 2^32-1 meaning the
// whole image), NOT bounded by the image: a 64 x 64 image in 12000 x 12000 tiles made it
// allocate and clear 576 MB (issue 51). So the largest buffer is the largest of the image, the
// tile and the strip, over every page of the chain, and a tag that appears twice counts with its
// larger value. libtiff refuses a size tag of another type or count than one integer, which
// refuses the file here too.
class TiffReader {
  public:
    explicit TiffReader(std::string_view bytes) : bytes_(bytes) {}

    std::optional<DeclaredImage> read() {
        little_ = starts_with(bytes_, std::string_view("II", 2));
        if (bytes_.size() < 8) {
            return std::nullopt;
        }
        const std::int64_t version = number(2, 2);
        std::uint64_t directory = 0;
        if (version == 42) {
            directory = static_cast<std::uint64_t>(number(4, 4));
        } else if (version == 43 && bytes_.size() >= 16 && number(4, 2) == 8 && number(6, 2) == 0) {
            big_ = true;
            directory = static_cast<std::uint64_t>(number(8, 8));
        } else {
            return std::nullopt;
        }
        std::optional<DeclaredImage> first;
        std::set<std::uint64_t> seen;
        for (int page = 1; directory != 0; ++page) {
            if (page > kMaxPages || !seen.insert(directory).second) {
                return std::nullopt;  // a loop, or more pages than any stereo input has
            }
            const auto image = read_directory(directory);
            if (!image) {
                if (page == 1) {
                    return std::nullopt;  // libtiff cannot open the file
                }
                break;  // libtiff stops here; nothing after it can be decoded
            }
            if (!first) {
                first = image;
            } else if (image->largest_pixels > first->largest_pixels) {
                first->largest_pixels = image->largest_pixels;
                first->largest_what =
                    "page " + std::to_string(page) + ", " +
                    (image->largest_what.empty() ? size_text(image->width, image->height)
                                                 : image->largest_what);
            }
            directory = next_;
        }
        return first;
    }

  private:
    static constexpr int kMaxPages = 1024;

    // The integer field types of TIFF 6.0 and BigTIFF: type code, size in bytes, signed.
    struct IntegerType {
        std::int64_t type;
        int size;
        bool is_signed;
    };
    static constexpr std::array<IntegerType, 10> kIntegerTypes = {{
        {1, 1, false},   // BYTE
        {6, 1, true},    // SBYTE
        {3, 2, false},   // SHORT
        {8, 2, true},    // SSHORT
        {4, 4, false},   // LONG
        {13, 4, false},  // IFD
        {9, 4, true},    // SLONG
        {16, 8, false},  // LONG8
        {18, 8, false},  // IFD8
        {17, 8, true},   // SLONG8
    }};

    std::int64_t number(std::size_t at, int count) const {
        return little_ ? little_endian(bytes_, at, count) : big_endian(bytes_, at, count);
    }

    // The value of a one-integer entry whose value field is at `field`; nullopt for another type,
    // count, a negative value or an offset outside the file.
    std::optional<std::int64_t> integer(std::int64_t type, std::uint64_t count,
                                        std::size_t field) const {
        const auto kind = std::find_if(kIntegerTypes.begin(), kIntegerTypes.end(),
                                       [&](const IntegerType& t) { return t.type == type; });
        if (kind == kIntegerTypes.end()) {
            return std::nullopt;
        }
        const int size = kind->size;
        const bool is_signed = kind->is_signed;
        if (count != 1) {
            return std::nullopt;
        }
        std::size_t at = field;
        if (size > (big_ ? 8 : 4)) {  // not inline: at an offset
            const auto offset = static_cast<std::uint64_t>(number(field, big_ ? 8 : 4));
            if (offset > bytes_.size() || bytes_.size() - offset < static_cast<std::size_t>(size)) {
                return std::nullopt;
            }
            at = static_cast<std::size_t>(offset);
        }
        const auto raw = static_cast<std::uint64_t>(number(at, size));
        const std::uint64_t sign_bit = std::uint64_t{1} << (8 * size - 1);
        if (is_signed && (raw & sign_bit) != 0) {
            return std::nullopt;  // libtiff: a negative size is out of range
        }
        return raw > static_cast<std::uint64_t>(kHuge) ? kHuge : static_cast<std::int64_t>(raw);
    }

    std::optional<DeclaredImage> read_directory(std::uint64_t directory) {
        const std::size_t count_size = big_ ? 8 : 2;
        const std::size_t entry_size = big_ ? 20 : 12;
        const std::size_t offset_size = big_ ? 8 : 4;
        if (directory > bytes_.size() || bytes_.size() - directory < count_size) {
            return std::nullopt;
        }
        const auto at = static_cast<std::size_t>(directory);
        const auto entries = static_cast<std::uint64_t>(number(at, static_cast<int>(count_size)));
        if (entries > (bytes_.size() - at - count_size) / entry_size) {
            return std::nullopt;  // the directory runs past the end of the file
        }
        // Tag -> largest value: ImageWidth, ImageLength, RowsPerStrip, TileWidth, TileLength.
        std::int64_t width = -1;
        std::int64_t height = -1;
        std::int64_t rows_per_strip = -1;
        std::int64_t tile_width = -1;
        std::int64_t tile_height = -1;
        for (std::uint64_t i = 0; i < entries; ++i) {
            const std::size_t entry = at + count_size + static_cast<std::size_t>(i) * entry_size;
            const std::int64_t tag = number(entry, 2);
            std::int64_t* slot = tag == 256   ? &width
                                 : tag == 257 ? &height
                                 : tag == 278 ? &rows_per_strip
                                 : tag == 322 ? &tile_width
                                 : tag == 323 ? &tile_height
                                              : nullptr;
            if (slot == nullptr) {
                continue;
            }
            const auto count = static_cast<std::uint64_t>(number(entry + 4, big_ ? 8 : 4));
            const auto value = integer(number(entry + 2, 2), count, entry + 4 + (big_ ? 8 : 4));
            if (!value) {
                return std::nullopt;
            }
            *slot = std::max(*slot, *value);
        }
        const std::size_t next_at =
            at + count_size + static_cast<std::size_t>(entries) * entry_size;
        next_ = bytes_.size() - next_at >= offset_size
                    ? static_cast<std::uint64_t>(number(next_at, static_cast<int>(offset_size)))
                    : 0;
        if (width < 0 || height < 0) {
            return std::nullopt;  // libtiff: "MissingRequired"
        }
        DeclaredImage image = image_of(width, height);
        const auto consider = [&](std::int64_t w, std::int64_t h, const char* what) {
            const std::int64_t pixels = product(w, h);
            if (pixels > image.largest_pixels) {
                image.largest_pixels = pixels;
                image.largest_what = size_text(w, h) + " " + what;
            }
        };
        if (tile_width >= 0 || tile_height >= 0) {
            consider(tile_width > 0 ? tile_width : width, tile_height > 0 ? tile_height : height,
                     "tiles");
        }
        const bool whole = rows_per_strip <= 0 || rows_per_strip == 0xFFFFFFFFLL;
        consider(width, whole ? height : rows_per_strip, "strips");
        return image;
    }

    std::string_view bytes_;
    bool little_ = false;
    bool big_ = false;
    std::uint64_t next_ = 0;
};

// WebP: the RIFF container's first chunk, lossy ("VP8 ": 14-bit sizes after the start code),
// lossless ("VP8L": 14-bit sizes minus one after the signature) or extended ("VP8X": 24-bit
// canvas sizes minus one).
std::optional<DeclaredImage> webp_image(std::string_view bytes) {
    if (bytes.size() < 30 || bytes.substr(0, 4) != "RIFF" || bytes.substr(8, 4) != "WEBP") {
        return std::nullopt;
    }
    const std::string_view chunk = bytes.substr(12, 4);
    if (chunk == "VP8 ") {
        if (bytes.substr(23, 3) != "\x9d\x01\x2a") {
            return std::nullopt;
        }
        return image_of(little_endian(bytes, 26, 2) & 0x3FFF, little_endian(bytes, 28, 2) & 0x3FFF);
    }
    if (chunk == "VP8L") {
        if (static_cast<unsigned char>(bytes[20]) != 0x2F) {
            return std::nullopt;
        }
        const std::int64_t bits = little_endian(bytes, 21, 4);
        return image_of((bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1);
    }
    if (chunk == "VP8X") {
        return image_of(little_endian(bytes, 24, 3) + 1, little_endian(bytes, 27, 3) + 1);
    }
    return std::nullopt;
}

// BMP: BITMAPINFOHEADER (or later) width and height, little-endian, height negative for top-down
// images; OS/2's BITMAPCOREHEADER (12 bytes) has 16-bit sizes.
std::optional<DeclaredImage> bmp_image(std::string_view bytes) {
    if (bytes.size() >= 26 && little_endian(bytes, 14, 4) >= 40) {
        const auto as_signed = [](std::int64_t v) {
            return v >= (std::int64_t{1} << 31) ? v - (std::int64_t{1} << 32) : v;
        };
        const std::int64_t width = as_signed(little_endian(bytes, 18, 4));
        const std::int64_t height = as_signed(little_endian(bytes, 22, 4));
        return image_of(width < 0 ? -width : width, height < 0 ? -height : height);
    }
    if (bytes.size() >= 22 && little_endian(bytes, 14, 4) == 12) {
        return image_of(little_endian(bytes, 18, 2), little_endian(bytes, 20, 2));
    }
    return std::nullopt;
}

// Whether OpenCV 4's decoders that come after WebP in its list and read nothing here (DICOM:
// "DICM" at 128; GDAL: "DTED" at 140) would claim the file.
bool claimed_by_later_decoder(std::string_view bytes) {
    return has_at(bytes, 128, "DICM") || has_at(bytes, 140, "DTED");
}

}  // namespace

std::int64_t max_image_pixels() {
    return configured_limit();
}

void set_max_image_pixels(std::int64_t pixels) {
    if (pixels < 1 || pixels > kLargestLimit) {
        throw std::invalid_argument("the image size limit must be in [1, 2^34] pixels, got " +
                                    std::to_string(pixels));
    }
    configured_limit() = pixels;
}

// OpenCV 4.6's decoders in the order cv::imdecode tries them (loadsave.cpp, ImageCodecInitializer),
// each with its own signature test: BMP "BM"; Radiance HDR; JPEG FF D8 FF; WebP (libwebp accepts
// the first 32 bytes); Sun raster; PNM 'P', '1'..'6', white space; PAM; PFM; TIFF and BigTIFF;
// PNG; then DICOM, JPEG 2000, OpenEXR and GDAL. The first that matches decodes the file, so the
// header read here must be the one that decoder reads: a PNM without the white space after "P5",
// or FF D8 without the third FF, goes to another decoder (or none) and is refused.
std::optional<DeclaredImage> declared_image(std::string_view bytes) {
    const auto byte = [&](std::size_t at) { return static_cast<unsigned char>(bytes[at]); };
    if (starts_with(bytes, "BM")) {
        return bmp_image(bytes);
    }
    if (starts_with(bytes, "#?RGBE") || starts_with(bytes, "#?RADIANCE")) {
        return std::nullopt;
    }
    if (bytes.size() >= 3 && byte(0) == 0xFF && byte(1) == 0xD8 && byte(2) == 0xFF) {
        return jpeg_image(bytes);
    }
    if (has_at(bytes, 0, "RIFF") && has_at(bytes, 8, "WEBP")) {
        // When libwebp refuses the header OpenCV goes on down its list; refuse the file rather
        // than decide which later decoder would take it.
        return claimed_by_later_decoder(bytes) ? std::nullopt : webp_image(bytes);
    }
    if (bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6' &&
        std::isspace(byte(2)) != 0) {
        return pnm_image(bytes);
    }
    if (starts_with(bytes, std::string_view("II*\0", 4)) ||
        starts_with(bytes, std::string_view("MM\0*", 4)) ||
        starts_with(bytes, std::string_view("II+\0", 4)) ||
        starts_with(bytes, std::string_view("MM\0+", 4))) {
        return TiffReader(bytes).read();
    }
    constexpr std::string_view kPng = "\x89PNG\r\n\x1a\n";
    if (bytes.size() >= 24 && starts_with(bytes, kPng) && bytes.substr(12, 4) == "IHDR") {
        return image_of(big_endian(bytes, 16, 4), big_endian(bytes, 20, 4));
    }
    return std::nullopt;
}

std::optional<std::pair<std::int64_t, std::int64_t>> declared_size(std::string_view bytes) {
    const auto image = declared_image(bytes);
    if (!image) {
        return std::nullopt;
    }
    return std::make_pair(image->width, image->height);
}

}  // namespace stereo::io
