// Image files that declare, or hide, a size above the pixel limit (issue 51), built from bytes:
// small files made with OpenCV's encoders and then patched, or written byte by byte. Shared by
// tests/test_io.cpp (Limits.*, DecodeBound.*) and tests/cli/make_cli_fixtures.cpp (the rows
// hostile_* of tests/cli/bad_inputs.txt, and their peak memory in cli.hostile_peak_memory).
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace stereo::test::hostile {

inline std::string encoded(const char* extension, const cv::Mat& image) {
    std::vector<uchar> bytes;
    if (!cv::imencode(extension, image, bytes)) {
        throw std::runtime_error(std::string("cannot encode ") + extension);
    }
    return {bytes.begin(), bytes.end()};
}

inline std::string big_endian(std::uint64_t value, int bytes) {
    std::string out(static_cast<std::size_t>(bytes), '\0');
    for (int i = bytes - 1; i >= 0; --i, value >>= 8) {
        out[static_cast<std::size_t>(i)] = static_cast<char>(value & 0xFF);
    }
    return out;
}

inline std::string little_endian(std::uint64_t value, int bytes) {
    std::string out = big_endian(value, bytes);
    std::reverse(out.begin(), out.end());
    return out;
}

inline void put(std::string& bytes, std::size_t at, const std::string& value) {
    bytes.replace(at, value.size(), value);
}

// CRC-32 of PNG chunks (ISO 3309), so that a patched IHDR is still one libpng accepts.
inline std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFU;
    for (const char c : bytes) {
        crc ^= static_cast<unsigned char>(c);
        for (int k = 0; k < 8; ++k) {
            crc = (crc >> 1) ^ (0xEDB88320U & (0U - (crc & 1U)));
        }
    }
    return crc ^ 0xFFFFFFFFU;
}

// ---- JPEG ---------------------------------------------------------------------------------

// A 16 x 16 baseline colour JPEG whose frame header (SOF0) declares width x height.
inline std::string jpeg_declaring(int width, int height) {
    std::string jpeg = encoded(".jpg", cv::Mat(16, 16, CV_8UC3, cv::Scalar(40, 80, 120)));
    const std::size_t frame = jpeg.find("\xFF\xC0");
    put(jpeg, frame + 5, big_endian(static_cast<std::uint64_t>(height), 2));
    put(jpeg, frame + 7, big_endian(static_cast<std::uint64_t>(width), 2));
    return jpeg;
}

// jpeg_declaring(width, height) with, right after SOI, `marker` (TEM 0x01, RSTn 0xD0..0xD7, or
// 0x00: FF 00, a stuffed zero), which has no length, then two bytes libjpeg skips as garbage,
// then a comment holding a decoy frame header declaring 16 x 16. A reader that takes the two
// bytes after `marker` for a segment length (0x0010) lands on the decoy; libjpeg skips the
// comment and decodes the real frame. The old header walk said 16 x 16 here (issue 51).
inline std::string jpeg_hidden_frame(int width, int height, unsigned char marker) {
    const std::string real = jpeg_declaring(width, height);
    const std::string decoy = std::string("\xFF\xC0\x00\x11\x08", 5) + big_endian(16, 2) +
                              big_endian(16, 2) +
                              std::string("\x03\x01\x11\x00\x02\x11\x01\x03\x11\x01", 10);
    // Offsets: FF D8 | FF marker (2) | 00 10 (4) | FF FE len (6) | payload (10..) | rest.
    // The decoy sits at 2 + 2 + 0x10 = 20, which is payload byte 10.
    std::string payload(10, 'x');
    payload += decoy;
    payload += std::string(4, 'x');
    std::string out = real.substr(0, 2);
    out += '\xFF';
    out += static_cast<char>(marker);
    out += std::string("\x00\x10", 2);
    out += std::string("\xFF\xFE", 2) + big_endian(payload.size() + 2, 2) + payload;
    out += real.substr(2);
    return out;
}

// ---- PNG ----------------------------------------------------------------------------------

// A 16 x 16 grey PNG whose IHDR declares width x height, with a correct CRC.
inline std::string png_declaring(std::uint32_t width, std::uint32_t height) {
    std::string png = encoded(".png", cv::Mat(16, 16, CV_8UC1, cv::Scalar(90)));
    put(png, 16, big_endian(width, 4));
    put(png, 20, big_endian(height, 4));
    put(png, 29, big_endian(crc32(png.substr(12, 17)), 4));
    return png;
}

