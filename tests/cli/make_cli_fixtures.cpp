// Writes the small images the command-line tests run `stereo` on, into the folder given as the
// only argument. Deterministic (fixed seed), so every run sees the same files.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "../hostile_images.hpp"
#include "fixture_main.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"

namespace {

namespace fs = std::filesystem;
namespace io = stereo::io;

constexpr int kWidth = 64;
constexpr int kHeight = 32;
constexpr int kShift = 4;  // true disparity of the generated pair

cv::Mat random_texture(int width, int height, std::mt19937& rng) {
    cv::Mat image(height, width, CV_8UC3);
    std::uniform_int_distribution<int> value(0, 255);
    for (auto it = image.begin<cv::Vec3b>(); it != image.end<cv::Vec3b>(); ++it) {
        *it = cv::Vec3b(static_cast<uchar>(value(rng)), static_cast<uchar>(value(rng)),
                        static_cast<uchar>(value(rng)));
    }
    return image;
}

// right(x) = left(x + shift), so the model, which compares L(x) with R(x - d), finds d = shift.
cv::Mat shifted(const cv::Mat& left, int shift) {
    cv::Mat right(left.size(), left.type());
    for (int y = 0; y < left.rows; ++y) {
        for (int x = 0; x < left.cols; ++x) {
            right.at<cv::Vec3b>(y, x) = left.at<cv::Vec3b>(y, std::min(left.cols - 1, x + shift));
        }
    }
    return right;
}

// The equality-test scene (issue 52): a pair whose true disparity varies, so that two engines
// that agree on it agree on more than one constant plane. Disparity in the partner image's
// coordinates (the model compares reference (x, y) with partner (x - d sx, y - d sy)):
//   background 2; a slanted plane 3 .. 5.9 (fractional everywhere); a box at 7 (occludes what lies
//   beside it); a plane at -2.5 (negative, fractional); four 7 x 7 islands at 9 (speckles).
constexpr int kSceneWidth = 64;
constexpr int kSceneHeight = 48;

double scene_disparity(int u, int v) {
    const auto in = [&](int x0, int y0, int x1, int y1) {
        return u >= x0 && u < x1 && v >= y0 && v < y1;
    };
    for (const auto& [sx, sy] :
         {std::pair{18, 10}, std::pair{47, 4}, std::pair{28, 33}, std::pair{54, 24}}) {
        if (in(sx, sy, sx + 7, sy + 7)) {
            return 9.0;
        }
    }
    if (in(36, 26, 56, 44)) {
        return 7.0;
    }
    if (in(4, 30, 28, 46)) {
        return -2.5;
    }
    if (in(6, 4, 40, 24)) {
        return 3.0 + 0.0875 * (u - 6);
    }
    return 2.0;
}

// The texture at a real position, bilinear between pixels, clamped at the edges.
cv::Vec3b sample(const cv::Mat& texture, double x, double y) {
    x = std::clamp(x, 0.0, texture.cols - 1.0);
    y = std::clamp(y, 0.0, texture.rows - 1.0);
    const int x0 = std::min(static_cast<int>(x), texture.cols - 2);
    const int y0 = std::min(static_cast<int>(y), texture.rows - 2);
    const double fx = x - x0;
    const double fy = y - y0;
    cv::Vec3b out;
    for (int c = 0; c < 3; ++c) {
        const auto at = [&](int yy, int xx) { return texture.at<cv::Vec3b>(yy, xx)[c]; };
        const double value = (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x0 + 1)) +
                             fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x0 + 1));
        out[c] = cv::saturate_cast<uchar>(value);
    }
    return out;
}

// The partner image along step (sx, sy): partner(u, v) = reference(u + d sx, v + d sy).
cv::Mat scene_partner(const cv::Mat& reference, int sx, int sy) {
    cv::Mat partner(reference.size(), reference.type());
    for (int v = 0; v < reference.rows; ++v) {
        for (int u = 0; u < reference.cols; ++u) {
            const double d = scene_disparity(u, v);
            partner.at<cv::Vec3b>(v, u) = sample(reference, u + d * sx, v + d * sy);
        }
    }
    return partner;
}

