#include "stereo_io/disparity_files.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "quoted.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/limits.hpp"

namespace stereo::io {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

using detail::quoted;

// The next whitespace-delimited token of a PFM header, advancing `at`.
std::string_view next_token(std::string_view bytes, std::size_t& at) {
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at])) != 0) {
        ++at;
    }
    const std::size_t start = at;
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at])) == 0 &&
           at - start < 32) {
        ++at;
    }
    return bytes.substr(start, at - start);
}

std::int64_t parse_dimension(std::string_view token, const std::string& name) {
    std::int64_t value = 0;
    if (token.empty() || token.size() > 9) {
        throw std::runtime_error("cannot read " + name + ": bad PFM size '" + std::string(token) +
                                 "'");
    }
    for (const char c : token) {
        if (c < '0' || c > '9') {
            throw std::runtime_error("cannot read " + name + ": bad PFM size '" +
                                     std::string(token) + "'");
        }
        value = value * 10 + (c - '0');
    }
    if (value < 1) {
        throw std::runtime_error("cannot read " + name + ": PFM size must be positive");
    }
    return value;
}

}  // namespace

cv::Mat to_float_disparity(const ValidatedDisparity& validated) {
    cv::Mat out(validated.height, validated.width, CV_32FC1);
    for (int y = 0; y < validated.height; ++y) {
        for (int x = 0; x < validated.width; ++x) {
            const std::size_t i = validated.index(x, y);
            out.at<float>(y, x) =
                validated.valid(i) ? static_cast<float>(validated.disparity(i)) : kNaN;
        }
    }
    return out;
}

cv::Mat to_offset16(const ValidatedDisparity& validated) {
    cv::Mat out(validated.height, validated.width, CV_16UC1, cv::Scalar(0));
    for (int y = 0; y < validated.height; ++y) {
        for (int x = 0; x < validated.width; ++x) {
            const std::size_t i = validated.index(x, y);
            if (validated.valid(i)) {
                // |fixed| < 2^15 - 1 (constants.hpp), so the code is in 1 .. 65535.
                out.at<std::uint16_t>(y, x) =
                    static_cast<std::uint16_t>(kOffset16Zero + validated.fixed[i]);
            }
        }
    }
    return out;
}

std::string encode_pfm(const cv::Mat& disparity) {
    if (disparity.empty() || disparity.type() != CV_32FC1) {
        throw std::invalid_argument("a PFM disparity must be a non-empty float map");
    }
    static_assert(std::endian::native == std::endian::little, "PFM is written little-endian");
    std::string bytes =
        "Pf\n" + std::to_string(disparity.cols) + " " + std::to_string(disparity.rows) + "\n-1\n";
    const std::size_t header = bytes.size();
    bytes.resize(header + sizeof(float) * disparity.total());
    char* out = bytes.data() + header;
    for (int y = disparity.rows - 1; y >= 0; --y) {  // bottom row first
        for (int x = 0; x < disparity.cols; ++x) {
            float value = disparity.at<float>(y, x);
            if (!std::isfinite(value)) {
                value = std::numeric_limits<float>::infinity();
            }
            std::memcpy(out, &value, sizeof value);
            out += sizeof value;
        }
    }
    return bytes;
}