// ---- PNM ----------------------------------------------------------------------------------

// A PGM header whose width ends with '#': OpenCV's reader takes that character as the end of the
// number, so "4096#65536" is width 4096 and height 65536 (then maxval 255), while a reader that
// took '#' for the start of a comment saw 4096 x 255 (issue 51).
inline std::string pgm_comment_terminator() {
    return "P5 4096#65536\n255 255\n" + std::string(64, '\x80');
}

// ---- TIFF ---------------------------------------------------------------------------------

struct TiffPage {
    std::uint32_t width = 8;
    std::uint32_t height = 8;
    std::uint32_t tile = 0;            // square tiles of this side; 0: strips
    std::uint32_t rows_per_strip = 0;  // 0: tag absent (one strip)
    bool pixels = true;                // the pixel data; without, the offsets point at 16 bytes
    std::vector<std::pair<std::uint16_t, std::uint32_t>> extra;  // more LONG entries
};

// A little-endian TIFF (or BigTIFF) of 8-bit grey pages, uncompressed, in the order given.
inline std::string tiff(const std::vector<TiffPage>& pages, bool big = false) {
    struct Entry {
        std::uint16_t tag;
        std::uint16_t type;
        std::uint32_t value;
    };
    const std::size_t count_size = big ? 8 : 2;
    const std::size_t entry_size = big ? 20 : 12;
    const std::size_t offset_size = big ? 8 : 4;
    std::string out = big ? std::string("II+\0\x08\0\0\0", 8) : std::string("II*\0", 4);
    const std::size_t first_offset_at = out.size();
    out += std::string(offset_size, '\0');
    std::size_t link_at = first_offset_at;  // where the offset of the next directory goes
    for (const TiffPage& page : pages) {
        const bool tiled = page.tile > 0;
        const std::uint32_t across = tiled ? (page.width + page.tile - 1) / page.tile : 1;
        const std::uint32_t down =
            tiled ? (page.height + page.tile - 1) / page.tile
                  : (page.rows_per_strip > 0
                         ? (page.height + page.rows_per_strip - 1) / page.rows_per_strip
                         : 1);
        if (across * down != 1) {
            throw std::invalid_argument("tiff(): one strip or tile per page only");
        }
        const std::uint32_t data_bytes =
            tiled ? page.tile * page.tile
                  : page.width * std::min(page.height, page.rows_per_strip > 0 ? page.rows_per_strip
                                                                               : page.height);
        std::vector<Entry> entries = {{256, 4, page.width}, {257, 4, page.height}, {258, 3, 8},
                                      {259, 3, 1},          {262, 3, 1},           {277, 3, 1}};
        if (tiled) {
            entries.push_back({322, 4, page.tile});
            entries.push_back({323, 4, page.tile});
            entries.push_back({324, 4, 0});  // offset, filled in below
            entries.push_back({325, 4, data_bytes});
        } else {
            entries.push_back({273, 4, 0});
            entries.push_back({279, 4, data_bytes});
            if (page.rows_per_strip > 0) {
                entries.push_back({278, 4, page.rows_per_strip});
            }
        }
        for (const auto& [tag, value] : page.extra) {
            entries.push_back({tag, 4, value});
        }
        std::stable_sort(entries.begin(), entries.end(),
                         [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
        const std::size_t directory = out.size();
        const std::size_t data = directory + count_size + entries.size() * entry_size + offset_size;
        for (Entry& entry : entries) {
            if (entry.tag == 273 || entry.tag == 324) {
                entry.value = static_cast<std::uint32_t>(data);
            }
        }
        put(out, link_at, little_endian(directory, static_cast<int>(offset_size)));
        out += little_endian(entries.size(), static_cast<int>(count_size));
        for (const Entry& entry : entries) {
            out += little_endian(entry.tag, 2) + little_endian(entry.type, 2);
            out += little_endian(1, big ? 8 : 4);  // count
            const int value_size = entry.type == 3 ? 2 : 4;
            out += little_endian(entry.value, value_size);
            out += std::string(offset_size - static_cast<std::size_t>(value_size), '\0');
        }
        link_at = out.size();
        out += std::string(offset_size, '\0');  // no next directory (yet)
        out += std::string(page.pixels ? data_bytes : 16, '\x60');
    }
    return out;
}

}  // namespace stereo::test::hostile