// The reference image's true disparity (horizontal pair): every partner pixel u lands at
// x = u + d(u); where two land on one pixel the nearer surface (larger d) wins; a reference pixel
// no partner pixel reaches is occluded (NaN, unknown).
cv::Mat scene_ground_truth() {
    cv::Mat truth(kSceneHeight, kSceneWidth, CV_32FC1,
                  cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
    for (int v = 0; v < kSceneHeight; ++v) {
        for (int u = 0; u < kSceneWidth; ++u) {
            const double d = scene_disparity(u, v);
            const long x = std::lround(u + d);
            if (x < 0 || x >= kSceneWidth) {
                continue;
            }
            float& at = truth.at<float>(v, static_cast<int>(x));
            if (std::isnan(at) || d > at) {
                at = static_cast<float>(d);
            }
        }
    }
    return truth;
}

void write_scene(const fs::path& dir, std::mt19937& rng) {
    // Random colour blurred a little, so that a fractional shift is a real interpolation and the
    // three channels differ (LCDM needs colour).
    cv::Mat reference;
    cv::GaussianBlur(random_texture(kSceneWidth, kSceneHeight, rng), reference, cv::Size(3, 3),
                     0.7);
    io::write_png(dir / "scene_left.png", reference);
    io::write_png(dir / "scene_right.png", scene_partner(reference, 1, 0));
    io::write_png(dir / "scene_vertical.png", scene_partner(reference, 0, 1));
    io::write_png(dir / "scene_diagonal.png", scene_partner(reference, 1, 1));
    std::ofstream(dir / "scene_gt.pfm", std::ios::binary) << io::encode_pfm(scene_ground_truth());
    // The right image of a rolled rig: column u lower by 1 + 3 u / W rows (1 at the left edge to
    // 3 at the right), a vertical plane that the hierarchical search's tracker fits in frames.
    const cv::Mat right = scene_partner(reference, 1, 0);
    cv::Mat rolled(right.size(), right.type());
    for (int v = 0; v < right.rows; ++v) {
        for (int u = 0; u < right.cols; ++u) {
            const int row = std::clamp(v - (1 + 3 * u / right.cols), 0, right.rows - 1);
            rolled.at<cv::Vec3b>(v, u) = right.at<cv::Vec3b>(row, u);
        }
    }
    io::write_png(dir / "scene_rolled.png", rolled);
}

// Files that declare or hide a size above the limit (issue 51; tests/hostile_images.hpp), for
// the hostile_* rows of bad_inputs.txt, run with --max-pixels 1048576; cli.hostile_peak_memory
// also measures the peak memory of each. Before the fix the JPEGs decoded to 12000 x 12000
// (499 MB) and the tiled TIFF cleared a 576 MB tile buffer (640 MB).
void write_hostile(const fs::path& dir) {
    namespace hostile = stereo::test::hostile;
    const auto write = [&](const char* name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
    };
    write("hostile_jpeg_tem.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0x01));
    write("hostile_jpeg_rst.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0xD0));
    write("hostile_jpeg_ff00.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0x00));
    write("hostile_png.png", hostile::png_declaring(12000, 12000));
    write("hostile_comment.pgm", hostile::pgm_comment_terminator());
    write("hostile_huge.ppm", "P6 99999999999999 2 255\n");
    hostile::TiffPage tiled;
    tiled.width = 64;
    tiled.height = 64;
    tiled.tile = 12000;
    tiled.pixels = false;
    write("hostile_tiles.tif", hostile::tiff({tiled}));
    write("hostile_tiles_bigtiff.tif", hostile::tiff({tiled}, true));
    hostile::TiffPage strips = tiled;
    strips.tile = 0;
    strips.rows_per_strip = 1U << 23;
    strips.pixels = true;
    write("hostile_strips.tif", hostile::tiff({strips}));
    hostile::TiffPage small;
    small.width = kWidth;
    small.height = kHeight;
    hostile::TiffPage huge;
    huge.width = 40000;
    huge.height = 40000;
    huge.pixels = false;
    write("hostile_pages.tif", hostile::tiff({small, huge}));
    write("hostile_bigtiff.tif", hostile::tiff({huge}, true));
    write("hostile_image.pfm", "PF\n12000 12000\n-1\n" + std::string(48, '\0'));
    // A BigTIFF of the left image's size that decodes (it was refused before: exit 1).
    write("bigtiff_grey.tif", hostile::tiff({small}, true));
}

void write_fixtures(const fs::path& dir) {
    fs::create_directories(dir);
    std::mt19937 rng(20240611U);

    const cv::Mat left = random_texture(kWidth, kHeight, rng);
    io::write_png(dir / "left.png", left);
    io::write_png(dir / "right.png", shifted(left, kShift));
    io::write_png(dir / "right_wide.png", random_texture(kWidth + 8, kHeight, rng));
    const cv::Mat tiny = random_texture(12, 8, rng);
    io::write_png(dir / "tiny_left.png", tiny);
    io::write_png(dir / "tiny_right.png", shifted(tiny, 1));
    io::write_png(dir / "deep.png",
                  cv::Mat(kHeight, kWidth, CV_16UC3, cv::Scalar(1000, 2000, 3000)));
    std::ofstream(dir / "not_an_image.png") << "plain text, not a PNG\n";
    // A PNG cut in half: libpng complains on stderr unless `stereo` keeps it quiet.
    std::vector<uchar> png;
    cv::imencode(".png", left, png);
    std::ofstream(dir / "truncated.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()),
               static_cast<std::streamsize>(png.size() / 2));
    // The same PNG declaring 30000 x 30000 in its header (IHDR width and height, big-endian, at
    // bytes 16..23; the chunk CRC is left wrong): refused from the header, before decoding.
    std::vector<uchar> huge = png;
    for (const std::size_t at : {std::size_t{16}, std::size_t{20}}) {
        huge[at] = 0;
        huge[at + 1] = 0;
        huge[at + 2] = 30000 >> 8;
        huge[at + 3] = 30000 & 0xFF;
    }
    std::ofstream(dir / "huge_header.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(huge.data()),
               static_cast<std::streamsize>(huge.size()));

    // A TIFF of a few bytes whose first directory declares 40000 x 40000 (ImageWidth and
    // ImageLength, LONG, little-endian), and a Radiance HDR image (a format OpenCV decodes but
    // whose size is not read before decoding): both refused before decoding.
    const std::string huge_tiff(
        "II*\0\x08\0\0\0\x02\0"
        "\x00\x01\x04\0\x01\0\0\0\x40\x9c\0\0"
        "\x01\x01\x04\0\x01\0\0\0\x40\x9c\0\0",
        34);
    std::ofstream(dir / "huge_header.tif", std::ios::binary) << huge_tiff;
    std::vector<uchar> hdr;
    cv::imencode(".hdr", cv::Mat(kHeight, kWidth, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5)), hdr);
    std::ofstream(dir / "radiance.hdr", std::ios::binary)
        .write(reinterpret_cast<const char*>(hdr.data()), static_cast<std::streamsize>(hdr.size()));

    // Broken PFM disparities: a size that is no number, data cut short, three channels (PF),
    // and a header declaring 30000 x 30000.
    std::ofstream(dir / "bad_size.pfm", std::ios::binary) << "Pf\n4 x\n-1\n";
    std::ofstream(dir / "short_data.pfm", std::ios::binary) << "Pf\n4 2\n-1\n"
                                                            << std::string(4 * 2 * 4 - 4, '\0');
    std::ofstream(dir / "colour.pfm", std::ios::binary) << "PF\n1 1\n-1\n" << std::string(12, '\0');
    std::ofstream(dir / "huge_header.pfm", std::ios::binary) << "Pf\n30000 30000\n-1\n";

    write_hostile(dir);

    // File kinds for the bad-input table (bad_inputs.txt): an empty file, a folder and a FIFO
    // named like images, a file nobody may read, and calibrations no rig has.
    std::ofstream(dir / "empty.png", std::ios::binary).flush();
    fs::create_directories(dir / "folder.png");
    fs::remove(dir / "fifo.png");
    if (::mkfifo((dir / "fifo.png").c_str(), 0644) != 0) {
        throw std::runtime_error("cannot create the FIFO fifo.png");
    }
    const fs::path unreadable = dir / "unreadable.png";
    fs::remove(unreadable);
    io::write_png(unreadable, left);
    fs::permissions(unreadable, fs::perms::none);
    std::ofstream(dir / "calib_nan.txt") << "P0: nan 0 32 0 0 nan 16 0 0 0 1 0\n"
                                         << "P1: nan 0 32 -10 0 nan 16 0 0 0 1 0\n";
    std::ofstream(dir / "calib_huge.txt") << "P0: 1e308 0 32 0 0 1e308 16 0 0 0 1 0\n"
                                          << "P1: 1e308 0 32 -1e308 0 1e308 16 0 0 0 1 0\n";
    // An avoidance sequence whose second frame is missing: refused before the first line.
    std::ofstream(dir / "list_missing_frame.txt") << "left.png right.png\nleft.png nope.png\n";
    std::ofstream(dir / "calib.txt") << "P0: 100 0 32 0 0 100 16 0 0 0 1 0\n"
                                     << "P1: 100 0 32 -20 0 100 16 0 0 0 1 0\n";

    // Ground truth and masks for `stereo eval`: the true shift everywhere, stored times 4.
    io::write_png(dir / "gt.png", cv::Mat(kHeight, kWidth, CV_8UC1, cv::Scalar(kShift * 4)));
    io::write_png(dir / "gt_narrow.png", cv::Mat(kHeight, kWidth - 4, CV_8UC1, cv::Scalar(16)));
    io::write_png(dir / "mask.png", cv::Mat(kHeight, kWidth, CV_8UC1, cv::Scalar(255)));
    io::write_png(dir / "mask_short.png", cv::Mat(kHeight - 2, kWidth, CV_8UC1, cv::Scalar(255)));

    write_scene(dir, rng);
    // A pair larger than the built hierarchical core (64x48), for its size error; its own
    // generator, so that the fixtures above keep their pixels.
    std::mt19937 large_rng(4564U);
    const cv::Mat large = random_texture(96, 72, large_rng);
    io::write_png(dir / "large_left.png", large);
    io::write_png(dir / "large_right.png", shifted(large, kShift));
}

}  // namespace

int main(int argc, char** argv) {
    return stereo::test::fixture_main(argc, argv, "make_cli_fixtures", write_fixtures);
}
