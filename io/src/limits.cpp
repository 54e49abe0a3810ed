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
        if (static_cast<unsigned char>(bytes[at]) != 0xFF) {
            return std::nullopt;
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
    return std::nullopt;
}

}  // namespace stereo::io
