#include "stereo_io/limits.hpp"

#include <cstdlib>
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

std::int64_t big_endian(std::string_view bytes, std::size_t at, int count) {
    std::int64_t value = 0;
    for (int i = 0; i < count; ++i) {
        value = value * 256 + static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    }
    return value;
}

// JPEG: walk the marker segments to the first start-of-frame (SOF0..SOF15 but DHT, JPG, DAC).
std::optional<std::pair<std::int64_t, std::int64_t>> jpeg_size(std::string_view bytes) {
    std::size_t at = 2;  // after SOI
    while (at + 9 < bytes.size()) {
        // libjpeg skips bytes that are not a marker ("extraneous bytes before marker") and still
        // finds a frame header behind them, so the walk resynchronises the same way: a JPEG with
        // garbage before its SOF declared 14884 x 65312 unchecked (found by fuzz_image_loaders).
        if (static_cast<unsigned char>(bytes[at]) != 0xFF) {
            ++at;
            continue;
        }
        const auto marker = static_cast<unsigned char>(bytes[at + 1]);
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        const std::int64_t length = big_endian(bytes, at + 2, 2);
        const bool frame =
            marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {
            return std::make_pair(big_endian(bytes, at + 7, 2), big_endian(bytes, at + 5, 2));
        }
        if (length < 2) {
            return std::nullopt;
        }
        at += 2 + static_cast<std::size_t>(length);
    }
    return std::nullopt;
}

std::int64_t little_endian(std::string_view bytes, std::size_t at, int count) {
    std::int64_t value = 0;
    for (int i = count - 1; i >= 0; --i) {
        value = value * 256 + static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    }
    return value;
}

// PNM (P1..P6, PAM P7 aside): "P<n>", then width and height as decimal numbers separated by
// white space and '#' comments. nullopt when they are not there.
std::optional<std::pair<std::int64_t, std::int64_t>> pnm_size(std::string_view bytes) {
    std::size_t at = 2;
    std::int64_t numbers[2] = {0, 0};
    for (std::int64_t& number : numbers) {
        while (at < bytes.size()) {
            const char c = bytes[at];
            if (c == '#') {
                while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') {
                    ++at;
                }
            } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
                ++at;
            } else {
                break;
            }
        }
        int digits = 0;
        while (at < bytes.size() && bytes[at] >= '0' && bytes[at] <= '9') {
            if (++digits > 12) {
                return std::make_pair(std::int64_t{1} << 40, std::int64_t{1});  // over any limit
            }
            number = number * 10 + (bytes[at] - '0');
            ++at;
        }
        if (digits == 0) {
            return std::nullopt;
        }
    }
    return std::make_pair(numbers[0], numbers[1]);
}

// TIFF: the first image file directory's ImageWidth (256) and ImageLength (257) entries, SHORT
// or LONG, in the file's byte order. The first page is the one OpenCV decodes. BigTIFF and a
// directory that does not name both are not told (the file is then refused).
std::optional<std::pair<std::int64_t, std::int64_t>> tiff_size(std::string_view bytes) {
    const bool little = bytes.substr(0, 4) == std::string_view("II*\0", 4);
    const bool big = bytes.substr(0, 4) == std::string_view("MM\0*", 4);
    if ((!little && !big) || bytes.size() < 8) {
        return std::nullopt;
    }
    const auto read = [&](std::size_t at, int count) {
        return little ? little_endian(bytes, at, count) : big_endian(bytes, at, count);
    };
    const auto directory = static_cast<std::size_t>(read(4, 4));
    if (directory > bytes.size() || bytes.size() - directory < 2) {
        return std::nullopt;
    }
    const auto entries = static_cast<std::size_t>(read(directory, 2));
    std::int64_t width = -1;
    std::int64_t height = -1;
    for (std::size_t i = 0; i < entries; ++i) {
        const std::size_t entry = directory + 2 + 12 * i;
        if (entry + 12 > bytes.size()) {
            return std::nullopt;
        }
        const std::int64_t tag = read(entry, 2);
        const std::int64_t type = read(entry + 2, 2);
        if (tag != 256 && tag != 257) {
            continue;
        }
        std::int64_t value = 0;
        if (type == 3) {  // SHORT, left-justified in the value field
            value = read(entry + 8, 2);
        } else if (type == 4) {  // LONG
            value = read(entry + 8, 4);
        } else {
            return std::nullopt;
        }
        (tag == 256 ? width : height) = value;
    }
    if (width < 0 || height < 0) {
        return std::nullopt;
    }
    return std::make_pair(width, height);
}

// WebP: the RIFF container's first chunk, lossy ("VP8 ": 14-bit sizes after the start code),
// lossless ("VP8L": 14-bit sizes minus one after the signature) or extended ("VP8X": 24-bit
// canvas sizes minus one).
std::optional<std::pair<std::int64_t, std::int64_t>> webp_size(std::string_view bytes) {
    if (bytes.size() < 30 || bytes.substr(0, 4) != "RIFF" || bytes.substr(8, 4) != "WEBP") {
        return std::nullopt;
    }
    const std::string_view chunk = bytes.substr(12, 4);
    if (chunk == "VP8 ") {
        if (bytes.substr(23, 3) != "\x9d\x01\x2a") {
            return std::nullopt;
        }
        return std::make_pair(little_endian(bytes, 26, 2) & 0x3FFF,
                              little_endian(bytes, 28, 2) & 0x3FFF);
    }
    if (chunk == "VP8L") {
        if (static_cast<unsigned char>(bytes[20]) != 0x2F) {
            return std::nullopt;
        }
        const std::int64_t bits = little_endian(bytes, 21, 4);
        return std::make_pair((bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1);
    }
    if (chunk == "VP8X") {
        return std::make_pair(little_endian(bytes, 24, 3) + 1, little_endian(bytes, 27, 3) + 1);
    }
    return std::nullopt;
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

std::optional<std::pair<std::int64_t, std::int64_t>> declared_size(std::string_view bytes) {
    constexpr std::string_view kPng = "\x89PNG\r\n\x1a\n";
    if (bytes.size() >= 24 && bytes.substr(0, 8) == kPng && bytes.substr(12, 4) == "IHDR") {
        return std::make_pair(big_endian(bytes, 16, 4), big_endian(bytes, 20, 4));
    }
    if (bytes.size() >= 4 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
        static_cast<unsigned char>(bytes[1]) == 0xD8) {
        return jpeg_size(bytes);
    }
    if (bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6') {
        return pnm_size(bytes);
    }
    // BMP: BITMAPINFOHEADER (or later) width and height, little-endian, height negative for
    // top-down images.
    if (bytes.size() >= 26 && bytes.substr(0, 2) == "BM" && little_endian(bytes, 14, 4) >= 40) {
        const auto as_signed = [](std::int64_t v) {
            return v >= (std::int64_t{1} << 31) ? v - (std::int64_t{1} << 32) : v;
        };
        const std::int64_t width = as_signed(little_endian(bytes, 18, 4));
        const std::int64_t height = as_signed(little_endian(bytes, 22, 4));
        return std::make_pair(width < 0 ? -width : width, height < 0 ? -height : height);
    }
    // OS/2 BMP (BITMAPCOREHEADER, 12 bytes): 16-bit width and height.
    if (bytes.size() >= 22 && bytes.substr(0, 2) == "BM" && little_endian(bytes, 14, 4) == 12) {
        return std::make_pair(little_endian(bytes, 18, 2), little_endian(bytes, 20, 2));
    }
    if (auto size = tiff_size(bytes)) {
        return size;
    }
    return webp_size(bytes);
}

}  // namespace stereo::io
