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
    return std::nullopt;
}

}  // namespace stereo::io
