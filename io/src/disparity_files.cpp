#include "stereo_io/disparity_files.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

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
            return encode_disparity_png(to_offset16(validated),
                                        {.encoding = DisparityEncoding::offset16}, path);
        case DisparityEncoding::scaled:
            break;
    }
    return encode_disparity_png(disparity_to_mat(to_label_map(validated), ndisp, scale),
                                {.encoding = DisparityEncoding::scaled, .scale = double(scale)},
                                path);
}

namespace {

constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P',  'N',  'G',
                                                        '\r', '\n', 0x1A, '\n'};

std::uint32_t read_be32(const unsigned char* at) {
    return (std::uint32_t{at[0]} << 24) | (std::uint32_t{at[1]} << 16) |
           (std::uint32_t{at[2]} << 8) | std::uint32_t{at[3]};
}

void append_be32(std::string& out, std::uint32_t value) {
    for (const int shift : {24, 16, 8, 0}) {
        out.push_back(static_cast<char>((value >> shift) & 0xFFU));
    }
}

bool is_png(std::span<const unsigned char> bytes) {
    return bytes.size() >= kPngSignature.size() &&
           std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin());
}

// Calls visit(type, data) for each chunk of a PNG until it returns false or the bytes end.
template <class Visit>
void for_each_chunk(std::span<const unsigned char> bytes, Visit visit) {
    std::size_t at = kPngSignature.size();
    while (at + 12 <= bytes.size()) {
        const std::uint32_t length = read_be32(bytes.data() + at);
        if (length > bytes.size() - at - 12) {
            return;
        }
        const std::string_view type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
        if (!visit(type, bytes.subspan(at + 8, length), at)) {
            return;
        }
        at += 12 + std::size_t{length};
    }
}

}  // namespace

std::uint32_t png_crc32(std::span<const unsigned char> bytes) {
    // zlib's CRC-32 is the one PNG specifies (ISO 3309, polynomial 0xEDB88320).
    uLong crc = crc32(0L, Z_NULL, 0);
    std::size_t done = 0;
    while (done < bytes.size()) {  // crc32 takes a uInt length: a chunk of at most 1 GiB at a time
        const auto length = static_cast<uInt>(std::min<std::size_t>(bytes.size() - done, 1U << 30));
        crc = crc32(crc, bytes.data() + done, length);
        done += length;
    }
    return static_cast<std::uint32_t>(crc);
}

std::string with_png_text(std::string png, std::string_view keyword, std::string_view text) {
    if (keyword.empty() || keyword.size() > 79 ||
        std::any_of(keyword.begin(), keyword.end(), [](char c) {
            const auto u = static_cast<unsigned char>(c);
            return u < 32 || (u > 126 && u < 161);
        })) {
        throw std::invalid_argument("a PNG text keyword must be 1 to 79 printable characters");
    }
    const std::span<const unsigned char> bytes(reinterpret_cast<const unsigned char*>(png.data()),
                                               png.size());
    std::optional<std::size_t> iend;
    if (is_png(bytes)) {
        for_each_chunk(bytes, [&](std::string_view type, auto, std::size_t at) {
            if (type == "IEND") {
                iend = at;
                return false;
            }
            return true;
        });
    }
    if (!iend) {
        throw std::invalid_argument("cannot add a PNG text chunk: not a PNG ending in IEND");
    }
    std::string chunk;
    append_be32(chunk, static_cast<std::uint32_t>(keyword.size() + 1 + text.size()));
    chunk += "tEXt";
    chunk += keyword;
    chunk.push_back('\0');
    chunk += text;
    append_be32(chunk, png_crc32({reinterpret_cast<const unsigned char*>(chunk.data()) + 4,
                                  chunk.size() - 4}));
    png.insert(*iend, chunk);
    return png;
}

std::optional<std::string> png_text(std::span<const unsigned char> bytes,
                                    std::string_view keyword) {
    std::optional<std::string> found;
    if (!is_png(bytes)) {
        return found;
    }
    for_each_chunk(
        bytes, [&](std::string_view type, std::span<const unsigned char> data, std::size_t) {
            if (type == "IEND") {
                return false;
            }
            const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
            if (type == "tEXt" && text.size() > keyword.size() && text.starts_with(keyword) &&
                text[keyword.size()] == '\0') {
                found = std::string(text.substr(keyword.size() + 1));
                return false;
            }
            return true;
        });
    return found;
}

std::string disparity_tag_text(const DisparityTag& tag) {
    if (tag.encoding == DisparityEncoding::offset16) {
        return "encoding=offset16";
    }
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.10g", tag.scale);
    return std::string("encoding=scaled scale=") + scale;
}

DisparityTag parse_disparity_tag(std::string_view text, const std::string& name) {
    const auto bad = [&] {
        return std::runtime_error("cannot read " + name + ": its " +
                                  std::string(kDisparityTagKeyword) + " text '" +
                                  std::string(text.substr(0, 80)) +
                                  "' is neither 'encoding=offset16' nor 'encoding=scaled scale=K'");
    };
    if (text == "encoding=offset16") {
        return {.encoding = DisparityEncoding::offset16, .scale = 1.0};
    }
    constexpr std::string_view prefix = "encoding=scaled scale=";
    if (!text.starts_with(prefix)) {
        throw bad();
    }
    const std::string number(text.substr(prefix.size()));
    std::size_t used = 0;
    double scale = 0.0;
    try {
        scale = std::stod(number, &used);
    } catch (const std::exception&) {
        throw bad();
    }
    if (used != number.size() || !std::isfinite(scale) || !(scale > 0.0)) {
        throw bad();
    }
    return {.encoding = DisparityEncoding::scaled, .scale = scale};
}

std::optional<DisparityTag> read_disparity_tag(const std::filesystem::path& path) {
    const std::vector<unsigned char> bytes = read_input_file(path);
    const std::optional<std::string> text = png_text(bytes, kDisparityTagKeyword);
    if (!text) {
        return std::nullopt;
    }
    return parse_disparity_tag(*text, quoted(path));
}

std::string encode_disparity_png(const cv::Mat& mat, const DisparityTag& tag,
                                 const std::filesystem::path& path) {
    return with_png_text(encode_png(mat, path), kDisparityTagKeyword, disparity_tag_text(tag));
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