cv::Mat decode_pfm(std::string_view bytes, const std::string& name) {
    std::size_t at = 0;
    const std::string_view magic = next_token(bytes, at);
    if (magic == "PF") {
        throw std::runtime_error("cannot read " + name +
                                 ": a 3-channel PFM, expected a 1-channel (Pf) disparity");
    }
    if (magic != "Pf") {
        throw std::runtime_error("cannot read " + name + ": not a PFM file");
    }
    const std::int64_t width = parse_dimension(next_token(bytes, at), name);
    const std::int64_t height = parse_dimension(next_token(bytes, at), name);
    if (width * height > max_image_pixels()) {
        throw std::runtime_error("cannot read " + name + ": " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is above the image limit of " +
                                 std::to_string(max_image_pixels()) + " pixels");
    }
    const std::string scale_text(next_token(bytes, at));
    double scale = 0.0;
    std::istringstream scale_stream(scale_text);
    if (!(scale_stream >> scale) || !std::isfinite(scale) || scale == 0.0) {
        throw std::runtime_error("cannot read " + name + ": bad PFM scale '" + scale_text + "'");
    }
    ++at;  // the single whitespace character after the scale
    const auto expected = static_cast<std::size_t>(width * height) * sizeof(float);
    if (at > bytes.size() || bytes.size() - at != expected) {
        throw std::runtime_error("cannot read " + name + ": PFM data is " +
                                 std::to_string(at > bytes.size() ? 0 : bytes.size() - at) +
                                 " bytes, expected " + std::to_string(expected));
    }
    const bool little = scale < 0.0;
    cv::Mat out(static_cast<int>(height), static_cast<int>(width), CV_32FC1);
    const char* in = bytes.data() + at;
    for (int y = out.rows - 1; y >= 0; --y) {
        for (int x = 0; x < out.cols; ++x) {
            std::uint32_t word = 0;
            std::memcpy(&word, in, sizeof word);
            in += sizeof word;
            if (little != (std::endian::native == std::endian::little)) {
                word = (word >> 24) | ((word >> 8) & 0xFF00U) | ((word << 8) & 0xFF0000U) |
                       (word << 24);
            }
            const float value = std::bit_cast<float>(word);
            if (std::isnan(value)) {
                throw std::runtime_error("cannot read " + name + ": NaN at (" + std::to_string(x) +
                                         ", " + std::to_string(y) + ")");
            }
            out.at<float>(y, x) = std::isinf(value) ? kNaN : value;
        }
    }
    return out;
}

DisparityEncoding encoding_of(const std::filesystem::path& path, DisparityEncoding png_encoding) {
    std::string extension = path.extension().string();
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return extension == ".pfm" ? DisparityEncoding::pfm : png_encoding;
}

DisparityEncoding output_encoding(const std::filesystem::path& path, DisparityEncoding png_encoding,
                                  const std::string& option) {
    std::string extension = path.extension().string();
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (!extension.empty() && extension != ".png" && extension != ".pfm") {
        throw std::invalid_argument(
            option + " must name a .png or .pfm file (or have no extension), got " + quoted(path));
    }
    return encoding_of(path, png_encoding);
}

std::string encode_disparity(const ValidatedDisparity& validated, DisparityEncoding encoding,
                             int ndisp, int scale, const std::filesystem::path& path) {
    switch (encoding) {
        case DisparityEncoding::pfm:
            return encode_pfm(to_float_disparity(validated));
        case DisparityEncoding::offset16:
            return encode_png(to_offset16(validated), path);
        case DisparityEncoding::scaled:
            break;
    }
    return encode_png(disparity_to_mat(to_label_map(validated), ndisp, scale), path);
}

cv::Mat load_disparity_file(const std::filesystem::path& path, DisparityEncoding encoding,
                            double scale) {
    if (encoding == DisparityEncoding::pfm) {
        const auto bytes = read_input_file(path);
        return decode_pfm(
            std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
            quoted(path));
    }
    if (encoding == DisparityEncoding::scaled) {
        cv::Mat disparity = load_disparity(path, scale);
        disparity.setTo(kNaN, disparity <= 0.0F);  // 0 = invalid / unknown
        return disparity;
    }
    const cv::Mat raw = load_disparity(path, 1.0);  // the code as a float
    cv::Mat disparity(raw.size(), CV_32FC1);
    for (int y = 0; y < raw.rows; ++y) {
        for (int x = 0; x < raw.cols; ++x) {
            const float code = raw.at<float>(y, x);
            disparity.at<float>(y, x) =
                code == 0.0F ? kNaN
                             : (code - static_cast<float>(kOffset16Zero)) / fx::kSubpixelScale;
        }
    }
    return disparity;
}

}  // namespace stereo::io
